// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-assign-storage --convert-simit-to-loops --canonicalize | FileCheck %s

// A host function's matrix result: the host stores three pointers
// (row pointers, column indices, blocks) into stack slots; the runtime
// checks them and counts the blocks, the lowered code allocates arrays of
// its own, and the runtime copies into them (through a shim whose memref
// parameters the buffer deallocation sees). The product then reads those
// arrays as any BCSR matrix's.

!Point = !simit.element<"Point", {x : f64, y : f64}>
!Points = !simit.set<"points", !Point>
!K = !simit.tensor<["points", "points"] x f64>
!X = !simit.tensor<["points"] x f64>
simit.extern @points : !Points
func.func private @tridiagonal() -> !K attributes {simit.extern_function = "tridiagonal"}

// CHECK-LABEL: func.func @main(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[X:[^:]*]]: memref<?xf64>, %[[Y:[^:]*]]: memref<?xf64>)
// CHECK-DAG: %[[BLOCKS:.*]] = memref.alloca() : memref<1x!llvm.ptr>
// CHECK-DAG: %[[COLIDX:.*]] = memref.alloca() : memref<1x!llvm.ptr>
// CHECK-DAG: %[[ROWPTR:.*]] = memref.alloca() : memref<1x!llvm.ptr>
// CHECK: call @simit_host.dtridiagonal(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %c1_i32, %c1_i32, %{{.*}})
// Functions with matrix results may return void (the original runtime's
// tests declare them so): no status check, the arrays are checked.
// CHECK-NOT: cf.assert
// CHECK: %[[R:.*]] = memref.load %[[ROWPTR]][%c0]
// CHECK: %[[C:.*]] = memref.load %[[COLIDX]][%c0]
// CHECK: %[[B:.*]] = memref.load %[[BLOCKS]][%c0]
// CHECK: %[[COUNT:.*]] = call @simit_rt_host_matrix_blocks(%[[R]], %[[C]], %[[B]], %{{.*}}, %{{.*}}, %{{.*}}) : (!llvm.ptr, !llvm.ptr, !llvm.ptr, i64, i64, !llvm.ptr) -> i64
// CHECK: %[[NB:.*]] = arith.index_cast %[[COUNT]] : i64 to index
// CHECK: %[[NR:.*]] = arith.addi %[[N]], %c1 : index
// CHECK: %[[RP:.*]] = memref.alloc(%[[NR]]) : memref<?xi32>
// CHECK: %[[CI:.*]] = memref.alloc(%[[NB]]) : memref<?xi32>
// CHECK: %[[V:.*]] = memref.alloc(%[[NB]]) : memref<?xf64>
// CHECK: call @simit_host.simit_rt_host_matrix_adopt(%[[R]], %[[C]], %[[B]], %{{.*}}, %c8_i64, %[[RP]], %[[CI]], %[[V]])
// CHECK: scf.parallel (%[[I:[^)]*]]) =
// CHECK: memref.load %[[RP]][%[[I]]]
// CHECK: scf.for %[[K:[^ ]*]] =
// CHECK: memref.load %[[CI]][%[[K]]]
// CHECK: memref.load %[[V]][%[[K]]]
func.func @main() attributes {simit.export} {
  %T = func.call @tridiagonal() : () -> !K loc("h.sim":3:5)
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !X
  %y = simit.matvec %T, %x : !K, !X -> !X
  simit.field_write %y, %points["y"] : !X, !Points
  return
}
