// RUN: simit-opt %s --simit-lower-assertions | FileCheck %s

// A failed assertion calls the runtime with its message; the run ends there.
// CHECK: llvm.mlir.global internal constant @[[MSG_GLOBAL:simit_str_[0-9A-F]+]]("index out of range (prog.sim:2:3)\00")
// CHECK-LABEL: func.func @checked(
// CHECK-SAME: %[[OK:.*]]: i1)
// CHECK: %[[FAILED:.*]] = arith.xori %[[OK]], %true
// CHECK: scf.if %[[FAILED]] {
// CHECK:   %[[MSG:.*]] = llvm.mlir.addressof @[[MSG_GLOBAL]]
// CHECK:   func.call @simit_rt_fail(%[[MSG]]) : (!llvm.ptr) -> ()
// CHECK: }
// CHECK-NOT: cf.assert
func.func @checked(%ok : i1) {
  cf.assert %ok, "index out of range (prog.sim:2:3)"
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
