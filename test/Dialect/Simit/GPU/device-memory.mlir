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
// CHECK:         %[[DX:.*]] = gpu.alloc (%{{.*}}) : memref<?xf64>
// CHECK-NEXT:    gpu.memcpy %[[DX]], %[[X]]
// CHECK:         %[[DY:.*]] = gpu.alloc (%{{.*}}) : memref<?xf64>
// CHECK-NEXT:    gpu.memcpy %[[DY]], %[[Y]]
// CHECK:         %[[TMP:.*]] = memref.alloc(%[[N]]) : memref<?xf64>
// CHECK-NEXT:    %[[DIM:.*]] = memref.dim %[[TMP]]
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
// CHECK-NEXT:    gpu.dealloc %[[DX]]
// CHECK-NEXT:    gpu.dealloc %[[DY]]
// CHECK-NEXT:    gpu.memcpy %[[X]], %[[DX]]
// CHECK-NEXT:    gpu.dealloc %[[DX]]
// CHECK-NEXT:    return
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
