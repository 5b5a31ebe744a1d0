// RUN: simit-opt %s --simit-assign-storage | FileCheck %s

// A host function's matrix results have patterns known at run time: each
// its own `host` encoding, numbered in the function. The call keeps the
// callee's unencoded types; a conversion after it gives the storage.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>
!X = !simit.tensor<["points"] x f64>

// CHECK-DAG: #host_neg_0 = #simit.storage<host("neg", 0)>
// CHECK-DAG: #host_pair_1 = #simit.storage<host("pair", 1)>
// CHECK-DAG: #host_pair_2 = #simit.storage<host("pair", 2)>
// CHECK-DAG: #pat_springs = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
// CHECK-DAG: #[[HOSTS:.*]] = #simit.storage<union(host("pair", 1), host("pair", 2))>
// CHECK-DAG: #[[UNION:.*]] = #simit.storage<union(host("pair", 1), pattern("springs", rows [0, 1], cols [0, 1]))>

simit.extern @points : !Points
simit.extern @springs : !Springs

func.func private @edge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %b = simit.tuple_get %e[1] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %b] : f64 into !K, (!Point, !Point)
  return %K : !K
}

func.func private @neg(!K) -> !K attributes {simit.extern_function = "neg"}
func.func private @pair() -> (!K, !K) attributes {simit.extern_function = "pair"}

// CHECK-LABEL: func.func @calls
// CHECK: %[[K:.*]] = simit.assemble @edge
// An operand forgets its storage (the host reads BCSR arrays).
// CHECK: %[[ARG:.*]] = simit.convert %[[K]] : !simit.tensor<["points", "points"] x f64, #pat_springs> -> !simit.tensor<["points", "points"] x f64>
// CHECK: %[[N:.*]] = call @neg(%[[ARG]]) : (!simit.tensor<["points", "points"] x f64>) -> !simit.tensor<["points", "points"] x f64>
// CHECK: %[[NS:.*]] = simit.convert %[[N]] : !simit.tensor<["points", "points"] x f64> -> !simit.tensor<["points", "points"] x f64, #host_neg_0>
// CHECK: %[[P:.*]]:2 = call @pair()
// CHECK: %[[P0:.*]] = simit.convert %[[P]]#0 : {{.*}} -> !simit.tensor<["points", "points"] x f64, #host_pair_1>
// CHECK: %[[P1:.*]] = simit.convert %[[P]]#1 : {{.*}} -> !simit.tensor<["points", "points"] x f64, #host_pair_2>
// The sum of one host matrix with itself keeps its pattern.
// CHECK: simit.add %[[NS]], %[[NS]] : !simit.tensor<["points", "points"] x f64, #host_neg_0>
// Two calls may return any two patterns: the sum of two host matrices, or
// of one and an assembled matrix, is their union.
// CHECK: simit.add %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x f64, #[[HOSTS]]>
// CHECK: simit.add %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x f64, #[[UNION]]>
func.func @calls(%x : !X) -> (!X, !X, !X) attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %N = func.call @neg(%K) : (!K) -> !K
  %P:2 = func.call @pair() : () -> (!K, !K)
  %NN = simit.add %N, %N : !K
  %PP = simit.add %P#0, %P#1 : !K
  %PK = simit.add %P#0, %K : !K
  %y0 = simit.matvec %NN, %x : !K, !X -> !X
  %y1 = simit.matvec %PP, %x : !K, !X -> !X
  %y2 = simit.matvec %PK, %x : !K, !X -> !X
  return %y0, %y1, %y2 : !X, !X, !X
}
