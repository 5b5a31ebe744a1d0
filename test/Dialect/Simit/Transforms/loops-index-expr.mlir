// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-fuse-index-expr \
// RUN:   --convert-simit-to-loops --canonicalize --cse | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %blk = simit.broadcast %m : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%p, %p] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

func.func @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !K {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

// A pattern matrix times a vector: each row's blocks (rowptr/colidx) are
// visited once; each of a block's nine terms (row of the block, column) is
// summed over the row's blocks in a loop-carried lane of its own (two
// vectors of four, the ninth alone), the lanes of each row component are
// added in term order after the loop, and the row is stored once, so the
// result is not zero filled.
// CHECK-LABEL: func.func @spmv(
// CHECK-SAME: %[[NP:[^:]*]]: index, {{.*}}%[[X:[^:]*]]: memref<?x3xf64>, %{{[^:]*}}: memref<?xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>)
// CHECK: %[[KV:.*]] = memref.alloc
// CHECK: scf.parallel
// CHECK: } {simit.scatter}
// CHECK: %[[Y:.*]] = memref.alloc(%[[NP]]) : memref<?x3xf64>
// CHECK-NOT: memref.store %cst, %[[Y]]
// CHECK: scf.parallel (%[[I:.*]]) = (%c0) to (%[[NP]])
// CHECK:   %[[I1:.*]] = arith.addi %[[I]], %c1
// CHECK:   %[[LO:.*]] = memref.load %[[ROWPTR]][%[[I]]]
// CHECK:   %[[HI:.*]] = memref.load %[[ROWPTR]][%[[I1]]]
// CHECK:   %[[ROW:.*]]:3 = scf.for %[[K:.*]] = %{{.*}} to %{{.*}} step %c1 iter_args(%[[S4:.*]] = %{{.*}}, %[[T4:.*]] = %{{.*}}, %[[S1:.*]] = %{{.*}}) -> (vector<4xf64>, vector<4xf64>, f64) {
// CHECK:     %[[J32:.*]] = memref.load %[[COLIDX]][%[[K]]]
// CHECK:     %[[J:.*]] = arith.index_cast %[[J32]]
// CHECK:     %[[K00:.*]] = memref.load %[[KV]][%[[K]], %c0, %c0]
// CHECK:     %[[X0:.*]] = memref.load %[[X]][%[[J]], %c0]
// CHECK:     %[[P00:.*]] = arith.mulf %[[K00]], %[[X0]]
// CHECK:     %[[K01:.*]] = memref.load %[[KV]][%[[K]], %c0, %c1]
// CHECK:     %[[X1:.*]] = memref.load %[[X]][%[[J]], %c1]
// CHECK:     %[[P01:.*]] = arith.mulf %[[K01]], %[[X1]]
// CHECK:     %[[K10:.*]] = memref.load %[[KV]][%[[K]], %c1, %c0]
// CHECK:     %[[P10:.*]] = arith.mulf %[[K10]], %[[X0]]
// CHECK:     %[[K22:.*]] = memref.load %[[KV]][%[[K]], %c2, %c2]
// CHECK:     %[[P22:.*]] = arith.mulf %[[K22]], %{{.*}}
// CHECK:     %[[TERMS0:.*]] = vector.from_elements %[[P00]], %[[P01]], %{{.*}}, %[[P10]] : vector<4xf64>
// CHECK:     %[[U4:.*]] = arith.addf %[[S4]], %[[TERMS0]] : vector<4xf64>
// CHECK:     %[[TERMS1:.*]] = vector.from_elements %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}} : vector<4xf64>
// CHECK:     %[[V4:.*]] = arith.addf %[[T4]], %[[TERMS1]] : vector<4xf64>
// CHECK:     %[[U1:.*]] = arith.addf %[[S1]], %[[P22]] : f64
// CHECK:     scf.yield %[[U4]], %[[V4]], %[[U1]] : vector<4xf64>, vector<4xf64>, f64
// CHECK-NOT: memref.store
// CHECK:   }
// CHECK:   %[[L0:.*]] = vector.extract %[[ROW]]#0[0]
// CHECK:   %[[A0:.*]] = arith.addf %[[L0]], %cst
// CHECK:   %[[L1:.*]] = vector.extract %[[ROW]]#0[1]
// CHECK:   %[[A1:.*]] = arith.addf %[[A0]], %[[L1]]
// CHECK:   %[[L2:.*]] = vector.extract %[[ROW]]#0[2]
// CHECK:   %[[Y0:.*]] = arith.addf %[[A1]], %[[L2]]
// CHECK:   %[[L8:.*]] = vector.extract %[[ROW]]#1[3]
// CHECK:   %[[A8:.*]] = arith.addf %{{.*}}, %[[L8]]
// CHECK:   %[[Y2:.*]] = arith.addf %[[A8]], %[[ROW]]#2
// CHECK:   memref.store %[[Y0]], %[[Y]][%[[I]], %c0]
// CHECK:   memref.store %{{.*}}, %[[Y]][%[[I]], %c1]
// CHECK:   memref.store %[[Y2]], %[[Y]][%[[I]], %c2]
// CHECK: return %[[Y]]
func.func @spmv() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %K, %x : !K, !F -> !F
  return %y : !F
}

