// RUN: simit-opt %s --simit-gpu-scatter-atomics --split-input-file | FileCheck %s

// Assembly of a spring stiffness through the per-edge location table: two
// springs that share a vertex write the same BCSR block, so the accumulation
// becomes one atomic add; the force scatter through the endpoints as well,
// with the subtraction turned into the addition of the negated value.

// CHECK-LABEL: func.func @assemble_springs
// CHECK:         scf.parallel (%[[E:.*]]) =
// CHECK:           %[[A:.*]] = arith.index_cast
// CHECK:           %[[B:.*]] = arith.index_cast
// CHECK:           scf.for %[[C:.*]] =
// CHECK:             %[[FA:.*]] = arith.mulf
// CHECK-NOT:         memref.store
// CHECK:             memref.atomic_rmw addf %[[FA]], %{{.*}}[%[[A]], %[[C]]] : (f64, memref<?x3xf64>) -> f64
// CHECK:             %[[NEG:.*]] = arith.negf %[[FA]] : f64
// CHECK:             memref.atomic_rmw addf %[[NEG]], %{{.*}}[%[[B]], %[[C]]] : (f64, memref<?x3xf64>) -> f64
// CHECK:           scf.for %[[BLK:.*]] =
// CHECK:             %[[L:.*]] = arith.index_cast
// CHECK:             scf.for %[[R:.*]] =
// CHECK:               scf.for %[[CC:.*]] =
// CHECK-NOT:             memref.load %{{.*}}[%[[L]], %[[R]], %[[CC]]]
// CHECK:                 memref.atomic_rmw addf %{{.*}}, %{{.*}}[%[[L]], %[[R]], %[[CC]]] : (f64, memref<?x3x3xf64>) -> f64
// CHECK-NOT:             memref.store
// CHECK:           scf.reduce
func.func @assemble_springs(%n: index, %endpoints: memref<?x2xi32>,
                            %loc: memref<?x4xi32>, %x: memref<?x3xf64>,
                            %k: f64, %vals: memref<?x3x3xf64>,
                            %f: memref<?x3xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %c4 = arith.constant 4 : index
  scf.parallel (%e) = (%c0) to (%n) step (%c1) {
    %a32 = memref.load %endpoints[%e, %c0] : memref<?x2xi32>
    %b32 = memref.load %endpoints[%e, %c1] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b = arith.index_cast %b32 : i32 to index
    scf.for %c = %c0 to %c3 step %c1 {
      %xa = memref.load %x[%a, %c] : memref<?x3xf64>
      %xb = memref.load %x[%b, %c] : memref<?x3xf64>
      %d = arith.subf %xb, %xa : f64
      %fa = arith.mulf %k, %d : f64
      %fa_old = memref.load %f[%a, %c] : memref<?x3xf64>
      %fa_new = arith.addf %fa_old, %fa : f64
      memref.store %fa_new, %f[%a, %c] : memref<?x3xf64>
      %fb_old = memref.load %f[%b, %c] : memref<?x3xf64>
      %fb_new = arith.subf %fb_old, %fa : f64
      memref.store %fb_new, %f[%b, %c] : memref<?x3xf64>
    }
    scf.for %blk = %c0 to %c4 step %c1 {
      %l32 = memref.load %loc[%e, %blk] : memref<?x4xi32>
      %l = arith.index_cast %l32 : i32 to index
      scf.for %r = %c0 to %c3 step %c1 {
        scf.for %cc = %c0 to %c3 step %c1 {
          %old = memref.load %vals[%l, %r, %cc] : memref<?x3x3xf64>
          %new = arith.addf %k, %old : f64
          memref.store %new, %vals[%l, %r, %cc] : memref<?x3x3xf64>
        }
      }
    }
    scf.reduce
  }
  return
}

// -----

// Stores indexed by the loop's induction variable are owned by their
// iteration, stores into memory allocated inside the loop are private, and
// `contribution - old` is no accumulation: all three stay plain.

