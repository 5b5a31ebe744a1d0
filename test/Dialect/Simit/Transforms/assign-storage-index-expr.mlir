// RUN: simit-opt %s --simit-assign-storage | FileCheck %s

// Index expressions with a matrix result: the body read as a path
// expression over the inputs' storage.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>

// CHECK-DAG: #diag_points = #simit.storage<diag("points")>
// CHECK-DAG: #pat_springs = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
// CHECK-DAG: #product = #simit.storage<product(pattern("springs", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>
// CHECK-DAG: #pat_springs_t = #simit.storage<transpose(pattern("springs", rows [0, 1], cols [0, 1]))>

func.func private @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["x"] : !Point -> f64
  %z = simit.zeros : !K
  %M = simit.insert %m into %z[%p, %p] : f64 into !K, (!Point, !Point)
  return %M : !K
}

func.func private @edge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %b = simit.tuple_get %e[1] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %b] : f64 into !K, (!Point, !Point)
  return %K : !K
}

// CHECK-LABEL: func.func @paths
func.func @paths(%points : !Points, %springs : !Springs, %x : !V, %h : f64) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  // A sum joins; scalars and vectors scale.
  // CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #pat_springs>
  %A = simit.index_expr [i : "points", j : "points"] (i, j) = (%M(i, j), %K(i, j), %x(i), %h())
       : (!K, !K, !V, f64) -> !K {
  ^bb0(%m: f64, %k: f64, %xi: f64, %hh: f64):
    %hk = arith.mulf %k, %hh : f64
    %s = arith.addf %m, %hk : f64
    %r = arith.mulf %xi, %s : f64
    simit.yield %r : f64
  }
  // A product of components at (i, j) keeps the smaller storage.
  // CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #diag_points>
  %P = simit.index_expr [i : "points", j : "points"] (i, j) = (%M(i, j), %K(i, j))
       : (!K, !K) -> !K {
  ^bb0(%m: f64, %k: f64):
    %p = arith.mulf %m, %k : f64
    simit.yield %p : f64
  }
  // Swapped indices transpose.
  // CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #pat_springs_t>
  %T = simit.index_expr [i : "points", j : "points"] (i, j) = (%K(j, i))
       : (!K) -> !K {
  ^bb0(%k: f64):
    %n = arith.negf %k : f64
    simit.yield %n : f64
  }
  // A summed index composes.
  // CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #product>
  %C = simit.index_expr [i : "points", j : "points", k : "points"] (i, j) = (%K(i, k), %x(k), %K(k, j))
       : (!K, !V, !K) -> !K {
  ^bb0(%a: f64, %d: f64, %b: f64):
    %ad = arith.mulf %a, %d : f64
    %p = arith.mulf %ad, %b : f64
    simit.yield %p : f64
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// The quotient A ./ B as simit-linalg-to-index-expr writes it (zero where
// the dividend is zero): a comparison only chooses, a select joins its
// choices, and a quotient keeps the dividend's storage where the divisor's
// holds it.
// CHECK-LABEL: func.func @quotient
// CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #diag_points>
func.func @quotient(%points : !Points, %springs : !Springs) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %Q = simit.index_expr [i : "points", j : "points"] (i, j) = (%M(i, j), %K(i, j))
       : (!K, !K) -> !K {
  ^bb0(%m: f64, %k: f64):
    %zero = arith.constant 0.0 : f64
    %isZero = arith.cmpf oeq, %m, %zero : f64
    %q = arith.divf %m, %k : f64
    %r = arith.select %isZero, %zero, %q : f64
    simit.yield %r : f64
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// A product of two edge sets' components, neither storage holding the
// other's: stored on their join (the intersection has no encoding).
// CHECK-LABEL: func.func @unrelated_product
// CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #union>
!Hinges = !simit.set<"hinges", !Spring, ["points", "points"]>
func.func @unrelated_product(%springs : !Springs, %hinges : !Hinges) -> f64 {
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %H = simit.assemble @edge() to %hinges reduce <add> : (!Hinges) -> !K
  %P = simit.index_expr [i : "points", j : "points"] (i, j) = (%K(i, j), %H(i, j))
       : (!K, !K) -> !K {
  ^bb0(%k: f64, %h: f64):
    %p = arith.mulf %k, %h : f64
    simit.yield %p : f64
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// A matrix plus a term without a matrix factor is nonzero outside every
// matrix operand's blocks: it is stored dense.
// CHECK-LABEL: func.func @dense_index_expr
// CHECK: simit.index_expr {{.*}} -> !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>
func.func @dense_index_expr(%points : !Points, %x : !V) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %A = simit.index_expr [i : "points", j : "points"] (i, j) = (%M(i, j), %x(i))
       : (!K, !V) -> !K {
  ^bb0(%m: f64, %xi: f64):
    %s = arith.addf %m, %xi : f64
    simit.yield %s : f64
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}