// M + K (diagonal into a pattern): the result has K's pattern, M is read on
// the diagonal only.
// CHECK-LABEL: func.func @union(
// CHECK: %[[MV:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: %[[KV:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: %[[AV:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: scf.parallel (%[[I:.*]]) =
// CHECK:   scf.for %[[K:.*]] =
// CHECK:     %[[J:.*]] = arith.index_cast
// CHECK:     scf.for %[[A:.*]] = %c0 to %c3
// CHECK:       scf.for %[[B:.*]] = %c0 to %c3
// CHECK:         %[[MD:.*]] = memref.load %[[MV]][%[[I]], %[[A]], %[[B]]]
// CHECK:         %[[ON:.*]] = arith.cmpi eq, %[[I]], %[[J]]
// CHECK:         %[[MIJ:.*]] = arith.select %[[ON]], %[[MD]], %cst
// CHECK:         %[[KIJ:.*]] = memref.load %[[KV]][%[[K]], %[[A]], %[[B]]]
// CHECK:         %[[S:.*]] = arith.addf %[[MIJ]], %[[KIJ]]
// CHECK:         memref.store %[[S]], %[[AV]][%[[K]], %[[A]], %[[B]]]
// Two uses of A: it is built once, then multiplied twice.
// CHECK: scf.parallel
// CHECK: memref.load %[[AV]]
// CHECK: scf.parallel
// CHECK: memref.load %[[AV]]
func.func @union() -> (!F, !F) attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %A = simit.add %M, %K : !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %A, %x : !K, !F -> !F
  %z = simit.matvec %A, %y : !K, !F -> !F
  return %y, %z : !F, !F
}

// dot: scf.parallel with scf.reduce over the set, dense loop over blocks.
// CHECK-LABEL: func.func @dot(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[X:[^:]*]]: memref<?x3xf64>)
// CHECK: %[[D:.*]] = scf.parallel (%[[I:.*]]) = (%c0) to (%[[N]]) step (%c1) init (%cst) -> f64
// CHECK:   %[[ROW:.*]] = scf.for %[[A:.*]] = %c0 to %c3 step %c1 iter_args(%[[ACC:.*]] = %cst) -> (f64)
// CHECK:     %[[V:.*]] = memref.load %[[X]][%[[I]], %[[A]]]
// CHECK:     %[[SQ:.*]] = arith.mulf %[[V]], %[[V]]
// CHECK:     arith.addf %[[ACC]], %[[SQ]]
// CHECK:   scf.reduce(%[[ROW]] : f64)
// CHECK:     arith.addf
// CHECK:     scf.reduce.return
// CHECK: return %[[D]]
func.func @dot() -> f64 attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !F
  %d = simit.dot %x, %x : !F, !F -> f64
  return %d : f64
}

// Fused x + K x: the row sum is a loop-carried scalar inside the row loop,
// added to x in place; no temporary vector but the result.
// CHECK-LABEL: func.func @fused(
// CHECK-SAME: %[[NP:[^:]*]]: index, {{.*}}%[[X:[^:]*]]: memref<?x3xf64>, %{{[^:]*}}: memref<?xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>
// CHECK: %[[Y:.*]] = memref.alloc(%[[NP]]) : memref<?x3xf64>
// CHECK-NOT: memref.alloc
// CHECK: scf.parallel (%[[I:.*]]) =
// CHECK:   scf.for %[[A:.*]] = %c0 to %c3
// CHECK:     %[[ROW:.*]] = scf.for %{{.*}} iter_args
// CHECK:     %[[XI:.*]] = memref.load %[[X]][%[[I]], %[[A]]]
// CHECK:     %[[S:.*]] = arith.addf %[[XI]], %[[ROW]]
// CHECK:     memref.store %[[S]], %[[Y]][%[[I]], %[[A]]]
func.func @fused() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %Kx = simit.matvec %K, %x : !K, !F -> !F
  %y = simit.add %x, %Kx : !F
  return %y : !F
}
