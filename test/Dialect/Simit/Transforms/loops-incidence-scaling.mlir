// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// An incidence D over (edges, vertices) times a block diagonal M over the
// vertices keeps D's storage (simit-assign-storage drops the diagonal
// factor): a loop over the edges writes each of the edge's blocks once,
// D's block at endpoint position k times M's block at endpoint k.

!Point = !simit.element<"Point", {m : f64, x : f64}>
!Spring = !simit.element<"Spring", {y : f64}>
!D = !simit.tensor<["springs", "points"] x f64>
!M = !simit.tensor<["points", "points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @incidence(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !D {
  %one = arith.constant 1.0 : f64
  %p = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %q = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %z = simit.zeros : !D
  %d0 = simit.insert %one into %z[%s, %p] : f64 into !D, (!Spring, !Point)
  %d1 = simit.insert %one into %d0[%s, %q] : f64 into !D, (!Spring, !Point)
  return %d1 : !D
}

func.func @mass(%p : !Point) -> !M {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %z = simit.zeros : !M
  %a = simit.insert %m into %z[%p, %p] : f64 into !M, (!Point, !Point)
  return %a : !M
}

// CHECK-LABEL: func.func @scaled(
// CHECK-SAME: %[[NP:[^:]*]]: index, %[[NS:[^:]*]]: index, %[[ENDS:[^:]*]]: memref<?x2xi32>
// CHECK: scf.for %[[E:.*]] = %{{.*}} to %[[NS]] step
// CHECK: %[[FIRST:.*]] = arith.muli %[[E]], %{{.*}} : index
// CHECK: %[[AT:.*]] = arith.addi %[[FIRST]], %{{.*}} : index
// CHECK: %[[END:.*]] = memref.load %[[ENDS]][%[[E]], %{{.*}}] : memref<?x2xi32>
// CHECK: %[[V:.*]] = arith.index_cast %[[END]] : i32 to index
// CHECK: %[[X:.*]] = memref.load %{{.*}}[%[[AT]]] : memref<?xf64>
// CHECK: %[[Y:.*]] = memref.load %{{.*}}[%[[V]]] : memref<?xf64>
// CHECK: %[[XY:.*]] = arith.mulf %[[X]], %[[Y]] : f64
// CHECK: memref.store %[[XY]], %{{.*}}[%[[AT]]] : memref<?xf64>
func.func @scaled() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %d = simit.assemble @incidence() to %springs reduce <add> : (!Springs) -> !D
  %m = simit.assemble @mass() to %points reduce <add> : (!Points) -> !M
  %dm = simit.matmul %d, %m : !D, !M -> !D
  %x = simit.field_read %points["x"] : !Points -> !simit.tensor<["points"] x f64>
  %y = simit.matvec %dm, %x : !D, !simit.tensor<["points"] x f64> -> !simit.tensor<["springs"] x f64>
  simit.field_write %y, %springs["y"] : !simit.tensor<["springs"] x f64>, !Springs
  return
}
