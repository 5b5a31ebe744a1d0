// RUN: simit-opt %s --convert-simit-to-loops --canonicalize | FileCheck %s

// A dynamic index into a local tensor is asserted to lie in its dimension,
// each dimension on its own; the variable of a loop within the dimension
// and constant indices need no check.
// CHECK-LABEL: func.func @indices(
// CHECK-SAME: %[[K:[^:]*]]: i32
// CHECK: %[[I:.*]] = arith.index_cast %[[K]] : i32 to index
// CHECK: %[[OK:.*]] = arith.cmpi ult, %[[I]], %c3 : index
// CHECK: cf.assert %[[OK]], "index out of range for a dimension of size 3 (checks.sim:4:7)"
// CHECK: scf.for %[[IV:.*]] = %c0 to %c3 step %c1
// CHECK-NOT: cf.assert
// CHECK: vector.extract %{{.*}}[%[[IV]]]
// CHECK: }
func.func @indices(%k : i32, %v : tensor<3xf64>) -> f64 attributes {simit.export} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %i = arith.index_cast %k : i32 to index
  %a = simit.extract %v[%i] : tensor<3xf64>, (index) -> f64 loc("checks.sim":4:7)
  %zero = arith.constant 0.0 : f64
  %sum = scf.for %j = %c0 to %c3 step %c1 iter_args(%acc = %zero) -> f64 {
    %b = simit.extract %v[%j] : tensor<3xf64>, (index) -> f64
    %next = arith.addf %acc, %b : f64
    scf.yield %next : f64
  }
  %c = simit.extract %v[%c1] : tensor<3xf64>, (index) -> f64
  %r0 = arith.addf %a, %sum : f64
  %r = arith.addf %r0, %c : f64
  return %r : f64
}
