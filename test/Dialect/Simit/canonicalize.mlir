// RUN: simit-opt %s -canonicalize -split-input-file | FileCheck %s

!F = !simit.tensor<["points"] x tensor<3xf64>>
!A = !simit.tensor<["points", "springs"] x tensor<3x2xf64>>
!AT = !simit.tensor<["springs", "points"] x tensor<2x3xf64>>

// CHECK-LABEL: func.func @transpose_twice
// CHECK-SAME: (%[[A:.*]]: !simit.tensor
// CHECK-NEXT: return %[[A]]
func.func @transpose_twice(%a : !A) -> !A {
  %t = simit.transpose %a : !A -> !AT
  %tt = simit.transpose %t : !AT -> !A
  return %tt : !A
}

// A single transpose stays.
// CHECK-LABEL: func.func @transpose_once
// CHECK: simit.transpose
func.func @transpose_once(%a : !A) -> !AT {
  %t = simit.transpose %a : !A -> !AT
  return %t : !AT
}

// CHECK-LABEL: func.func @scale_by_one
// CHECK-SAME: (%[[X:.*]]: !simit.tensor
// CHECK-NEXT: return %[[X]]
func.func @scale_by_one(%x : !F) -> !F {
  %one = arith.constant 1.0 : f64
  %s = simit.scale %one, %x : f64, !F
  return %s : !F
}

// CHECK-LABEL: func.func @scale_int_by_one
// CHECK-SAME: (%[[X:.*]]: tensor<3xi32>
// CHECK-NEXT: return %[[X]]
func.func @scale_int_by_one(%x : tensor<3xi32>) -> tensor<3xi32> {
  %one = arith.constant 1 : i32
  %s = simit.scale %one, %x : i32, tensor<3xi32>
  return %s : tensor<3xi32>
}

// CHECK-LABEL: func.func @scale_by_zero
// CHECK-NEXT: %[[Z:.*]] = simit.zeros : !simit.tensor<["points"] x tensor<3xf64>>
// CHECK-NEXT: return %[[Z]]
func.func @scale_by_zero(%x : !F) -> !F {
  %zero = arith.constant 0.0 : f64
  %s = simit.scale %zero, %x : f64, !F
  return %s : !F
}

// Other scalars are kept.
// CHECK-LABEL: func.func @scale_by_two
// CHECK: simit.scale
func.func @scale_by_two(%x : !F) -> !F {
  %two = arith.constant 2.0 : f64
  %s = simit.scale %two, %x : f64, !F
  return %s : !F
}

// CHECK-LABEL: func.func @scale_by_unknown
// CHECK: simit.scale
func.func @scale_by_unknown(%x : !F, %h : f64) -> !F {
  %s = simit.scale %h, %x : f64, !F
  return %s : !F
}

// CHECK-LABEL: func.func @add_zeros
// CHECK-SAME: (%[[X:.*]]: !simit.tensor
// CHECK-NEXT: return %[[X]], %[[X]]
func.func @add_zeros(%x : !F) -> (!F, !F) {
  %z = simit.zeros : !F
  %a = simit.add %x, %z : !F
  %b = simit.add %z, %x : !F
  return %a, %b : !F, !F
}

// CHECK-LABEL: func.func @sub_zeros
// CHECK-SAME: (%[[X:.*]]: !simit.tensor
// CHECK-NEXT: return %[[X]]
func.func @sub_zeros(%x : !F) -> !F {
  %z = simit.zeros : !F
  %a = simit.sub %x, %z : !F
  return %a : !F
}

// zeros - x is -x, not x.
// CHECK-LABEL: func.func @zeros_sub
// CHECK: simit.sub
func.func @zeros_sub(%x : !F) -> !F {
  %z = simit.zeros : !F
  %a = simit.sub %z, %x : !F
  return %a : !F
}

// CHECK-LABEL: func.func @neg_neg
// CHECK-SAME: (%[[X:.*]]: !simit.tensor
// CHECK-NEXT: return %[[X]]
func.func @neg_neg(%x : !F) -> !F {
  %n = simit.neg %x : !F
  %nn = simit.neg %n : !F
  return %nn : !F
}

// CHECK-LABEL: func.func @neg_once
// CHECK: simit.neg
func.func @neg_once(%x : !F) -> !F {
  %n = simit.neg %x : !F
  return %n : !F
}
