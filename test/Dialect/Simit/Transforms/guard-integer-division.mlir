// RUN: simit-opt %s --pass-pipeline='builtin.module(func.func(simit-guard-integer-division))' | FileCheck %s

// A dynamic signed divisor is checked for zero and for the one overflowing
// quotient, with the source position in each message.
// CHECK-LABEL: func.func @signed_division(
// CHECK-SAME: %[[N:.*]]: i32, %[[D:.*]]: i32)
// CHECK: %[[ZERO:.*]] = arith.constant 0 : i32
// CHECK: %[[ISZERO:.*]] = arith.cmpi eq, %[[D]], %[[ZERO]]
// CHECK: %[[OK:.*]] = arith.xori %[[ISZERO]], %true
// CHECK: cf.assert %[[OK]], "integer division by zero (prog.sim:3:7)"
// CHECK: %[[M1:.*]] = arith.constant -1 : i32
// CHECK: %[[ISM1:.*]] = arith.cmpi eq, %[[D]], %[[M1]]
// CHECK: %[[MIN:.*]] = arith.constant -2147483648 : i32
// CHECK: %[[ISMIN:.*]] = arith.cmpi eq, %[[N]], %[[MIN]]
// CHECK: %[[OVER:.*]] = arith.andi %[[ISM1]], %[[ISMIN]]
// CHECK: %[[NOOVER:.*]] = arith.xori %[[OVER]],
// CHECK: cf.assert %[[NOOVER]], "integer overflow: the minimum integer divided by -1 (prog.sim:3:7)"
// CHECK: arith.divsi %[[N]], %[[D]]
func.func @signed_division(%n : i32, %d : i32) -> i32 {
  %q = arith.divsi %n, %d : i32 loc("prog.sim":3:7)
  return %q : i32
}

// A signed remainder by -1 is 0: its divisor becomes 1, not an error.
// CHECK-LABEL: func.func @signed_remainder(
// CHECK-SAME: %[[N:.*]]: i32, %[[D:.*]]: i32)
// CHECK: cf.assert %{{.*}}, "mod by zero (prog.sim:4:9)"
// CHECK: %[[ISM1:.*]] = arith.cmpi eq, %[[D]], %{{.*}}
// CHECK: %[[SAFE:.*]] = arith.select %[[ISM1]], %{{.*}}, %[[D]]
// CHECK-NOT: cf.assert
// CHECK: arith.remsi %[[N]], %[[SAFE]]
func.func @signed_remainder(%n : i32, %d : i32) -> i32 {
  %r = arith.remsi %n, %d : i32 loc("prog.sim":4:9)
  return %r : i32
}

// Unsigned division only needs the zero check.
// CHECK-LABEL: func.func @unsigned_division(
// CHECK: cf.assert %{{.*}}, "integer division by zero (
// CHECK-NOT: cf.assert
// CHECK: arith.divui
func.func @unsigned_division(%n : i64, %d : i64) -> i64 {
  %q = arith.divui %n, %d : i64
  return %q : i64
}

// Lanes of integer vectors: any zero lane fails.
// CHECK-LABEL: func.func @vector_division(
// CHECK: %[[ZEROS:.*]] = arith.cmpi eq, %{{.*}}, %{{.*}} : vector<3xi32>
// CHECK: %[[ANY:.*]] = vector.reduction <or>, %[[ZEROS]] : vector<3xi1> into i1
// CHECK: %[[OK:.*]] = arith.xori %[[ANY]], %{{.*}}
// CHECK: cf.assert %[[OK]], "integer division by zero (
func.func @vector_division(%n : vector<3xi32>, %d : vector<3xi32>) -> vector<3xi32> {
  %q = arith.divsi %n, %d : vector<3xi32>
  return %q : vector<3xi32>
}

// Safe constant divisors, and index arithmetic of the lowering, are left
// alone; a constant -1 still needs the overflow check.
// CHECK-LABEL: func.func @unchecked(
// CHECK-NOT: cf.assert
// CHECK: arith.divsi
// CHECK-NOT: cf.assert
// CHECK: arith.remsi
// CHECK: arith.divsi %{{.*}}, %{{.*}} : index
// CHECK: cf.assert %{{.*}}, "integer overflow
// CHECK: arith.divsi
func.func @unchecked(%n : i32, %i : index, %j : index) -> (i32, i32, index, i32) {
  %c3 = arith.constant 3 : i32
  %cm1 = arith.constant -1 : i32
  %q = arith.divsi %n, %c3 : i32
  %r = arith.remsi %n, %c3 : i32
  %k = arith.divsi %i, %j : index
  %m = arith.divsi %n, %cm1 : i32
  return %q, %r, %k, %m : i32, i32, index, i32
}
