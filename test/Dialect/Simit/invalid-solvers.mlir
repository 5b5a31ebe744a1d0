// RUN: simit-opt %s --split-input-file --verify-diagnostics

func.func @f(%m : tensor<2x3xf64>) {
  // expected-error @+1 {{a factorised matrix is square: rows and columns: dimension [2] of 'tensor<2x3xf64>' differs from dimension [3]}}
  %h = simit.factorize lu %m : tensor<2x3xf64>
  return
}

// -----

func.func @f(%m : tensor<2x2xi32>) {
  // expected-error @+1 {{operand must have float components, got 'tensor<2x2xi32>'}}
  %h = simit.factorize chol %m : tensor<2x2xi32>
  return
}

// -----

func.func @f(%v : tensor<3xf64>) {
  // expected-error @+1 {{matrix must have order 2, got 'tensor<3xf64>'}}
  %h = simit.factorize lu %v : tensor<3xf64>
  return
}

// -----

func.func @f(%h : !simit.opaque, %b : tensor<3xf64>) {
  // expected-error @+1 {{result must have order 1, got 'tensor<3x1xf64>'}}
  %x = simit.factor_solve lu %h, %b : tensor<3xf64> -> tensor<3x1xf64>
  return
}

// -----

func.func @f(%h : !simit.opaque, %b : tensor<3x2xf64>) {
  // expected-error @+1 {{right-hand side and result columns: dimension [2] of 'tensor<3x2xf64>' differs from dimension [3]}}
  %x = simit.factor_solve chol %h, %b : tensor<3x2xf64> -> tensor<3x3xf64>
  return
}

// -----

func.func @f(%h : !simit.opaque, %b : tensor<2x2x2xf64>) {
  // expected-error @+1 {{right-hand side must be a vector or a matrix, got 'tensor<2x2x2xf64>'}}
  %x = simit.factor_solve lu %h, %b : tensor<2x2x2xf64> -> tensor<2x2x2xf64>
  return
}

// -----

func.func @f(%m : tensor<3x3xf64>, %b : tensor<2xf64>) {
  // expected-error @+1 {{matrix rows and right-hand side: dimension [3] of}}
  %x = simit.triangular_solve %m, %b : tensor<3x3xf64>, tensor<2xf64> -> tensor<3xf64>
  return
}

// -----

!A = !simit.tensor<["p", "p"] x f64>
!V = !simit.tensor<["p"] x f64>
func.func @f(%A : !A, %b : !V, %u : !V) {
  // expected-error @+1 {{needs k >= 1 vectors each of u, v and w, got 1, 1 and 0}}
  %x = "simit.woodbury"(%A, %b, %b, %u, %u) {operandSegmentSizes = array<i32: 1, 1, 1, 1, 1, 0>} : (!A, !V, !V, !V, !V) -> !V
  return
}

// -----

!A = !simit.tensor<["p", "p"] x f64>
!V = !simit.tensor<["p"] x f64>
func.func @f(%A : !A, %b : !V, %u : !simit.tensor<["p"] x f32>) {
  // expected-error @+1 {{every u must have the right-hand side's type '!simit.tensor<["p"] x f64>'}}
  %x = "simit.woodbury"(%A, %b, %b, %u, %b, %b) {operandSegmentSizes = array<i32: 1, 1, 1, 1, 1, 1>} : (!A, !V, !V, !simit.tensor<["p"] x f32>, !V, !V) -> !V
  return
}

// -----

// Over (p, q), v is over the columns q: one over the rows p is wrong.
!A = !simit.tensor<["p", "q"] x f64>
!P = !simit.tensor<["p"] x f64>
!Q = !simit.tensor<["q"] x f64>
func.func @f(%A : !A, %b : !P, %c : !Q, %u : !P, %w : !Q) {
  // expected-error @+1 {{c and every v and w must have the result's type '!simit.tensor<["q"] x f64>'}}
  %x = "simit.woodbury"(%A, %b, %c, %u, %u, %w) {operandSegmentSizes = array<i32: 1, 1, 1, 1, 1, 1>} : (!A, !P, !Q, !P, !P, !Q) -> !Q
  return
}
