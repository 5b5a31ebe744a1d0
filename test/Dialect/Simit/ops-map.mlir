// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Cell = !simit.element<"Cell", {c : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @springs : !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @cells : !simit.set<"cells", !Cell, grid 2 over "points">

// Writes the 2x2 blocks of an edge and its endpoints' forces.
func.func @springForce(%k : f64, %s : !Spring, %ends : !simit.tuple<!Point x 2>) -> (!K, !F) {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K2 = simit.insert %blk into %K1[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K3 = simit.insert %blk into %K2[%b, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K4 = simit.insert %blk into %K3[%b, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  %f0 = simit.zeros : !F
  %v = simit.elem_read %a["x"] : !Point -> tensor<3xf64>
  %f1 = simit.insert %v into %f0[%b] : tensor<3xf64> into !F, (!Point)
  return %K4, %f1 : !K, !F
}

// CHECK-LABEL: func.func @assemble
func.func @assemble(%k : f64) -> (!K, !F) {
  %springs = simit.get_set @springs : !simit.set<"springs", !Spring, ["points", "points"]>
  // CHECK: simit.assemble @springForce(%{{.*}}) to %{{.*}} reduce <add> : (f64, !simit.set<"springs", !Spring, ["points", "points"]>) -> (!simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x tensor<3xf64>>)
  %K, %f = simit.assemble @springForce(%k) to %springs reduce <add>
      : (f64, !simit.set<"springs", !Spring, ["points", "points"]>) -> (!K, !F)
  // CHECK: simit.assemble @springForce(%{{.*}}) to %{{.*}} reduce <max>
  %K2, %f2 = simit.assemble @springForce(%k) to %springs reduce <max>
      : (f64, !simit.set<"springs", !Spring, ["points", "points"]>) -> (!K, !F)
  return %K, %f : !K, !F
}

// A vertex-set map onto the diagonal, with the result kept in a slot.
func.func @mass(%p : !Point) -> !K {
  %r = simit.alloc : !simit.ref<!K>
  %m = simit.elem_read %p["m"] : !Point -> f64
  %blk = simit.broadcast %m : f64 -> tensor<3x3xf64>
  %K0 = simit.load %r : !simit.ref<!K>
  %K1 = simit.insert %blk into %K0[%p, %p] : tensor<3x3xf64> into !K, (!Point, !Point)
  simit.store %K1, %r : !simit.ref<!K>
  %K2 = simit.load %r : !simit.ref<!K>
  return %K2 : !K
}

// CHECK-LABEL: func.func @diagonal
func.func @diagonal() -> !K {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // CHECK: simit.assemble @mass() to %{{.*}} reduce <add> : (!simit.set<"points", !Point>) -> !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  %M = simit.assemble @mass() to %points reduce <add> : (!simit.set<"points", !Point>) -> !K
  return %M : !K
}

// An edge map without the endpoint parameter, writing a vector over the edges.
func.func @stiffness(%s : !Spring) -> !simit.tensor<["springs"] x f64> {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %w0 = simit.zeros : !simit.tensor<["springs"] x f64>
  %w1 = simit.insert %k into %w0[%s] : f64 into !simit.tensor<["springs"] x f64>, (!Spring)
  return %w1 : !simit.tensor<["springs"] x f64>
}

func.func @move(%dt : f64, %p : !Point) {
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  %s = simit.scale %dt, %x : f64, tensor<3xf64>
  simit.elem_write %s, %p["x"] : tensor<3xf64>, !Point
  return
}

// CHECK-LABEL: func.func @maps
func.func @maps(%dt : f64) -> !simit.tensor<["springs"] x f64> {
  %springs = simit.get_set @springs : !simit.set<"springs", !Spring, ["points", "points"]>
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // CHECK: simit.map @stiffness() to %{{.*}} : (!simit.set<"springs", !Spring, ["points", "points"]>) -> !simit.tensor<["springs"] x f64>
  %w = simit.map @stiffness() to %springs : (!simit.set<"springs", !Spring, ["points", "points"]>) -> !simit.tensor<["springs"] x f64>
  // CHECK: simit.map @move(%{{.*}}) to %{{.*}} : (f64, !simit.set<"points", !Point>) -> ()
  simit.map @move(%dt) to %points : (f64, !simit.set<"points", !Point>) -> ()
  return %w : !simit.tensor<["springs"] x f64>
}

// A grid stencil writes the point's row at its neighbours.
func.func @stencil(%p : !Point, %g : !simit.set<"cells", !Cell, grid 2 over "points">)
    -> !simit.tensor<["points", "points"] x f64> {
  %right = simit.grid_point %g, %p [1, 0] : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
  %e = simit.grid_edge %g, %p [0, 0] dir [1, 0] : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
  %c = simit.elem_read %e["c"] : !Cell -> f64
  %A0 = simit.zeros : !simit.tensor<["points", "points"] x f64>
  %A1 = simit.insert %c into %A0[%p, %right] : f64 into !simit.tensor<["points", "points"] x f64>, (!Point, !Point)
  %A2 = simit.insert %c into %A1[%p, %p] : f64 into !simit.tensor<["points", "points"] x f64>, (!Point, !Point)
  return %A2 : !simit.tensor<["points", "points"] x f64>
}

// CHECK-LABEL: func.func @through_grid
func.func @through_grid() -> !simit.tensor<["points", "points"] x f64> {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  %cells = simit.get_set @cells : !simit.set<"cells", !Cell, grid 2 over "points">
  // CHECK: simit.map @stencil() to %{{.*}} through %{{.*}} : (!simit.set<"points", !Point>, !simit.set<"cells", !Cell, grid 2 over "points">) -> !simit.tensor<["points", "points"] x f64>
  %A = simit.map @stencil() to %points through %cells
      : (!simit.set<"points", !Point>, !simit.set<"cells", !Cell, grid 2 over "points">) -> !simit.tensor<["points", "points"] x f64>
  return %A : !simit.tensor<["points", "points"] x f64>
}

// Writes inside loops and conditionals are traced to their indices.
func.func @looped(%c : i1, %s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !F {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %v = simit.zeros : tensor<3xf64>
  %f0 = simit.zeros : !F
  %lb = arith.constant 0 : index
  %ub = arith.constant 4 : index
  %st = arith.constant 1 : index
  %f1 = scf.for %i = %lb to %ub step %st iter_args(%acc = %f0) -> (!F) {
    %n = simit.insert %v into %acc[%a] : tensor<3xf64> into !F, (!Point)
    scf.yield %n : !F
  }
  %f2 = scf.if %c -> (!F) {
    %n = simit.insert %v into %f1[%a] : tensor<3xf64> into !F, (!Point)
    scf.yield %n : !F
  } else {
    scf.yield %f1 : !F
  }
  return %f2 : !F
}

// CHECK-LABEL: func.func @control_flow
func.func @control_flow(%c : i1) -> !F {
  %springs = simit.get_set @springs : !simit.set<"springs", !Spring, ["points", "points"]>
  // CHECK: simit.assemble @looped
  %f = simit.assemble @looped(%c) to %springs reduce <add> : (i1, !simit.set<"springs", !Spring, ["points", "points"]>) -> !F
  return %f : !F
}

// An `inout` extra argument: the result starts from extra argument 1.
func.func @clamp(%lo : f64, %w : !simit.tensor<["points"] x f64>, %p : !Point)
    -> !simit.tensor<["points"] x f64> {
  %w1 = simit.insert %lo into %w[%p] : f64 into !simit.tensor<["points"] x f64>, (!Point)
  return %w1 : !simit.tensor<["points"] x f64>
}

// CHECK-LABEL: func.func @result_inits
func.func @result_inits(%lo : f64, %w : !simit.tensor<["points"] x f64>) -> !simit.tensor<["points"] x f64> {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // CHECK: simit.map @clamp(%{{.*}}, %{{.*}}) to %{{.*}} {result_inits = array<i64: 1>} : (f64, !simit.tensor<["points"] x f64>, !simit.set<"points", !Point>) -> !simit.tensor<["points"] x f64>
  %w2 = simit.map @clamp(%lo, %w) to %points {result_inits = array<i64: 1>} : (f64, !simit.tensor<["points"] x f64>, !simit.set<"points", !Point>) -> !simit.tensor<["points"] x f64>
  return %w2 : !simit.tensor<["points"] x f64>
}
