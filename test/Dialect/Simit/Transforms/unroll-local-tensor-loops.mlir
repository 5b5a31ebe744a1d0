// RUN: simit-opt %s --simit-unroll-local-tensor-loops --canonicalize | FileCheck %s
// RUN: simit-opt %s --simit-unroll-local-tensor-loops=max-unrolled-ops=8 --canonicalize | FileCheck %s --check-prefix=SMALL

// A loop whose induction variable picks components of a local tensor is
// unrolled, inner loops first, and every position becomes a constant.
// CHECK-LABEL: func.func @transpose(
// CHECK-NOT: scf.for
// CHECK-NOT: vector.extract %{{.*}}[%
// CHECK-NOT: vector.insert %{{.*}}[%
// CHECK: return
// With a budget below the unrolled size the loops stay.
// SMALL-LABEL: func.func @transpose(
// SMALL: scf.for
func.func @transpose(%a : vector<9xf64>) -> vector<9xf64> {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %zero = arith.constant dense<0.0> : vector<9xf64>
  %t = scf.for %i = %c0 to %c3 step %c1 iter_args(%outer = %zero) -> vector<9xf64> {
    %r = scf.for %j = %c0 to %c3 step %c1 iter_args(%inner = %outer) -> vector<9xf64> {
      %ij = arith.muli %i, %c3 : index
      %from = arith.addi %ij, %j : index
      %ji = arith.muli %j, %c3 : index
      %to = arith.addi %ji, %i : index
      %x = vector.extract %a[%from] : f64 from vector<9xf64>
      %next = vector.insert %x, %inner[%to] : f64 into vector<9xf64>
      scf.yield %next : vector<9xf64>
    }
    scf.yield %r : vector<9xf64>
  }
  return %t : vector<9xf64>
}

// Loops that index no local tensor, or have dynamic bounds, stay loops.
// CHECK-LABEL: func.func @other_loops(
// CHECK: scf.for
// CHECK: scf.for
func.func @other_loops(%n : index, %out : memref<?xf64>, %v : vector<3xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1.0 : f64
  scf.for %i = %c0 to %c3 step %c1 {
    memref.store %one, %out[%i] : memref<?xf64>
  }
  scf.for %i = %c0 to %n step %c1 {
    %x = vector.extract %v[%i] : f64 from vector<3xf64>
    memref.store %x, %out[%i] : memref<?xf64>
  }
  return
}
