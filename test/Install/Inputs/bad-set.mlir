// A field name used twice is rejected by the installed dialect's verifier.
!Point = !simit.element<"Point", {x : f64, x : f64}>
simit.extern @points : !simit.set<"points", !Point>
