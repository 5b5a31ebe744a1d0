// Explicit Euler under gravity in single precision, at the loops level with the host ABI of
// docs/lowering.md: v += h g, then x += h v, for every point.
func.func @step(%n: index, %x: memref<?x3xf32>, %v: memref<?x3xf32>,
                %h: memref<f32>, %g: memref<3xf32>)
    attributes {simit.bindings = [
      {kind = "set_size", set = "points"},
      {kind = "field", set = "points", field = "x"},
      {kind = "field", set = "points", field = "v"},
      {kind = "extern", name = "h"},
      {kind = "extern", name = "g"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %hv = memref.load %h[] : memref<f32>
  scf.for %i = %c0 to %n step %c1 {
    scf.for %j = %c0 to %c3 step %c1 {
      %gj = memref.load %g[%j] : memref<3xf32>
      %vij = memref.load %v[%i, %j] : memref<?x3xf32>
      %dv = arith.mulf %hv, %gj : f32
      %v1 = arith.addf %vij, %dv : f32
      memref.store %v1, %v[%i, %j] : memref<?x3xf32>
      %xij = memref.load %x[%i, %j] : memref<?x3xf32>
      %dx = arith.mulf %hv, %v1 : f32
      %x1 = arith.addf %xij, %dx : f32
      memref.store %x1, %x[%i, %j] : memref<?x3xf32>
    }
  }
  return
}
