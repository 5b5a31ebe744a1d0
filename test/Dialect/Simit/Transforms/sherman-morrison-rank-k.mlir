// RUN: simit-opt %s --simit-sherman-morrison | FileCheck %s

// A + u1 v1^T + u2 v2^T (rank 2): the Woodbury form, k + 1 = 3 solves with
// A (one factorisation) and the runtime's last step, which solves the 2 x 2
// system I + V^T W (docs/solvers.md). More than 4 terms are left as written.

!Point = !simit.element<"Point", {u : tensor<3xf64>, v : tensor<3xf64>, b : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
func.func private @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A

// CHECK-LABEL: func.func @rank_two(
// CHECK: %[[A:.*]] = simit.assemble @stiffness()
// CHECK-DAG: %[[U:.*]] = simit.field_read %{{.*}}["u"]
// CHECK-DAG: %[[V:.*]] = simit.field_read %{{.*}}["v"]
// CHECK-DAG: %[[B:.*]] = simit.field_read %{{.*}}["b"]
// CHECK: %[[W1:.*]] = simit.solve %[[A]], %[[V]] {simit.solve_note = "Woodbury A^-1 u1"}
// CHECK: %[[W2:.*]] = simit.solve %[[A]], %[[U]] {simit.solve_note = "Woodbury A^-1 u2"}
// CHECK: %[[C:.*]] = simit.solve %[[A]], %[[B]] {simit.solve_note = "Woodbury A^-1 b"}
// CHECK: %[[X:.*]] = simit.woodbury %[[A]], %[[B]], %[[C]], u[%[[V]], %[[U]]], v[%[[B]], %[[V]]], w[%[[W1]], %[[W2]]]
// CHECK-NOT: simit.add
// CHECK: return %[[X]]
func.func @rank_two() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %vb = simit.outer %v, %b : !V, !V -> !A
  %A1 = simit.add %A, %uv : !A
  %M = simit.add %A1, %vb : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}

// CHECK-LABEL: func.func @rank_five(
// CHECK-NOT: simit.woodbury
// CHECK: simit.solve %{{.*}}, %{{.*}} : !simit.tensor
// CHECK-NOT: simit.woodbury
// CHECK: return
func.func @rank_five() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uu = simit.outer %u, %u : !V, !V -> !A
  %A1 = simit.add %A, %uu : !A
  %A2 = simit.add %A1, %uu : !A
  %A3 = simit.add %A2, %uu : !A
  %A4 = simit.add %A3, %uu : !A
  %M = simit.add %A4, %uu : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}
