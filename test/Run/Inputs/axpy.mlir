// Parameters in, mixed results out: (a * x + y, a + x(0), n + 1).
func.func @axpy(%a: f64, %x: memref<3xf64>, %y: memref<3xf64>, %n: i32)
    -> (memref<3xf64>, f64, i32)
    attributes {simit.bindings = [
      {kind = "param", index = 0}, {kind = "param", index = 1},
      {kind = "param", index = 2}, {kind = "param", index = 3}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1 : i32
  %r = memref.alloc() : memref<3xf64>
  scf.for %i = %c0 to %c3 step %c1 {
    %xi = memref.load %x[%i] : memref<3xf64>
    %yi = memref.load %y[%i] : memref<3xf64>
    %p = arith.mulf %a, %xi : f64
    %s = arith.addf %p, %yi : f64
    memref.store %s, %r[%i] : memref<3xf64>
  }
  %x0 = memref.load %x[%c0] : memref<3xf64>
  %ax = arith.addf %a, %x0 : f64
  %n1 = arith.addi %n, %one : i32
  return %r, %ax, %n1 : memref<3xf64>, f64, i32
}

// The transpose of a 2 x 3 matrix and whether its (0, 1) entry is positive.
func.func @flip(%m: memref<2x3xf64>) -> (memref<3x2xf64>, i1)
    attributes {simit.bindings = [{kind = "param", index = 0}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %c3 = arith.constant 3 : index
  %zero = arith.constant 0.0 : f64
  %t = memref.alloc() : memref<3x2xf64>
  scf.for %i = %c0 to %c2 step %c1 {
    scf.for %j = %c0 to %c3 step %c1 {
      %v = memref.load %m[%i, %j] : memref<2x3xf64>
      memref.store %v, %t[%j, %i] : memref<3x2xf64>
    }
  }
  %m01 = memref.load %m[%c0, %c1] : memref<2x3xf64>
  %positive = arith.cmpf ogt, %m01, %zero : f64
  return %t, %positive : memref<3x2xf64>, i1
}
