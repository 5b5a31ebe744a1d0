// Explicit Euler under gravity, at the loops level with the host ABI of
// docs/lowering.md: v += h g, then x += h v, for every point.
func.func @step(%n: index, %x: memref<?x3xf64>, %v: memref<?x3xf64>,
                %h: memref<f64>, %g: memref<3xf64>)
    attributes {simit.bindings = [
      {kind = "set_size", set = "points"},
      {kind = "field", set = "points", field = "x"},
      {kind = "field", set = "points", field = "v"},
      {kind = "extern", name = "h"},
      {kind = "extern", name = "g"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %hv = memref.load %h[] : memref<f64>
  scf.for %i = %c0 to %n step %c1 {
    scf.for %j = %c0 to %c3 step %c1 {
      %gj = memref.load %g[%j] : memref<3xf64>
      %vij = memref.load %v[%i, %j] : memref<?x3xf64>
      %dv = arith.mulf %hv, %gj : f64
      %v1 = arith.addf %vij, %dv : f64
      memref.store %v1, %v[%i, %j] : memref<?x3xf64>
      %xij = memref.load %x[%i, %j] : memref<?x3xf64>
      %dx = arith.mulf %hv, %v1 : f64
      %x1 = arith.addf %xij, %dx : f64
      memref.store %x1, %x[%i, %j] : memref<?x3xf64>
    }
  }
  return
}
