// RUN: simit-opt %s --simit-parallel-loops=scatter-chunk=32 | FileCheck %s

// Colour-by-colour order differs from set order, so an element loop runs
// by colours only when no element can see another's writes: every write
// adds to the value read at its own location (an accumulation), and every
// read is such an accumulation's. Reading endpoint 0 of a field written at
// endpoint 1 (`p(1).x = p(0).x` in an apply), adding it to endpoint 1
// (`p(1).x = p(1).x + p(0).x`), scaling what was read (`w(p(0)) = k *
// w(p(0))`), or storing at an endpoint without reading it (a map without
// `reduce`, where the last writer in set order wins), stays sequential.

// CHECK-LABEL: func.func @accumulates(
// CHECK: } {simit.parallel = "scatter"}
func.func @accumulates(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>, %w : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}, {field = "w", kind = "field", set = "springs"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b32 = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %b = arith.index_cast %b32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    %xa = memref.load %x[%a] : memref<?xf64>
    %na = arith.addf %xa, %we : f64
    memref.store %na, %x[%a] : memref<?xf64>
    %xb = memref.load %x[%b] : memref<?xf64>
    %nb = arith.subf %xb, %we : f64
    memref.store %nb, %x[%b] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}

// CHECK-LABEL: func.func @reads_another_endpoint(
// CHECK-NOT: element_colours
// CHECK-NOT: simit.parallel
// CHECK: return
func.func @reads_another_endpoint(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>, %w : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}, {field = "w", kind = "field", set = "springs"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b32 = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %b = arith.index_cast %b32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    %xa = memref.load %x[%a] : memref<?xf64>
    %nb = arith.addf %xa, %we : f64
    memref.store %nb, %x[%b] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}

// CHECK-LABEL: func.func @overwrites(
// CHECK-NOT: element_colours
// CHECK-NOT: simit.parallel
// CHECK: return
func.func @overwrites(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>, %w : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}, {field = "w", kind = "field", set = "springs"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    memref.store %we, %x[%a] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}

// CHECK-LABEL: func.func @adds_another_endpoint(
// CHECK-NOT: element_colours
// CHECK-NOT: simit.parallel
// CHECK: return
func.func @adds_another_endpoint(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b32 = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %b = arith.index_cast %b32 : i32 to index
    %xa = memref.load %x[%a] : memref<?xf64>
    %xb = memref.load %x[%b] : memref<?xf64>
    %nb = arith.addf %xb, %xa : f64
    memref.store %nb, %x[%b] : memref<?xf64>
    memref.store %xa, %x[%a] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}

// CHECK-LABEL: func.func @scales_what_it_reads(
// CHECK-NOT: element_colours
// CHECK-NOT: simit.parallel
// CHECK: return
func.func @scales_what_it_reads(%ne : index, %ends : memref<?x2xi32>, %x : memref<?xf64>, %k : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "x", kind = "field", set = "points"}, {field = "k", kind = "field", set = "springs"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %ke = memref.load %k[%e] : memref<?xf64>
    %xa = memref.load %x[%a] : memref<?xf64>
    %scaled = arith.mulf %ke, %xa : f64
    %na = arith.addf %scaled, %one : f64
    memref.store %na, %x[%a] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}
