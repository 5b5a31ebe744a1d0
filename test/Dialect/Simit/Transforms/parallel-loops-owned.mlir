// RUN: simit-opt %s --simit-parallel-loops | FileCheck %s

// Loops whose writes are all indexed by the iteration are marked as they
// are; loops the pass cannot prove race-free stay sequential (unmarked).

// A vertex loop writing its own blocks, reading anything.
// CHECK-LABEL: func.func @vertex_update(
// CHECK: scf.parallel
// CHECK: memref.store
// CHECK: } {simit.parallel = "owned"}
func.func @vertex_update(%n : index, %x : memref<?x3xf64>, %v : memref<?x3xf64>, %h : memref<f64>) attributes {simit.bindings = [{kind = "set_size", set = "points"}, {field = "x", kind = "field", set = "points"}, {field = "v", kind = "field", set = "points"}, {kind = "extern", name = "h"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %hv = memref.load %h[] : memref<f64>
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    scf.for %k = %c0 to %c3 step %c1 {
      %vi = memref.load %v[%i, %k] : memref<?x3xf64>
      %xi = memref.load %x[%i, %k] : memref<?x3xf64>
      %d = arith.mulf %hv, %vi : f64
      %s = arith.addf %xi, %d : f64
      memref.store %s, %x[%i, %k] : memref<?x3xf64>
    }
    scf.reduce
  }
  return
}

// Every induction variable of a multi-dimensional loop indexes the store;
// a vector store spans the dimensions after them.
// CHECK-LABEL: func.func @zero_fill(
// CHECK: } {simit.parallel = "owned"}
// CHECK: } {simit.parallel = "owned"}
func.func @zero_fill(%n : index, %a : memref<?x3x3xf64>, %b : memref<?x4xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %zero = arith.constant 0.0 : f64
  %zeros = arith.constant dense<0.0> : vector<4xf64>
  scf.parallel (%i, %j, %k) = (%c0, %c0, %c0) to (%n, %c3, %c3) step (%c1, %c1, %c1) {
    memref.store %zero, %a[%i, %j, %k] : memref<?x3x3xf64>
    scf.reduce
  }
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    vector.store %zeros, %b[%i, %c0] : memref<?x4xf64>, vector<4xf64>
    scf.reduce
  }
  return
}

// Row i writes the blocks rowptr[i] .. rowptr[i+1] of a BCSR matrix (the
// rows' ranges do not overlap) and row i of y.
// CHECK-LABEL: func.func @bcsr_rows(
// CHECK: } {simit.parallel = "owned"}
// CHECK: } {simit.parallel = "owned"}
func.func @bcsr_rows(%n : index, %rowptr : memref<?xi32>, %colidx : memref<?xi32>, %vals : memref<?xf64>, %x : memref<?xf64>, %y : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "points"}, {cols = "points", kind = "pattern_rowptr", rows = "points", set = "springs"}, {cols = "points", kind = "pattern_colidx", rows = "points", set = "springs"}, {index = 0 : i64, kind = "param"}, {index = 1 : i64, kind = "param"}, {index = 2 : i64, kind = "param"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %zero = arith.constant 0.0 : f64
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %i1 = arith.addi %i, %c1 : index
    %lo32 = memref.load %rowptr[%i] : memref<?xi32>
    %lo = arith.index_cast %lo32 : i32 to index
    %hi32 = memref.load %rowptr[%i1] : memref<?xi32>
    %hi = arith.index_cast %hi32 : i32 to index
    scf.for %k = %lo to %hi step %c1 {
      memref.store %zero, %vals[%k] : memref<?xf64>
    }
    scf.reduce
  }
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %i1 = arith.addi %i, %c1 : index
    %lo32 = memref.load %rowptr[%i] : memref<?xi32>
    %lo = arith.index_cast %lo32 : i32 to index
    %hi32 = memref.load %rowptr[%i1] : memref<?xi32>
    %hi = arith.index_cast %hi32 : i32 to index
    scf.for %k = %lo to %hi step %c1 {
      %j32 = memref.load %colidx[%k] : memref<?xi32>
      %j = arith.index_cast %j32 : i32 to index
      %a = memref.load %vals[%k] : memref<?xf64>
      %xj = memref.load %x[%j] : memref<?xf64>
      %p = arith.mulf %a, %xj : f64
      %old = memref.load %y[%i] : memref<?xf64>
      %new = arith.addf %old, %p : f64
      memref.store %new, %y[%i] : memref<?xf64>
    }
    scf.reduce
  }
  return
}

