// RUN: simit-opt %s --simit-linalg-to-index-expr | FileCheck %s

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!R = !simit.tensor<["points", "springs"] x tensor<3x2xf64>>

// CHECK-LABEL: func.func @elementwise
func.func @elementwise(%a : !F, %b : !F, %s : f64) -> !F {
  // CHECK: %[[ADD:.*]] = simit.index_expr [i : "points" x 3] (i) = (%{{.*}}(i), %{{.*}}(i))
  // CHECK: arith.addf
  %0 = simit.add %a, %b : !F
  // CHECK: %[[SUB:.*]] = simit.index_expr [i : "points" x 3] (i) = (%[[ADD]](i), %{{.*}}(i))
  // CHECK: arith.subf
  %1 = simit.sub %0, %b : !F
  // CHECK: %[[SCALE:.*]] = simit.index_expr [i : "points" x 3] (i) = (%{{.*}}(), %[[SUB]](i))
  // CHECK: arith.mulf
  %2 = simit.scale %s, %1 : f64, !F
  // CHECK: simit.index_expr [i : "points" x 3] (i) = (%[[SCALE]](i))
  // CHECK: arith.negf
  %3 = simit.neg %2 : !F
  // CHECK: simit.index_expr [i : "points" x 3] (i) = (%{{.*}}(i), %{{.*}}(i))
  // CHECK: arith.mulf
  %4 = simit.mul %3, %a : !F
  // CHECK: simit.index_expr [i : "points" x 3] (i) = (%{{.*}}(i), %{{.*}}(i))
  // CHECK: arith.divf
  %5 = simit.div %4, %a : !F
  return %5 : !F
}

// CHECK-LABEL: func.func @products
func.func @products(%A : !K, %x : !F, %R : !R) -> (!F, f64, f64, !K, !simit.tensor<["springs", "points"] x tensor<2x3xf64>>, !K) {
  // y(i) = A(i, j) x(j)
  // CHECK: simit.index_expr [i : "points" x 3, j : "points" x 3] (i) = (%{{.*}}(i, j), %{{.*}}(j))
  // CHECK-NEXT: ^bb0(%[[A:.*]]: f64, %[[X:.*]]: f64):
  // CHECK-NEXT: arith.mulf %[[A]], %[[X]]
  %y = simit.matvec %A, %x : !K, !F -> !F
  // CHECK: simit.index_expr [i : "points" x 3] () = (%{{.*}}(i), %{{.*}}(i)) {{.*}} -> f64
  %d = simit.dot %x, %y : !F, !F -> f64
  // norm: the sum of squares, then the square root.
  // CHECK: %[[SQ:.*]] = simit.index_expr [i : "points" x 3] () = (%{{.*}}(i)) {{.*}} -> f64
  // CHECK-NEXT: ^bb0(%[[Y:.*]]: f64):
  // CHECK-NEXT: arith.mulf %[[Y]], %[[Y]]
  // CHECK: math.sqrt %[[SQ]] : f64
  %n = simit.norm %y : !F -> f64
  // A product of system matrices stays: the loop lowering stores it on the
  // product's pattern.
  // CHECK: simit.matmul %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  %C = simit.matmul %A, %A : !K, !K -> !K
  // CHECK: simit.index_expr [i : "points" x 3, j : "springs" x 2] (j, i) = (%{{.*}}(i, j))
  // CHECK-NEXT: ^bb0(%[[V:.*]]: f64):
  // CHECK-NEXT: simit.yield %[[V]] : f64
  %T = simit.transpose %R : !R -> !simit.tensor<["springs", "points"] x tensor<2x3xf64>>
  // CHECK: simit.index_expr [i : "points" x 3, j : "points" x 3] (i, j) = (%{{.*}}(i), %{{.*}}(j))
  %O = simit.outer %x, %y : !F, !F -> !K
  return %y, %d, %n, %C, %T, %O : !F, f64, f64, !K, !simit.tensor<["springs", "points"] x tensor<2x3xf64>>, !K
}

// Local tensors are left to the loop lowering.
// CHECK-LABEL: func.func @local
// CHECK-NOT: simit.index_expr
// CHECK: simit.add
// CHECK: simit.matvec
func.func @local(%a : tensor<3xf64>, %m : tensor<3x3xf64>) -> tensor<3xf64> {
  %0 = simit.add %a, %a : tensor<3xf64>
  %1 = simit.matvec %m, %0 : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  return %1 : tensor<3xf64>
}
