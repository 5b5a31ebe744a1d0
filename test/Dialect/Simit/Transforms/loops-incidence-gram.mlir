// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// D' * D of an incidence D over (edges, vertices) is stored on the edge
// set's pattern (simit-assign-storage composes transpose(incidence) and
// incidence): a sequential loop over the edges adds, for each pair of
// endpoint positions (i, j), the product of the edge's blocks i of D' and
// j of D at the pattern's block of (endpoint i, endpoint j), found in the
// bind-time pattern_locations of an assembly over the edge set.

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Spring = !simit.element<"Spring", {}>
!D = !simit.tensor<["springs", "points"] x tensor<3x3xf64>>
!DT = !simit.tensor<["points", "springs"] x tensor<3x3xf64>>
!L = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @incidence(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !D {
  %b = arith.constant dense<1.0> : tensor<3x3xf64>
  %p = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %q = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %z = simit.zeros : !D
  %d0 = simit.insert %b into %z[%s, %p] : tensor<3x3xf64> into !D, (!Spring, !Point)
  %d1 = simit.insert %b into %d0[%s, %q] : tensor<3x3xf64> into !D, (!Spring, !Point)
  return %d1 : !D
}

// CHECK-LABEL: func.func @laplacian(
// CHECK-SAME: %{{[^:]*}}: index, %[[NS:[^:]*]]: index, %{{[^:]*}}: memref<?x2xi32>, %{{[^:]*}}: memref<?x3xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?xi32>, %[[LOC:[^:]*]]: memref<?x4xi32>)
// CHECK: %[[NB:.*]] = memref.load %[[ROWPTR]][%{{.*}}] : memref<?xi32>
// CHECK: %[[NBI:.*]] = arith.index_cast %[[NB]] : i32 to index
// CHECK: %[[L:.*]] = memref.alloc(%[[NBI]]) : memref<?x3x3xf64>
// CHECK: scf.for %[[E:.*]] = %{{.*}} to %[[NS]] step
// CHECK: %[[FIRST:.*]] = arith.muli %[[E]], %{{.*}} : index
// CHECK: %[[HPOS:.*]] = arith.addi %[[FIRST]], %{{.*}} : index
// CHECK: %[[GPOS:.*]] = arith.addi %[[FIRST]], %{{.*}} : index
// CHECK: %[[AT:.*]] = memref.load %[[LOC]][%[[E]], %{{.*}}] : memref<?x4xi32>
// CHECK: %[[POS:.*]] = arith.index_cast %[[AT]] : i32 to index
// CHECK: %[[OLD:.*]] = memref.load %[[L]][%[[POS]], %{{.*}}, %{{.*}}] : memref<?x3x3xf64>
// CHECK: %[[X:.*]] = memref.load %{{.*}}[%[[HPOS]], %{{.*}}, %{{.*}}] : memref<?x3x3xf64>
// CHECK: %[[Y:.*]] = memref.load %{{.*}}[%[[GPOS]], %{{.*}}, %{{.*}}] : memref<?x3x3xf64>
// CHECK: %[[XY:.*]] = arith.mulf %[[X]], %[[Y]] : f64
// CHECK: arith.addf %[[OLD]], %[[XY]] : f64
// CHECK-COUNT-2: arith.mulf
// CHECK: memref.store %{{.*}}, %[[L]][%[[POS]], %{{.*}}, %{{.*}}] : memref<?x3x3xf64>
func.func @laplacian() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %d = simit.assemble @incidence() to %springs reduce <add> : (!Springs) -> !D
  %dt = simit.transpose %d : !D -> !DT
  %l = simit.matmul %dt, %d : !DT, !D -> !L
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %l, %x : !L, !V -> !V
  simit.field_write %y, %points["x"] : !V, !Points
  return
}
