// RUN: simit-opt %s --split-input-file --verify-diagnostics --convert-simit-to-loops | FileCheck %s

// Factorisations and solves of local tensors call the runtime's dense
// solvers: tensors are stored to stack buffers passed as memref<?xf64>
// (row-major), the factorisation handle is an !llvm.ptr, tensor results come
// back through a buffer, and i64 sizes are appended (n for lu/chol/
// triangularSolve, the columns of a matrix right-hand side). The
// declarations get llvm.emit_c_interface (the JIT binds
// _mlir_ciface_simit_rt_<name>), except the frees.

// CHECK: func.func private @simit_rt_lufree(!llvm.ptr, !llvm.ptr){{$}}
// CHECK-LABEL: func.func @lumat
// CHECK-SAME: (%[[A:.*]]: vector<9xf64>, %[[B:.*]]: vector<6xf64>) -> vector<6xf64>
// CHECK-DAG: %[[XBUF:.*]] = memref.alloca() : memref<6xf64>
// CHECK-DAG: %[[BBUF:.*]] = memref.alloca() : memref<6xf64>
// CHECK-DAG: %[[ABUF:.*]] = memref.alloca() : memref<9xf64>
// CHECK: %[[AC:.*]] = memref.cast %[[ABUF]] : memref<9xf64> to memref<?xf64>
// CHECK: vector.store %[[A]], %[[ABUF]][%{{.*}}] : memref<9xf64>, vector<9xf64>
// CHECK: %[[N:.*]] = arith.constant 3 : i64
// CHECK: %[[H:.*]] = call @simit_rt_lu(%[[AC]], %[[N]], %{{.*}}) : (memref<?xf64>, i64, !llvm.ptr) -> !llvm.ptr
// CHECK: %[[BC:.*]] = memref.cast %[[BBUF]] : memref<6xf64> to memref<?xf64>
// CHECK: vector.store %[[B]], %[[BBUF]]
// CHECK: %[[XC:.*]] = memref.cast %[[XBUF]] : memref<6xf64> to memref<?xf64>
// CHECK: %[[K:.*]] = arith.constant 2 : i64
// CHECK: call @simit_rt_lumatsolve(%[[H]], %[[BC]], %[[XC]], %[[K]], %{{.*}}) : (!llvm.ptr, memref<?xf64>, memref<?xf64>, i64, !llvm.ptr) -> ()
// CHECK: %[[X:.*]] = vector.load %[[XBUF]][%{{.*}}] : memref<6xf64>, vector<6xf64>
// CHECK: call @simit_rt_lufree(%[[H]], %{{.*}}) : (!llvm.ptr, !llvm.ptr) -> ()
// CHECK: return %[[X]] : vector<6xf64>
// CHECK-DAG: func.func private @simit_rt_lu(memref<?xf64>, i64, !llvm.ptr) -> !llvm.ptr attributes {llvm.emit_c_interface}
// CHECK-DAG: func.func private @simit_rt_lumatsolve(!llvm.ptr, memref<?xf64>, memref<?xf64>, i64, !llvm.ptr) attributes {llvm.emit_c_interface}
func.func @lumat(%a: tensor<3x3xf64>, %b: tensor<3x2xf64>) -> tensor<3x2xf64> attributes {simit.export} {
  %h = simit.factorize lu %a : tensor<3x3xf64>
  %x = simit.factor_solve lu %h, %b : tensor<3x2xf64> -> tensor<3x2xf64>
  simit.factor_free lu %h
  return %x : tensor<3x2xf64>
}

// -----

