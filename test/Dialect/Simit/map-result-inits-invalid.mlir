// RUN: simit-opt %s -split-input-file -verify-diagnostics

// `result_inits` names, per result, the extra argument it starts from.

!Point = !simit.element<"Point", {m : f64}>
!W = !simit.tensor<["points"] x f64>
simit.extern @points : !simit.set<"points", !Point>

func.func @clamp(%lo : f64, %w : !W, %p : !Point) -> !W {
  %w1 = simit.insert %lo into %w[%p] : f64 into !W, (!Point)
  return %w1 : !W
}

func.func @count(%lo : f64, %w : !W) {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // expected-error @+1 {{has 2 result_inits for 1 results}}
  %w2 = simit.map @clamp(%lo, %w) to %points {result_inits = array<i64: 1, -1>} : (f64, !W, !simit.set<"points", !Point>) -> !W
  return
}

// -----

!Point = !simit.element<"Point", {m : f64}>
!W = !simit.tensor<["points"] x f64>
simit.extern @points : !simit.set<"points", !Point>

func.func @clamp(%lo : f64, %w : !W, %p : !Point) -> !W {
  %w1 = simit.insert %lo into %w[%p] : f64 into !W, (!Point)
  return %w1 : !W
}

func.func @range(%lo : f64, %w : !W) {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // expected-error @+1 {{result_inits[0] = 2 names no extra argument}}
  %w2 = simit.map @clamp(%lo, %w) to %points {result_inits = array<i64: 2>} : (f64, !W, !simit.set<"points", !Point>) -> !W
  return
}

// -----

!Point = !simit.element<"Point", {m : f64}>
!W = !simit.tensor<["points"] x f64>
simit.extern @points : !simit.set<"points", !Point>

func.func @clamp(%lo : f64, %w : !W, %p : !Point) -> !W {
  %w1 = simit.insert %lo into %w[%p] : f64 into !W, (!Point)
  return %w1 : !W
}

func.func @type(%lo : f64, %w : !W) {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // expected-error @+1 {{result #0 starts from extra argument #0 of another type}}
  %w2 = simit.map @clamp(%lo, %w) to %points {result_inits = array<i64: 0>} : (f64, !W, !simit.set<"points", !Point>) -> !W
  return
}
