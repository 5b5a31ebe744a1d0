// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops=prefetch-scatter-blocks=1 --canonicalize | FileCheck %s
// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops --canonicalize | FileCheck %s --check-prefix=NONE
// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops=prefetch-scatter-blocks=1 --canonicalize --simit-parallel-loops | FileCheck %s --check-prefix=PARALLEL

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
  %K2 = simit.insert %blk into %K1[%b, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K2 : !K
}

// Before its first instruction, the element prefetches the blocks it adds
// into, [a, b] and [b, a] (positions 1 and 2 of its row of the location
// table; the diagonal blocks 0 and 3 it leaves alone), each block (72
// bytes) at its first component and at its last, in the next cache line.
// CHECK-LABEL: func.func @assemble(
// CHECK-SAME: %[[LOC:[^:]*]]: memref<?x4xi32>
// CHECK: %[[KV:.*]] = memref.alloc(%{{.*}}) : memref<?x3x3xf64>
// CHECK: scf.parallel (%[[E:[^,)]*]]) =
// CHECK-NEXT: %[[L1:.*]] = memref.load %[[LOC]][%[[E]], %c1] : memref<?x4xi32>
// CHECK-NEXT: %[[B1:.*]] = arith.index_cast %[[L1]]
// CHECK-NEXT: memref.prefetch %[[KV]][%[[B1]], %c0, %c0], write, locality<3>, data
// CHECK-NEXT: memref.prefetch %[[KV]][%[[B1]], %c2, %c2], write, locality<3>, data
// CHECK-NEXT: %[[L2:.*]] = memref.load %[[LOC]][%[[E]], %c2] : memref<?x4xi32>
// CHECK-NEXT: %[[B2:.*]] = arith.index_cast %[[L2]]
// CHECK-NEXT: memref.prefetch %[[KV]][%[[B2]], %c0, %c0], write, locality<3>, data
// CHECK-NEXT: memref.prefetch %[[KV]][%[[B2]], %c2, %c2], write, locality<3>, data
// CHECK-NOT: memref.prefetch
// CHECK: } {simit.scatter}
// NONE-LABEL: func.func @assemble(
// NONE-NOT: memref.prefetch
// The prefetches write nothing: the loop still runs colour by colour.
// PARALLEL-LABEL: func.func @assemble(
// PARALLEL: memref.prefetch
// PARALLEL: } {simit.parallel = "scatter"}
func.func @assemble() -> !F attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %K, %x : !K, !F -> !F
  return %y : !F
}
