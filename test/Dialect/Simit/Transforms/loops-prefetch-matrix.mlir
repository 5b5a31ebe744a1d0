// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops=prefetch-matrix-bytes=1024 --canonicalize --cse | FileCheck %s
// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops --canonicalize --cse | FileCheck %s --check-prefix=NONE

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

// At each block k of a row, K * x prefetches the block 1024 bytes on:
// ceil(1024 / 72) = 15 blocks of 3x3 doubles, at most the last block, at
// its first component and at its last (the next cache line).
// CHECK-LABEL: func.func @spmv(
// CHECK: %[[KV:.*]] = memref.alloc(%[[NB:.*]]) : memref<?x3x3xf64>
// CHECK: scf.parallel
// CHECK: } {simit.scatter}
// CHECK: scf.parallel
// CHECK:   scf.for %[[K:.*]] = {{.*}} iter_args
// CHECK:     %[[LAST:.*]] = arith.subi %[[NB]], %c1
// CHECK:     %[[AHEAD:.*]] = arith.addi %[[K]], %c15
// CHECK:     %[[AT:.*]] = arith.minsi %[[AHEAD]], %[[LAST]]
// CHECK:     memref.prefetch %[[KV]][%[[AT]], %c0, %c0], read, locality<3>, data
// CHECK:     memref.prefetch %[[KV]][%[[AT]], %c2, %c2], read, locality<3>, data
// CHECK:     memref.load %[[KV]][%[[K]], %c0, %c0]
// NONE-LABEL: func.func @spmv(
// NONE-NOT: memref.prefetch {{.*}} read
func.func @spmv() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %K, %x : !K, !F -> !F
  return %y : !F
}
