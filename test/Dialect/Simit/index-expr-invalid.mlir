// RUN: simit-opt %s -split-input-file -verify-diagnostics

!F = !simit.tensor<["points"] x tensor<3xf64>>
func.func @f(%x : !F) -> !F {
  // expected-error @+1 {{index variable 'i' has domain ["points"] but indexes dimension 0 ["points", 3] of the result}}
  %r = simit.index_expr [i : "points"] (i) = (%x(i)) : (!F) -> !F {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : !F
}

// -----

!F = !simit.tensor<["points"] x f64>
!G = !simit.tensor<["springs"] x f64>
func.func @f(%x : !F) -> !G {
  // expected-error @+1 {{index variable 'i' has domain ["springs"] but indexes dimension 0 ["points"] of input #0}}
  %r = simit.index_expr [i : "springs"] (i) = (%x(i)) : (!F) -> !G {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : !G
}

// -----

func.func @f(%m : tensor<3x3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{input #0 of type 'tensor<3x3xf64>' needs 2 index variables, got 1}}
  %r = simit.index_expr [i : 3] (i) = (%m(i)) : (tensor<3x3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%m : tensor<3x3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{the result of type 'tensor<3xf64>' needs 1 index variables, got 2}}
  %r = simit.index_expr [i : 3, j : 3] (i, j) = (%m(i, j)) : (tensor<3x3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%m : tensor<3x3xf64>) -> tensor<3x3xf64> {
  // expected-error @+1 {{result index variable 'i' appears more than once}}
  %r = simit.index_expr [i : 3] (i, i) = (%m(i, i)) : (tensor<3x3xf64>) -> tensor<3x3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3x3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{index variable 'j' is not used}}
  %r = simit.index_expr [i : 3, j : 3] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{undeclared index variable 'k'}}
  %r = simit.index_expr [i : 3] (i) = (%v(k)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{redefinition of index variable 'i'}}
  %r = simit.index_expr [i : 3, i : 3] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{domain level 0 : i64 must be a set name or a positive range}}
  %r = simit.index_expr [i : 0] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{body argument #0 must have the component type 'f64' of input #0, got 'f32'}}
  %r = simit.index_expr [i : 3] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f32):
    %b = arith.extf %a : f32 to f64
    simit.yield %b : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  // expected-error @+1 {{body must take one argument per input (1), got 2}}
  %r = simit.index_expr [i : 3] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64, %b: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf32> {
  // expected-error @+1 {{body yields 'f64' but the result component type is 'f32'}}
  %r = simit.index_expr [i : 3] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf32> {
  ^bb0(%a: f64):
    simit.yield %a : f64
  }
  return %r : tensor<3xf32>
}

// -----

func.func @f(%v : tensor<3xf64>) -> tensor<3xf64> {
  %r = simit.index_expr [i : 3] (i) = (%v(i)) : (tensor<3xf64>) -> tensor<3xf64> {
  ^bb0(%a: f64):
    // expected-error @+1 {{'func.return' op expects parent op 'func.func'}}
    func.return
  }
  return %r : tensor<3xf64>
}

// -----

func.func @f(%x : f64) {
  // expected-error @+1 {{'simit.yield' op expects parent op 'simit.index_expr'}}
  simit.yield %x : f64
}
