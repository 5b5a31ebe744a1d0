// RUN: simit-opt %s --simit-parallel-loops=scatter-chunk=32 | FileCheck %s

// An element loop that adds into its endpoints' rows and into the BCSR
// blocks its location table names runs colour by colour over the host's
// colouring of chunks of 32 consecutive elements: an `element_colours`
// argument [K, start_0 .. start_K, chunks...]; the chunks of one colour run
// in parallel, each its elements in order.

// CHECK-LABEL: func.func @assemble(
// CHECK-SAME: %[[NE:[^:]*]]: index, %[[ENDS:[^:]*]]: memref<?x2xi32>, %[[LOCS:[^:]*]]: memref<?x4xi32>, %[[W:[^:]*]]: memref<?xf64>, %[[F:[^:]*]]: memref<?x3xf64>, %[[K:[^:]*]]: memref<?xf64>, %[[COLOURS:[^:]*]]: memref<?xi32>)
// CHECK-SAME: simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {cols = "points", kind = "pattern_locations", rows = "points", set = "springs"}, {field = "w", kind = "field", set = "springs"}, {index = 0 : i64, kind = "param"}, {index = 1 : i64, kind = "param"}, {chunk = 32 : i64, kind = "element_colours", set = "springs"}]
// CHECK: %[[C32:.*]] = arith.constant 32 : index
// CHECK: %[[NC32:.*]] = memref.load %[[COLOURS]][%{{.*}}] : memref<?xi32>
// CHECK: %[[NC:.*]] = arith.index_cast %[[NC32]] : i32 to index
// CHECK: scf.for %[[C:.*]] = %{{.*}} to %[[NC]] step
// CHECK:   %[[S:.*]] = arith.addi %[[C]], %{{.*}} : index
// CHECK:   memref.load %[[COLOURS]][%[[S]]]
// CHECK:   %[[E:.*]] = arith.addi %[[C]], %{{.*}} : index
// CHECK:   memref.load %[[COLOURS]][%[[E]]]
// CHECK:   scf.parallel (%[[Q:.*]]) =
// CHECK:     %[[CHUNK32:.*]] = memref.load %[[COLOURS]][%[[Q]]] : memref<?xi32>
// CHECK:     %[[CHUNK:.*]] = arith.index_cast %[[CHUNK32]] : i32 to index
// CHECK:     %[[FIRST:.*]] = arith.muli %[[CHUNK]], %[[C32]] : index
// CHECK:     %[[END:.*]] = arith.addi %[[FIRST]], %[[C32]] : index
// CHECK:     %[[LAST:.*]] = arith.minui %[[END]], %[[NE]] : index
// CHECK:     scf.parallel (%[[EL:.*]]) = (%[[FIRST]]) to (%[[LAST]]) step
// CHECK:       memref.load %[[ENDS]][%[[EL]], %{{.*}}]
// CHECK:       memref.store %{{.*}}, %[[F]][%{{.*}}, %{{.*}}] : memref<?x3xf64>
// CHECK:       memref.store %{{.*}}, %[[K]][%{{.*}}] : memref<?xf64>
// CHECK:     } {simit.scatter}
// CHECK:   } {simit.parallel = "scatter"}
// The second loop over the set uses the same colouring.
// CHECK: scf.for
// CHECK:   } {simit.parallel = "scatter"}
// CHECK: return
func.func @assemble(%ne : index, %ends : memref<?x2xi32>, %locs : memref<?x4xi32>, %w : memref<?xf64>, %f : memref<?x3xf64>, %kv : memref<?xf64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {cols = "points", kind = "pattern_locations", rows = "points", set = "springs"}, {field = "w", kind = "field", set = "springs"}, {index = 0 : i64, kind = "param"}, {index = 1 : i64, kind = "param"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    %old = memref.load %f[%a, %c1] : memref<?x3xf64>
    %new = arith.addf %old, %we : f64
    memref.store %new, %f[%a, %c1] : memref<?x3xf64>
    %l32 = memref.load %locs[%e, %c3] : memref<?x4xi32>
    %l = arith.index_cast %l32 : i32 to index
    %kold = memref.load %kv[%l] : memref<?xf64>
    %knew = arith.addf %kold, %we : f64
    memref.store %knew, %kv[%l] : memref<?xf64>
    memref.store %we, %w[%e] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %b32 = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %b = arith.index_cast %b32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    %old = memref.load %f[%b, %c0] : memref<?x3xf64>
    %new = arith.subf %old, %we : f64
    memref.store %new, %f[%b, %c0] : memref<?x3xf64>
    scf.reduce
  } {simit.scatter}
  return
}

// A scalar result accumulated over the elements, a memref indexed by an
// endpoint in one access and by a location in another, and a loop that is
// not over all elements of the set stay sequential.
// CHECK-LABEL: func.func @sequential(
// CHECK-SAME: %{{[^:]*}}: memref<f64>)
// CHECK-NOT: element_colours
// CHECK-NOT: simit.parallel
func.func @sequential(%ne : index, %ends : memref<?x2xi32>, %locs : memref<?x4xi32>, %w : memref<?xf64>, %f : memref<?xf64>, %s : memref<f64>) attributes {simit.bindings = [{kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {cols = "points", kind = "pattern_locations", rows = "points", set = "springs"}, {field = "w", kind = "field", set = "springs"}, {index = 0 : i64, kind = "param"}, {index = 1 : i64, kind = "param"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %half = arith.divui %ne, %c1 : index
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %we = memref.load %w[%e] : memref<?xf64>
    %old = memref.load %s[] : memref<f64>
    %new = arith.addf %old, %we : f64
    memref.store %new, %s[] : memref<f64>
    scf.reduce
  } {simit.scatter}
  scf.parallel (%e) = (%c0) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %l32 = memref.load %locs[%e, %c1] : memref<?x4xi32>
    %l = arith.index_cast %l32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    memref.store %we, %f[%a] : memref<?xf64>
    memref.store %we, %f[%l] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  %n2 = arith.addi %ne, %c1 : index
  scf.parallel (%e) = (%c1) to (%ne) step (%c1) {
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %we = memref.load %w[%e] : memref<?xf64>
    memref.store %we, %f[%a] : memref<?xf64>
    scf.reduce
  } {simit.scatter}
  return
}
