# Compares pair.csv (frame,element,m,v_0..2,x_0..2) with the closed form of
# springs-pair.test, to 1e-12.
function near(a, b) { d = a - b; if (d < 0) d = -d; return d <= 1e-12 }
NR == 1 { next }
{
  f = $1; e = $2
  vy = f == 0 ? 0 : (f == 1 ? -1 / 1.2 : (-1 / 1.2 - 1) / 1.2)
  xy = f == 0 ? 0 : (f == 1 ? 0.1 * (-1 / 1.2) : 0.1 * (-1 / 1.2) + 0.1 * vy)
  ok = near($3, 1) && near($4, 0) && near($5, vy) && near($6, 0) &&
       near($7, e) && near($8, xy) && near($9, 0)
  if (ok) n++; else print "row " NR " differs: " $0
}
END { print n " rows match" }
