// RUN: simit-opt %s --simit-parallel-loops-to-gpu="block-size=64" --split-input-file | FileCheck %s

// A two-dimensional loop with lower bounds and steps is linearised: the trip
// counts are ceil((ub - lb) / step), the last dimension varies fastest, and
// each index is lb + index * step.

// CHECK-LABEL: func.func @two_dimensional
// CHECK-SAME:    (%[[N:.*]]: index, %[[M:.*]]: index, %[[A:.*]]: memref<?x?xf64>)
// CHECK-DAG:     %[[C1:.*]] = arith.constant 1 : index
// CHECK-DAG:     %[[C2:.*]] = arith.constant 2 : index
// CHECK-DAG:     %[[C3:.*]] = arith.constant 3 : index
// CHECK:         %[[EXT0:.*]] = arith.subi %[[N]], %[[C1]]
// CHECK:         %[[POS0:.*]] = arith.maxsi %[[EXT0]], %{{.*}}
// CHECK:         %[[TRIP0:.*]] = arith.ceildivui %[[POS0]], %[[C2]]
// CHECK:         %[[EXT1:.*]] = arith.subi %[[M]], %[[C3]]
// CHECK:         %[[TRIP1:.*]] = arith.maxsi %[[EXT1]], %{{.*}}
// CHECK:         %[[TOTAL:.*]] = arith.muli %[[TRIP0]], %[[TRIP1]]
// CHECK:         %[[C64:.*]] = arith.constant 64 : index
// CHECK:         %[[BLOCKS:.*]] = arith.ceildivui %[[TOTAL]], %[[C64]]
// CHECK:         %[[GRID:.*]] = arith.maxui %[[BLOCKS]], %{{.*}}
// CHECK:         gpu.launch blocks(%[[BX:.*]], %{{.*}}, %{{.*}}) in (%{{.*}} = %[[GRID]], {{.*}} threads(%[[TX:.*]], %{{.*}}, %{{.*}}) in (%{{.*}} = %[[C64]],
// CHECK:           %[[BASE:.*]] = arith.muli %[[BX]], %[[C64]]
// CHECK:           %[[LIN:.*]] = arith.addi %[[BASE]], %[[TX]]
// CHECK:           %[[IN:.*]] = arith.cmpi ult, %[[LIN]], %[[TOTAL]]
// CHECK:           scf.if %[[IN]] {
// CHECK:             %[[J0:.*]] = arith.remui %[[LIN]], %[[TRIP1]]
// CHECK:             %[[I0:.*]] = arith.divui %[[LIN]], %[[TRIP1]]
// CHECK:             %[[J:.*]] = arith.addi %[[J0]], %[[C3]]
// CHECK:             %[[I1:.*]] = arith.muli %[[I0]], %[[C2]]
// CHECK:             %[[I:.*]] = arith.addi %[[I1]], %[[C1]]
// CHECK:             memref.store %{{.*}}, %[[A]][%[[I]], %[[J]]]
// CHECK:           }
// CHECK:           gpu.terminator
// CHECK-NOT:     scf.parallel
// CHECK:         return
func.func @two_dimensional(%n: index, %m: index, %a: memref<?x?xf64>) {
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1.0 : f64
  scf.parallel (%i, %j) = (%c1, %c3) to (%n, %m) step (%c2, %c1) {
    memref.store %one, %a[%i, %j] : memref<?x?xf64>
    scf.reduce
  }
  return
}

// -----

// Two reductions of one loop, a float and an integer sum, each with its own
// accumulator starting at the loop's initial value; a parallel loop nested
// in the set loop runs sequentially inside the thread; a set loop inside a
// host loop keeps its accumulator at the function's start.

// CHECK-LABEL: func.func @two_sums
// CHECK-SAME:    (%{{.*}}: index, %[[X:.*]]: memref<?x3xf64>, %[[INITF:.*]]: f64, %[[INITI:.*]]: i32, %[[STEPS:.*]]: index)
// CHECK-NEXT:    %[[ACCF:.*]] = memref.alloca() : memref<f64>
// CHECK-NEXT:    %[[ACCI:.*]] = memref.alloca() : memref<i32>
// CHECK:         %[[OUT:.*]]:2 = scf.for {{.*}} iter_args(%[[F:.*]] = %[[INITF]], %[[I:.*]] = %[[INITI]])
// CHECK:           memref.store %[[F]], %[[ACCF]][]
// CHECK:           memref.store %[[I]], %[[ACCI]][]
// CHECK:           gpu.launch
// CHECK:             %[[P:.*]]:2 = scf.if %{{.*}} -> (f64, i32) {
// CHECK:               scf.parallel
// CHECK:               scf.yield %{{.*}}, %{{.*}} : f64, i32
// CHECK:             } else {
// CHECK-DAG:           %[[ZF:.*]] = arith.constant 0.000000e+00 : f64
// CHECK-DAG:           %[[ZI:.*]] = arith.constant 0 : i32
// CHECK:               scf.yield %[[ZF]], %[[ZI]] : f64, i32
// CHECK:             }
// CHECK:             %[[SF:.*]] = gpu.all_reduce add %[[P]]#0 uniform
// CHECK:             %[[SI:.*]] = gpu.all_reduce add %[[P]]#1 uniform
// CHECK:             scf.if
// CHECK-NEXT:          memref.atomic_rmw addf %[[SF]], %[[ACCF]][] : (f64, memref<f64>) -> f64
// CHECK-NEXT:          memref.atomic_rmw addi %[[SI]], %[[ACCI]][] : (i32, memref<i32>) -> i32
// CHECK:           gpu.terminator
// CHECK:           %[[RF:.*]] = memref.load %[[ACCF]][]
// CHECK:           %[[RI:.*]] = memref.load %[[ACCI]][]
// CHECK:           scf.yield %[[RF]], %[[RI]] : f64, i32
// CHECK:         return %[[OUT]]#0, %[[OUT]]#1
func.func @two_sums(%n: index, %x: memref<?x3xf64>, %initf: f64, %initi: i32,
                    %steps: index) -> (f64, i32) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1 : i32
  %zero = arith.constant 0.0 : f64
  %out:2 = scf.for %s = %c0 to %steps step %c1
      iter_args(%f = %initf, %i = %initi) -> (f64, i32) {
    %r:2 = scf.parallel (%v) = (%c0) to (%n) step (%c1) init (%f, %i) -> (f64, i32) {
      %sq = scf.parallel (%k) = (%c0) to (%c3) step (%c1) init (%zero) -> f64 {
        %xk = memref.load %x[%v, %k] : memref<?x3xf64>
        %xk2 = arith.mulf %xk, %xk : f64
        scf.reduce(%xk2 : f64) {
        ^bb0(%a: f64, %b: f64):
          %s2 = arith.addf %a, %b : f64
          scf.reduce.return %s2 : f64
        }
      }
      scf.reduce(%sq, %one : f64, i32) {
      ^bb0(%a: f64, %b: f64):
        %s2 = arith.addf %b, %a : f64
        scf.reduce.return %s2 : f64
      }, {
      ^bb0(%a: i32, %b: i32):
        %s2 = arith.addi %a, %b : i32
        scf.reduce.return %s2 : i32
      }
    }
    scf.yield %r#0, %r#1 : f64, i32
  }
  return %out#0, %out#1 : f64, i32
}
