// convert-simit-to-loops calls the runtime's scan after each op that
// simit-check-numerics marked, once per float system tensor result: the
// array as memref<*xf64>, its layout (0 vector, 1 diagonal, 2 BCSR pattern,
// 3 incidence rows of perRow blocks), perRow, the index arrays the layout
// reads (the pattern's rowptr/colidx bindings, the edge set's endpoints
// flattened; else an empty stack slot at the function entry), and the
// strings: op, result name, row set, column set; then, for a map over an
// edge set whose endpoints are the result's row (and column) set, the
// set's endpoints flattened, its cardinality and its name (else the empty
// array, 0 and "").
// RUN: simit-translate --import-sim %S/Inputs/check-numerics.sim --print-locations | simit-opt --simit-inline-functions --simit-check-numerics --simit-linalg-to-index-expr --simit-fuse-index-expr --convert-simit-to-loops | FileCheck %s

// CHECK-DAG: llvm.mlir.global internal constant @[[ASM:simit_str_[0-9A-F]+]]("map spring to springs (check-numerics.sim:26:10)\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[SOLVE:simit_str_[0-9A-F]+]]("solve (check-numerics.sim:22:9)\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[K:simit_str_[0-9A-F]+]]("K\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[F:simit_str_[0-9A-F]+]]("f\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[SOLUTION:simit_str_[0-9A-F]+]]("solution\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[POINTS:simit_str_[0-9A-F]+]]("points\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[SPRINGS:simit_str_[0-9A-F]+]]("springs\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[APPLY:simit_str_[0-9A-F]+]]("apply shift to points (check-numerics.sim:28:3)\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[POINTSX:simit_str_[0-9A-F]+]]("points.x\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[NONE:simit_str_[0-9A-F]+]]("\00")

// CHECK-LABEL: func.func @step(
// CHECK-SAME: %[[ENDS:[^:]*]]: memref<?x2xi32>, %[[XARG:[^:]*]]: memref<?xf64>
// CHECK-SAME: %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>)
// Each scan casts its array to an unranked memref inside an alloca scope:
// the descriptor's stack slot is freed after the call, so scans in a loop
// do not grow the stack.
// One empty index array serves every scan that needs none.
// CHECK: %[[EMPTY:.*]] = memref.cast %{{.*}} : memref<0xi32> to memref<?xi32>
// The assembly over springs: K (BCSR), then f (vector), each with the
// springs' endpoints.
// CHECK: %[[KENDS:.*]] = memref.collapse_shape %[[ENDS]] {{\[\[}}0, 1]] : memref<?x2xi32> into memref<?xi32>
// CHECK-NEXT: %[[PATTERN:.*]] = arith.constant 2 : i32
// CHECK-NEXT: %[[ZERO:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[WHAT:.*]] = llvm.mlir.addressof @[[ASM]]
// CHECK-NEXT: %[[NAME:.*]] = llvm.mlir.addressof @[[K]]
// CHECK-NEXT: %[[ROWS:.*]] = llvm.mlir.addressof @[[POINTS]]
// CHECK-NEXT: %[[COLS:.*]] = llvm.mlir.addressof @[[POINTS]]
// CHECK-NEXT: %[[CARD:.*]] = arith.constant 2 : i64
// CHECK-NEXT: %[[MAPSET:.*]] = llvm.mlir.addressof @[[SPRINGS]]
// CHECK-NEXT: memref.alloca_scope {
// CHECK-NEXT: %[[KARRAY:.*]] = memref.cast %{{.*}} : memref<?xf64> to memref<*xf64>
// CHECK-NEXT: call @simit_rt_check_numerics_f64(%[[KARRAY]], %[[PATTERN]], %[[ZERO]], %[[ROWPTR]], %[[COLIDX]], %[[WHAT]], %[[NAME]], %[[ROWS]], %[[COLS]], %[[KENDS]], %[[CARD]], %[[MAPSET]])
// CHECK: %[[FENDS:.*]] = memref.collapse_shape %[[ENDS]]
// CHECK-NEXT: %[[VECTOR:.*]] = arith.constant 0 : i32
// CHECK-NEXT: %[[ZERO:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[WHAT:.*]] = llvm.mlir.addressof @[[ASM]]
// CHECK-NEXT: %[[NAME:.*]] = llvm.mlir.addressof @[[F]]
// CHECK-NEXT: %[[ROWS:.*]] = llvm.mlir.addressof @[[POINTS]]
// CHECK-NEXT: %[[COLS:.*]] = llvm.mlir.addressof @[[NONE]]
// CHECK-NEXT: %[[CARD:.*]] = arith.constant 2 : i64
// CHECK-NEXT: %[[MAPSET:.*]] = llvm.mlir.addressof @[[SPRINGS]]
// CHECK-NEXT: memref.alloca_scope {
// CHECK-NEXT: %[[FARRAY:.*]] = memref.cast %{{.*}} : memref<?xf64> to memref<*xf64>
// CHECK-NEXT: call @simit_rt_check_numerics_f64(%[[FARRAY]], %[[VECTOR]], %[[ZERO]], %[[EMPTY]], %[[EMPTY]], %[[WHAT]], %[[NAME]], %[[ROWS]], %[[COLS]], %[[FENDS]], %[[CARD]], %[[MAPSET]])
// The solve's result, after the call of the solver.
// CHECK: call @simit_rt_solve_bcsr(
// CHECK-NEXT: %[[VECTOR:.*]] = arith.constant 0 : i32
// CHECK-NEXT: %[[ZERO:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[WHAT:.*]] = llvm.mlir.addressof @[[SOLVE]]
// CHECK-NEXT: %[[NAME:.*]] = llvm.mlir.addressof @[[SOLUTION]]
// CHECK-NEXT: %[[ROWS:.*]] = llvm.mlir.addressof @[[POINTS]]
// CHECK-NEXT: %[[COLS:.*]] = llvm.mlir.addressof @[[NONE]]
// CHECK-NEXT: %[[NOCARD:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[NOSET:.*]] = llvm.mlir.addressof @[[NONE]]
// CHECK-NEXT: memref.alloca_scope {
// CHECK-NEXT: %[[X:.*]] = memref.cast %{{.*}} : memref<?xf64> to memref<*xf64>
// CHECK-NEXT: call @simit_rt_check_numerics_f64(%[[X]], %[[VECTOR]], %[[ZERO]], %[[EMPTY]], %[[EMPTY]], %[[WHAT]], %[[NAME]], %[[ROWS]], %[[COLS]], %[[EMPTY]], %[[NOCARD]], %[[NOSET]])
// The apply of shift writes the field points.x (the bound array): scanned
// as a vector over points, named "points.x".
// CHECK: scf.parallel
// CHECK: %[[VECTOR:.*]] = arith.constant 0 : i32
// CHECK-NEXT: %[[ZERO:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[WHAT:.*]] = llvm.mlir.addressof @[[APPLY]]
// CHECK-NEXT: %[[NAME:.*]] = llvm.mlir.addressof @[[POINTSX]]
// CHECK-NEXT: %[[ROWS:.*]] = llvm.mlir.addressof @[[POINTS]]
// CHECK-NEXT: %[[COLS:.*]] = llvm.mlir.addressof @[[NONE]]
// CHECK-NEXT: %[[NOCARD:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[NOSET:.*]] = llvm.mlir.addressof @[[NONE]]
// CHECK-NEXT: memref.alloca_scope {
// CHECK-NEXT: %[[XFIELD:.*]] = memref.cast %[[XARG]] : memref<?xf64> to memref<*xf64>
// CHECK-NEXT: call @simit_rt_check_numerics_f64(%[[XFIELD]], %[[VECTOR]], %[[ZERO]], %[[EMPTY]], %[[EMPTY]], %[[WHAT]], %[[NAME]], %[[ROWS]], %[[COLS]], %[[EMPTY]], %[[NOCARD]], %[[NOSET]])
// CHECK-NOT: call @simit_rt_check_numerics
// CHECK: return

