// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops --canonicalize | FileCheck %s

// A zero matrix (stored as `empty`: a matrix variable nothing assigns) is a
// zero-filled array in the smallest layout without a pattern: a diagonal
// over one set, dense blocks over two.

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!R = !simit.tensor<["springs", "points"] x tensor<1x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!G = !simit.tensor<["springs"] x tensor<1xf64>>
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @springs : !simit.set<"springs", !Spring, ["points", "points"]>

// CHECK-LABEL: func.func @zeros(
// CHECK-SAME: %{{.*}}: memref<?x3xf64>, %[[P:.*]]: index, %[[S:.*]]: index)
// CHECK: %[[D:.*]] = memref.alloc(%[[P]]) : memref<?x3x3xf64>
// CHECK: scf.parallel
// CHECK-NEXT: memref.store %[[ZERO:.*]], %[[D]][
// CHECK: %[[N:.*]] = arith.muli %[[S]], %[[P]]
// CHECK: %[[R:.*]] = memref.alloc(%[[N]]) : memref<?x1x3xf64>
// CHECK: scf.parallel
// CHECK-NEXT: memref.store %[[ZERO]], %[[R]][
func.func @zeros(%x : !F) -> (!F, !G) attributes {simit.export} {
  %A = simit.zeros : !K
  %y = simit.matvec %A, %x : !K, !F -> !F
  %R = simit.zeros : !R
  %z = simit.matvec %R, %x : !R, !F -> !G
  return %y, %z : !F, !G
}
