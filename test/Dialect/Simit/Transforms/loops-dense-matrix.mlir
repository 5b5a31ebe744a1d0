// RUN: simit-opt %s --simit-assign-storage | FileCheck %s --check-prefix=STORAGE
// RUN: simit-opt %s --simit-assign-storage --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops | FileCheck %s

// X = lumatsolve(lu(A), B) is dense (A^-1 B fills in every block):
// simit-assign-storage gives it #simit.storage<dense>, and the loop lowering
// stores block (r, c) at r * |cols| + c. It is solved column by column: B's
// column j is gathered into a vector (zero where B's pattern has no block,
// found by a search of the row), solved with the runtime's vector solve and
// written into X's column j. X * x then loops over whole sets, reading X
// at r * |cols| + c without a search.

!Point = !simit.element<"Point", {x : f64, y : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @link(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%a, %b] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

// STORAGE-LABEL: func.func @matsolve(
// STORAGE: simit.factor_solve lu %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x f64, #pat_springs> -> !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>

// CHECK-LABEL: func.func @matsolve(
// CHECK-SAME: %[[NP:[^:]*]]: index
// CHECK: %[[H:.*]] = call @simit_rt_lu_bcsr(
// CHECK: %[[COLUMN:.*]] = memref.alloc(%[[NP]]) : memref<?xf64>
// CHECK: %[[SOLUTION:.*]] = memref.alloc(%[[NP]]) : memref<?xf64>
// CHECK: %[[BLOCKS:.*]] = arith.muli %[[NP]], %[[NP]] : index
// CHECK: %[[X:.*]] = memref.alloc(%[[BLOCKS]]) : memref<?xf64>
// CHECK: scf.for %[[J:.*]] = %{{.*}} to %[[NP]]
// CHECK:   scf.for %[[R:.*]] = %{{.*}} to %[[NP]]
// CHECK:     scf.for
// CHECK:     memref.store %{{.*}}, %[[COLUMN]][%[[R]]] : memref<?xf64>
// CHECK:   call @simit_rt_lusolve_bcsr(%[[H]], %{{.*}}, %{{.*}}, %{{.*}})
// CHECK:   scf.for %[[R2:.*]] = %{{.*}} to %[[NP]]
// CHECK:     %[[ROW:.*]] = arith.muli %[[R2]], %[[NP]] : index
// CHECK:     %[[AT:.*]] = arith.addi %[[ROW]], %[[J]] : index
// CHECK:     %[[V:.*]] = memref.load %[[SOLUTION]][%[[R2]]] : memref<?xf64>
// CHECK:     memref.store %[[V]], %[[X]][%[[AT]]] : memref<?xf64>
// CHECK: call @simit_rt_lufree(%[[H]], %{{.*}})
// The product X * x over whole sets, X read at r * |points| + c.
// CHECK: scf.parallel (%[[I:.*]]) = (%{{.*}}) to (%[[NP]])
// CHECK:   scf.for %[[C:.*]] = %{{.*}} to %[[NP]]
// CHECK:     %[[IR:.*]] = arith.muli %[[I]], %[[NP]] : index
// CHECK:     %[[IC:.*]] = arith.addi %[[IR]], %[[C]] : index
// CHECK:     memref.load %[[X]][%[[IC]]] : memref<?xf64>
func.func @matsolve() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %h = simit.factorize lu %A : !A
  %X = simit.factor_solve lu %h, %A : !A -> !A
  simit.factor_free lu %h
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %X, %x : !A, !V -> !V
  simit.field_write %y, %points["y"] : !V, !Points
  return
}

// A product with a dense factor is dense: the runtime's product reads the
// dense matrices row by row (layout 3, no index arrays).
// CHECK-LABEL: func.func @dense_product(
// CHECK: %[[DENSE:.*]] = arith.constant 3 : i32
// CHECK: %[[BCSR:.*]] = arith.constant 0 : i32
// CHECK: %[[RESULT:.*]] = arith.constant 3 : i32
// CHECK: call @simit_rt_matmul_bcsr(%[[DENSE]], %[[NONE:[^,]*]], %[[NONE]], %[[NONE]], %{{[^,]*}}, %[[BCSR]], %{{[^,]*}}, %{{[^,]*}}, %[[NONE]], %{{[^,]*}}, %[[RESULT]], %[[NONE]], %[[NONE]],
func.func @dense_product() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %h = simit.factorize lu %A : !A
  %X = simit.factor_solve lu %h, %A : !A -> !A
  simit.factor_free lu %h
  %XA = simit.matmul %X, %A : !A, !A -> !A
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %XA, %x : !A, !V -> !V
  simit.field_write %y, %points["y"] : !V, !Points
  return
}

// A dense matrix is factorised as BCSR with every block: row r's blocks
// start at r * |points| and hold the columns 0 .. |points| - 1, the dense
// layout's order, so the values array is passed as it is.
// CHECK-LABEL: func.func @dense_factorised(
// CHECK-SAME: %[[NP:[^:]*]]: index
// CHECK: %[[BLOCKS:.*]] = arith.muli %[[NP]], %[[NP]] : index
// CHECK: %[[X:.*]] = memref.alloc(%[[BLOCKS]]) : memref<?xf64>
// CHECK: call @simit_rt_lufree(
// CHECK: %[[ROWPTR:.*]] = memref.alloc(%{{.*}}) : memref<?xi32>
// CHECK: %[[ALL:.*]] = arith.muli %[[NP]], %[[NP]] : index
// CHECK: %[[COLIDX:.*]] = memref.alloc(%[[ALL]]) : memref<?xi32>
// CHECK: scf.for %[[R:[^ ]*]] =
// CHECK:   %[[FIRST:.*]] = arith.muli %[[R]], %[[NP]] : index
// CHECK:   %[[FIRST32:.*]] = arith.index_cast %[[FIRST]] : index to i32
// CHECK:   memref.store %[[FIRST32]], %[[ROWPTR]][%[[R]]]
// CHECK:   scf.if
// CHECK:     scf.for %[[C:[^ ]*]] = %{{.*}} to %[[NP]]
// CHECK:       %[[AT:.*]] = arith.addi %[[FIRST]], %[[C]] : index
// CHECK:       %[[C32:.*]] = arith.index_cast %[[C]] : index to i32
// CHECK:       memref.store %[[C32]], %[[COLIDX]][%[[AT]]]
// CHECK: %[[VALUES:.*]] = memref.expand_shape %[[X]]
// CHECK: %[[CAST:.*]] = memref.cast %[[VALUES]]
// CHECK: call @simit_rt_lu_bcsr(%[[ROWPTR]], %[[COLIDX]], %[[CAST]],
func.func @dense_factorised() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %h = simit.factorize lu %A : !A
  %X = simit.factor_solve lu %h, %A : !A -> !A
  simit.factor_free lu %h
  %g = simit.factorize lu %X : !A
  simit.factor_free lu %g
  return
}
