// RUN: simit-opt %s --split-input-file --verify-diagnostics --convert-simit-to-loops | FileCheck %s

// The dense solver runtime functions: local tensors are stored to stack
// buffers passed as memref<?xf64> (row-major), the factorisation handle is an
// !llvm.ptr, tensor results come back through a buffer, and i64 sizes are
// appended (n for lu/chol/triangularSolve, the columns of a matrix
// right-hand side). Declarations are retyped and get llvm.emit_c_interface
// (the JIT binds _mlir_ciface_simit_rt_<name>), except the frees.

// CHECK-LABEL: func.func @lumat
// CHECK-SAME: (%[[A:.*]]: vector<9xf64>, %[[B:.*]]: vector<6xf64>) -> vector<6xf64>
// CHECK-DAG: %[[XBUF:.*]] = memref.alloca() : memref<6xf64>
// CHECK-DAG: %[[BBUF:.*]] = memref.alloca() : memref<6xf64>
// CHECK-DAG: %[[ABUF:.*]] = memref.alloca() : memref<9xf64>
// CHECK: vector.store %[[A]], %[[ABUF]][%{{.*}}] : memref<9xf64>, vector<9xf64>
// CHECK: %[[AC:.*]] = memref.cast %[[ABUF]] : memref<9xf64> to memref<?xf64>
// CHECK: %[[N:.*]] = arith.constant 3 : i64
// CHECK: %[[H:.*]] = call @simit_rt_lu(%[[AC]], %[[N]]) : (memref<?xf64>, i64) -> !llvm.ptr
// CHECK: vector.store %[[B]], %[[BBUF]]
// CHECK: %[[BC:.*]] = memref.cast %[[BBUF]] : memref<6xf64> to memref<?xf64>
// CHECK: %[[XC:.*]] = memref.cast %[[XBUF]] : memref<6xf64> to memref<?xf64>
// CHECK: %[[K:.*]] = arith.constant 2 : i64
// CHECK: call @simit_rt_lumatsolve(%[[H]], %[[BC]], %[[XC]], %[[K]]) : (!llvm.ptr, memref<?xf64>, memref<?xf64>, i64) -> ()
// CHECK: %[[X:.*]] = vector.load %[[XBUF]][%{{.*}}] : memref<6xf64>, vector<6xf64>
// CHECK: call @simit_rt_lufree(%[[H]]) : (!llvm.ptr) -> ()
// CHECK: return %[[X]] : vector<6xf64>
// CHECK-DAG: func.func private @simit_rt_lu(memref<?xf64>, i64) -> !llvm.ptr attributes {llvm.emit_c_interface, simit.runtime_function = "lu"}
// CHECK-DAG: func.func private @simit_rt_lumatsolve(!llvm.ptr, memref<?xf64>, memref<?xf64>, i64) attributes {llvm.emit_c_interface, simit.runtime_function = "lumatsolve"}
// CHECK-DAG: func.func private @simit_rt_lufree(!llvm.ptr) attributes {simit.runtime_function = "lufree"}
func.func @lumat(%a: tensor<3x3xf64>, %b: tensor<3x2xf64>) -> tensor<3x2xf64> attributes {simit.export} {
  %h = call @simit_rt_lu(%a) : (tensor<3x3xf64>) -> !simit.opaque
  %x = call @simit_rt_lumatsolve(%h, %b) : (!simit.opaque, tensor<3x2xf64>) -> tensor<3x2xf64>
  call @simit_rt_lufree(%h) : (!simit.opaque) -> ()
  return %x : tensor<3x2xf64>
}
func.func private @simit_rt_lu(tensor<3x3xf64>) -> !simit.opaque attributes {simit.runtime_function = "lu"}
func.func private @simit_rt_lumatsolve(!simit.opaque, tensor<3x2xf64>) -> tensor<3x2xf64> attributes {simit.runtime_function = "lumatsolve"}
func.func private @simit_rt_lufree(!simit.opaque) attributes {simit.runtime_function = "lufree"}

// -----

// CHECK-LABEL: func.func @cholesky
// CHECK: %[[H:.*]] = call @simit_rt_chol(%{{.*}}, %{{.*}}) : (memref<?xf64>, i64) -> !llvm.ptr
// CHECK: call @simit_rt_lltsolve(%[[H]], %{{.*}}, %{{.*}}) : (!llvm.ptr, memref<?xf64>, memref<?xf64>) -> ()
// CHECK: %[[X:.*]] = vector.load %{{.*}} : memref<2xf64>, vector<2xf64>
// CHECK: call @simit_rt_cholfree(%[[H]]) : (!llvm.ptr) -> ()
// CHECK: %[[T:.*]] = arith.constant 2 : i64
// CHECK: call @simit_rt_triangularSolve(%{{.*}}, %{{.*}}, %{{.*}}, %[[T]]) : (memref<?xf64>, memref<?xf64>, memref<?xf64>, i64) -> ()
// CHECK-DAG: func.func private @simit_rt_chol(memref<?xf64>, i64) -> !llvm.ptr attributes {llvm.emit_c_interface, simit.runtime_function = "chol"}
// CHECK-DAG: func.func private @simit_rt_lltsolve(!llvm.ptr, memref<?xf64>, memref<?xf64>) attributes {llvm.emit_c_interface, simit.runtime_function = "lltsolve"}
// CHECK-DAG: func.func private @simit_rt_cholfree(!llvm.ptr) attributes {simit.runtime_function = "cholfree"}
// CHECK-DAG: func.func private @simit_rt_triangularSolve(memref<?xf64>, memref<?xf64>, memref<?xf64>, i64) attributes {llvm.emit_c_interface, simit.runtime_function = "triangularSolve"}
func.func @cholesky(%a: tensor<2x2xf64>, %b: tensor<2xf64>) -> tensor<2xf64> attributes {simit.export} {
  %h = call @simit_rt_chol(%a) : (tensor<2x2xf64>) -> !simit.opaque
  %x = call @simit_rt_lltsolve(%h, %b) : (!simit.opaque, tensor<2xf64>) -> tensor<2xf64>
  call @simit_rt_cholfree(%h) : (!simit.opaque) -> ()
  %y = call @simit_rt_triangularSolve(%a, %x) : (tensor<2x2xf64>, tensor<2xf64>) -> tensor<2xf64>
  return %y : tensor<2xf64>
}
func.func private @simit_rt_chol(tensor<2x2xf64>) -> !simit.opaque attributes {simit.runtime_function = "chol"}
func.func private @simit_rt_lltsolve(!simit.opaque, tensor<2xf64>) -> tensor<2xf64> attributes {simit.runtime_function = "lltsolve"}
func.func private @simit_rt_cholfree(!simit.opaque) attributes {simit.runtime_function = "cholfree"}
func.func private @simit_rt_triangularSolve(tensor<2x2xf64>, tensor<2xf64>) -> tensor<2xf64> attributes {simit.runtime_function = "triangularSolve"}

// -----

// Only dense local f64 operands are supported.
func.func @bad(%a: tensor<2x3xf64>) attributes {simit.export} {
  // expected-error @below {{'@simit_rt_lu' is supported by the loop lowering on dense local f64 matrices and vectors (and opaque handles) only}}
  %h = call @simit_rt_lu(%a) : (tensor<2x3xf64>) -> !simit.opaque
  return
}
func.func private @simit_rt_lu(tensor<2x3xf64>) -> !simit.opaque attributes {simit.runtime_function = "lu"}
