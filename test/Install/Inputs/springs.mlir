!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @springs : !simit.set<"springs", !Spring, ["points", "points"]>
