//===- GPUPipeline.cpp - Loops-level IR to LLVM with PTX kernels ----------===//
//
// simit-gpu-pipeline is a pass that runs a nested pipeline, like
// simit-cpu-pipeline, so registerSimitPasses() registers it with the others
// and its options (chip, PTX version, format) travel in the pass syntax.
// After Simit's own GPU passes it reuses MLIR's NVVM pipeline, which lowers
// the host code, the kernels and the gpu.module serialisation in one go.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Conversion/Passes.h"
#include "mlir/Dialect/Bufferization/Pipelines/Passes.h"
#include "mlir/Dialect/GPU/IR/GPUDialect.h"
#include "mlir/Dialect/GPU/Pipelines/Passes.h"
#include "mlir/Dialect/GPU/Transforms/Passes.h"
#include "mlir/InitAllExtensions.h"
#include "mlir/Pass/PassManager.h"
#include "mlir/Target/LLVM/NVVM/Target.h"
#include "mlir/Target/LLVMIR/Dialect/All.h"
#include "mlir/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITGPUPIPELINE
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;

namespace {
struct GpuPipeline : public simit::impl::SimitGpuPipelineBase<GpuPipeline> {
  using Base::Base;

  void buildPipeline(OpPassManager &pm) const {
    if (lowerSimit) {
      // The CPU pipeline's first half, without its hoisting of allocas out
      // of parallel loops: on the GPU those stay private to each thread.
      pm.addPass(simit::createSimitInlineFunctions());
      pm.addPass(simit::createSimitIndexProductsToMatMul());
      pm.addPass(simit::createSimitLinalgToIndexExpr());
      pm.addPass(simit::createSimitFuseIndexExpr());
      pm.addPass(simit::createSimitAssignStorage());
      pm.addPass(simit::createConvertSimitToLoops());
      pm.addPass(createCanonicalizerPass());
      pm.addPass(createCSEPass());
      pm.addNestedPass<func::FuncOp>(simit::createSimitGuardIntegerDivision());
      bufferization::buildBufferDeallocationPipeline(pm);
    }
    // Complex arithmetic on the parts, before kernels are outlined: the
    // NVVM conversions handle complex.create/re/im but not the arithmetic.
    pm.addPass(createConvertComplexToStandardPass());
    // Elements that read what others write run in set order, on one thread.
    simit::SimitParallelLoopsOptions setOrder;
    setOrder.setOrderOnly = true;
    pm.addPass(simit::createSimitParallelLoops(setOrder));
    pm.addPass(simit::createSimitGpuScatterAtomics());
    pm.addPass(simit::createSimitParallelLoopsToGpu({blockSize, fpContract}));
    // Host code's assertions end the run; those in launches stay for the
    // NVVM lowering (__assertfail).
    pm.addPass(simit::createSimitLowerAssertions());
    pm.addPass(simit::createSimitGpuDeviceMemory());
    pm.addPass(createGpuLaunchSinkIndexComputationsPass());
    pm.addPass(createGpuKernelOutliningPass());
    // Device allocations and copies lower to runtime calls only in their
    // async form; the pass also makes the host wait before it touches memory.
    pm.addNestedPass<func::FuncOp>(createGpuAsyncRegionPass());
    gpu::GPUToNVVMPipelineOptions nvvm;
    nvvm.cubinChip = chip;
    nvvm.cubinFeatures = features;
    nvvm.cubinFormat = format;
    nvvm.optLevel = optLevel;
    simit::SimitRecordHostABIOptions hostABI;
    hostABI.barePointers = nvvm.hostUseBarePtrCallConv;
    pm.addPass(simit::createSimitRecordHostABI(hostABI));
    gpu::buildLowerToNVVMPassPipeline(pm, nvvm);
  }

  void getDependentDialects(DialectRegistry &registry) const override {
    OpPassManager pm(ModuleOp::getOperationName());
    buildPipeline(pm);
    pm.getDependentDialects(registry);
    // The conversions to LLVM find their patterns through dialect
    // interfaces, and serialising a gpu.module needs the NVVM target and
    // the LLVM IR translations; simit-opt registers none of these itself.
    registerAllExtensions(registry);
    registerAllGPUToLLVMIRTranslations(registry);
    NVVM::registerNVVMTargetInterfaceExternalModels(registry);
  }

  void runOnOperation() override {
    if (format != "isa" && format != "assembly" && format != "bin" &&
        format != "binary" && format != "fatbin" && format != "fatbinary") {
      getOperation().emitError("simit-gpu-pipeline: format must be isa, bin "
                               "or fatbin, got '")
          << format << "'";
      return signalPassFailure();
    }
    OpPassManager pm(ModuleOp::getOperationName());
    buildPipeline(pm);
    if (failed(runPipeline(pm, getOperation())))
      signalPassFailure();
  }
};
} // namespace