// A row range over an array that is not a row pointer binding may overlap.
// CHECK-LABEL: func.func @ranges_of_a_field(
// CHECK-NOT: simit.parallel
func.func @ranges_of_a_field(%n : index, %starts : memref<?xi32>, %vals : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "points"}, {field = "s", kind = "field", set = "points"}, {index = 0 : i64, kind = "param"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %zero = arith.constant 0.0 : f64
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %i1 = arith.addi %i, %c1 : index
    %lo32 = memref.load %starts[%i] : memref<?xi32>
    %lo = arith.index_cast %lo32 : i32 to index
    %hi32 = memref.load %starts[%i1] : memref<?xi32>
    %hi = arith.index_cast %hi32 : i32 to index
    scf.for %k = %lo to %hi step %c1 {
      memref.store %zero, %vals[%k] : memref<?xf64>
    }
    scf.reduce
  }
  return
}

// The call of a failed assertion (simit-lower-assertions) does not keep a
// loop sequential: in a parallel region the runtime records the failure.
// CHECK-LABEL: func.func @asserting(
// CHECK: func.call @simit_rt_fail
// CHECK: } {simit.parallel = "owned"}
func.func @asserting(%n : index, %a : memref<?xf64>, %ok : i1, %msg : !llvm.ptr) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    scf.if %ok {
      memref.store %one, %a[%i] : memref<?xf64>
    } else {
      func.call @simit_rt_fail(%msg) : (!llvm.ptr) -> ()
    }
    scf.reduce
  }
  return
}
func.func private @simit_rt_fail(!llvm.ptr)

// Reading a neighbour's location of an array the loop writes, writing a
// location shared by all iterations, a call, a vector store spanning the
// iterations, and a small constant trip count all keep a loop sequential.
// CHECK-LABEL: func.func @sequential(
// CHECK-NOT: simit.parallel
func.func @sequential(%n : index, %a : memref<?xf64>, %s : memref<f64>, %p : memref<4x4xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1.0 : f64
  %ones = arith.constant dense<1.0> : vector<4xf64>
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %i1 = arith.addi %i, %c1 : index
    %next = memref.load %a[%i1] : memref<?xf64>
    memref.store %next, %a[%i] : memref<?xf64>
    scf.reduce
  }
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %old = memref.load %s[] : memref<f64>
    %new = arith.addf %old, %one : f64
    memref.store %new, %s[] : memref<f64>
    scf.reduce
  }
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %v = memref.load %a[%i] : memref<?xf64>
    func.call @print(%v) : (f64) -> ()
    scf.reduce
  }
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    vector.store %ones, %a[%i] : memref<?xf64>, vector<4xf64>
    scf.reduce
  }
  scf.parallel (%i) = (%c0) to (%c3) step (%c1) {
    memref.store %one, %a[%i] : memref<?xf64>
    scf.reduce
  }
  return
}
func.func private @print(f64)

// Nested loops run inside their outermost loop's iteration.
// CHECK-LABEL: func.func @nested(
// CHECK: scf.parallel
// CHECK: scf.parallel
// CHECK-NOT: simit.parallel
// CHECK: } {simit.parallel = "owned"}
func.func @nested(%n : index, %a : memref<?x16xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c16 = arith.constant 16 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    scf.parallel (%j) = (%c0) to (%c16) step (%c1) {
      memref.store %one, %a[%i, %j] : memref<?x16xf64>
      scf.reduce
    }
    scf.reduce
  }
  return
}
