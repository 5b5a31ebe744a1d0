// RUN: simit-opt %s --convert-simit-to-loops | FileCheck %s

// A matrix read at blocks the loop nest does not enumerate is searched.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @link(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%a, %b] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

// (A A) x fused into one sum: the loops enumerate row i of A for k and
// every j, so A(k, j) is not at a position the loops give; its block is
// found by a search of row k (zero where there is none).
// CHECK-LABEL: func.func @product_times_vector
// CHECK: scf.for
// CHECK: scf.for
// CHECK: scf.for %{{.*}} = %{{.*}} to %{{.*}} step %{{.*}} iter_args(%[[FOUND:.*]] = %c-1)
// CHECK: %[[COL:.*]] = memref.load
// CHECK: %[[MATCH:.*]] = arith.cmpi eq
// CHECK: arith.select %[[MATCH]], %{{.*}}, %[[FOUND]]
func.func @product_times_vector() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.index_expr [i : "points", j : "points", k : "points"] (i) = (%x(j), %A(i, k), %A(k, j)) : (!V, !A, !A) -> !V {
  ^bb0(%xj: f64, %aik: f64, %akj: f64):
    %s = simit.index_sum vars [2] : f64 {
      %p = arith.mulf %aik, %akj : f64
      simit.index_sum_yield %p : f64
    }
    %r = arith.mulf %s, %xj : f64
    simit.yield %r : f64
  }
  return %y : !V
}
