// RUN: simit-opt %s --split-input-file --simit-sherman-morrison | FileCheck %s

// (A + u v^T) \ b with A assembled from an edge set and u, v, b system
// vectors becomes two solves with A (marked for --stats) and the runtime's
// last step; the dense sum and outer product are left to die.

!Point = !simit.element<"Point", {u : tensor<3xf64>, v : tensor<3xf64>, b : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
func.func private @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A

// CHECK-LABEL: func.func @rank_one(
// CHECK: %[[A:.*]] = simit.assemble @stiffness()
// CHECK-DAG: %[[U:.*]] = simit.field_read %{{.*}}["u"]
// CHECK-DAG: %[[V:.*]] = simit.field_read %{{.*}}["v"]
// CHECK-DAG: %[[B:.*]] = simit.field_read %{{.*}}["b"]
// CHECK: %[[W:.*]] = simit.solve %[[A]], %[[U]] {simit.solve_note = "Sherman-Morrison A^-1 u"}
// CHECK: %[[C:.*]] = simit.solve %[[A]], %[[B]] {simit.solve_note = "Sherman-Morrison A^-1 b"}
// CHECK: %[[X:.*]] = simit.woodbury %[[A]], %[[B]], %[[C]], u[%[[U]]], v[%[[V]]], w[%[[W]]] : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x tensor<3xf64>>
// CHECK-NOT: simit.outer
// CHECK: return %[[X]]
func.func @rank_one() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %M = simit.add %A, %uv : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}

// -----

// The outer product may come first, and the vectors may be scalar.

!Point = !simit.element<"Point", {u : f32, v : f32, b : f32}>
!Spring = !simit.element<"Spring", {k : f32}>
!A = !simit.tensor<["points", "points"] x f32>
!V = !simit.tensor<["points"] x f32>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
func.func private @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A

// CHECK-LABEL: func.func @outer_first(
// CHECK: %[[A:.*]] = simit.assemble @stiffness()
// CHECK: simit.solve %[[A]], %{{.*}} {simit.solve_note = "Sherman-Morrison A^-1 u"}
// CHECK: simit.solve %[[A]], %{{.*}} {simit.solve_note = "Sherman-Morrison A^-1 b"}
// CHECK: simit.woodbury %[[A]],
func.func @outer_first() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %M = simit.add %uv, %A : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}
