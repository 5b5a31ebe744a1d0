// RUN: simit-opt %s --simit-gpu-device-memory --split-input-file | FileCheck %s

// Host code between two kernels: a host loop reading and writing x is one
// host-only region, so x comes back before it and goes out after it, once;
// a host read inside a loop that also launches is bracketed on its own; an
// opaque call may read and write. The scratch buffer is freshly allocated
// (no copy in) and freed where the host frees it; x, an argument written by
// a kernel, is copied back before the return; y is never written on the
// device and is not copied back.

func.func private @host_work(memref<?xf64>)

// CHECK-LABEL: func.func @host_between_kernels
// CHECK-SAME:    (%[[N:.*]]: index, %[[X:.*]]: memref<?xf64>, %[[Y:.*]]: memref<?xf64>)
// CHECK-DAG:     %[[DIMX:.*]] = memref.dim %[[X]]
// CHECK-DAG:     %[[DX:.*]] = gpu.alloc (%[[DIMX]]) : memref<?xf64>
// CHECK-DAG:     gpu.memcpy %[[DX]], %[[X]]
// CHECK-DAG:     %[[DIMY:.*]] = memref.dim %[[Y]]
// CHECK-DAG:     %[[DY:.*]] = gpu.alloc (%[[DIMY]]) : memref<?xf64>
// CHECK-DAG:     gpu.memcpy %[[DY]], %[[Y]]
// CHECK:         %[[TMP:.*]] = memref.alloc(%[[N]]) : memref<?xf64>
// CHECK:         %[[DIM:.*]] = memref.dim %[[TMP]]
// CHECK-NEXT:    %[[DTMP:.*]] = gpu.alloc (%[[DIM]]) : memref<?xf64>
// CHECK-NOT:     gpu.memcpy %[[DTMP]]
// CHECK:         gpu.launch
// CHECK:           memref.load %[[DY]]
// CHECK:           memref.store %{{.*}}, %[[DX]]
// CHECK:           memref.store %{{.*}}, %[[DTMP]]
// CHECK:           gpu.terminator
// CHECK-NEXT:    }
// CHECK-NEXT:    gpu.memcpy %[[X]], %[[DX]]
// CHECK-NEXT:    scf.for
// CHECK-NEXT:      memref.load %[[X]]
// CHECK-NEXT:      arith.addf
// CHECK-NEXT:      memref.store %{{.*}}, %[[X]]
// CHECK-NEXT:    }
// CHECK-NEXT:    gpu.memcpy %[[DX]], %[[X]]
// CHECK-NEXT:    scf.for
// CHECK-NEXT:      gpu.launch
// CHECK:           }
// CHECK-NEXT:      gpu.memcpy %[[TMP]], %[[DTMP]]
// CHECK-NEXT:      memref.load %[[TMP]]
// CHECK-NOT:       gpu.memcpy %[[DTMP]], %[[TMP]]
// CHECK:         }
// CHECK-NEXT:    gpu.memcpy %[[X]], %[[DX]]
// CHECK-NEXT:    call @host_work(%[[X]])
// CHECK-NEXT:    gpu.memcpy %[[DX]], %[[X]]
// CHECK-NEXT:    gpu.dealloc %[[DTMP]]
// CHECK-NEXT:    memref.dealloc %[[TMP]]
// CHECK-NOT:     gpu.memcpy %[[Y]]
// CHECK-DAG:     gpu.dealloc %[[DY]]
// CHECK-DAG:     gpu.memcpy %[[X]], %[[DX]]
// CHECK-DAG:     gpu.dealloc %[[DX]]
// CHECK:         return
func.func @host_between_kernels(%n: index, %x: memref<?xf64>, %y: memref<?xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %tmp = memref.alloc(%n) : memref<?xf64>
  gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
             threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
    %v = memref.load %y[%bx] : memref<?xf64>
    memref.store %v, %x[%bx] : memref<?xf64>
    memref.store %v, %tmp[%bx] : memref<?xf64>
    gpu.terminator
  }
  scf.for %i = %c0 to %n step %c1 {
    %v = memref.load %x[%i] : memref<?xf64>
    %w = arith.addf %v, %v : f64
    memref.store %w, %x[%i] : memref<?xf64>
  }
  scf.for %i = %c0 to %n step %c1 {
    gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
               threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
      %v = memref.load %x[%bx] : memref<?xf64>
      memref.store %v, %tmp[%bx] : memref<?xf64>
      gpu.terminator
    }
    %t = memref.load %tmp[%i] : memref<?xf64>
  }
  call @host_work(%x) : (memref<?xf64>) -> ()
  memref.dealloc %tmp : memref<?xf64>
  return
}

// -----

// A memref that lives inside a host loop body gets its device buffer there,
// freed at the end of the body; a scalar the host reads after the kernel
// wrote it comes back right before the read.

// CHECK-LABEL: func.func @per_iteration
// CHECK:         scf.for
// CHECK-NEXT:      %[[ACC:.*]] = memref.alloca() : memref<f64>
// CHECK-NEXT:      %[[DACC:.*]] = gpu.alloc () : memref<f64>
// CHECK-NEXT:      gpu.launch
// CHECK:             memref.atomic_rmw addf %{{.*}}, %[[DACC]][]
// CHECK:           }
// CHECK-NEXT:      gpu.memcpy %[[ACC]], %[[DACC]]
// CHECK-NEXT:      memref.load %[[ACC]][]
// CHECK-NEXT:      gpu.dealloc %[[DACC]]
// CHECK-NEXT:    }
func.func @per_iteration(%n: index, %out: memref<?xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1.0 : f64
  scf.for %i = %c0 to %n step %c1 {
    %acc = memref.alloca() : memref<f64>
    gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
               threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
      %old = memref.atomic_rmw addf %one, %acc[] : (f64, memref<f64>) -> f64
      gpu.terminator
    }
    %v = memref.load %acc[] : memref<f64>
  }
  return
}

// -----

// An initial value stored under a condition does not overwrite the device's
// value for sure, so the accumulator comes back first; the unconditional
// store after the kernel does not need that.

// CHECK-LABEL: func.func @conditional_init
// CHECK:         %[[ACC:.*]] = memref.alloca() : memref<f64>
// CHECK-NEXT:    %[[DACC:.*]] = gpu.alloc () : memref<f64>
// CHECK-NEXT:    gpu.memcpy %[[ACC]], %[[DACC]]
// CHECK-NEXT:    scf.if
// CHECK-NEXT:      memref.store
// CHECK-NEXT:    }
// CHECK-NEXT:    gpu.memcpy %[[DACC]], %[[ACC]]
// CHECK-NEXT:    gpu.launch
// CHECK:         }
// CHECK-NEXT:    memref.store %{{.*}}, %[[ACC]][]
// CHECK-NEXT:    gpu.memcpy %[[DACC]], %[[ACC]]
// CHECK-NEXT:    gpu.dealloc %[[DACC]]
// CHECK-NEXT:    return
func.func @conditional_init(%n: index, %reset: i1) {
  %c1 = arith.constant 1 : index
  %zero = arith.constant 0.0 : f64
  %one = arith.constant 1.0 : f64
  %acc = memref.alloca() : memref<f64>
  scf.if %reset {
    memref.store %zero, %acc[] : memref<f64>
  }
  gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
             threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
    %old = memref.atomic_rmw addf %one, %acc[] : (f64, memref<f64>) -> f64
    gpu.terminator
  }
  memref.store %zero, %acc[] : memref<f64>
  return
}
