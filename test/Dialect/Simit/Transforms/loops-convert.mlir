// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-assign-storage \
// RUN:   --convert-simit-to-loops | FileCheck %s

// simit.convert, inserted where a variable, loop or branch holds matrices of
// several storages: the larger storage is zero-filled and each source block
// is added at its place, row by row.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Hinges = !simit.set<"hinges", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>
simit.extern @points : !Points
simit.extern @springs : !Springs
simit.extern @hinges : !Hinges

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

// A diagonal into a pattern: row r's block (r, r) is found by a search of
// the pattern's row r, then added.
// CHECK-LABEL: func.func @diagonal_to_pattern
// CHECK: scf.parallel (%[[R:.*]]) =
// CHECK: %[[FOUND:.*]] = scf.for %{{.*}} iter_args(%{{.*}} = %c-1) -> (index)
// CHECK: %[[HAS:.*]] = arith.cmpi sge, %[[FOUND]], %c0
// CHECK: scf.if %[[HAS]] {
// CHECK: %[[OLD:.*]] = memref.load %{{.*}}[%[[FOUND]]]
// CHECK: %[[ADD:.*]] = memref.load %{{.*}}[%[[R]]]
// CHECK: arith.addf %[[OLD]], %[[ADD]]
func.func @diagonal_to_pattern(%n : index) -> !V attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %springs = simit.get_set @springs : !Springs
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %R = scf.for %i = %c0 to %n step %c1 iter_args(%A = %M) -> (!K) {
    %S = simit.add %A, %K : !K
    scf.yield %S : !K
  }
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %R, %x : !K, !V -> !V
  return %y : !V
}

// A pattern into the union with another edge set's: the gather map from the
// union's blocks to the pattern's (-1 where it has none), along the union's
// row r.
// CHECK-LABEL: func.func @pattern_to_union
// CHECK-SAME: {cols = "points", kind = "union_gather", part = "springs", rows = "points", set = "hinges+springs"}
// CHECK: scf.if
// CHECK: scf.parallel
// CHECK: scf.for %[[P:.*]] =
// CHECK: %[[G:.*]] = memref.load %{{.*}}[%[[P]]] : memref<?xi32>
// CHECK: %[[AT:.*]] = arith.index_cast %[[G]]
// CHECK: %[[HAS:.*]] = arith.cmpi sge, %[[AT]], %c0
// CHECK: %[[PLACE:.*]] = arith.select %[[HAS]], %[[P]], %c-1
// CHECK: %[[OK:.*]] = arith.cmpi sge, %[[PLACE]], %c0
// CHECK: scf.if %[[OK]] {
// CHECK: memref.load %{{.*}}[%[[PLACE]]]
// CHECK: memref.load %{{.*}}[%[[AT]]]
func.func @pattern_to_union(%c : i1) -> !V attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %springs = simit.get_set @springs : !Springs
  %hinges = simit.get_set @hinges : !Hinges
  %K = simit.assemble @edge() to %springs reduce <add> : (!Springs) -> !K
  %H = simit.assemble @edge() to %hinges reduce <add> : (!Hinges) -> !K
  %B = scf.if %c -> (!K) {
    scf.yield %K : !K
  } else {
    %S = simit.add %K, %H : !K
    scf.yield %S : !K
  }
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %B, %x : !K, !V -> !V
  return %y : !V
}
