// RUN: simit-opt %s -split-input-file -verify-diagnostics

func.func @f(%a : tensor<3xf64>, %b : tensor<2xf64>) {
  // expected-error @+1 {{'simit.add' op requires the same type for all operands and results}}
  %c = "simit.add"(%a, %b) : (tensor<3xf64>, tensor<2xf64>) -> tensor<3xf64>
  return
}

// -----

func.func @f(%a : tensor<3xi1>) {
  // expected-error @+1 {{operand must have a numeric component type, got 'tensor<3xi1>'}}
  %c = simit.add %a, %a : tensor<3xi1>
  return
}

// -----

func.func @f(%a : f64) {
  // expected-error @+1 {{'simit.sub' op operand #0 must be builtin ranked tensor or !simit.tensor, but got 'f64'}}
  %c = simit.sub %a, %a : f64
  return
}

// -----

func.func @f(%a : !simit.tensor<["points"] x i1>) {
  // expected-error @+1 {{operand must have a numeric component type}}
  %c = simit.neg %a : !simit.tensor<["points"] x i1>
  return
}

// -----

func.func @f(%s : f32, %a : tensor<3xf64>) {
  // expected-error @+1 {{scalar type 'f32' differs from the component type 'f64'}}
  %c = simit.scale %s, %a : f32, tensor<3xf64>
  return
}

// -----

func.func @f(%A : tensor<3x3xf64>, %x : tensor<2xf64>) {
  // expected-error @+1 {{matrix columns and vector: dimension [3] of 'tensor<3x3xf64>' differs from dimension [2] of 'tensor<2xf64>'}}
  %y = simit.matvec %A, %x : tensor<3x3xf64>, tensor<2xf64> -> tensor<3xf64>
  return
}

// -----

// Blocked operands compare whole hierarchies.
func.func @f(%K : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, %x : !simit.tensor<["points"] x f64>) {
  // expected-error @+1 {{matrix columns and vector: dimension ["points", 3] of}}
  %y = simit.matvec %K, %x : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x tensor<3xf64>>
  return
}

// -----

func.func @f(%A : !simit.tensor<["points", "springs"] x f64>, %x : !simit.tensor<["springs"] x f64>) {
  // expected-error @+1 {{matrix rows and result: dimension ["points"] of}}
  %y = simit.matvec %A, %x : !simit.tensor<["points", "springs"] x f64>, !simit.tensor<["springs"] x f64> -> !simit.tensor<["springs"] x f64>
  return
}

// -----

func.func @f(%A : tensor<3x3xf64>, %x : tensor<3xf32>) {
  // expected-error @+1 {{component types of 'tensor<3x3xf64>' and 'tensor<3xf32>' differ}}
  %y = simit.matvec %A, %x : tensor<3x3xf64>, tensor<3xf32> -> tensor<3xf64>
  return
}

// -----

func.func @f(%A : tensor<3xf64>, %x : tensor<3xf64>) {
  // expected-error @+1 {{matrix must have order 2, got 'tensor<3xf64>'}}
  %y = simit.matvec %A, %x : tensor<3xf64>, tensor<3xf64> -> tensor<3xf64>
  return
}

// -----

func.func @f(%A : tensor<2x3xf64>, %B : tensor<2x3xf64>) {
  // expected-error @+1 {{inner dimensions: dimension [3] of 'tensor<2x3xf64>' differs from dimension [2] of 'tensor<2x3xf64>'}}
  %C = simit.matmul %A, %B : tensor<2x3xf64>, tensor<2x3xf64> -> tensor<2x3xf64>
  return
}

// -----

func.func @f(%A : tensor<2x3xf64>, %B : tensor<3x4xf64>) {
  // expected-error @+1 {{result columns: dimension [4] of 'tensor<3x4xf64>' differs from dimension [3]}}
  %C = simit.matmul %A, %B : tensor<2x3xf64>, tensor<3x4xf64> -> tensor<2x3xf64>
  return
}

// -----

func.func @f(%A : tensor<2x3x4xf64>) {
  // expected-error @+1 {{operand must have order 2, got 'tensor<2x3x4xf64>'}}
  %T = simit.transpose %A : tensor<2x3x4xf64> -> tensor<4x3x2xf64>
  return
}

