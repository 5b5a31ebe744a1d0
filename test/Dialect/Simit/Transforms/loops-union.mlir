// RUN: simit-opt %s --split-input-file --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops | FileCheck %s

// Element-wise sums of matrices on different patterns, and transposed
// operands: the result loops over the union of the patterns (or the
// transposed pattern) and reads each operand through a gather map that the
// runtime builds once per binding; -1 (no block) reads zero.


!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !K {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

// CHECK-LABEL: func.func @transposed(
// CHECK-SAME: %[[NP:[^:]*]]: index
// CHECK-SAME: %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>, %[[TPOS:[^:]*]]: memref<?xi32>)
// CHECK-SAME: {cols = "points", kind = "union_gather", part = "~springs", rows = "points", set = "springs"}
// CHECK: %[[K:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: %[[KT:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: scf.parallel (%[[R:.*]]) = (%{{.*}}) to (%[[NP]])
// CHECK: scf.for %[[B:.*]] = %{{.*}} to %{{.*}} {
// CHECK: %[[P:.*]] = memref.load %[[TPOS]][%[[B]]] : memref<?xi32>
// CHECK: %[[PI:.*]] = arith.index_cast %[[P]] : i32 to index
// CHECK: scf.for %[[I:.*]] = %{{.*}} to %{{.*}}
// CHECK: scf.for %[[J:.*]] = %{{.*}} to %{{.*}}
// CHECK: %[[HAS:.*]] = arith.cmpi sge, %[[PI]], %{{.*}} : index
// CHECK: %[[SAFE:.*]] = arith.select %[[HAS]], %[[PI]], %{{.*}} : index
// CHECK: %[[V:.*]] = memref.load %[[K]][%[[SAFE]], %[[J]], %[[I]]]
// CHECK: %[[Z:.*]] = arith.select %[[HAS]], %[[V]], %{{.*}} : f64
// CHECK: memref.store %[[Z]], %[[KT]][%[[B]], %[[I]], %[[J]]]
func.func @transposed() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %Kt = simit.transpose %K : !K -> !K
  %y = simit.matvec %Kt, %x : !K, !F -> !F
  return %y : !F
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
simit.extern @rods : !simit.set<"rods", !Spring, ["points", "points"]>

func.func @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !K {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

// CHECK-LABEL: func.func @patterns(
// CHECK-SAME: %[[NP:[^:]*]]: index
// CHECK-SAME: %[[UROWPTR:[^:]*]]: memref<?xi32>, %[[UCOLIDX:[^:]*]]: memref<?xi32>, %[[GS:[^:]*]]: memref<?xi32>, %[[GR:[^:]*]]: memref<?xi32>)
// CHECK-SAME: {cols = "points", kind = "union_rowptr", rows = "points", set = "rods+springs"}, {cols = "points", kind = "union_colidx", rows = "points", set = "rods+springs"}, {cols = "points", kind = "union_gather", part = "springs", rows = "points", set = "rods+springs"}, {cols = "points", kind = "union_gather", part = "rods", rows = "points", set = "rods+springs"}]
// CHECK: %[[K:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: %[[R:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: %[[N:.*]] = memref.load %[[UROWPTR]][%[[NP]]] : memref<?xi32>
// CHECK: %[[NB:.*]] = arith.index_cast %[[N]] : i32 to index
// CHECK: %[[A:.*]] = memref.alloc(%[[NB]]) : memref<?x3x3xf64>
// CHECK: scf.for %[[B:.*]] = %{{.*}} to %{{.*}} {
// CHECK: memref.load %[[UCOLIDX]][%[[B]]]
// CHECK: memref.load %[[GS]][%[[B]]]
// CHECK: memref.load %[[GR]][%[[B]]]
// CHECK: memref.load %[[K]][
// CHECK: memref.load %[[R]][
// CHECK: memref.store %{{.*}}, %[[A]][%[[B]], %{{.*}}, %{{.*}}]
func.func @patterns() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %rods = simit.get_set @rods : !simit.set<"rods", !Spring, ["points", "points"]>
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %R = simit.assemble @stiffness() to %rods reduce <add> : (!simit.set<"rods", !Spring, ["points", "points"]>) -> !K
  %A = simit.add %K, %R : !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %A, %x : !K, !F -> !F
  return %y : !F
}