// CHECK-LABEL: func.func @owned_private_and_overwrite
// CHECK-NOT:     memref.atomic_rmw
// CHECK:         memref.store
// CHECK:         memref.store
// CHECK:         memref.store
// CHECK-NOT:     memref.atomic_rmw
// CHECK:         return
func.func @owned_private_and_overwrite(%n: index, %h: f64,
                                       %x: memref<?x3xf64>,
                                       %v: memref<?x3xf64>,
                                       %idx: memref<?xi32>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %xi = memref.load %x[%i, %c1] : memref<?x3xf64>
    %vi = memref.load %v[%i, %c1] : memref<?x3xf64>
    %hv = arith.mulf %h, %vi : f64
    %sum = arith.addf %xi, %hv : f64
    memref.store %sum, %x[%i, %c1] : memref<?x3xf64>
    %tmp = memref.alloca() : memref<3xf64>
    %t = memref.load %tmp[%c0] : memref<3xf64>
    %t2 = arith.addf %t, %hv : f64
    memref.store %t2, %tmp[%c0] : memref<3xf64>
    %j32 = memref.load %idx[%i] : memref<?xi32>
    %j = arith.index_cast %j32 : i32 to index
    %old = memref.load %v[%j, %c0] : memref<?x3xf64>
    %diff = arith.subf %hv, %old : f64
    memref.store %diff, %v[%j, %c0] : memref<?x3xf64>
    scf.reduce
  }
  return
}

// -----

// Integer accumulations (a histogram of endpoint degrees) use addi; a
// subtraction negates through `0 - x`. In a two-dimensional loop a store
// owns its location only when both induction variables index it.

// CHECK-LABEL: func.func @degrees
// CHECK:         memref.atomic_rmw addi %{{.*}}, %{{.*}}[%{{.*}}] : (i32, memref<?xi32>) -> i32
// CHECK:         %[[ZERO:.*]] = arith.constant 0 : i32
// CHECK:         %[[NEG:.*]] = arith.subi %[[ZERO]], %{{.*}} : i32
// CHECK:         memref.atomic_rmw addi %[[NEG]]
// CHECK-LABEL: func.func @two_dimensional
// CHECK:         scf.parallel (%[[I:.*]], %[[J:.*]]) =
// CHECK:           memref.atomic_rmw addf %{{.*}}, %{{.*}}[%[[I]]] : (f64, memref<?xf64>) -> f64
// CHECK:           memref.store %{{.*}}, %{{.*}}[%[[I]], %[[J]]] : memref<?x?xf64>
func.func @degrees(%n: index, %endpoints: memref<?x2xi32>,
                   %degree: memref<?xi32>, %balance: memref<?xi32>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1 : i32
  scf.parallel (%e) = (%c0) to (%n) step (%c1) {
    %a32 = memref.load %endpoints[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %d = memref.load %degree[%a] : memref<?xi32>
    %d1 = arith.addi %d, %one : i32
    memref.store %d1, %degree[%a] : memref<?xi32>
    %b = memref.load %balance[%a] : memref<?xi32>
    %b1 = arith.subi %b, %one : i32
    memref.store %b1, %balance[%a] : memref<?xi32>
    scf.reduce
  }
  return
}

func.func @two_dimensional(%n: index, %m: index, %a: memref<?x?xf64>,
                           %rowsum: memref<?xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%i, %j) = (%c0, %c0) to (%n, %m) step (%c1, %c1) {
    %v = memref.load %a[%i, %j] : memref<?x?xf64>
    %s = memref.load %rowsum[%i] : memref<?xf64>
    %s1 = arith.addf %s, %v : f64
    memref.store %s1, %rowsum[%i] : memref<?xf64>
    %w = memref.load %a[%i, %j] : memref<?x?xf64>
    %w1 = arith.addf %w, %v : f64
    memref.store %w1, %a[%i, %j] : memref<?x?xf64>
    scf.reduce
  }
  return
}