// -----

// Transposition swaps block dimensions too.
func.func @f(%A : !simit.tensor<["points", "springs"] x tensor<2x3xf64>>) {
  // expected-error @+1 {{result rows: dimension ["springs", 3] of}}
  %T = simit.transpose %A : !simit.tensor<["points", "springs"] x tensor<2x3xf64>> -> !simit.tensor<["springs", "points"] x tensor<2x3xf64>>
  return
}

// -----

func.func @f(%a : tensor<3xf64>, %b : tensor<2xf64>) {
  // expected-error @+1 {{operands: dimension [3] of 'tensor<3xf64>' differs from dimension [2] of 'tensor<2xf64>'}}
  %d = simit.dot %a, %b : tensor<3xf64>, tensor<2xf64> -> f64
  return
}

// -----

func.func @f(%a : tensor<3xf64>) {
  // expected-error @+1 {{result type 'f32' differs from the component type 'f64'}}
  %d = simit.dot %a, %a : tensor<3xf64>, tensor<3xf64> -> f32
  return
}

// -----

func.func @f(%a : tensor<3x3xf64>) {
  // expected-error @+1 {{left operand must have order 1, got 'tensor<3x3xf64>'}}
  %d = simit.dot %a, %a : tensor<3x3xf64>, tensor<3x3xf64> -> f64
  return
}

// -----

func.func @f(%a : tensor<3xf64>, %b : tensor<2xf64>) {
  // expected-error @+1 {{result columns: dimension [2] of 'tensor<2xf64>' differs from dimension [3] of 'tensor<3x3xf64>'}}
  %o = simit.outer %a, %b : tensor<3xf64>, tensor<2xf64> -> tensor<3x3xf64>
  return
}

// -----

func.func @f(%a : tensor<3xf64>) {
  // expected-error @+1 {{result type 'f32' should be 'f64'}}
  %n = simit.norm %a : tensor<3xf64> -> f32
  return
}

// -----

func.func @f(%a : tensor<3xi32>) {
  // expected-error @+1 {{operand must have float or complex components, got 'tensor<3xi32>'}}
  %n = simit.norm %a : tensor<3xi32> -> f32
  return
}

// -----

func.func @f(%A : !simit.tensor<["points", "points"] x f64>, %b : !simit.tensor<["springs"] x f64>) {
  // expected-error @+1 {{matrix rows and right-hand side: dimension ["points"] of}}
  %x = simit.solve %A, %b : !simit.tensor<["points", "points"] x f64>, !simit.tensor<["springs"] x f64> -> !simit.tensor<["points"] x f64>
  return
}

// -----

func.func @f(%A : !simit.tensor<["points", "springs"] x f64>, %b : !simit.tensor<["points"] x f64>) {
  // expected-error @+1 {{matrix columns and result: dimension ["springs"] of}}
  %x = simit.solve %A, %b : !simit.tensor<["points", "springs"] x f64>, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x f64>
  return
}

// -----

func.func @f(%m : tensor<5x5xf64>) {
  // expected-error @+1 {{operand must be a 2x2, 3x3 or 4x4 float matrix, got 'tensor<5x5xf64>'}}
  %d = simit.det %m : tensor<5x5xf64> -> f64
  return
}

// -----

func.func @f(%m : tensor<3x3xi32>) {
  // expected-error @+1 {{operand must be a 2x2, 3x3 or 4x4 float matrix, got 'tensor<3x3xi32>'}}
  %d = simit.inv %m : tensor<3x3xi32>
  return
}

// -----

func.func @f(%m : tensor<2x3xf64>) {
  // expected-error @+1 {{operand must be a 2x2, 3x3 or 4x4 float matrix}}
  %d = simit.inv %m : tensor<2x3xf64>
  return
}

// -----

func.func @f(%m : tensor<3x3xf64>) {
  // expected-error @+1 {{result type 'f32' differs from the component type 'f64'}}
  %d = simit.det %m : tensor<3x3xf64> -> f32
  return
}

// -----

func.func @f(%v : tensor<4xf64>) {
  // expected-error @+1 {{operands must be float 3-vectors, got 'tensor<4xf64>'}}
  %c = simit.cross %v, %v : tensor<4xf64>
  return
}
