// RUN: simit-opt %s --split-input-file --verify-diagnostics \
// RUN:   --simit-linalg-to-index-expr --convert-simit-to-loops

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
simit.extern @points : !simit.set<"points", !Point>

// expected-error @below {{exported functions cannot take system matrices}}
func.func @matrix_param(%A : !K) attributes {simit.export} {
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @twice(%v : !F) -> !F {
  return %v : !F
}

func.func @call() -> !F attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !F
  // expected-error @below {{calls must be inlined by simit-inline-functions before the loop lowering}}
  %y = func.call @twice(%x) : (!F) -> !F
  return %y : !F
}

// -----

!Point = !simit.element<"Point", {x : f64}>
!Cell = !simit.element<"Cell", {c : f64}>
!Points = !simit.set<"points", !Point>
!Cells = !simit.set<"cells", !Cell, grid 2 over "points">
!A = !simit.tensor<["points", "points"] x f64>
simit.extern @points : !Points
simit.extern @cells : !Cells

// A stencil row belongs to its point: (P[1, 0], p) is another point's row.
func.func @transposed(%p : !Point, %g : !Cells) -> !A {
  %one = arith.constant 1.0 : f64
  %right = simit.grid_point %g, %p [1, 0] : !Cells, !Point
  %A0 = simit.zeros : !A
  %A1 = simit.insert %one into %A0[%right, %p] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

func.func @grid() -> !simit.tensor<["points"] x f64> attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %cells = simit.get_set @cells : !Cells
  // expected-error @below {{cannot store result 0 as a grid stencil: a matrix assembled through a grid can only be written at (p, p) and (p, P[offset]) of the mapped point p}}
  %A = simit.map @transposed() to %points through %cells : (!Points, !Cells) -> !A
  %x = simit.field_read %points["x"] : !Points -> !simit.tensor<["points"] x f64>
  %y = simit.matvec %A, %x : !A, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x f64>
  return %y : !simit.tensor<["points"] x f64>
}

// -----

func.func private @simit_rt_clock() -> f64

func.func @clock() -> f64 attributes {simit.export} {
  // expected-error @below {{'@simit_rt_clock' is implemented by the host or runtime; calling it is not supported by the loop lowering yet}}
  %t = func.call @simit_rt_clock() : () -> f64
  return %t : f64
}

// -----

!Point = !simit.element<"Point", {m : f64}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @direct(%p : !Point) -> f64 {
  %m = simit.elem_read %p["m"] : !Point -> f64
  // expected-error @below {{result 0 of element function 'direct' must be the value of a variable}}
  return %m : f64
}

func.func @scalar_not_a_variable() -> f64 attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %t = simit.assemble @direct() to %points reduce <add> : (!Points) -> f64
  return %t : f64
}

