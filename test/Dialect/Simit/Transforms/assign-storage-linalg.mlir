// RUN: simit-opt %s --simit-assign-storage | FileCheck %s

// The storage of linear algebra on matrices over two sets, one rule per op.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Hinges = !simit.set<"hinges", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>
!I = !simit.tensor<["springs", "points"] x f64>
!V = !simit.tensor<["points"] x f64>

// CHECK-DAG: #diag_points = #simit.storage<diag("points")>
// CHECK-DAG: #pat_springs = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
// CHECK-DAG: #pat_hinges = #simit.storage<pattern("hinges", rows [0, 1], cols [0, 1])>
// CHECK-DAG: #union = #simit.storage<union(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>
// CHECK-DAG: #inc_springs = #simit.storage<incidence("springs", cols [0, 1])>
// CHECK-DAG: #inc_springs_t = #simit.storage<transpose(incidence("springs", cols [0, 1]))>
// CHECK-DAG: #pat_hinges_t = #simit.storage<transpose(pattern("hinges", rows [0, 1], cols [0, 1]))>
// CHECK-DAG: #product = #simit.storage<product(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>
// CHECK-DAG: #product1 = #simit.storage<product(transpose(pattern("springs", rows [0, 1], cols [0, 1])), transpose(pattern("hinges", rows [0, 1], cols [0, 1])))>
// CHECK-DAG: #product2 = #simit.storage<product(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]), transpose(pattern("springs", rows [0, 1], cols [0, 1])), transpose(pattern("hinges", rows [0, 1], cols [0, 1])))>
// CHECK-DAG: #lowrank = #simit.storage<lowrank(empty, 1)>
// CHECK-DAG: #lowrank1 = #simit.storage<lowrank(pattern("springs", rows [0, 1], cols [0, 1]), 1)>

func.func private @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["x"] : !Point -> f64
  %z = simit.zeros : !K
  %M = simit.insert %m into %z[%p, %p] : f64 into !K, (!Point, !Point)
  return %M : !K
}

func.func private @edge(%s : !Spring, %e : !Ends) -> (!K, !I) {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %a] : f64 into !K, (!Point, !Point)
  %zi = simit.zeros : !I
  %I = simit.insert %k into %zi[%s, %a] : f64 into !I, (!Spring, !Point)
  return %K, %I : !K, !I
}

func.func private @hinge(%s : !Spring, %e : !Ends) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %a] : f64 into !K, (!Point, !Point)
  return %K : !K
}

// Sums join: the diagonal goes into the pattern (converted up), two
// patterns make their union. Negation and scaling keep the storage.
// CHECK-LABEL: func.func @sums
// CHECK: %[[M:.*]] = simit.assemble @mass
// CHECK: %[[K:.*]]:2 = simit.assemble @edge() to %{{.*}} : {{.*}} -> (!simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: %[[H:.*]] = simit.assemble @hinge() {{.*}} -> !simit.tensor<["points", "points"] x f64, #pat_hinges>
// CHECK: %[[MC:.*]] = simit.convert %[[M]] : !simit.tensor<["points", "points"] x f64, #diag_points> -> !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: %[[A:.*]] = simit.add %[[MC]], %[[K]]#0 : !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: %[[N:.*]] = simit.neg %[[A]] : !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: %[[S:.*]] = simit.scale %{{.*}}, %[[N]] : f64, !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: %[[SC:.*]] = simit.convert %[[S]] : {{.*}}#pat_springs> -> {{.*}}#union>
// CHECK: %[[HC:.*]] = simit.convert %[[H]] : {{.*}}#pat_hinges> -> {{.*}}#union>
// CHECK: simit.sub %[[SC]], %[[HC]] : !simit.tensor<["points", "points"] x f64, #union>
func.func @sums(%points : !Points, %springs : !Springs, %hinges : !Hinges, %h : f64) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K, %I = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> (!K, !I)
  %H = simit.assemble @hinge() to %hinges reduce <add> : (!Hinges) -> !K
  %A = simit.add %M, %K : !K
  %N = simit.neg %A : !K
  %S = simit.scale %h, %N : f64, !K
  %D = simit.sub %S, %H : !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// Element-wise products keep the smaller storage and restrict the other
