// RUN: simit-opt %s --simit-sherman-morrison | FileCheck %s

// (A + u v^T) \ b with A over two sets (q, v): u and b are over the rows
// q, v and the solution over the columns v, and so are the solves with A
// and the runtime's last step.

!Q = !simit.element<"Q", {u : f64, b : f64}>
!V = !simit.element<"V", {v : f64}>
!E = !simit.element<"E", {w : f64}>
!A = !simit.tensor<["q", "v"] x f64>
!Rows = !simit.tensor<["q"] x f64>
!Cols = !simit.tensor<["v"] x f64>
!Qs = !simit.set<"q", !Q>
!Vs = !simit.set<"v", !V>
!Es = !simit.set<"e", !E, ["q", "v"]>
simit.extern @q : !Qs
simit.extern @v : !Vs
simit.extern @e : !Es
func.func private @couple(%e : !E, %ends : !simit.tuple<{q : !Q, v : !V}>) -> !A

// CHECK-LABEL: func.func @two_sets(
// CHECK: %[[A:.*]] = simit.assemble @couple()
// CHECK-DAG: %[[U:.*]] = simit.field_read %{{.*}}["u"]
// CHECK-DAG: %[[V:.*]] = simit.field_read %{{.*}}["v"]
// CHECK-DAG: %[[B:.*]] = simit.field_read %{{.*}}["b"]
// CHECK: %[[W:.*]] = simit.solve %[[A]], %[[U]] {simit.solve_note = "Sherman-Morrison A^-1 u"} : !simit.tensor<["q", "v"] x f64>, !simit.tensor<["q"] x f64> -> !simit.tensor<["v"] x f64>
// CHECK: %[[C:.*]] = simit.solve %[[A]], %[[B]] {simit.solve_note = "Sherman-Morrison A^-1 b"} : !simit.tensor<["q", "v"] x f64>, !simit.tensor<["q"] x f64> -> !simit.tensor<["v"] x f64>
// CHECK: %[[X:.*]] = simit.woodbury %[[A]], %[[B]], %[[C]], u[%[[U]]], v[%[[V]]], w[%[[W]]] : !simit.tensor<["q", "v"] x f64>, !simit.tensor<["q"] x f64> -> !simit.tensor<["v"] x f64>
// CHECK: return %[[X]]
func.func @two_sets() -> !Cols attributes {simit.export} {
  %e = simit.get_set @e : !Es
  %q = simit.get_set @q : !Qs
  %v = simit.get_set @v : !Vs
  %A = simit.assemble @couple() to %e reduce <add> : (!Es) -> !A
  %u = simit.field_read %q["u"] : !Qs -> !Rows
  %vv = simit.field_read %v["v"] : !Vs -> !Cols
  %b = simit.field_read %q["b"] : !Qs -> !Rows
  %uv = simit.outer %u, %vv : !Rows, !Cols -> !A
  %M = simit.add %A, %uv : !A
  %x = simit.solve %M, %b : !A, !Rows -> !Cols
  return %x : !Cols
}
