// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// An extern vector over a set is bound like a field: a memref with a block
// per element of the set the binding names, read and written in place (`u = 2 * u` scales
// each block where it lies).

!Point = !simit.element<"Point", {m : f64}>
!Points = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !Points
simit.extern @force : !F

// CHECK-LABEL: func.func @push(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[F:[^:]*]]: memref<?x3xf64>)
// CHECK-SAME: simit.bindings = [{kind = "set_size", set = "points"}, {kind = "extern", name = "force", set = "points"}]
// CHECK: scf.parallel (%[[P:[^)]*]]) = (%{{.*}}) to (%[[N]])
// CHECK: %[[X:.*]] = memref.load %[[F]][%[[P]], %[[C:[a-z0-9_]*]]] : memref<?x3xf64>
// CHECK: %[[Y:.*]] = arith.mulf %{{.*}}, %[[X]] : f64
// CHECK: memref.store %[[Y]], %[[F]][%[[P]], %[[C]]] : memref<?x3xf64>
func.func @push() attributes {simit.export} {
  %two = arith.constant 2.0 : f64
  %slot = simit.extern_ref @force : !simit.ref<!F>
  %f = simit.load %slot : !simit.ref<!F>
  %g = simit.scale %two, %f : f64, !F
  simit.store %g, %slot : !simit.ref<!F>
  return
}