// operand to it; a quotient keeps the dividend's.
// CHECK-LABEL: func.func @products_elementwise
// CHECK: %[[KR:.*]] = simit.convert restrict %{{.*}} : {{.*}}#pat_springs> -> {{.*}}#diag_points>
// CHECK: simit.mul %{{.*}}, %[[KR]] : !simit.tensor<["points", "points"] x f64, #diag_points>
// CHECK: %[[KR2:.*]] = simit.convert restrict %{{.*}} : {{.*}}#pat_springs> -> {{.*}}#diag_points>
// CHECK: simit.div %{{.*}}, %[[KR2]] : !simit.tensor<["points", "points"] x f64, #diag_points>
func.func @products_elementwise(%points : !Points, %springs : !Springs) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K, %I = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> (!K, !I)
  %P = simit.mul %M, %K : !K
  %Q = simit.div %P, %K : !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// Transposes are views; products compose, and the transposed incidence
// times the incidence of one edge set is the edge set's pattern.
// CHECK-LABEL: func.func @composition
// CHECK: simit.transpose %{{.*}} : !simit.tensor<["springs", "points"] x f64, #inc_springs> -> !simit.tensor<["points", "springs"] x f64, #inc_springs_t>
// CHECK: simit.matmul %{{.*}}, %{{.*}} : {{.*}}#inc_springs_t>, {{.*}}#inc_springs> -> !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: simit.matmul %{{.*}}, %{{.*}} : {{.*}}#pat_hinges>, {{.*}}#pat_springs> -> !simit.tensor<["points", "points"] x f64, #product>
// CHECK: simit.matmul %{{.*}}, %{{.*}} : {{.*}}#diag_points>, {{.*}}#pat_springs> -> !simit.tensor<["points", "points"] x f64, #pat_springs>
// A transposed square pattern is a view of it.
// CHECK: simit.transpose %{{.*}} : {{.*}}#pat_hinges> -> !simit.tensor<["points", "points"] x f64, #pat_hinges_t>
// CHECK: simit.transpose %{{.*}} : {{.*}}#diag_points> -> !simit.tensor<["points", "points"] x f64, #diag_points>
// The transpose of a product is the product of the transposed factors in
// reverse order, and composes with the product itself.
// CHECK: simit.transpose %{{.*}} : {{.*}}#product> -> !simit.tensor<["points", "points"] x f64, #product1>
// CHECK: simit.matmul %{{.*}}, %{{.*}} : {{.*}}#product>, {{.*}}#product1> -> !simit.tensor<["points", "points"] x f64, #product2>
func.func @composition(%points : !Points, %springs : !Springs, %hinges : !Hinges) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K, %I = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> (!K, !I)
  %H = simit.assemble @hinge() to %hinges reduce <add> : (!Hinges) -> !K
  %T = simit.transpose %I : !I -> !simit.tensor<["points", "springs"] x f64>
  %L = simit.matmul %T, %I : !simit.tensor<["points", "springs"] x f64>, !I -> !K
  %HK = simit.matmul %H, %K : !K, !K -> !K
  %MK = simit.matmul %M, %K : !K, !K -> !K
  %HT = simit.transpose %H : !K -> !K
  %MT = simit.transpose %M : !K -> !K
  %HKT = simit.transpose %HK : !K -> !K
  %HKHKT = simit.matmul %HK, %HKT : !K, !K -> !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// zeros is empty, outer products are rank-one terms, and a sum keeps them.
// CHECK-LABEL: func.func @zeros_and_outer
// CHECK: simit.zeros : !simit.tensor<["points", "points"] x f64, #simit.storage<empty>>
// CHECK: simit.outer %{{.*}}, %{{.*}} : {{.*}} -> !simit.tensor<["points", "points"] x f64, #lowrank>
// CHECK: simit.add %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x f64, #lowrank1>
func.func @zeros_and_outer(%springs : !Springs, %x : !V) -> f64 {
  %Z = simit.zeros : !K
  %O = simit.outer %x, %x : !V, !V -> !K
  %K, %I = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> (!K, !I)
  %S = simit.add %K, %O : !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// Vectors from matrices carry no storage; writing a block keeps the storage.
// CHECK-LABEL: func.func @vectors_and_blocks
// CHECK: simit.matvec %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x f64, #pat_springs>, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x f64>
// CHECK: simit.solve %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x f64, #pat_springs>, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x f64>
// CHECK: simit.insert %{{.*}} into %{{.*}}[%{{.*}}, %{{.*}}] : f64 into !simit.tensor<["points", "points"] x f64, #pat_springs>
func.func @vectors_and_blocks(%springs : !Springs, %x : !V, %p : !Point) -> f64 {
  %K, %I = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> (!K, !I)
  %y = simit.matvec %K, %x : !K, !V -> !V
  %s = simit.solve %K, %y : !K, !V -> !V
  %one = arith.constant 1.0 : f64
  %K2 = simit.insert %one into %K[%p, %p] : f64 into !K, (!Point, !Point)
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}
