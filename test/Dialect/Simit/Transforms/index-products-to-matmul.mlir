// RUN: simit-opt %s --simit-index-products-to-matmul | FileCheck %s

!M = !simit.tensor<["points", "points"] x f64>
!R = !simit.tensor<["springs", "points"] x f64>
!V = !simit.tensor<["points"] x f64>

// The whole body is the product: the expression reads P = A * B.
// CHECK-LABEL: func.func @product
// CHECK: %[[P:.*]] = simit.matmul %arg0, %arg1 : !simit.tensor<["points", "points"] x f64>, !simit.tensor<["points", "points"] x f64> -> !simit.tensor<["points", "points"] x f64>
// CHECK-NEXT: %[[C:.*]] = simit.index_expr [i : "points", j : "points"] (i, j) = (%[[P]](i, j))
// CHECK-NEXT: ^bb0(%[[X:.*]]: f64):
// CHECK-NEXT:   simit.yield %[[X]] : f64
// CHECK: return %[[C]]
func.func @product(%A : !M, %B : !M) -> !M {
  %C = simit.index_expr [i : "points", j : "points", k : "points"] (i, j) = (%A(i, k), %B(k, j)) : (!M, !M) -> !M {
  ^bb0(%a: f64, %b: f64):
    %p = arith.mulf %a, %b : f64
    simit.yield %p : f64
  }
  return %C : !M
}


// A sum inside the body over k, with k first in A's index list: A is
// transposed, k leaves the variables and D keeps its list.
// CHECK-LABEL: func.func @transposed_plus
// CHECK: %[[T:.*]] = simit.transpose %arg0 : !simit.tensor<["springs", "points"] x f64> -> !simit.tensor<["points", "springs"] x f64>
// CHECK-NEXT: %[[P:.*]] = simit.matmul %[[T]], %arg1 : !simit.tensor<["points", "springs"] x f64>, !simit.tensor<["springs", "points"] x f64> -> !simit.tensor<["points", "points"] x f64>
// CHECK-NEXT: %[[C:.*]] = simit.index_expr [i : "points", j : "points"] (i, j) = (%arg2(j, i), %[[P]](i, j))
// CHECK-NEXT: ^bb0(%[[D:.*]]: f64, %[[AB:.*]]: f64):
// CHECK-NEXT:   %[[R:.*]] = arith.addf %[[AB]], %[[D]] : f64
// CHECK-NEXT:   simit.yield %[[R]] : f64
// CHECK-NOT: simit.index_sum
// CHECK: return %[[C]]
func.func @transposed_plus(%A : !R, %B : !R, %D : !M) -> !M {
  %C = simit.index_expr [i : "points", j : "points", k : "springs"] (i, j) = (%A(k, i), %B(k, j), %D(j, i)) : (!R, !R, !M) -> !M {
  ^bb0(%a: f64, %b: f64, %d: f64):
    %s = simit.index_sum vars [2] : f64 {
      %p = arith.mulf %a, %b : f64
      simit.index_sum_yield %p : f64
    }
    %r = arith.addf %s, %d : f64
    simit.yield %r : f64
  }
  return %C : !M
}


// A vector factor: a matrix-vector product, left to the index expression.
// CHECK-LABEL: func.func @matvec
// CHECK-NOT: simit.matmul
// CHECK: simit.index_expr [i : "points", j : "points"] (i) = (%arg0(i, j), %arg1(j))
func.func @matvec(%A : !M, %x : !V) -> !V {
  %y = simit.index_expr [i : "points", j : "points"] (i) = (%A(i, j), %x(j)) : (!M, !V) -> !V {
  ^bb0(%a: f64, %b: f64):
    %p = arith.mulf %a, %b : f64
    simit.yield %p : f64
  }
  return %y : !V
}


// k also indexes a third factor: no product of two matrices alone.
// CHECK-LABEL: func.func @three_factors
// CHECK-NOT: simit.matmul
// CHECK: simit.index_expr [i : "points", j : "points", k : "points"] (i, j) = (%arg0(i, k), %arg1(k, j), %arg2(k))
func.func @three_factors(%A : !M, %B : !M, %x : !V) -> !M {
  %C = simit.index_expr [i : "points", j : "points", k : "points"] (i, j) = (%A(i, k), %B(k, j), %x(k)) : (!M, !M, !V) -> !M {
  ^bb0(%a: f64, %b: f64, %c: f64):
    %p = arith.mulf %a, %b : f64
    %q = arith.mulf %p, %c : f64
    simit.yield %q : f64
  }
  return %C : !M
}
