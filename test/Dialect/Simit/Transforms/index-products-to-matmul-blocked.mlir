// RUN: simit-opt %s --simit-index-products-to-matmul | FileCheck %s

// On matrices of blocks a variable runs over the set and then the block's
// rows or columns: the sum over k of A(i,k) B(k,j) is the product of the
// blocked matrices, whose blocks are the products of theirs (2x3 times
// 3x2), and a factor indexed (k, i) is transposed with its blocks.

!A = !simit.tensor<["points", "springs"] x tensor<2x3xf64>>
!B = !simit.tensor<["springs", "points"] x tensor<3x2xf64>>
!C = !simit.tensor<["points", "points"] x tensor<2x2xf64>>

// CHECK-LABEL: func.func @product
// CHECK: %[[P:.*]] = simit.matmul %arg0, %arg1 : !simit.tensor<["points", "springs"] x tensor<2x3xf64>>, !simit.tensor<["springs", "points"] x tensor<3x2xf64>> -> !simit.tensor<["points", "points"] x tensor<2x2xf64>>
// CHECK-NEXT: %[[C:.*]] = simit.index_expr [i : "points" x 2, j : "points" x 2] (i, j) = (%[[P]](i, j))
// CHECK: return %[[C]]
func.func @product(%A : !A, %B : !B) -> !C {
  %C = simit.index_expr [i : "points" x 2, j : "points" x 2, k : "springs" x 3] (i, j) = (%A(i, k), %B(k, j)) : (!A, !B) -> !C {
  ^bb0(%a: f64, %b: f64):
    %p = arith.mulf %a, %b : f64
    simit.yield %p : f64
  }
  return %C : !C
}

// CHECK-LABEL: func.func @transposed
// CHECK: %[[T:.*]] = simit.transpose %arg1 : !simit.tensor<["springs", "points"] x tensor<3x2xf64>> -> !simit.tensor<["points", "springs"] x tensor<2x3xf64>>
// CHECK-NEXT: %[[P:.*]] = simit.matmul %[[T]], %arg0 : !simit.tensor<["points", "springs"] x tensor<2x3xf64>>, !simit.tensor<["springs", "points"] x tensor<3x2xf64>> -> !simit.tensor<["points", "points"] x tensor<2x2xf64>>
// CHECK: return
func.func @transposed(%B2 : !B, %B : !B) -> !C {
  %C = simit.index_expr [i : "points" x 2, j : "points" x 2, k : "springs" x 3] (i, j) = (%B(k, i), %B2(k, j)) : (!B, !B) -> !C {
  ^bb0(%a: f64, %b: f64):
    %p = arith.mulf %a, %b : f64
    simit.yield %p : f64
  }
  return %C : !C
}
