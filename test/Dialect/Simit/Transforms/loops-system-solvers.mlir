// RUN: simit-opt %s --split-input-file --verify-diagnostics \
// RUN:   --convert-simit-to-loops | FileCheck %s

// Solvers on system matrices of scalars: the arrays gain unit block
// dimensions (memref.expand_shape) before the cast to the dynamic BCSR
// shapes of the runtime. simit.factorize and simit.factor_solve on system
// tensors call the _bcsr runtime functions; simit.factor_free calls the
// (shared) free.

!Point = !simit.element<"Point", {b : f64}>
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

// CHECK-LABEL: func.func @cholesky(
// CHECK-SAME: %[[NP:[^:]*]]: index, %{{[^:]*}}: index, %{{[^:]*}}: memref<?x2xi32>, %[[B:[^:]*]]: memref<?xf64>, %{{[^:]*}}: memref<?xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>)
// CHECK: %[[AV:.*]] = memref.alloc(%{{.*}}) : memref<?xf64>
// CHECK: %[[AE:.*]] = memref.expand_shape %[[AV]] {{\[\[}}0, 1, 2]] output_shape [%{{.*}}, 1, 1] : memref<?xf64> into memref<?x1x1xf64>
// CHECK: %[[AC:.*]] = memref.cast %[[AE]] : memref<?x1x1xf64> to memref<?x?x?xf64>
// CHECK: %[[H:.*]] = call @simit_rt_chol_bcsr(%[[ROWPTR]], %[[COLIDX]], %[[AC]], %[[CHOL:.*]]) : (memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, !llvm.ptr) -> !llvm.ptr
// CHECK: %[[X:.*]] = memref.alloc(%[[NP]]) : memref<?xf64>
// CHECK: memref.expand_shape %[[B]] {{\[\[}}0, 1]]
// CHECK: memref.expand_shape %[[X]] {{\[\[}}0, 1]]
// CHECK: call @simit_rt_lltsolve_bcsr(%[[H]], %{{.*}}, %{{.*}}, %{{.*}}) : (!llvm.ptr, memref<?x?xf64>, memref<?x?xf64>, !llvm.ptr) -> ()
// CHECK: call @simit_rt_cholfree(%[[H]], %{{.*}}) : (!llvm.ptr, !llvm.ptr) -> ()
// CHECK: return %[[X]]
func.func @cholesky() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %h = simit.factorize chol %A : !A
  %b = simit.field_read %points["b"] : !Points -> !V
  %x = simit.factor_solve chol %h, %b : !V -> !V
  simit.factor_free chol %h
  return %x : !V
}

// CHECK-LABEL: func.func @backslash(
// CHECK: %[[AE:.*]] = memref.expand_shape %{{.*}} {{\[\[}}0, 1, 2]]
// CHECK: %[[AC:.*]] = memref.cast %[[AE]] : memref<?x1x1xf64> to memref<?x?x?xf64>
// CHECK: call @simit_rt_solve_bcsr(%{{.*}}, %{{.*}}, %[[AC]], %{{.*}}, %{{.*}}, %{{.*}}) : (memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, !llvm.ptr) -> ()
// CHECK-DAG: func.func private @simit_rt_chol_bcsr(memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, !llvm.ptr) -> !llvm.ptr attributes {llvm.emit_c_interface}
// CHECK-DAG: func.func private @simit_rt_lltsolve_bcsr(!llvm.ptr, memref<?x?xf64>, memref<?x?xf64>, !llvm.ptr) attributes {llvm.emit_c_interface}
func.func @backslash() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %b = simit.field_read %points["b"] : !Points -> !V
  %x = simit.solve %A, %b : !A, !V -> !V
  return %x : !V
}

// -----

!Point = !simit.element<"Point", {m : f64, b : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @mass(%p : !Point) -> !A {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %m into %A0[%p, %p] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

// lu of a diagonal matrix: the sparse LU of the runtime, on the identity
// pattern (row pointers 0, 1, ..., n; column r in row r) made for the call.
// CHECK-LABEL: func.func @diagonal
// CHECK: %[[N:.*]] = arith.addi %[[SIZE:.*]], %c1
// CHECK: %[[ROWPTR:.*]] = memref.alloc(%[[N]]) : memref<?xi32>
// CHECK: %[[COLIDX:.*]] = memref.alloc(%[[SIZE]]) : memref<?xi32>
// CHECK: scf.for %[[I:.*]] =
// CHECK:   %[[I32:.*]] = arith.index_cast %[[I]] : index to i32
// CHECK:   memref.store %[[I32]], %[[ROWPTR]][%[[I]]]
// CHECK:   scf.if
// CHECK:     memref.store %[[I32]], %[[COLIDX]][%[[I]]]
// CHECK: call @simit_rt_lu_bcsr(%[[ROWPTR]], %[[COLIDX]],
func.func @diagonal() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %A = simit.assemble @mass() to %points reduce <add> : (!Points) -> !A
  %h = simit.factorize lu %A : !A
  simit.factor_free lu %h
  return
}

// -----

// A solve with a block diagonal matrix (a vertex-set assembly) calls the
// runtime's diagonal form with the statement's position.

!Point = !simit.element<"Point", {m : f64, b : f64}>
!M = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @mass(%p : !Point) -> !M {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %M0 = simit.zeros : !M
  %M1 = simit.insert %m into %M0[%p, %p] : f64 into !M, (!Point, !Point)
  return %M1 : !M
}

// CHECK: llvm.mlir.global internal constant @[[STR:.*]]("solve (loops-system-solvers.mlir:[[@LINE+8]]:8)\00")
// CHECK-LABEL: func.func @backslash_diagonal(
// CHECK: %[[WHERE:.*]] = llvm.mlir.addressof @[[STR]] : !llvm.ptr
// CHECK: call @simit_rt_solve_diag(%{{.*}}, %{{.*}}, %{{.*}}, %[[WHERE]]) : (memref<?x?x?xf64>, memref<?x?xf64>, memref<?x?xf64>, !llvm.ptr) -> ()
func.func @backslash_diagonal() -> !V attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !M
  %b = simit.field_read %points["b"] : !Points -> !V
  %x = simit.solve %M, %b : !M, !V -> !V
  return %x : !V
}
