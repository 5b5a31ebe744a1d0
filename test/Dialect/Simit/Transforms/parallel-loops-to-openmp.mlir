// RUN: simit-opt %s --simit-parallel-loops-to-openmp | FileCheck %s
// RUN: simit-opt %s --simit-parallel-loops-to-openmp=max-copied-ops=0 | FileCheck %s --check-prefix=CLAUSE

// A marked loop becomes a parallel region with a worksharing loop over its
// bounds (no barrier: the region's end joins the threads); its stack slots
// move to the start of the region, one set per thread. Unmarked loops, and
// loops nested in marked ones, stay scf.parallel (run sequentially). With
// fewer than 2048 iterations (here n * 3) the work is not shared: a small
// body runs as an unmarked copy instead; a larger one (max-copied-ops=0)
// runs its region on the calling thread alone (the `if` clause).

// CHECK-LABEL: func.func @marked(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[A:[^:]*]]: memref<?x3xf64>)
// CHECK: %[[EXTENT:.*]] = arith.maxsi %[[N]], %{{.*}} : index
// CHECK: %[[TRIPS:.*]] = arith.muli %[[EXTENT]], %{{.*}} : index
// CHECK-NEXT: %[[LEAST:.*]] = arith.constant 2048 : index
// CHECK-NEXT: %[[SHARE:.*]] = arith.cmpi uge, %[[TRIPS]], %[[LEAST]] : index
// CHECK: scf.if %[[SHARE]] {
// CHECK-NEXT: omp.parallel {
// CHECK-NEXT: %[[SLOT:.*]] = memref.alloca() : memref<3xf64>
// CHECK-NEXT: omp.wsloop nowait {
// CHECK-NEXT: omp.loop_nest (%[[I:.*]], %[[J:.*]]) : index = (%{{.*}}, %{{.*}}) to (%[[N]], %{{.*}}) step (%{{.*}}, %{{.*}}) {
// CHECK: memref.store %{{.*}}, %[[SLOT]][%[[J]]]
// CHECK: scf.parallel
// CHECK: memref.store %{{.*}}, %[[A]][%[[I]], %[[J]]]
// CHECK: omp.yield
// CHECK: omp.terminator
// CHECK: } else {
// CHECK-NEXT: scf.parallel (%[[CI:.*]], %[[CJ:.*]]) = (%{{.*}}, %{{.*}}) to (%[[N]], %{{.*}})
// CHECK: memref.store %{{.*}}, %[[A]][%[[CI]], %[[CJ]]]
// CHECK-NOT: simit.parallel
// CHECK-NOT: omp.parallel
// CHECK: scf.parallel
// CHECK-NOT: simit.parallel
// CHECK: return

// CLAUSE-LABEL: func.func @marked(
// CLAUSE: %[[SHARE:.*]] = arith.cmpi uge
// CLAUSE-NOT: scf.if
// CLAUSE: omp.parallel if(%[[SHARE]]) {
// CLAUSE: omp.terminator
// CLAUSE-NOT: omp.parallel
// CLAUSE: return
func.func @marked(%n : index, %a : memref<?x3xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%i, %j) = (%c0, %c0) to (%n, %c3) step (%c1, %c1) {
    %slot = memref.alloca() : memref<3xf64>
    memref.store %one, %slot[%j] : memref<3xf64>
    scf.parallel (%k) = (%c0) to (%c3) step (%c1) {
      memref.store %one, %slot[%k] : memref<3xf64>
      scf.reduce
    }
    %v = memref.load %slot[%j] : memref<3xf64>
    memref.store %v, %a[%i, %j] : memref<?x3xf64>
    scf.reduce
  } {simit.parallel = "owned"}
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    memref.store %one, %a[%c0, %c0] : memref<?x3xf64>
    scf.reduce
  }
  return
}

// A region that may fail (simit-lower-assertions) is followed by the call
// that raises the failure its threads recorded; regions that cannot fail
// are not.
// CHECK-LABEL: func.func @may_fail(
// CHECK: omp.parallel {
// CHECK: func.call @simit_rt_fail
// CHECK: omp.terminator
// CHECK-NEXT: }
// CHECK-NEXT: call @simit_rt_raise_parallel_failure() : () -> ()
// CHECK: } else {
// CHECK: omp.parallel {
// CHECK: omp.terminator
// CHECK-NEXT: }
// CHECK-NEXT: } else {
// CHECK: return
func.func @may_fail(%n : index, %ok : i1, %p : !llvm.ptr) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    scf.if %ok {
    } else {
      func.call @simit_rt_fail(%p) : (!llvm.ptr) -> ()
    }
    scf.reduce
  } {simit.parallel = "owned"}
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    scf.reduce
  } {simit.parallel = "owned"}
  return
}
func.func private @simit_rt_fail(!llvm.ptr)
// CHECK: func.func private @simit_rt_raise_parallel_failure()