// CHECK: func.func private @simit_rt_cholfree(!llvm.ptr, !llvm.ptr){{$}}
// CHECK-LABEL: func.func @cholesky
// CHECK: %[[H:.*]] = call @simit_rt_chol(%{{.*}}, %{{.*}}, %{{.*}}) : (memref<?xf64>, i64, !llvm.ptr) -> !llvm.ptr
// CHECK: call @simit_rt_lltsolve(%[[H]], %{{.*}}, %{{.*}}, %{{.*}}) : (!llvm.ptr, memref<?xf64>, memref<?xf64>, !llvm.ptr) -> ()
// CHECK: %[[X:.*]] = vector.load %{{.*}} : memref<2xf64>, vector<2xf64>
// CHECK: call @simit_rt_cholfree(%[[H]], %{{.*}}) : (!llvm.ptr, !llvm.ptr) -> ()
// CHECK: %[[T:.*]] = arith.constant 2 : i64
// CHECK: call @simit_rt_triangularSolve(%{{.*}}, %{{.*}}, %{{.*}}, %[[T]], %{{.*}}) : (memref<?xf64>, memref<?xf64>, memref<?xf64>, i64, !llvm.ptr) -> ()
// CHECK-DAG: func.func private @simit_rt_chol(memref<?xf64>, i64, !llvm.ptr) -> !llvm.ptr attributes {llvm.emit_c_interface}
// CHECK-DAG: func.func private @simit_rt_lltsolve(!llvm.ptr, memref<?xf64>, memref<?xf64>, !llvm.ptr) attributes {llvm.emit_c_interface}
// CHECK-DAG: func.func private @simit_rt_triangularSolve(memref<?xf64>, memref<?xf64>, memref<?xf64>, i64, !llvm.ptr) attributes {llvm.emit_c_interface}
func.func @cholesky(%a: tensor<2x2xf64>, %b: tensor<2xf64>) -> tensor<2xf64> attributes {simit.export} {
  %h = simit.factorize chol %a : tensor<2x2xf64>
  %x = simit.factor_solve chol %h, %b : tensor<2xf64> -> tensor<2xf64>
  simit.factor_free chol %h
  %y = simit.triangular_solve %a, %x : tensor<2x2xf64>, tensor<2xf64> -> tensor<2xf64>
  return %y : tensor<2xf64>
}

// -----

// Two sizes of one factorisation share the runtime function (the size is an
// argument).
// CHECK-LABEL: func.func @two_sizes
// CHECK: call @simit_rt_lu(%{{.*}}, %{{.*}}, %{{.*}}) : (memref<?xf64>, i64, !llvm.ptr) -> !llvm.ptr
// CHECK: call @simit_rt_lu(%{{.*}}, %{{.*}}, %{{.*}}) : (memref<?xf64>, i64, !llvm.ptr) -> !llvm.ptr
func.func @two_sizes(%a: tensor<2x2xf64>, %b: tensor<3x3xf64>) attributes {simit.export} {
  %h = simit.factorize lu %a : tensor<2x2xf64>
  %g = simit.factorize lu %b : tensor<3x3xf64>
  simit.factor_free lu %h
  simit.factor_free lu %g
  return
}

// -----

// With float32 the operands are widened to f64 for the runtime and the
// result rounded back.
// CHECK-LABEL: func.func @solve_f32
// CHECK-SAME: (%[[A:.*]]: vector<4xf32>, %[[B:.*]]: vector<2xf32>) -> vector<2xf32>
// CHECK: %[[AW:.*]] = arith.extf %[[A]] : vector<4xf32> to vector<4xf64>
// CHECK: vector.store %[[AW]]
// CHECK: call @simit_rt_lu(
// CHECK: %[[BW:.*]] = arith.extf %[[B]] : vector<2xf32> to vector<2xf64>
// CHECK: vector.store %[[BW]]
// CHECK: call @simit_rt_lusolve(
// CHECK: %[[XW:.*]] = vector.load %{{.*}} : memref<2xf64>, vector<2xf64>
// CHECK: %[[X:.*]] = arith.truncf %[[XW]] : vector<2xf64> to vector<2xf32>
// CHECK: return %[[X]] : vector<2xf32>
func.func @solve_f32(%a: tensor<2x2xf32>, %b: tensor<2xf32>) -> tensor<2xf32> attributes {simit.export} {
  %h = simit.factorize lu %a : tensor<2x2xf32>
  %x = simit.factor_solve lu %h, %b : tensor<2xf32> -> tensor<2xf32>
  simit.factor_free lu %h
  return %x : tensor<2xf32>
}

// -----

// The runtime's dense solvers take f64 (and f32, widened) only.
func.func @bad(%a: tensor<2x2xf16>) attributes {simit.export} {
  // expected-error @below {{'lu' is supported by the loop lowering on dense local float matrices and vectors of static shapes, its result of the right-hand side's type}}
  %h = simit.factorize lu %a : tensor<2x2xf16>
  return
}
