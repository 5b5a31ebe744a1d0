// RUN: simit-opt %s --simit-sherman-morrison | FileCheck %s

// A - u v^T is not the pattern (a simit.sub): left as written.

!Point = !simit.element<"Point", {u : tensor<3xf64>, v : tensor<3xf64>, b : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
func.func private @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A

// CHECK-LABEL: func.func @difference(
// CHECK: %[[M:.*]] = simit.sub
// CHECK: simit.solve %[[M]], %{{.*}} : !simit.tensor
// CHECK-NOT: simit_rt_sherman_morrison
func.func @difference() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %M = simit.sub %A, %uv : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}
