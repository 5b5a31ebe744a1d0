// RUN: simit-opt %s --pass-pipeline='builtin.module(func.func(simit-hoist-parallel-allocas))' | FileCheck %s

// Slots of a sequentially run scf.parallel body are made once, at the entry;
// slots of sequential loops and dynamic slots stay.
// CHECK-LABEL: func.func @slots(
// CHECK-NEXT: %[[S:.*]] = memref.alloca() : memref<9xf64>
// CHECK-NEXT: %[[C0:.*]] = arith.constant 0 : index
// CHECK: scf.parallel (%[[E:.*]]) =
// CHECK-NOT: memref.alloca() : memref<9xf64>
// CHECK:   memref.store %{{.*}}, %[[S]][%[[C0]]]
// CHECK:   memref.alloca(%{{.*}}) : memref<?xf64>
// CHECK: scf.for
// CHECK:   memref.alloca() : memref<3xf64>
func.func @slots(%n : index, %out : memref<?xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%e) = (%c0) to (%n) step (%c1) {
    %slot = memref.alloca() : memref<9xf64>
    memref.store %one, %slot[%c0] : memref<9xf64>
    %v = memref.load %slot[%c0] : memref<9xf64>
    memref.store %v, %out[%e] : memref<?xf64>
    %dyn = memref.alloca(%n) : memref<?xf64>
    scf.reduce
  }
  scf.for %i = %c0 to %n step %c1 {
    %local = memref.alloca() : memref<3xf64>
    memref.store %one, %local[%c0] : memref<3xf64>
  }
  return
}
