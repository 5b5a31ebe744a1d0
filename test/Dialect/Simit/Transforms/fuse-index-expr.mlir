// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-fuse-index-expr | FileCheck %s

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>

// x + A b: one expression, the product summed inside the body (Figure 10).
// CHECK-LABEL: func.func @axpy
// CHECK: %[[Y:.*]] = simit.index_expr [i : "points" x 3, j : "points" x 3] (i) = (%arg0(i), %arg1(i, j), %arg2(j))
// CHECK-NEXT: ^bb0(%[[X:.*]]: f64, %[[A:.*]]: f64, %[[B:.*]]: f64):
// CHECK-NEXT:   %[[S:.*]] = simit.index_sum vars [1] : f64 {
// CHECK-NEXT:     %[[P:.*]] = arith.mulf %[[A]], %[[B]] : f64
// CHECK-NEXT:     simit.index_sum_yield %[[P]] : f64
// CHECK-NEXT:   }
// CHECK-NEXT:   %[[R:.*]] = arith.addf %[[X]], %[[S]] : f64
// CHECK-NEXT:   simit.yield %[[R]] : f64
// CHECK-NEXT: }
// CHECK-NEXT: return %[[Y]]
func.func @axpy(%x : !F, %A : !K, %b : !F) -> !F {
  %Ab = simit.matvec %A, %b : !K, !F -> !F
  %y = simit.add %x, %Ab : !F
  return %y : !F
}

// An element-wise producer needs no sum: (M + h K) x never builds M + h K.
// CHECK-LABEL: func.func @sum_times
// CHECK: simit.index_expr [i : "points" x 3, j : "points" x 3] (i) = (%arg3(j), %arg0(i, j), %arg2(), %arg1(i, j))
// CHECK-NEXT: ^bb0(%[[X:.*]]: f64, %[[M:.*]]: f64, %[[H:.*]]: f64, %[[K:.*]]: f64):
// CHECK-NEXT:   %[[HK:.*]] = arith.mulf %[[H]], %[[K]] : f64
// CHECK-NEXT:   %[[A:.*]] = arith.addf %[[M]], %[[HK]] : f64
// CHECK-NEXT:   %[[P:.*]] = arith.mulf %[[A]], %[[X]] : f64
// CHECK-NEXT:   simit.yield %[[P]] : f64
// CHECK-NOT: simit.index_expr
// CHECK: return
func.func @sum_times(%M : !K, %K : !K, %h : f64, %x : !F) -> !F {
  %hK = simit.scale %h, %K : f64, !K
  %A = simit.add %M, %hK : !K
  %y = simit.matvec %A, %x : !K, !F -> !F
  return %y : !F
}

// dot(r, A x) visits each row once: fused, the row sum nested.
// CHECK-LABEL: func.func @energy
// CHECK: simit.index_expr [i : "points" x 3, j : "points" x 3] () = (%arg0(i), %arg1(i, j), %arg2(j)) {{.*}} -> f64
// CHECK: simit.index_sum vars [1]
// CHECK-NOT: simit.index_expr
func.func @energy(%r : !F, %A : !K, %x : !F) -> f64 {
  %Ax = simit.matvec %A, %x : !K, !F -> !F
  %e = simit.dot %r, %Ax : !F, !F -> f64
  return %e : f64
}

// A (B x) would recompute B x for every block of A: not fused. A product
// used twice is not fused either.
// CHECK-LABEL: func.func @unfused
// CHECK: %[[BX:.*]] = simit.index_expr {{.*}} (i) = (%arg1(i, j), %arg2(j))
// CHECK: %[[ABX:.*]] = simit.index_expr {{.*}} (i) = (%arg0(i, j), %[[BX]](j))
// CHECK: %[[D:.*]] = simit.index_expr {{.*}} () = (%[[ABX]](i), %[[ABX]](i))
// CHECK-NOT: simit.index_sum
func.func @unfused(%A : !K, %B : !K, %x : !F) -> f64 {
  %Bx = simit.matvec %B, %x : !K, !F -> !F
  %ABx = simit.matvec %A, %Bx : !K, !F -> !F
  %d = simit.dot %ABx, %ABx : !F, !F -> f64
  return %d : f64
}
