// RUN: simit-opt %s --simit-parallel-loops-to-gpu --split-input-file --verify-diagnostics
// RUN: not simit-opt %s --simit-parallel-loops-to-gpu="block-size=2048" 2>&1 | FileCheck %s --check-prefix=BLOCK

// BLOCK: error: simit-parallel-loops-to-gpu: block-size must be in [1, 1024], got 2048

func.func @max_reduction(%n: index, %x: memref<?xf64>) -> f64 {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %init = arith.constant 0.0 : f64
  // expected-error @+1 {{'scf.parallel' op has a reduction that the GPU path cannot combine: only arith.addf and arith.addi of the two region arguments, on float or integer (not index) values, are supported}}
  %r = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%init) -> f64 {
    %xi = memref.load %x[%i] : memref<?xf64>
    scf.reduce(%xi : f64) {
    ^bb0(%a: f64, %b: f64):
      %m = arith.maximumf %a, %b : f64
      scf.reduce.return %m : f64
    }
  }
  return %r : f64
}

// -----

// Adding a constant is not a combination of the two arguments.
func.func @not_a_sum(%n: index, %x: memref<?xf64>) -> f64 {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %init = arith.constant 0.0 : f64
  %two = arith.constant 2.0 : f64
  // expected-error @+1 {{has a reduction that the GPU path cannot combine}}
  %r = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%init) -> f64 {
    %xi = memref.load %x[%i] : memref<?xf64>
    scf.reduce(%xi : f64) {
    ^bb0(%a: f64, %b: f64):
      %m = arith.addf %a, %two : f64
      scf.reduce.return %m : f64
    }
  }
  return %r : f64
}

// -----

// memref.atomic_rmw has no index form.
func.func @index_count(%n: index) -> index {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  // expected-error @+1 {{has a reduction that the GPU path cannot combine}}
  %r = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%c0) -> index {
    scf.reduce(%c1 : index) {
    ^bb0(%a: index, %b: index):
      %m = arith.addi %a, %b : index
      scf.reduce.return %m : index
    }
  }
  return %r : index
}
