// RUN: simit-opt %s --simit-sherman-morrison | FileCheck %s

// (A - u v^T) \ b is (A + (-u) v^T) \ b: u is negated and the rewrite
// applies. u v^T - A is left as written.

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
// CHECK: %[[A:.*]] = simit.assemble @stiffness()
// CHECK-DAG: %[[U:.*]] = simit.field_read %{{.*}}["u"]
// CHECK-DAG: %[[V:.*]] = simit.field_read %{{.*}}["v"]
// CHECK-DAG: %[[B:.*]] = simit.field_read %{{.*}}["b"]
// CHECK: %[[NEG:.*]] = simit.neg %[[U]]
// CHECK: %[[W:.*]] = simit.solve %[[A]], %[[NEG]] {simit.solve_note = "Sherman-Morrison A^-1 u"}
// CHECK: %[[C:.*]] = simit.solve %[[A]], %[[B]] {simit.solve_note = "Sherman-Morrison A^-1 b"}
// CHECK: %[[X:.*]] = simit.woodbury %[[A]], %[[B]], %[[C]], u[%[[NEG]]], v[%[[V]]], w[%[[W]]]
// CHECK-NOT: simit.sub
// CHECK: return %[[X]]
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

// CHECK-LABEL: func.func @outer_minus_matrix(
// CHECK: %[[M:.*]] = simit.sub %{{.*}}, %{{.*}} : !simit.tensor
// CHECK: simit.solve %[[M]], %{{.*}} : !simit.tensor
// CHECK-NOT: simit.woodbury
// CHECK: return
func.func @outer_minus_matrix() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %M = simit.sub %uv, %A : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}

// CHECK-LABEL: func.func @rank_two_difference(
// A difference of two outer products (rank 2): both u are negated, and the
// Woodbury form takes the terms from the outermost sub inwards.
// CHECK: %[[A:.*]] = simit.assemble @stiffness()
// CHECK-DAG: %[[U:.*]] = simit.field_read %{{.*}}["u"]
// CHECK-DAG: %[[V:.*]] = simit.field_read %{{.*}}["v"]
// CHECK-DAG: %[[B:.*]] = simit.field_read %{{.*}}["b"]
// CHECK: %[[NV:.*]] = simit.neg %[[V]]
// CHECK: %[[W1:.*]] = simit.solve %[[A]], %[[NV]] {simit.solve_note = "Woodbury A^-1 u1"}
// CHECK: %[[NU:.*]] = simit.neg %[[U]]
// CHECK: %[[W2:.*]] = simit.solve %[[A]], %[[NU]] {simit.solve_note = "Woodbury A^-1 u2"}
// CHECK: %[[C:.*]] = simit.solve %[[A]], %[[B]] {simit.solve_note = "Woodbury A^-1 b"}
// CHECK: %[[X:.*]] = simit.woodbury %[[A]], %[[B]], %[[C]], u[%[[NV]], %[[NU]]], v[%[[B]], %[[V]]], w[%[[W1]], %[[W2]]]
// CHECK-NOT: simit.sub
// CHECK: return %[[X]]
func.func @rank_two_difference() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %vb = simit.outer %v, %b : !V, !V -> !A
  %A1 = simit.sub %A, %uv : !A
  %M = simit.sub %A1, %vb : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}
