// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>

// CHECK-LABEL: func.func @axpy
// CHECK: simit.index_expr [i : "points" x 3, j : "points" x 3] (i) = (%{{.*}}(i), %{{.*}}(i, j), %{{.*}}(j))
// CHECK-NEXT: ^bb0(%[[X:.*]]: f64, %[[A:.*]]: f64, %[[B:.*]]: f64):
// CHECK-NEXT:   %[[S:.*]] = simit.index_sum vars [1] : f64 {
// CHECK-NEXT:     %[[P:.*]] = arith.mulf %[[A]], %[[B]] : f64
// CHECK-NEXT:     simit.index_sum_yield %[[P]] : f64
// CHECK-NEXT:   }
// CHECK-NEXT:   %[[R:.*]] = arith.addf %[[X]], %[[S]] : f64
// CHECK-NEXT:   simit.yield %[[R]] : f64
func.func @axpy(%x : !F, %A : !K, %b : !F) -> !F {
  %y = simit.index_expr [i : "points" x 3, j : "points" x 3]
       (i) = (%x(i), %A(i, j), %b(j)) : (!F, !K, !F) -> !F {
  ^bb0(%xi: f64, %aij: f64, %bj: f64):
    %s = simit.index_sum vars [1] : f64 {
      %p = arith.mulf %aij, %bj : f64
      simit.index_sum_yield %p : f64
    }
    %r = arith.addf %xi, %s : f64
    simit.yield %r : f64
  }
  return %y : !F
}
