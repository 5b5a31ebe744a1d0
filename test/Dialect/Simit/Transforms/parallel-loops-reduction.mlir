// RUN: simit-opt %s --simit-parallel-loops=reduction-chunk=256 | FileCheck %s

// A reduction becomes a marked loop over chunks of 256 iterations, each
// reduced in order from the neutral element into its partial, and a
// sequential loop that combines the initial value with the partials in
// chunk order: the order does not depend on the number of threads.

// CHECK-LABEL: func.func @dot(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[A:[^:]*]]: memref<?xf64>, %[[B:[^:]*]]: memref<?xf64>
// CHECK-DAG: %[[C256:.*]] = arith.constant 256 : index
// CHECK-DAG: %[[INIT:.*]] = arith.constant 1.5
// CHECK: %[[TRIPS:.*]] = arith.maxsi %[[N]], %{{.*}} : index
// CHECK: %[[CHUNKS:.*]] = arith.ceildivui %[[TRIPS]], %[[C256]] : index
// CHECK: %[[PARTIALS:.*]] = memref.alloc(%[[CHUNKS]]) : memref<?xf64>
// CHECK: scf.parallel (%[[Q:.*]]) = (%{{.*}}) to (%[[CHUNKS]]) step
// CHECK:   %[[FIRST:.*]] = arith.muli %[[Q]], %[[C256]] : index
// CHECK:   %[[END:.*]] = arith.addi %[[FIRST]], %[[C256]] : index
// CHECK:   %[[LAST:.*]] = arith.minui %[[END]], %[[TRIPS]] : index
// CHECK:   %[[NEUTRAL:.*]] = arith.constant -0.000000e+00 : f64
// CHECK:   %[[PARTIAL:.*]] = scf.parallel (%[[I:.*]]) = (%[[FIRST]]) to (%[[LAST]]) step (%{{.*}}) init (%[[NEUTRAL]]) -> f64 {
// CHECK:     memref.load %[[A]][%[[I]]]
// CHECK:     scf.reduce
// CHECK:   memref.store %[[PARTIAL]], %[[PARTIALS]][%[[Q]]] : memref<?xf64>
// CHECK: } {simit.parallel = "reduction"}
// CHECK: %[[SUM:.*]] = scf.for %[[K:.*]] = %{{.*}} to %[[CHUNKS]] step %{{.*}} iter_args(%[[ACC:.*]] = %[[INIT]]) -> (f64) {
// CHECK:   %[[P:.*]] = memref.load %[[PARTIALS]][%[[K]]] : memref<?xf64>
// CHECK:   %[[NEXT:.*]] = arith.addf %[[ACC]], %[[P]] : f64
// CHECK:   scf.yield %[[NEXT]] : f64
// CHECK: return %[[SUM]] : f64
func.func @dot(%n : index, %a : memref<?xf64>, %b : memref<?xf64>) -> f64 {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %init = arith.constant 1.5 : f64
  %r = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%init) -> f64 {
    %x = memref.load %a[%i] : memref<?xf64>
    %y = memref.load %b[%i] : memref<?xf64>
    %p = arith.mulf %x, %y : f64
    scf.reduce(%p : f64) {
    ^bb0(%lhs : f64, %rhs : f64):
      %s = arith.addf %lhs, %rhs : f64
      scf.reduce.return %s : f64
    }
  }
  return %r : f64
}

// Several results, a non-unit lower bound and step, a write the iteration
// owns, and a maximum (neutral element -inf).
// CHECK-LABEL: func.func @sum_and_max(
// CHECK-SAME: %[[N:[^:]*]]: index
// CHECK: %[[TRIPS:.*]] = arith.ceildivui %{{.*}}, %[[C2:.*]] : index
// CHECK: memref.alloc(%{{.*}}) : memref<?xf64>
// CHECK: memref.alloc(%{{.*}}) : memref<?xi64>
// CHECK: scf.parallel
// CHECK:   %[[FIRST:.*]] = arith.muli
// CHECK:   %[[LAST:.*]] = arith.minui
// CHECK:   %[[LO:.*]] = arith.muli %[[FIRST]], %[[C2]]
// CHECK:   %[[LB:.*]] = arith.addi %[[LO]], %{{.*}}
// CHECK:   %[[HI:.*]] = arith.muli %[[LAST]], %[[C2]]
// CHECK:   %[[UB:.*]] = arith.addi %[[HI]], %{{.*}}
// CHECK:   %[[NEG_INF:.*]] = arith.constant 0xFFF0000000000000 : f64
// CHECK:   %[[ZERO:.*]] = arith.constant 0 : i64
// CHECK:   scf.parallel (%{{.*}}) = (%[[LB]]) to (%[[UB]]) step (%[[C2]]) init (%[[NEG_INF]], %[[ZERO]]) -> (f64, i64)
// CHECK: } {simit.parallel = "reduction"}
// CHECK: scf.for
// CHECK:   arith.maximumf
// CHECK:   arith.addi
func.func @sum_and_max(%n : index, %a : memref<?xf64>, %c : memref<?xi64>) -> (f64, i64) {
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %init = arith.constant 0.0 : f64
  %zero = arith.constant 0 : i64
  %r:2 = scf.parallel (%i) = (%c1) to (%n) step (%c2) init (%init, %zero) -> (f64, i64) {
    %x = memref.load %a[%i] : memref<?xf64>
    %k = memref.load %c[%i] : memref<?xi64>
    %twice = arith.addi %k, %k : i64
    memref.store %twice, %c[%i] : memref<?xi64>
    scf.reduce(%x, %k : f64, i64) {
    ^bb0(%lhs : f64, %rhs : f64):
      %m = arith.maximumf %lhs, %rhs : f64
      scf.reduce.return %m : f64
    }, {
    ^bb0(%lhs : i64, %rhs : i64):
      %s = arith.addi %lhs, %rhs : i64
      scf.reduce.return %s : i64
    }
  }
  return %r#0, %r#1 : f64, i64
}

// A combiner of more than one operation, and a reduction loop that writes a
// shared location, stay sequential.
// CHECK-LABEL: func.func @sequential(
// CHECK-NOT: simit.parallel
// CHECK-NOT: memref.alloc
func.func @sequential(%n : index, %a : memref<?xf64>, %s : memref<f64>) -> (f64, f64) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %init = arith.constant 0.0 : f64
  %r = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%init) -> f64 {
    %x = memref.load %a[%i] : memref<?xf64>
    scf.reduce(%x : f64) {
    ^bb0(%lhs : f64, %rhs : f64):
      %m = arith.mulf %rhs, %rhs : f64
      %t = arith.addf %lhs, %m : f64
      scf.reduce.return %t : f64
    }
  }
  %q = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%init) -> f64 {
    %x = memref.load %a[%i] : memref<?xf64>
    memref.store %x, %s[] : memref<f64>
    scf.reduce(%x : f64) {
    ^bb0(%lhs : f64, %rhs : f64):
      %t = arith.addf %lhs, %rhs : f64
      scf.reduce.return %t : f64
    }
  }
  return %r, %q : f64, f64
}
