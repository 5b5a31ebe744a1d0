// RUN: simit-opt %s --simit-parallel-loops=set-order-only | FileCheck %s

// For targets that run every scf.parallel concurrently (the GPU), an
// element loop whose elements see each other's writes becomes one
// iteration running the set in order; accumulations and owned loops are
// left for the target (atomics), and nothing is marked.

// CHECK-LABEL: func.func @prefix(
// CHECK-SAME: %[[NE:[^:]*]]: index
// CHECK: scf.parallel (%{{[^)]*}}) = (%[[ZERO:.*]]) to (%[[ONE:.*]]) step (%[[ONE]]) {
// CHECK-NEXT: scf.for %[[E:[^ ]*]] = %{{.*}} to %[[NE]] step %{{.*}} {
// CHECK: memref.load %{{.*}}[%[[E]], %{{.*}}] : memref<?x2xi32>
// CHECK-NOT: simit.parallel
// CHECK: return
func.func @prefix(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b32 = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %b = arith.index_cast %b32 : i32 to index
    %xa = memref.load %x[%a] : memref<?xf64>
    memref.store %xa, %x[%b] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}

// CHECK-LABEL: func.func @accumulates(
// CHECK: scf.parallel (%{{[^)]*}}) = (%{{.*}}) to (%[[NE:[^)]*]])
// CHECK-NOT: scf.for
// CHECK: } {simit.scatter}
func.func @accumulates(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %xa = memref.load %x[%a] : memref<?xf64>
    %na = arith.addf %xa, %one : f64
    memref.store %na, %x[%a] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}
