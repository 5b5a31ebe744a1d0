// RUN: simit-opt %s --convert-simit-to-loops | FileCheck %s

// A solve of a matrix over two sets (matrix[q,v], assembled from an edge
// set over (q, v)) passes its BCSR arrays to the runtime like a square
// one, after asserting that the two sets have one size.

!Q = !simit.element<"Q", {b : f64}>
!V = !simit.element<"V", {x : f64}>
!E = !simit.element<"E", {w : f64}>
!A = !simit.tensor<["q", "v"] x f64>
!Bq = !simit.tensor<["q"] x f64>
!Xv = !simit.tensor<["v"] x f64>
!Qs = !simit.set<"q", !Q>
!Vs = !simit.set<"v", !V>
!Es = !simit.set<"e", !E, ["q", "v"]>
simit.extern @q : !Qs
simit.extern @v : !Vs
simit.extern @e : !Es

func.func @couple(%e : !E, %ends : !simit.tuple<{q : !Q, v : !V}>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<{q : !Q, v : !V}> -> !Q
  %c = simit.tuple_get %ends[1] : !simit.tuple<{q : !Q, v : !V}> -> !V
  %w = simit.elem_read %e["w"] : !E -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %w into %A0[%a, %c] : f64 into !A, (!Q, !V)
  return %A1 : !A
}

// CHECK-LABEL: func.func @solve(
// CHECK-SAME: %{{[^:]*}}: index, %[[NQ:[^:]*]]: index, %[[NV:[^:]*]]: index,
// CHECK: %[[SAME:.*]] = arith.cmpi eq, %[[NQ]], %[[NV]] : index
// CHECK: cf.assert %[[SAME]], "solve: the matrix over ('q', 'v') is not square (its sets differ in size) (loops-solve-two-sets.mlir:[[@LINE+7]]:8)"
// CHECK: call @simit_rt_solve_bcsr(
func.func @solve() -> !Xv attributes {simit.export} {
  %e = simit.get_set @e : !Es
  %q = simit.get_set @q : !Qs
  %A = simit.assemble @couple() to %e reduce <add> : (!Es) -> !A
  %b = simit.field_read %q["b"] : !Qs -> !Bq
  %x = simit.solve %A, %b : !A, !Bq -> !Xv
  return %x : !Xv
}
