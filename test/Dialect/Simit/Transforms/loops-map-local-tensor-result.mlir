// RUN: simit-opt %s --convert-simit-to-loops --canonicalize | FileCheck %s

!Point = !simit.element<"Point", {m : f64}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// The frontend's result variable of a local tensor: m(1) = p.m, then the
// whole value [p.m, 0].
func.func @moments(%p : !Point) -> tensor<2xf64> {
  %r = simit.alloc : !simit.ref<tensor<2xf64>>
  %m = simit.elem_read %p["m"] : !Point -> f64
  %old = simit.load %r : !simit.ref<tensor<2xf64>>
  %c1 = arith.constant 1 : index
  %one = simit.insert %m into %old[%c1] : f64 into tensor<2xf64>, (index)
  simit.store %one, %r : !simit.ref<tensor<2xf64>>
  %z = simit.zeros : tensor<2xf64>
  %c0 = arith.constant 0 : index
  %whole = simit.insert %m into %z[%c0] : f64 into tensor<2xf64>, (index)
  simit.store %whole, %r : !simit.ref<tensor<2xf64>>
  %v = simit.load %r : !simit.ref<tensor<2xf64>>
  return %v : tensor<2xf64>
}

// One slot of two components that starts at zero: the component write adds
// into component 1 alone, the whole value adds component by component (a
// scalar update each, which the GPU pipeline makes atomic), and the map's
// value is the slot after the loop.
// CHECK-LABEL: func.func @total(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[M:[^:]*]]: memref<?xf64>) -> vector<2xf64>
// CHECK: %[[SLOT:.*]] = memref.alloca() : memref<2xf64>
// CHECK: scf.parallel (%[[P:.*]]) = (%c0) to (%[[N]])
// CHECK: %[[MP:.*]] = memref.load %[[M]][%[[P]]] : memref<?xf64>
// CHECK: %[[OLD:.*]] = memref.load %[[SLOT]][%c1] : memref<2xf64>
// CHECK: %[[NEW:.*]] = arith.addf %[[OLD]], %[[MP]] : f64
// CHECK: memref.store %[[NEW]], %[[SLOT]][%c1] : memref<2xf64>
// CHECK: %[[OLD0:.*]] = memref.load %[[SLOT]][%c0] : memref<2xf64>
// CHECK: %[[NEW0:.*]] = arith.addf %[[OLD0]], %[[MP]] : f64
// CHECK: memref.store %[[NEW0]], %[[SLOT]][%c0] : memref<2xf64>
// CHECK: %[[OLD1:.*]] = memref.load %[[SLOT]][%c1] : memref<2xf64>
// CHECK: %[[NEW1:.*]] = arith.addf %[[OLD1]], %cst{{.*}} : f64
// CHECK: memref.store %[[NEW1]], %[[SLOT]][%c1] : memref<2xf64>
// CHECK: } {simit.scatter}
// CHECK: %[[SUM:.*]] = vector.load %[[SLOT]][%c0] : memref<2xf64>, vector<2xf64>
// CHECK: return %[[SUM]] : vector<2xf64>
func.func @total() -> tensor<2xf64> attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %t = simit.assemble @moments() to %points reduce <add> : (!Points) -> tensor<2xf64>
  return %t : tensor<2xf64>
}
