// RUN: simit-opt %s --simit-sherman-morrison | FileCheck %s

// A sum of two sparse matrices has no outer product to take out.

!Point = !simit.element<"Point", {u : tensor<3xf64>, v : tensor<3xf64>, b : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
func.func private @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A

// CHECK-LABEL: func.func @sparse_sum(
// CHECK: %[[M:.*]] = simit.add
// CHECK: simit.solve %[[M]], %{{.*}} : !simit.tensor
// CHECK-NOT: simit.woodbury
func.func @sparse_sum() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %B = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %b = simit.field_read %points["b"] : !Points -> !V
  %M = simit.add %A, %B : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}
