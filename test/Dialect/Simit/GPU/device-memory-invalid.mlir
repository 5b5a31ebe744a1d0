// RUN: simit-opt %s --simit-gpu-device-memory --split-input-file --verify-diagnostics

// A kernel on a view would need the view's elements copied apart from the
// memref they alias.
func.func @view(%n: index, %x: memref<?x3xf64>) {
  %c1 = arith.constant 1 : index
  // expected-error @+1 {{a kernel uses a view of another memref; the GPU path copies whole memrefs and cannot keep aliases consistent}}
  %v = memref.cast %x : memref<?x3xf64> to memref<?x?xf64>
  gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
             threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
    %e = memref.load %v[%bx, %bx] : memref<?x?xf64>
    gpu.terminator
  }
  return
}

// -----

// expected-error @+1 {{a kernel uses 'memref<?xf64, strided<[2]>>', but the GPU path copies only ranked memrefs with the identity layout in the default memory space}}
func.func @strided(%n: index, %x: memref<?xf64, strided<[2]>>) {
  %c1 = arith.constant 1 : index
  gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
             threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
    %e = memref.load %x[%bx] : memref<?xf64, strided<[2]>>
    gpu.terminator
  }
  return
}

// -----

// A memref passed on by a nested region's terminator would have a second
// name that the copies do not follow.
func.func @yielded(%n: index, %x: memref<?xf64>) -> memref<?xf64> {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %r = scf.for %i = %c0 to %n step %c1 iter_args(%it = %x) -> memref<?xf64> {
    gpu.launch blocks(%bx, %by, %bz) in (%gx = %n, %gy = %c1, %gz = %c1)
               threads(%tx, %ty, %tz) in (%sx = %c1, %sy = %c1, %sz = %c1) {
      %e = memref.load %x[%bx] : memref<?xf64>
      gpu.terminator
    }
    // expected-error @+1 {{'scf.yield' op passes on a memref that a kernel uses; the GPU path cannot follow it through control flow}}
    scf.yield %x : memref<?xf64>
  }
  return %r : memref<?xf64>
}
