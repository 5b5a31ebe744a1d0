// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// A map result with `result_inits` starts as a copy of its extra argument,
// not zero-filled: an `inout` extra argument, written where the element
// function writes and kept elsewhere. A scalar result's slot starts from
// its extra argument's value.

!Point = !simit.element<"Point", {m : f64}>
!W = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// As the frontend writes `inout` parameters: a result slot (the parameter
// itself unused), read where the element function reads it.
func.func @clamp(%lo : f64, %w : !W, %p : !Point) -> !W {
  %slot = simit.alloc : !simit.ref<!W>
  %v = simit.load %slot : !simit.ref<!W>
  %old = simit.extract %v[%p] : !W, (!Point) -> f64
  %new = arith.maximumf %old, %lo : f64
  %v1 = simit.insert %new into %v[%p] : f64 into !W, (!Point)
  simit.store %v1, %slot : !simit.ref<!W>
  %out = simit.load %slot : !simit.ref<!W>
  return %out : !W
}

func.func @tally(%n : f64, %p : !Point) -> f64 {
  %slot = simit.alloc : !simit.ref<f64>
  %v = simit.load %slot : !simit.ref<f64>
  %m = simit.elem_read %p["m"] : !Point -> f64
  %sum = arith.addf %v, %m : f64
  simit.store %sum, %slot : !simit.ref<f64>
  %out = simit.load %slot : !simit.ref<f64>
  return %out : f64
}

// CHECK-LABEL: func.func @run(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[M:[^:]*]]: memref<?xf64>)
// CHECK: %[[SLOT:.*]] = memref.alloca() : memref<f64>
// CHECK: %[[LO:.*]] = arith.constant 5.000000e-01 : f64
// CHECK: %[[OUT:.*]] = memref.alloc(%[[N]]) : memref<?xf64>
// CHECK-NEXT: memref.copy %[[M]], %[[OUT]] : memref<?xf64> to memref<?xf64>
// CHECK: scf.parallel (%[[P:[^)]*]]) =
// CHECK: %[[OLD:.*]] = memref.load %[[OUT]][%[[P]]] : memref<?xf64>
// CHECK: %[[NEW:.*]] = arith.maximumf %[[OLD]], %[[LO]] : f64
// CHECK: memref.store %[[NEW]], %[[OUT]][%[[P]]] : memref<?xf64>
// CHECK: memref.copy %[[OUT]], %[[M]]
// CHECK-NEXT: memref.store %[[LO]], %[[SLOT]][] : memref<f64>
// CHECK: scf.parallel
// CHECK: %[[SUM:.*]] = memref.load %[[SLOT]][] : memref<f64>
// CHECK: %[[ADD:.*]] = arith.addf %[[SUM]], %{{.*}} : f64
// CHECK: memref.store %[[ADD]], %[[SLOT]][] : memref<f64>
func.func @run() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %m = simit.field_read %points["m"] : !Points -> !W
  %lo = arith.constant 0.5 : f64
  %w = simit.map @clamp(%lo, %m) to %points {result_inits = array<i64: 1>} : (f64, !W, !Points) -> !W
  simit.field_write %w, %points["m"] : !W, !Points
  %s = simit.map @tally(%lo) to %points {result_inits = array<i64: 0>} : (f64, !Points) -> f64
  %t = simit.scale %s, %w : f64, !W
  simit.field_write %t, %points["m"] : !W, !Points
  return
}
