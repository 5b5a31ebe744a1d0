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

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
simit.extern @points : !simit.set<"points", !Point>

func.func @zeros(%x : !F) -> !F attributes {simit.export} {
  // expected-error @below {{a system matrix of unknown sparsity cannot be created here; assemble it with a map}}
  %A = simit.zeros : !K
  %y = simit.matvec %A, %x : !K, !F -> !F
  return %y : !F
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !K {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

// The transpose of a pattern matrix would need its column-major index.
func.func @transposed() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  // expected-error @below {{input #0 is read transposed; the loop lowering needs matrices read in the result's orientation}}
  %Kt = simit.transpose %K : !K -> !K
  %y = simit.matvec %Kt, %x : !K, !F -> !F
  return %y : !F
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
simit.extern @rods : !simit.set<"rods", !Spring, ["points", "points"]>

func.func @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !K {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

// Two edge sets give two patterns; neither holds the other.
func.func @patterns() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %rods = simit.get_set @rods : !simit.set<"rods", !Spring, ["points", "points"]>
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %R = simit.assemble @stiffness() to %rods reduce <add> : (!simit.set<"rods", !Spring, ["points", "points"]>) -> !K
  // expected-error @below {{cannot combine matrices stored as pattern of 'springs' over ('points', 'points') and pattern of 'rods' over ('points', 'points'); neither sparsity contains the other}}
  %A = simit.add %K, %R : !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %A, %x : !K, !F -> !F
  return %y : !F
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

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Cell = !simit.element<"Cell", {c : f64}>
!Points = !simit.set<"points", !Point>
!Cells = !simit.set<"cells", !Cell, grid 2 over "points">
simit.extern @points : !Points
simit.extern @cells : !Cells

func.func @stencil(%p : !Point, %g : !Cells) {
  return
}

func.func @grid() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %cells = simit.get_set @cells : !Cells
  // expected-error @below {{grid stencils are not supported by the loop lowering yet}}
  simit.map @stencil() to %points through %cells : (!Points, !Cells) -> ()
  return
}

// -----

func.func private @simit_rt_clock() -> f64

func.func @clock() -> f64 attributes {simit.export} {
  // expected-error @below {{'@simit_rt_clock' is implemented by the host or runtime; calling it is not supported by the loop lowering yet}}
  %t = func.call @simit_rt_clock() : () -> f64
  return %t : f64
}

// -----

// Complex numbers are lowered as scalars and local tensors only.
!C = !simit.tensor<["points"] x complex<f64>>
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
simit.extern @points : !simit.set<"points", !Point>

// expected-error @below {{exported function parameter 0 of type '!simit.tensor<["points"] x complex<f64>>' cannot be lowered: complex system tensors are not supported by the loop lowering yet}}
func.func @complex_system_param(%z : !C) attributes {simit.export} {
  return
}

// -----

!Point = !simit.element<"Point", {z : complex<f64>}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @conj(%p : !Point) {
  // expected-error @below {{complex fields are not supported by the loop lowering yet}}
  %z = simit.elem_read %p["z"] : !Point -> complex<f64>
  %c = complex.conj %z : complex<f64>
  simit.elem_write %c, %p["z"] : complex<f64>, !Point
  return
}

func.func @step() attributes {simit.export} {
  %s = simit.get_set @points : !Points
  simit.map @conj() to %s : (!Points) -> ()
  return
}