// A sparse solve is scanned after the runtime's solve writes its result.
// CHECK-LABEL: func.func @direct(
// CHECK: call @simit_rt_lu_bcsr(
// CHECK-NOT: call @simit_rt_check_numerics
// CHECK: call @simit_rt_lusolve_bcsr(
// CHECK: memref.alloca_scope {
// CHECK-NEXT: memref.cast %{{.*}} : memref<?xf64> to memref<*xf64>
// CHECK-NEXT: call @simit_rt_check_numerics_f64(

// A diagonal matrix (layout 1) and an incidence matrix (layout 3, two
// blocks a row, the endpoints as column indices). Neither names assembling
// elements: the diagonal's map is over points itself, and the incidence
// matrix's rows are the springs themselves.
// CHECK-LABEL: func.func @storages(
// CHECK-SAME: %[[ENDPOINTS:[^:]*]]: memref<?x2xi32>
// CHECK: %[[DIAGONAL:.*]] = arith.constant 1 : i32
// CHECK-NEXT: %[[ZERO:.*]] = arith.constant 0 : i64
// CHECK: call @simit_rt_check_numerics_f64(%{{[^,]*}}, %[[DIAGONAL]], %[[ZERO]],
// CHECK: %[[TWO:.*]] = arith.constant 2 : i64
// CHECK-NEXT: %[[COLUMNS:.*]] = memref.collapse_shape %[[ENDPOINTS]] {{\[\[}}0, 1]] : memref<?x2xi32> into memref<?xi32>
// CHECK-NEXT: %[[INCIDENCE:.*]] = arith.constant 3 : i32
// CHECK: %[[NOCARD:.*]] = arith.constant 0 : i64
// CHECK-NEXT: %[[NOSET:.*]] = llvm.mlir.addressof @[[NONE]]
// CHECK-NEXT: memref.alloca_scope {
// CHECK-NEXT: memref.cast %{{.*}} : memref<?xf64> to memref<*xf64>
// CHECK-NEXT: call @simit_rt_check_numerics_f64(%{{[^,]*}}, %[[INCIDENCE]], %[[TWO]], %{{[^,]*}}, %[[COLUMNS]], %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}}, %[[NOCARD]], %[[NOSET]])

// CHECK: func.func private @simit_rt_check_numerics_f64(memref<*xf64>, i32, i64, memref<?xi32>, memref<?xi32>, !llvm.ptr, !llvm.ptr, !llvm.ptr, !llvm.ptr, memref<?xi32>, i64, !llvm.ptr) attributes {llvm.emit_c_interface}
