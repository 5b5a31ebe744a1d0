// RUN: not simit-opt %s --simit-gpu-pipeline="format=cubin" 2>&1 | FileCheck %s --check-prefix=FORMAT
// RUN: not simit-opt %s --simit-gpu-pipeline 2>&1 | FileCheck %s --check-prefix=COMBINER

// FORMAT: error: simit-gpu-pipeline: format must be isa, bin or fatbin, got 'cubin'

// An error of one of the pipeline's passes stops it, naming the place.
// COMBINER: pipeline-invalid.mlir:[[@LINE+5]]:8: error: 'scf.parallel' op has a reduction that the GPU path cannot combine
func.func @product(%n: index, %x: memref<?xf64>) -> f64 {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %init = arith.constant 1.0 : f64
  %r = scf.parallel (%i) = (%c0) to (%n) step (%c1) init (%init) -> f64 {
    %xi = memref.load %x[%i] : memref<?xf64>
    scf.reduce(%xi : f64) {
    ^bb0(%a: f64, %b: f64):
      %m = arith.mulf %a, %b : f64
      scf.reduce.return %m : f64
    }
  }
  return %r : f64
}
