// RUN: simit-opt %s --simit-gpu-scatter-atomics --simit-parallel-loops-to-gpu \
// RUN:   --simit-gpu-device-memory --gpu-launch-sink-index-computations \
// RUN:   --gpu-kernel-outlining | FileCheck %s --check-prefix=KERNEL
// RUN: simit-opt %s --simit-gpu-pipeline | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' \
// RUN:   | FileCheck %s --check-prefix=PTX
// RUN: %if ptxas %{ simit-opt %s --simit-gpu-pipeline=format=bin \
// RUN:   | FileCheck %s --check-prefix=CUBIN %}

// Springs sharing a vertex write the same force entry and the same BCSR
// block, so every scatter is an atomic add on the device; the difference
// vector d stays in the thread's private memory.

// KERNEL-LABEL: func.func @assemble_springs
// KERNEL:         gpu.launch_func @assemble_springs_kernel::@assemble_springs_kernel
// The forces and the matrix come back to the host; positions do not.
// KERNEL-NOT:     gpu.memcpy %arg3,
// KERNEL-DAG:     gpu.memcpy %arg5, %{{.*}} : memref<?x3x3xf64>, memref<?x3x3xf64>
// KERNEL-DAG:     gpu.memcpy %arg6, %{{.*}} : memref<?x3xf64>, memref<?x3xf64>
// KERNEL:         return

// KERNEL:       gpu.func @assemble_springs_kernel(
// KERNEL-SAME:      %[[N:[^:]*]]: index, %[[ENDS:[^:]*]]: memref<?x2xi32>, %[[X:[^:]*]]: memref<?x3xf64>, %[[K:[^:]*]]: f64, %[[F:[^:]*]]: memref<?x3xf64>, %[[LOC:[^:]*]]: memref<?x4xi32>, %[[VALS:[^:]*]]: memref<?x3x3xf64>) kernel
// KERNEL:         %[[E:.*]] = arith.addi %{{.*}}, %{{.*}}thread_id_x
// KERNEL:         %[[IN:.*]] = arith.cmpi ult, %[[E]], %[[N]]
// KERNEL:         scf.if %[[IN]] {
// KERNEL:           %[[A32:.*]] = memref.load %[[ENDS]][%[[E]], %c0]
// KERNEL:           %[[B32:.*]] = memref.load %[[ENDS]][%[[E]], %c1]
// KERNEL:           %[[A:.*]] = arith.index_cast %[[A32]]
// KERNEL:           %[[B:.*]] = arith.index_cast %[[B32]]
// KERNEL:           %[[D:.*]] = memref.alloca() : memref<3xf64>
// KERNEL:           scf.for %[[C:.*]] = %c0 to %c3
// KERNEL:             memref.store %{{.*}}, %[[D]][%[[C]]]
// KERNEL:             %[[FA:.*]] = arith.mulf %[[K]], %{{.*}} fastmath<contract>
// KERNEL:             memref.atomic_rmw addf %[[FA]], %[[F]][%[[A]], %[[C]]]
// KERNEL:             %[[NEG:.*]] = arith.negf %[[FA]]
// KERNEL:             memref.atomic_rmw addf %[[NEG]], %[[F]][%[[B]], %[[C]]]
// KERNEL:           scf.for %[[I:.*]] = %c0 to %c2
// KERNEL:             scf.for %[[J:.*]] = %c0 to %c2
// KERNEL:               %[[L32:.*]] = memref.load %[[LOC]][%[[E]], %{{.*}}] : memref<?x4xi32>
// KERNEL:               %[[L:.*]] = arith.index_cast %[[L32]]
// KERNEL:               scf.for %[[R:.*]] = %c0 to %c3
// KERNEL:                 scf.for %[[CC:.*]] = %c0 to %c3
// KERNEL-NOT:               memref.store
// KERNEL:                   memref.atomic_rmw addf %{{.*}}, %[[VALS]][%[[L]], %[[R]], %[[CC]]] : (f64, memref<?x3x3xf64>) -> f64
// KERNEL:         gpu.return

// 6 force updates and 4 blocks of 9 entries: 42 atomic adds once unrolled.
// PTX:     .target sm_90
// PTX:     .visible .entry assemble_springs_kernel(
// PTX-COUNT-42: atom.global.add.f64
// PTX-NOT: atom.global
// PTX:     ret;

// Assembly of a spring system: each spring e = (a, b) adds k (xb - xa) to
// the force of a and subtracts it from b's, and adds the stiffness block
// s k d d^T (s = +1 on the diagonal blocks, -1 off it) into the BCSR block
// that the location table gives for endpoint pair (i, j): loc[e][2 i + j].
func.func @assemble_springs(%n: index, %endpoints: memref<?x2xi32>,
                            %loc: memref<?x4xi32>, %x: memref<?x3xf64>,
                            %k: f64, %vals: memref<?x3x3xf64>,
                            %f: memref<?x3xf64>)
    attributes {llvm.emit_c_interface} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %c3 = arith.constant 3 : index
  scf.parallel (%e) = (%c0) to (%n) step (%c1) {
    %a32 = memref.load %endpoints[%e, %c0] : memref<?x2xi32>
    %b32 = memref.load %endpoints[%e, %c1] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b = arith.index_cast %b32 : i32 to index
    %d = memref.alloca() : memref<3xf64>
    scf.for %c = %c0 to %c3 step %c1 {
      %xa = memref.load %x[%a, %c] : memref<?x3xf64>
      %xb = memref.load %x[%b, %c] : memref<?x3xf64>
      %dc = arith.subf %xb, %xa : f64
      memref.store %dc, %d[%c] : memref<3xf64>
      %fa = arith.mulf %k, %dc : f64
      %fa_old = memref.load %f[%a, %c] : memref<?x3xf64>
      %fa_new = arith.addf %fa_old, %fa : f64
      memref.store %fa_new, %f[%a, %c] : memref<?x3xf64>
      %fb_old = memref.load %f[%b, %c] : memref<?x3xf64>
      %fb_new = arith.subf %fb_old, %fa : f64
      memref.store %fb_new, %f[%b, %c] : memref<?x3xf64>
    }
    %kneg = arith.negf %k : f64
    scf.for %i = %c0 to %c2 step %c1 {
      scf.for %j = %c0 to %c2 step %c1 {
        %i2 = arith.muli %i, %c2 : index
        %blk = arith.addi %i2, %j : index
        %l32 = memref.load %loc[%e, %blk] : memref<?x4xi32>
        %l = arith.index_cast %l32 : i32 to index
        %diag = arith.cmpi eq, %i, %j : index
        %s = arith.select %diag, %k, %kneg : f64
        scf.for %r = %c0 to %c3 step %c1 {
          %dr = memref.load %d[%r] : memref<3xf64>
          %sdr = arith.mulf %s, %dr : f64
          scf.for %cc = %c0 to %c3 step %c1 {
            %dc = memref.load %d[%cc] : memref<3xf64>
            %kij = arith.mulf %sdr, %dc : f64
            %old = memref.load %vals[%l, %r, %cc] : memref<?x3x3xf64>
            %new = arith.addf %old, %kij : f64
            memref.store %new, %vals[%l, %r, %cc] : memref<?x3x3xf64>
          }
        }
      }
    }
    scf.reduce
  }
  return
}

// ptxas accepts the generated assembly and makes an sm_90 ELF cubin.
// CUBIN: gpu.binary @assemble_springs_kernel [#gpu.object<#nvvm.target<O = 3, chip = "sm_90", features = "+ptx80">, properties = {{.*}}, bin = "\7FELF
