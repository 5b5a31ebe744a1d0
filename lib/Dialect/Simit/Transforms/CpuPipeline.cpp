//===- CpuPipeline.cpp - simit IR down to the LLVM dialect ----------------===//
//
// The pipeline is a pass (registered with the others by
// registerSimitPasses()) that runs buildSimitCpuPipeline() as a dynamic
// pipeline, so simit-opt and the JIT run the same passes.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Conversion/Passes.h"
#include "mlir/Dialect/Bufferization/Pipelines/Passes.h"
#include "mlir/Dialect/MemRef/Transforms/Passes.h"
#include "mlir/Pass/PassManager.h"
#include "mlir/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITCPUPIPELINE
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

void mlir::simit::buildSimitScenePasses(
    OpPassManager &pm, const SimitCpuPipelineOptions &options) {
  pm.addPass(createSimitInlineFunctions());
  if (options.foldSceneConstants)
    pm.addPass(createSimitFoldSceneConstants());
  if (options.eliminateDeadAssemblies)
    pm.addPass(createSimitEliminateDeadAssemblies());
}

void mlir::simit::buildSimitCpuPipeline(
    OpPassManager &pm, const SimitCpuPipelineOptions &options) {
  buildSimitScenePasses(pm, options);
  if (options.shermanMorrison)
    pm.addPass(createSimitShermanMorrison());
  if (options.timePhases)
    pm.addPass(createSimitTimePhases());
  if (options.checkNumerics)
    pm.addPass(createSimitCheckNumerics());
  pm.addPass(createSimitIndexProductsToMatMul());
  pm.addPass(createSimitLinalgToIndexExpr());
  pm.addPass(createSimitFuseIndexExpr());
  pm.addPass(createSimitAssignStorage());
  ConvertSimitToLoopsOptions loopsOptions;
  loopsOptions.prefetchScatterBlocks = true;
  loopsOptions.prefetchMatrixBytes = options.prefetchMatrixBytes;
  pm.addPass(createConvertSimitToLoops(loopsOptions));
  pm.addPass(createCanonicalizerPass());
  pm.addPass(createCSEPass());
  // Loops over the components of local tensors (element functions) become
  // straight-line code with constant positions: the tensors stay in
  // registers instead of on the stack.
  pm.addPass(createSimitUnrollLocalTensorLoops());
  pm.addPass(createCanonicalizerPass());
  pm.addPass(createCSEPass());
  // Checks that remain after folding (dynamic indices, divisors) end the
  // run with their source position instead of trapping or reading poison.
  pm.addNestedPass<func::FuncOp>(createSimitGuardIntegerDivision());
  pm.addPass(createSimitLowerAssertions());
  // Complex arithmetic becomes arith and math on the parts; what is left
  // (complex.create/re/im/constant, complex<T> as a struct) goes to LLVM
  // below.
  pm.addPass(createConvertComplexToStandardPass());
  // Which set loops may run on all cores, made independent of the number of
  // threads: with or without OpenMP, the same chunks and colours.
  SimitParallelLoopsOptions parallelOptions;
  parallelOptions.reductionChunk = options.reductionChunk;
  parallelOptions.scatterChunk = options.scatterChunk;
  pm.addPass(createSimitParallelLoops(parallelOptions));
  if (options.elementVectorBits > 0) {
    SimitVectorizeElementLoopsOptions vectorOptions;
    vectorOptions.vectorBits = options.elementVectorBits;
    pm.addPass(createSimitVectorizeElementLoops(vectorOptions));
  }
  // Temporaries of system tensors are freed once no value needs them.
  bufferization::buildBufferDeallocationPipeline(pm);
  if (options.openmp)
    pm.addPass(createSimitParallelLoopsToOpenMP());
  // Other scf.parallel loops run sequentially below: their stack slots are
  // made once.
  pm.addNestedPass<func::FuncOp>(createSimitHoistParallelAllocas());
  // Prints of vectors (test drivers) become loops of scalar prints.
  pm.addPass(createConvertVectorToSCFPass());
  pm.addPass(createSCFToControlFlowPass());
  pm.addPass(memref::createExpandStridedMetadataPass());
  pm.addPass(createLowerAffinePass());
  pm.addPass(createConvertMathToLLVMPass());
  // What LLVM has no intrinsic for (cbrt) becomes a call into libm.
  pm.addPass(createConvertMathToLibmPass());
  // Written while function arguments are still memrefs: the conversion
  // below makes them descriptors.
  pm.addPass(createSimitRecordHostABI());
  SimitConvertToLLVMOptions llvmOptions;
  llvmOptions.useGenericFunctions = options.runtimeAllocator;
  pm.addPass(createSimitConvertToLLVM(llvmOptions));
  pm.addPass(createReconcileUnrealizedCastsPass());
}

namespace {
struct CpuPipeline : public simit::impl::SimitCpuPipelineBase<CpuPipeline> {
  using Base::Base;
  SimitCpuPipelineOptions options() const {
    return {timePhases,
            checkNumerics,
            runtimeAllocator,
            shermanMorrison,
            openmp,
            reductionChunk,
            scatterChunk,
            foldSceneConstants,
            eliminateDeadAssemblies,
            prefetchMatrixBytes,
            elementVectorBits};
  }
  void getDependentDialects(DialectRegistry &registry) const override {
    OpPassManager pm(ModuleOp::getOperationName());
    buildSimitCpuPipeline(pm, options());
    pm.getDependentDialects(registry);
  }

  void runOnOperation() override {
    OpPassManager pm(ModuleOp::getOperationName());
    buildSimitCpuPipeline(pm, options());
    if (failed(runPipeline(pm, getOperation())))
      signalPassFailure();
  }
};
} // namespace
