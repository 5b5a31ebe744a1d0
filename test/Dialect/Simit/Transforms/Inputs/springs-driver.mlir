// Host data of e2e-springs.mlir: three points on a path of two springs,
// their BCSR pattern as SparsityPattern builds it, and a driver that calls
// the lowered @step in its `simit.bindings` order and prints the results.
  memref.global "private" @x : memref<3x3xf64> = dense<[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 2.0, 0.0]]>
  memref.global "private" @v : memref<3x3xf64> = dense<[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]>
  memref.global "private" @m : memref<3xf64> = dense<[1.0, 2.0, 3.0]>
  memref.global "private" @k : memref<2xf64> = dense<[10.0, 20.0]>
  memref.global "private" @ends : memref<2x2xi32> = dense<[[0, 1], [1, 2]]>
  // Row 0: columns 0 1; row 1: 0 1 2; row 2: 1 2.
  memref.global "private" @rowptr : memref<4xi32> = dense<[0, 2, 5, 7]>
  memref.global "private" @colidx : memref<7xi32> = dense<[0, 1, 0, 1, 2, 1, 2]>
  // Blocks of (e0, e0), (e0, e1), (e1, e0), (e1, e1) of each spring.
  memref.global "private" @loc : memref<2x4xi32> = dense<[[0, 1, 2, 3], [3, 4, 5, 6]]>
  memref.global "private" @h : memref<f64> = dense<0.5>
  memref.global "private" @out : memref<f64> = dense<0.0>

  func.func private @printMemrefF64(memref<*xf64>) attributes {llvm.emit_c_interface}

  func.func @main() {
    %points = arith.constant 3 : index
    %springs = arith.constant 2 : index
    %x0 = memref.get_global @x : memref<3x3xf64>
    %v0 = memref.get_global @v : memref<3x3xf64>
    %m0 = memref.get_global @m : memref<3xf64>
    %k0 = memref.get_global @k : memref<2xf64>
    %e0 = memref.get_global @ends : memref<2x2xi32>
    %r0 = memref.get_global @rowptr : memref<4xi32>
    %c0 = memref.get_global @colidx : memref<7xi32>
    %l0 = memref.get_global @loc : memref<2x4xi32>
    %h = memref.get_global @h : memref<f64>
    %out = memref.get_global @out : memref<f64>
    %x = memref.cast %x0 : memref<3x3xf64> to memref<?x3xf64>
    %v = memref.cast %v0 : memref<3x3xf64> to memref<?x3xf64>
    %m = memref.cast %m0 : memref<3xf64> to memref<?xf64>
    %k = memref.cast %k0 : memref<2xf64> to memref<?xf64>
    %e = memref.cast %e0 : memref<2x2xi32> to memref<?x2xi32>
    %r = memref.cast %r0 : memref<4xi32> to memref<?xi32>
    %c = memref.cast %c0 : memref<7xi32> to memref<?xi32>
    %l = memref.cast %l0 : memref<2x4xi32> to memref<?x4xi32>
    func.call @step(%points, %springs, %e, %m, %v, %x, %k, %r, %c, %l, %h, %out)
        : (index, index, memref<?x2xi32>, memref<?xf64>, memref<?x3xf64>,
           memref<?x3xf64>, memref<?xf64>, memref<?xi32>, memref<?xi32>,
           memref<?x4xi32>, memref<f64>, memref<f64>) -> ()
    %vu = memref.cast %v0 : memref<3x3xf64> to memref<*xf64>
    func.call @printMemrefF64(%vu) : (memref<*xf64>) -> ()
    %ou = memref.cast %out : memref<f64> to memref<*xf64>
    func.call @printMemrefF64(%ou) : (memref<*xf64>) -> ()
    return
  }
