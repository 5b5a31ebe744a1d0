// Assembles the scalar spring stiffness K (K(a,a) += k, K(a,b) -= k) into
// the BCSR pattern of (springs; points, points) through the location table,
// then writes f = K u; the host ABI of docs/lowering.md.
func.func @stiffness(%np: index, %ne: index, %k: memref<?xf64>,
    %rowptr: memref<?xi32>, %colidx: memref<?xi32>, %loc: memref<?x4xi32>,
    %u: memref<?xf64>, %f: memref<?xf64>)
    attributes {simit.bindings = [
      {kind = "set_size", set = "points"},
      {kind = "set_size", set = "springs"},
      {kind = "field", set = "springs", field = "k"},
      {kind = "pattern_rowptr", set = "springs", rows = "points", cols = "points"},
      {kind = "pattern_colidx", set = "springs", rows = "points", cols = "points"},
      {kind = "pattern_locations", set = "springs", rows = "points", cols = "points"},
      {kind = "field", set = "points", field = "u"},
      {kind = "field", set = "points", field = "f"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %zero = arith.constant 0.0 : f64
  %nb = memref.dim %colidx, %c0 : memref<?xi32>
  %vals = memref.alloc(%nb) : memref<?xf64>
  scf.for %b = %c0 to %nb step %c1 {
    memref.store %zero, %vals[%b] : memref<?xf64>
  }
  scf.for %e = %c0 to %ne step %c1 {
    %ke = memref.load %k[%e] : memref<?xf64>
    %nk = arith.negf %ke : f64
    scf.for %i = %c0 to %c2 step %c1 {
      scf.for %j = %c0 to %c2 step %c1 {
        %i2 = arith.muli %i, %c2 : index
        %ij = arith.addi %i2, %j : index
        %l32 = memref.load %loc[%e, %ij] : memref<?x4xi32>
        %l = arith.index_cast %l32 : i32 to index
        %same = arith.cmpi eq, %i, %j : index
        %v = arith.select %same, %ke, %nk : f64
        %old = memref.load %vals[%l] : memref<?xf64>
        %new = arith.addf %old, %v : f64
        memref.store %new, %vals[%l] : memref<?xf64>
      }
    }
  }
  scf.for %r = %c0 to %np step %c1 {
    %r1 = arith.addi %r, %c1 : index
    %s32 = memref.load %rowptr[%r] : memref<?xi32>
    %e32 = memref.load %rowptr[%r1] : memref<?xi32>
    %s = arith.index_cast %s32 : i32 to index
    %t = arith.index_cast %e32 : i32 to index
    %sum = scf.for %b = %s to %t step %c1 iter_args(%acc = %zero) -> (f64) {
      %c32 = memref.load %colidx[%b] : memref<?xi32>
      %c = arith.index_cast %c32 : i32 to index
      %a = memref.load %vals[%b] : memref<?xf64>
      %x = memref.load %u[%c] : memref<?xf64>
      %p = arith.mulf %a, %x : f64
      %acc1 = arith.addf %acc, %p : f64
      scf.yield %acc1 : f64
    }
    memref.store %sum, %f[%r] : memref<?xf64>
  }
  return
}
