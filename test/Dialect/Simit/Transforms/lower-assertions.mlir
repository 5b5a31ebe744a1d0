// RUN: simit-opt %s --simit-lower-assertions | FileCheck %s

// What follows an assertion runs only when it holds; otherwise the runtime
// gets its message and the values the rest defines are zeros.
// CHECK: llvm.mlir.global internal constant @[[MSG_GLOBAL:simit_str_[0-9A-F]+]]("index out of range (prog.sim:2:3)\00")
// CHECK-LABEL: func.func @checked(
// CHECK-SAME: %[[OK:.*]]: i1, %[[X:.*]]: f64)
// CHECK: %[[R:.*]] = scf.if %[[OK]] -> (f64) {
// CHECK:   %[[SQ:.*]] = arith.mulf %[[X]], %[[X]]
// CHECK:   scf.yield %[[SQ]] : f64
// CHECK: } else {
// CHECK:   %[[MSG:.*]] = llvm.mlir.addressof @[[MSG_GLOBAL]]
// CHECK:   func.call @simit_rt_fail(%[[MSG]]) : (!llvm.ptr) -> ()
// CHECK:   %[[ZERO:.*]] = arith.constant 0.000000e+00 : f64
// CHECK:   scf.yield %[[ZERO]] : f64
// CHECK: }
// CHECK: return %[[R]] : f64
// CHECK-NOT: cf.assert
func.func @checked(%ok : i1, %x : f64) -> f64 {
  cf.assert %ok, "index out of range (prog.sim:2:3)"
  %sq = arith.mulf %x, %x : f64
  return %sq : f64
}

// Values without a zero (memrefs) come out of the failed branch as poison;
// values used only inside the guarded part stay there.
// CHECK-LABEL: func.func @no_zero(
// CHECK: %[[M:.*]] = scf.if %{{.*}} -> (memref<4xf64>) {
// CHECK:   %[[A:.*]] = memref.alloc()
// CHECK:   memref.store %{{.*}}, %[[A]]
// CHECK:   scf.yield %[[A]]
// CHECK: } else {
// CHECK:   func.call @simit_rt_fail
// CHECK:   %[[P:.*]] = ub.poison : memref<4xf64>
// CHECK:   scf.yield %[[P]]
// CHECK: return %[[M]]
func.func @no_zero(%ok : i1, %v : f64, %i : index) -> memref<4xf64> {
  cf.assert %ok, "index out of range (prog.sim:5:3)"
  %a = memref.alloc() : memref<4xf64>
  memref.store %v, %a[%i] : memref<4xf64>
  return %a : memref<4xf64>
}

// Two assertions in one block nest: the second guards only what follows it.
// CHECK-LABEL: func.func @two(
// CHECK: scf.if %{{.*}} {
// CHECK:   scf.if %{{.*}} {
// CHECK:     memref.store
// CHECK:   } else {
// CHECK:     func.call @simit_rt_fail
// CHECK: } else {
// CHECK:   func.call @simit_rt_fail
func.func @two(%a : i1, %b : i1, %m : memref<4xf64>, %v : f64, %i : index) {
  cf.assert %a, "first (prog.sim:7:3)"
  cf.assert %b, "second (prog.sim:8:3)"
  memref.store %v, %m[%i] : memref<4xf64>
  return
}

// Assertions in GPU launches are left to the NVVM lowering.
// CHECK-LABEL: func.func @in_launch(
// CHECK: gpu.launch
// CHECK:   cf.assert %{{.*}}, "in a kernel"
func.func @in_launch(%ok : i1) {
  %c1 = arith.constant 1 : index
  gpu.launch blocks(%bx, %by, %bz) in (%gx = %c1, %gy = %c1, %gz = %c1)
             threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
    cf.assert %ok, "in a kernel"
    gpu.terminator
  }
  return
}

// The runtime function is declared once, at the end.
// CHECK: func.func private @simit_rt_fail(!llvm.ptr)
