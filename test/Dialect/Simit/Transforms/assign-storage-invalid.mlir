// RUN: simit-opt %s --simit-assign-storage -split-input-file -verify-diagnostics

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Hinges = !simit.set<"hinges", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>

func.func private @edge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %a] : f64 into !K, (!Point, !Point)
  return %K : !K
}

// Reported once, where it arises, not again at the uses.
func.func @unrelated_quotient(%springs : !Springs, %hinges : !Hinges) -> f64 {
  // expected-note @+1 {{'pattern("springs", rows [0, 1], cols [0, 1])' comes from here}}
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  // expected-note @+1 {{'pattern("hinges", rows [0, 1], cols [0, 1])' comes from here}}
  %H = simit.assemble @edge() to %hinges reduce <add> : (!Hinges) -> !K
  // expected-error @+1 {{cannot divide 'pattern("springs", rows [0, 1], cols [0, 1])' by 'pattern("hinges", rows [0, 1], cols [0, 1])': the divisor does not store every block of the dividend}}
  %P = simit.div %K, %H : !K
  %Q = simit.add %P, %K : !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// -----

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>

func.func private @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["x"] : !Point -> f64
  %z = simit.zeros : !K
  %M = simit.insert %m into %z[%p, %p] : f64 into !K, (!Point, !Point)
  return %M : !K
}

func.func private @edge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %a] : f64 into !K, (!Point, !Point)
  return %K : !K
}

func.func @division(%points : !Points, %springs : !Springs) -> f64 {
  // expected-note @+1 {{'diag("points")' comes from here}}
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  // expected-note @+1 {{'pattern("springs", rows [0, 1], cols [0, 1])' comes from here}}
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  // expected-error @+1 {{cannot divide 'pattern("springs", rows [0, 1], cols [0, 1])' by 'diag("points")': the divisor does not store every block of the dividend}}
  %Q = simit.div %K, %M : !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// -----

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>

func.func private @edge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %a] : f64 into !K, (!Point, !Point)
  return %K : !K
}

// A product in a loop composes once more per iteration.
func.func @growing(%springs : !Springs, %n : index) -> f64 {
  // expected-note @+1 {{'pattern("springs", rows [0, 1], cols [0, 1])' comes from here}}
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  // expected-error @+1 {{the storage of this loop-carried value keeps growing}}
  %R = scf.for %i = %c0 to %n step %c1 iter_args(%A = %K) -> (!K) {
    %P = simit.matmul %A, %K : !K, !K -> !K
    scf.yield %P : !K
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// -----

!K = !simit.tensor<["points", "points"] x f64>

// expected-error @+1 {{exported functions cannot take system matrices}}
func.func @parameter(%A : !K) -> f64 {
  %B = simit.neg %A : !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// -----

!K = !simit.tensor<["points", "points"] x f64>

func.func @result() -> !K {
  %Z = simit.zeros : !K
  // expected-error @+1 {{exported functions cannot return system matrices}}
  return %Z : !K
}

// -----

!K = !simit.tensor<["points", "points"] x f64>
simit.extern @K : !K

func.func @extern_matrix() -> f64 {
  // expected-error @+1 {{extern system matrices have no storage}}
  %slot = simit.extern_ref @K : !simit.ref<!K>
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// -----

!Point = !simit.element<"Point", {x : f64}>
!Cell = !simit.element<"Cell", {k : f64}>
!Points = !simit.set<"points", !Point>
!Cells = !simit.set<"cells", !Cell, grid 1 over "points">
!K = !simit.tensor<["points", "points"] x f64>

func.func private @backwards(%p : !Point, %g : !Cells) -> !K {
  %c = arith.constant 1.0 : f64
  %left = simit.grid_point %g, %p [-1] : !Cells, !Point
  %z = simit.zeros : !K
  %A = simit.insert %c into %z[%left, %p] : f64 into !K, (!Point, !Point)
  return %A : !K
}

func.func @stencil_rows(%points : !Points, %cells : !Cells) -> f64 {
  // expected-error @+1 {{cannot store result 0 as a grid stencil: a matrix assembled through a grid can only be written at (p, p) and (p, P[offset]) of the mapped point p}}
  %A = simit.map @backwards() to %points through %cells : (!Points, !Cells) -> !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// -----

// A quotient by a matrix whose storage does not hold the dividend's.
!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>

func.func private @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["x"] : !Point -> f64
  %z = simit.zeros : !K
  %M = simit.insert %m into %z[%p, %p] : f64 into !K, (!Point, !Point)
  return %M : !K
}

func.func private @edge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %b = simit.tuple_get %e[1] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %b] : f64 into !K, (!Point, !Point)
  return %K : !K
}

func.func @quotient_outside(%points : !Points, %springs : !Springs) -> f64 {
  // expected-note @+1 {{'diag("points")' comes from here}}
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  // expected-note @+1 {{'pattern("springs", rows [0, 1], cols [0, 1])' comes from here}}
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  // expected-error @+1 {{a division by a matrix component that does not store every block of the dividend has no storage}}
  %Q = simit.index_expr [i : "points", j : "points"] (i, j) = (%K(i, j), %M(i, j))
       : (!K, !K) -> !K {
  ^bb0(%k: f64, %m: f64):
    %q = arith.divf %k, %m : f64
    simit.yield %q : f64
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}
