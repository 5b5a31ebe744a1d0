// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>

// C(i, j) = A(i, k) * B(k, j), k summed; blocked dims are whole hierarchies.
// CHECK-LABEL: func.func @matmul
// CHECK: simit.index_expr [i : "points" x 3, j : "points" x 3, k : "points" x 3] (i, j) = (%{{.*}}(i, k), %{{.*}}(k, j)) : (!simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points", "points"] x tensor<3x3xf64>>) -> !simit.tensor<["points", "points"] x tensor<3x3xf64>> {
// CHECK-NEXT: ^bb0(%[[A:.*]]: f64, %[[B:.*]]: f64):
// CHECK-NEXT:   %[[P:.*]] = arith.mulf %[[A]], %[[B]] : f64
// CHECK-NEXT:   simit.yield %[[P]] : f64
// CHECK-NEXT: }
func.func @matmul(%A : !K, %B : !K) -> !K {
  %C = simit.index_expr [i : "points" x 3, j : "points" x 3, k : "points" x 3]
       (i, j) = (%A(i, k), %B(k, j)) : (!K, !K) -> !K {
  ^bb0(%a: f64, %b: f64):
    %p = arith.mulf %a, %b : f64
    simit.yield %p : f64
  }
  return %C : !K
}

// Everything summed into a scalar; a diagonal read; ranges and a scalar input.
// CHECK-LABEL: func.func @reductions
func.func @reductions(%x : !F, %m : tensor<3x3xf32>, %s : f32) -> (f64, tensor<3xf32>) {
  // CHECK: simit.index_expr [i : "points" x 3] () = (%{{.*}}(i), %{{.*}}(i)) : ({{.*}}) -> f64
  %d = simit.index_expr [i : "points" x 3] () = (%x(i), %x(i)) : (!F, !F) -> f64 {
  ^bb0(%a: f64, %b: f64):
    %p = arith.mulf %a, %b : f64
    simit.yield %p : f64
  }
  // CHECK: simit.index_expr [i : 3] (i) = (%{{.*}}(i, i), %{{.*}}()) : (tensor<3x3xf32>, f32) -> tensor<3xf32>
  %diag = simit.index_expr [i : 3] (i) = (%m(i, i), %s()) : (tensor<3x3xf32>, f32) -> tensor<3xf32> {
  ^bb0(%a: f32, %b: f32):
    %p = arith.mulf %a, %b : f32
    simit.yield %p : f32
  }
  return %d, %diag : f64, tensor<3xf32>
}

// Unblocked system dims with a set-and-range tensor.
// CHECK-LABEL: func.func @mixed
// CHECK: simit.index_expr [p : "points", c : 3] (c, p) = (%{{.*}}(p, c)) {{.*}} attributes {note = "kept"}
func.func @mixed(%t : !simit.tensor<["points", 3] x f64>) -> !simit.tensor<[3, "points"] x f64> {
  %r = simit.index_expr [p : "points", c : 3] (c, p) = (%t(p, c))
       : (!simit.tensor<["points", 3] x f64>) -> !simit.tensor<[3, "points"] x f64>
       attributes {note = "kept"} {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : !simit.tensor<[3, "points"] x f64>
}
