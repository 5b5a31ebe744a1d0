// RUN: simit-opt %s --split-input-file --verify-diagnostics

func.func @outside(%a : f64) -> f64 {
  // expected-error @below {{expects parent op to be one of 'simit.index_expr, simit.index_sum'}}
  %s = simit.index_sum vars [0] : f64 {
    simit.index_sum_yield %a : f64
  }
  return %s : f64
}

// -----

func.func @wrong_terminator(%v : tensor<3xf64>) -> f64 {
  %r = simit.index_expr [i : 3] () = (%v(i)) : (tensor<3xf64>) -> f64 {
  ^bb0(%x: f64):
    // expected-error @below {{'simit.index_sum_yield' op expects parent op 'simit.index_sum'}}
    simit.index_sum_yield %x : f64
  }
  return %r : f64
}
