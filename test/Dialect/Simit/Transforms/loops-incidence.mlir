// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-fuse-index-expr \
// RUN:   --convert-simit-to-loops --canonicalize --cse | FileCheck %s

// A matrix over (springs, points) assembled from the springs is stored as
// one block per (edge, endpoint k), at e * 2 + k; the endpoint array is its
// column index. D x walks each edge's endpoints; D' g runs over the edges
// and adds into the endpoints' rows.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {g : f64}>
!D = !simit.tensor<["springs", "points"] x f64>
!Dt = !simit.tensor<["points", "springs"] x f64>
!VP = !simit.tensor<["points"] x f64>
!VS = !simit.tensor<["springs"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

// CHECK-LABEL: func.func @incidence(
// CHECK-SAME: %[[NP:[^:]*]]: index, %[[NS:[^:]*]]: index, %[[ENDS:[^:]*]]: memref<?x2xi32>, %[[X:[^:]*]]: memref<?xf64>, %[[G:[^:]*]]: memref<?xf64>)
// CHECK: %[[NB:.*]] = arith.muli %[[NS]], %c2
// CHECK: %[[DV:.*]] = memref.alloc(%[[NB]]) : memref<?xf64>
// CHECK: scf.parallel (%[[E:.*]]) = (%c0) to (%[[NS]])
// CHECK:   %[[E2:.*]] = arith.muli %[[E]], %c2
// CHECK:   %[[OLD0:.*]] = memref.load %[[DV]][%[[E2]]]
// CHECK:   %[[NEW0:.*]] = arith.addf %[[OLD0]], %{{.*}}
// CHECK:   memref.store %[[NEW0]], %[[DV]][%[[E2]]]
// CHECK:   %[[E21:.*]] = arith.addi %[[E2]], %c1
// CHECK:   memref.store %{{.*}}, %[[DV]][%[[E21]]]
// CHECK-NOT: simit.scatter
// D x: row e, blocks e * 2 + k at columns ends[e, k], summed in a
// loop-carried value and stored once.
// CHECK: %[[DX:.*]] = memref.alloc(%[[NS]]) : memref<?xf64>
// CHECK-NEXT: scf.parallel (%[[R:.*]]) = (%c0) to (%[[NS]])
// CHECK:   %[[SUM:.*]] = scf.for %[[K:.*]] = %c0 to %c2 step %c1 iter_args(%[[ACC:.*]] = %cst{{.*}}) -> (f64) {
// CHECK:     %[[C32:.*]] = memref.load %[[ENDS]][%[[R]], %[[K]]]
// CHECK:     %[[C:.*]] = arith.index_cast %[[C32]]
// CHECK:     %[[R2:.*]] = arith.muli %[[R]], %c2
// CHECK:     %[[POS:.*]] = arith.addi %[[R2]], %[[K]]
// CHECK:     %[[DK:.*]] = memref.load %[[DV]][%[[POS]]]
// CHECK:     %[[XC:.*]] = memref.load %[[X]][%[[C]]]
// CHECK:     %[[T:.*]] = arith.mulf %[[DK]], %[[XC]]
// CHECK:     %[[NEXT:.*]] = arith.addf %[[ACC]], %[[T]]
// CHECK:     scf.yield %[[NEXT]]
// CHECK:   memref.store %[[SUM]], %[[DX]][%[[R]]]
// D' g: the same walk, added into row c of the result.
// CHECK: scf.for %[[R:.*]] = %c0 to %[[NS]] step %c1 {
// CHECK:   scf.for %[[K:.*]] = %c0 to %c2 step %c1 {
// CHECK:     %[[C32:.*]] = memref.load %[[ENDS]][%[[R]], %[[K]]]
// CHECK:     %[[C:.*]] = arith.index_cast %[[C32]]
// CHECK:     %[[GR:.*]] = memref.load %[[G]][%[[R]]]
// CHECK:     %[[P:.*]] = arith.mulf %{{.*}}, %[[GR]]
// CHECK:     %[[OLD:.*]] = memref.load %{{.*}}[%[[C]]]
// CHECK:     %[[NEW:.*]] = arith.addf %[[OLD]], %[[P]]
// CHECK:     memref.store %[[NEW]], %{{.*}}[%[[C]]]
func.func @incidence() -> (!VS, !VP) attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %D = simit.assemble @difference() to %springs reduce <add> : (!Springs) -> !D
  %x = simit.field_read %points["x"] : !Points -> !VP
  %dx = simit.matvec %D, %x : !D, !VP -> !VS
  %Dt = simit.transpose %D : !D -> !Dt
  %g = simit.field_read %springs["g"] : !Springs -> !VS
  %dg = simit.matvec %Dt, %g : !Dt, !VS -> !VP
  return %dx, %dg : !VS, !VP
}

func.func @difference(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !D {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %minus = arith.constant -1.0 : f64
  %plus = arith.constant 1.0 : f64
  %D0 = simit.zeros : !D
  %D1 = simit.insert %minus into %D0[%s, %a] : f64 into !D, (!Spring, !Point)
  %D2 = simit.insert %plus into %D1[%s, %b] : f64 into !D, (!Spring, !Point)
  return %D2 : !D
}
