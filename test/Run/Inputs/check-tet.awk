# Compares tet.csv (frame,element,m,v_0..2,x_0..2) with the closed form of
# fem-tet.test, to 1e-12.
function near(a, b) { d = a - b; if (d < 0) d = -d; return d <= 1e-12 }
NR == 1 { next }
{
  f = $1; e = $2
  x0 = e == 1; y0 = e == 2; z0 = e == 3
  ok = near($3, 1000 / 24) && near($4, 0) && near($5, -0.1 * f) &&
       near($6, 0) && near($7, x0) && near($8, y0 - 0.001 * f * (f + 1) / 2) &&
       near($9, z0)
  if (ok) n++; else print "row " NR " differs: " $0
}
END { print n " rows match" }
