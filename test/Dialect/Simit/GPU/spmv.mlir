// RUN: simit-opt %s --simit-gpu-scatter-atomics --simit-parallel-loops-to-gpu \
// RUN:   --simit-gpu-device-memory | FileCheck %s --check-prefix=LAUNCH
// RUN: simit-opt %s --simit-gpu-scatter-atomics --simit-parallel-loops-to-gpu \
// RUN:   --simit-gpu-device-memory --gpu-launch-sink-index-computations \
// RUN:   --gpu-kernel-outlining | FileCheck %s --check-prefix=KERNEL
// RUN: simit-opt %s --simit-gpu-pipeline | FileCheck %s --check-prefix=HOST
// RUN: simit-opt %s --simit-gpu-pipeline | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' \
// RUN:   | FileCheck %s --check-prefix=PTX
// RUN: %if ptxas %{ simit-opt %s --simit-gpu-pipeline=format=bin \
// RUN:   | FileCheck %s --check-prefix=CUBIN %}

// One thread per block row: 256-thread blocks, ceil(rows / 256) of them, the
// matrix, x and the pattern copied to the device once, y copied back.

// LAUNCH-LABEL: func.func @spmv
// LAUNCH-SAME:    (%[[ROWS:.*]]: index, %[[ROWPTR:.*]]: memref<?xi32>, %{{.*}}: memref<?xi32>, %[[VALS:.*]]: memref<?x3x3xf64>, %[[X:.*]]: memref<?x3xf64>, %[[Y:.*]]: memref<?x3xf64>)
// LAUNCH:         %[[DROWPTR:.*]] = gpu.alloc (%{{.*}}) : memref<?xi32>
// LAUNCH-NEXT:    gpu.memcpy %[[DROWPTR]], %[[ROWPTR]]
// LAUNCH:         %[[DVALS:.*]] = gpu.alloc (%{{.*}}) : memref<?x3x3xf64>
// LAUNCH-NEXT:    gpu.memcpy %[[DVALS]], %[[VALS]]
// LAUNCH:         %[[DX:.*]] = gpu.alloc (%{{.*}}) : memref<?x3xf64>
// LAUNCH-NEXT:    gpu.memcpy %[[DX]], %[[X]]
// LAUNCH:         %[[DY:.*]] = gpu.alloc (%{{.*}}) : memref<?x3xf64>
// LAUNCH-NEXT:    gpu.memcpy %[[DY]], %[[Y]]
// LAUNCH:         %[[TRIPS:.*]] = arith.maxsi %[[ROWS]], %c0
// LAUNCH:         %[[C256:.*]] = arith.constant 256 : index
// LAUNCH:         %[[NB:.*]] = arith.ceildivui %[[TRIPS]], %[[C256]]
// LAUNCH:         %[[GRID:.*]] = arith.maxui %[[NB]], %c1
// LAUNCH:         gpu.launch blocks(%[[BX:.*]], %{{.*}}, %{{.*}}) in (%{{.*}} = %[[GRID]], %{{.*}} = %c1{{.*}}, %{{.*}} = %c1{{.*}}) threads(%[[TX:.*]], %{{.*}}, %{{.*}}) in (%{{.*}} = %[[C256]],
// LAUNCH:           %[[BASE:.*]] = arith.muli %[[BX]], %[[C256]]
// LAUNCH:           %[[ROW:.*]] = arith.addi %[[BASE]], %[[TX]]
// LAUNCH:           %[[IN:.*]] = arith.cmpi ult, %[[ROW]], %[[TRIPS]]
// LAUNCH:           scf.if %[[IN]] {
// LAUNCH:             memref.load %[[DROWPTR]][%[[ROW]]]
// LAUNCH:             scf.for
// LAUNCH:               scf.for
// LAUNCH:                 scf.for
// LAUNCH:                   memref.load %[[DVALS]]
// LAUNCH:                   memref.load %[[DX]]
// LAUNCH:                   arith.mulf {{.*}} fastmath<contract>
// LAUNCH:                   arith.addf {{.*}} fastmath<contract>
// LAUNCH:               memref.store %{{.*}}, %[[DY]][%[[ROW]], %{{.*}}]
// LAUNCH:           gpu.terminator
// LAUNCH-NOT:     gpu.memcpy %[[VALS]]
// LAUNCH-NOT:     gpu.memcpy %[[X]]
// LAUNCH:         gpu.memcpy %[[Y]], %[[DY]]
// LAUNCH-NEXT:    gpu.dealloc %[[DY]]
// LAUNCH-NEXT:    return

