// RUN: simit-opt %s --simit-assign-storage | FileCheck %s

// Variables and structured control flow: a slot, a loop-carried value or a
// branch result holds the join of everything that reaches it; what reaches
// it with a smaller storage is converted up.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>

// CHECK-DAG: #diag_points = #simit.storage<diag("points")>
// CHECK-DAG: #pat_springs = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>

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

// The slot starts as zeros and holds the diagonal, then the pattern.
// CHECK-LABEL: func.func @variable
// CHECK: %[[SLOT:.*]] = simit.alloc : !simit.ref<!simit.tensor<["points", "points"] x f64, #pat_springs>>
// CHECK: %[[M:.*]] = simit.assemble @mass
// CHECK: %[[MC:.*]] = simit.convert %[[M]] : {{.*}}#diag_points> -> {{.*}}#pat_springs>
// CHECK: simit.store %[[MC]], %[[SLOT]] : !simit.ref<!simit.tensor<["points", "points"] x f64, #pat_springs>>
// CHECK: simit.store %{{.*}}, %[[SLOT]]
// CHECK: simit.load %[[SLOT]] : !simit.ref<!simit.tensor<["points", "points"] x f64, #pat_springs>>
func.func @variable(%points : !Points, %springs : !Springs) -> f64 {
  %slot = simit.alloc : !simit.ref<!K>
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  simit.store %M, %slot : !simit.ref<!K>
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  simit.store %K, %slot : !simit.ref<!K>
  %A = simit.load %slot : !simit.ref<!K>
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// A loop adding the pattern to a diagonal: the carried value is the pattern
// from the start.
// CHECK-LABEL: func.func @for_loop
// CHECK: %[[M:.*]] = simit.assemble @mass
// CHECK: %[[K:.*]] = simit.assemble @edge
// CHECK: %[[MC:.*]] = simit.convert %[[M]] : {{.*}}#diag_points> -> {{.*}}#pat_springs>
// CHECK: %[[R:.*]] = scf.for %{{.*}} = %{{.*}} to %{{.*}} step %{{.*}} iter_args(%[[A:.*]] = %[[MC]]) -> (!simit.tensor<["points", "points"] x f64, #pat_springs>)
// CHECK: %[[S:.*]] = simit.add %[[A]], %[[K]] : !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: scf.yield %[[S]] : !simit.tensor<["points", "points"] x f64, #pat_springs>
func.func @for_loop(%points : !Points, %springs : !Springs, %n : index) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %R = scf.for %i = %c0 to %n step %c1 iter_args(%A = %M) -> (!K) {
    %S = simit.add %A, %K : !K
    scf.yield %S : !K
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// Branches yield their join.
// CHECK-LABEL: func.func @branches
// CHECK: scf.if %{{.*}} -> (!simit.tensor<["points", "points"] x f64, #pat_springs>)
// CHECK: %[[MC:.*]] = simit.convert %{{.*}} : {{.*}}#diag_points> -> {{.*}}#pat_springs>
// CHECK: scf.yield %[[MC]] : !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: } else {
// CHECK: scf.yield %{{.*}} : !simit.tensor<["points", "points"] x f64, #pat_springs>
func.func @branches(%points : !Points, %springs : !Springs, %c : i1) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %B = scf.if %c -> (!K) {
    scf.yield %M : !K
  } else {
    scf.yield %K : !K
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// A while loop: before-region arguments join the inits and the after
// region's yields; after-region arguments and results are what the
// condition forwards.
// CHECK-LABEL: func.func @while_loop
// CHECK: %[[MC:.*]] = simit.convert %{{.*}} : {{.*}}#diag_points> -> {{.*}}#pat_springs>
// CHECK: scf.while (%[[B:.*]] = %[[MC]]) : (!simit.tensor<["points", "points"] x f64, #pat_springs>) -> !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: scf.condition(%{{.*}}) %[[B]] : !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: ^bb0(%[[AFTER:.*]]: !simit.tensor<["points", "points"] x f64, #pat_springs>):
// CHECK: simit.add %[[AFTER]], %{{.*}} : !simit.tensor<["points", "points"] x f64, #pat_springs>
func.func @while_loop(%points : !Points, %springs : !Springs, %c : i1) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %R = scf.while (%B = %M) : (!K) -> !K {
    scf.condition(%c) %B : !K
  } do {
  ^bb0(%A : !K):
    %S = simit.add %A, %K : !K
    scf.yield %S : !K
  }
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}
