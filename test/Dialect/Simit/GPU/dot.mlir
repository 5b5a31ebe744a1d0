// RUN: simit-opt %s --simit-gpu-scatter-atomics --simit-parallel-loops-to-gpu \
// RUN:   --simit-gpu-device-memory | FileCheck %s --check-prefix=LAUNCH
// RUN: simit-opt %s --simit-gpu-scatter-atomics --simit-parallel-loops-to-gpu \
// RUN:   --simit-gpu-device-memory --gpu-launch-sink-index-computations \
// RUN:   --gpu-kernel-outlining | FileCheck %s --check-prefix=KERNEL
// RUN: simit-opt %s --simit-gpu-pipeline | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' \
// RUN:   | FileCheck %s --check-prefix=PTX
// RUN: %if ptxas %{ simit-opt %s --simit-gpu-pipeline=format=bin \
// RUN:   | FileCheck %s --check-prefix=CUBIN %}

// Each thread computes its vertex's partial (0 when out of range), the block
// sums them with gpu.all_reduce, thread 0 adds the block's sum atomically
// into a device scalar that starts at the loop's initial value, and the host
// reads the result back after the launch.

// LAUNCH-LABEL: func.func @dot
// LAUNCH:         %[[ACC:.*]] = memref.alloca() : memref<f64>
// LAUNCH-NEXT:    %[[DACC:.*]] = gpu.alloc () : memref<f64>
// LAUNCH:         %[[INIT:.*]] = arith.constant 0.0
// The initial value overwrites the whole accumulator: no copy back first.
// LAUNCH-NOT:     gpu.memcpy %[[ACC]]
// LAUNCH:         memref.store %[[INIT]], %[[ACC]][]
// LAUNCH-NEXT:    gpu.memcpy %[[DACC]], %[[ACC]]
// LAUNCH:         gpu.launch
// LAUNCH:           %[[IN:.*]] = arith.cmpi ult
// LAUNCH:           %[[PARTIAL:.*]] = scf.if %[[IN]] -> (f64) {
// LAUNCH:             %[[SUM:.*]] = scf.for
// LAUNCH:             scf.yield %[[SUM]] : f64
// LAUNCH:           } else {
// LAUNCH:             %[[ZERO:.*]] = arith.constant 0.0
// LAUNCH:             scf.yield %[[ZERO]] : f64
// LAUNCH:           }
// LAUNCH:           %[[BLOCK:.*]] = gpu.all_reduce add %[[PARTIAL]] uniform
// LAUNCH:           %[[FIRST:.*]] = arith.cmpi eq, %{{.*}}, %c0
// LAUNCH:           scf.if %[[FIRST]] {
// LAUNCH:             memref.atomic_rmw addf %[[BLOCK]], %[[DACC]][] : (f64, memref<f64>) -> f64
// LAUNCH:           }
// LAUNCH:           gpu.terminator
// LAUNCH:         gpu.memcpy %[[ACC]], %[[DACC]]
// LAUNCH-NEXT:    %[[RESULT:.*]] = memref.load %[[ACC]][]
// The vectors were only read: nothing else is copied back.
// LAUNCH-NOT:     gpu.memcpy %arg
// LAUNCH:         return %[[RESULT]] : f64

// KERNEL:       gpu.func @dot_kernel(
// KERNEL:         gpu.all_reduce add
// KERNEL:         memref.atomic_rmw addf

// The block reduction is a butterfly of warp shuffles (a double is two
// 32-bit halves), then shared memory across the warps.
// PTX:      .visible .entry dot_kernel(
// PTX:      .shared .align 8 .b8 __wg_dot_kernel_0[256];
// PTX:      fma.rn.f64
// PTX:      shfl.sync.bfly.b32
// PTX:      st.shared.b64
// PTX:      bar.sync 0;
// PTX:      shfl.sync.bfly.b32
// PTX:      st.shared.b64 [__wg_dot_kernel_0], %{{.*}};
// PTX:      bar.sync 0;
// Thread 0 alone adds the block's sum to the accumulator.
// PTX-NEXT: setp.ne.b32 %[[NOTFIRST:p[0-9]+]], %r{{[0-9]+}}, 0;
// PTX-NEXT: @%[[NOTFIRST]] bra
// PTX-NEXT: ld.shared.b64 %[[SUM:rd[0-9]+]], [__wg_dot_kernel_0];
// PTX-NEXT: atom.global.add.f64 %rd{{[0-9]+}}, [%rd{{[0-9]+}}], %[[SUM]];
// PTX-NOT:  atom.global
// PTX:      ret;

// The dot product of two vectors over a vertex set (3 components each), a
// scalar reduction that the loop returns.
func.func @dot(%n: index, %a: memref<?x3xf64>, %b: memref<?x3xf64>) -> f64
    attributes {llvm.emit_c_interface} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %zero = arith.constant 0.0 : f64
  %dot = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%zero) -> f64 {
    %partial = scf.for %k = %c0 to %c3 step %c1 iter_args(%acc = %zero) -> (f64) {
      %ai = memref.load %a[%i, %k] : memref<?x3xf64>
      %bi = memref.load %b[%i, %k] : memref<?x3xf64>
      %prod = arith.mulf %ai, %bi : f64
      %next = arith.addf %acc, %prod : f64
      scf.yield %next : f64
    }
    scf.reduce(%partial : f64) {
    ^bb0(%lhs: f64, %rhs: f64):
      %s = arith.addf %lhs, %rhs : f64
      scf.reduce.return %s : f64
    }
  }
  return %dot : f64
}

// ptxas accepts the generated assembly and makes an sm_90 ELF cubin.
// CUBIN: gpu.binary @dot_kernel [#gpu.object<#nvvm.target<O = 3, chip = "sm_90", features = "+ptx80">, properties = {{.*}}, bin = "\7FELF
