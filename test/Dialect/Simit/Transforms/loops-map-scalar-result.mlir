// RUN: simit-opt %s --convert-simit-to-loops --canonicalize | FileCheck %s

!Point = !simit.element<"Point", {m : f64}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// The frontend's result variable: written once per element.
func.func @mass(%p : !Point) -> f64 {
  %r = simit.alloc : !simit.ref<f64>
  %m = simit.elem_read %p["m"] : !Point -> f64
  simit.store %m, %r : !simit.ref<f64>
  %v = simit.load %r : !simit.ref<f64>
  return %v : f64
}

// The variable is one slot that starts at zero; each write adds into it and
// the map's value is the slot after the loop.
// CHECK-LABEL: func.func @total(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[M:[^:]*]]: memref<?xf64>) -> f64
// CHECK: %[[SLOT:.*]] = memref.alloca() : memref<f64>
// CHECK: memref.store %cst, %[[SLOT]][] : memref<f64>
// CHECK: scf.parallel (%[[P:.*]]) = (%c0) to (%[[N]])
// CHECK: %[[MP:.*]] = memref.load %[[M]][%[[P]]] : memref<?xf64>
// CHECK: %[[OLD:.*]] = memref.load %[[SLOT]][] : memref<f64>
// CHECK: %[[NEW:.*]] = arith.addf %[[OLD]], %[[MP]] : f64
// CHECK: memref.store %[[NEW]], %[[SLOT]][] : memref<f64>
// CHECK: } {simit.scatter}
// CHECK: %[[SUM:.*]] = memref.load %[[SLOT]][] : memref<f64>
// CHECK: return %[[SUM]] : f64
func.func @total() -> f64 attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %t = simit.assemble @mass() to %points reduce <add> : (!Points) -> f64
  return %t : f64
}