// KERNEL:       gpu.launch_func @spmv_kernel::@spmv_kernel blocks in (%{{.*}}, %{{.*}}, %{{.*}}) threads in (%{{.*}}, %{{.*}}, %{{.*}}) args(%{{.*}} : index, %{{.*}} : memref<?xi32>, %{{.*}} : memref<?xi32>, %{{.*}} : memref<?x3x3xf64>, %{{.*}} : memref<?x3xf64>, %{{.*}} : memref<?x3xf64>)
// KERNEL:       gpu.module @spmv_kernel
// KERNEL:         gpu.func @spmv_kernel({{.*}}) kernel attributes {known_block_size = array<i32: 256, 1, 1>}
// KERNEL:           gpu.block_id x
// KERNEL:           gpu.thread_id x
// KERNEL-NOT:       memref.atomic_rmw
// KERNEL:           gpu.return

// The host calls the GPU runtime: device buffers, copies, the launch.
// HOST-LABEL: llvm.func @spmv(
// HOST:         llvm.call @mgpuMemAlloc
// HOST:         llvm.call @mgpuMemcpy
// HOST:         gpu.launch_func <%{{.*}} : !llvm.ptr> @spmv_kernel::@spmv_kernel
// HOST:         llvm.call @mgpuMemcpy
// HOST:         llvm.call @mgpuMemFree
// HOST-LABEL: llvm.func @_mlir_ciface_spmv(
// HOST:       gpu.binary @spmv_kernel [#gpu.object<#nvvm.target<O = 3, chip = "sm_90", features = "+ptx80">

// PTX:      .version 8.0
// PTX-NEXT: .target sm_90
// PTX-NEXT: .address_size 64
// PTX:      .visible .entry spmv_kernel(
// PTX:      .maxntid 256, 1, 1
// PTX:      mov.u32 {{.*}}%ctaid.x
// PTX:      mov.u32 {{.*}}%tid.x
// rowptr and colidx are 32-bit, the block entries and x 64-bit floats.
// PTX:      ld.global.b32
// PTX:      ld.global.b64
// PTX:      fma.rn.f64
// PTX:      st.global.b64
// PTX-NOT:  atom.
// PTX:      ret;

// y = A x with A a BCSR matrix of 3x3 blocks on the pattern of an edge set:
// one iteration per block row, a sparse loop over rowptr/colidx, dense loops
// over the block.
func.func @spmv(%rows: index, %rowptr: memref<?xi32>, %colidx: memref<?xi32>,
                %vals: memref<?x3x3xf64>, %x: memref<?x3xf64>,
                %y: memref<?x3xf64>) attributes {llvm.emit_c_interface} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %zero = arith.constant 0.0 : f64
  scf.parallel (%i) = (%c0) to (%rows) step (%c1) {
    %i1 = arith.addi %i, %c1 : index
    %begin32 = memref.load %rowptr[%i] : memref<?xi32>
    %end32 = memref.load %rowptr[%i1] : memref<?xi32>
    %begin = arith.index_cast %begin32 : i32 to index
    %end = arith.index_cast %end32 : i32 to index
    scf.for %r = %c0 to %c3 step %c1 {
      %sum = scf.for %p = %begin to %end step %c1 iter_args(%acc = %zero) -> (f64) {
        %j32 = memref.load %colidx[%p] : memref<?xi32>
        %j = arith.index_cast %j32 : i32 to index
        %row = scf.for %c = %c0 to %c3 step %c1 iter_args(%acc2 = %acc) -> (f64) {
          %a = memref.load %vals[%p, %r, %c] : memref<?x3x3xf64>
          %xj = memref.load %x[%j, %c] : memref<?x3xf64>
          %prod = arith.mulf %a, %xj : f64
          %next = arith.addf %acc2, %prod : f64
          scf.yield %next : f64
        }
        scf.yield %row : f64
      }
      memref.store %sum, %y[%i, %r] : memref<?x3xf64>
    }
    scf.reduce
  }
  return
}

// ptxas accepts the generated assembly and makes an sm_90 ELF cubin.
// CUBIN: gpu.binary @spmv_kernel [#gpu.object<#nvvm.target<O = 3, chip = "sm_90", features = "+ptx80">, properties = {{.*}}, bin = "\7FELF
