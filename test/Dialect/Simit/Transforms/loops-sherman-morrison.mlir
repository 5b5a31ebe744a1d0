// RUN: simit-opt %s --simit-sherman-morrison --convert-simit-to-loops | FileCheck %s

// The rewritten solve lowered to loops: two calls of the runtime's `\`
// whose `where` says which Sherman–Morrison solve they are (so --stats
// tells them apart), and the last step on BCSR arrays, which names the
// statement too.

!Point = !simit.element<"Point", {u : f64, v : f64, b : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @link(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%a, %a] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

// CHECK-DAG: llvm.mlir.global internal constant @[[SOLVEU:.*]]("solve [Sherman-Morrison A^-1 u] (loops-sherman-morrison.mlir:[[@LINE+21]]:8)\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[SOLVEB:.*]]("solve [Sherman-Morrison A^-1 b] (loops-sherman-morrison.mlir:[[@LINE+20]]:8)\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[LAST:.*]]("Sherman-Morrison (loops-sherman-morrison.mlir:[[@LINE+19]]:8)\00")
// CHECK-LABEL: func.func @rank_one(
// CHECK: %[[WU:.*]] = llvm.mlir.addressof @[[SOLVEU]]
// CHECK: call @simit_rt_solve_bcsr(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %[[WU]])
// CHECK: %[[WB:.*]] = llvm.mlir.addressof @[[SOLVEB]]
// CHECK: call @simit_rt_solve_bcsr(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %[[WB]])
// CHECK: %[[WL:.*]] = llvm.mlir.addressof @[[LAST]]
// CHECK: call @simit_rt_sherman_morrison_bcsr(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %[[WL]]) : (memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, !llvm.ptr) -> ()
// CHECK-NOT: simit.outer
// CHECK: func.func private @simit_rt_sherman_morrison_bcsr(memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, !llvm.ptr) attributes {llvm.emit_c_interface}
func.func @rank_one() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %u = simit.field_read %points["u"] : !Points -> !V
  %v = simit.field_read %points["v"] : !Points -> !V
  %b = simit.field_read %points["b"] : !Points -> !V
  %uv = simit.outer %u, %v : !V, !V -> !A
  %M = simit.add %A, %uv : !A
  %x = simit.solve %M, %b : !A, !V -> !V
  return %x : !V
}
