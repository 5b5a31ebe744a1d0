//===--- Lowering.h - From the simit dialect to JIT-compiled code ---------===//

#ifndef SIMIT_LIB_ENGINE_LOWERING_H
#define SIMIT_LIB_ENGINE_LOWERING_H

#include "ObjectCode.h"

#include "simit/Engine/Program.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/BuiltinOps.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/Support/Error.h"

#include <optional>
#include <string>

namespace mlir {
class DialectRegistry;
} // namespace mlir

namespace simit {

/// Registers every dialect a Simit module may hold on its way to LLVM, and
/// their translations to LLVM IR.
void registerEngineDialects(mlir::DialectRegistry &registry);

/// What lowering learnt on the way.
struct LoweringResult {
  /// The host ABI of every function carrying `simit.bindings`, read from
  /// the attributes of its llvm.func (simit-record-host-abi).
  llvm::StringMap<HostSignature> signatures;
  /// The module right after convert-simit-to-loops, when asked for (empty
  /// when the input was already loops).
  std::string loopsText;
};

/// What the kernels of Target::GPU are compiled for: the NVVM chip and the
/// PTX ISA version it needs.
struct GPUKernelTarget {
  std::string chip = "sm_90";
  std::string features = "+ptx80";
};

/// The kernel target of a device of compute capability `capability`
/// (major * 10 + minor): sm_<capability>, with the oldest PTX version that
/// knows the chip, and no older than 8.0.
GPUKernelTarget gpuKernelTargetFor(int capability);

/// Lowers `module` in place to the LLVM dialect. Errors carry the MLIR
/// diagnostics with their locations.
/// Runs simit-cpu-pipeline with `options` (the JIT always uses the
/// runtime allocator); with `gpu`, the passes of `options` that precede
/// the loops (Sherman–Morrison, phase timer, numerics checks) and then
/// simit-gpu-pipeline for `gpu`, and marks every kernel launch with its
/// Simit statement (simit_rt_gpu_statement) for the runtime's messages.
/// With `keepLoopsStage`, also prints the module after the loop lowering
/// into result.loopsText.
llvm::Error
lowerToLLVM(mlir::ModuleOp module, LoweringResult &result,
            mlir::simit::SimitCpuPipelineOptions options = {},
            const std::optional<GPUKernelTarget> &gpu = std::nullopt,
            bool keepLoopsStage = false);

/// Compiles a module in the LLVM dialect at -O3 for the host (hostTarget())
/// into an object with a packed entry point for every function in
/// `signatures`, and the module's constructors and destructors (GPU code
/// loads its kernels in one) gathered into `_simit_module_init` and
/// `_simit_module_fini` (packed, `void (void **)`), which loadObjectCode
/// and the CompiledModule's end call; records the time of LLVM's optimization and code
/// generation in `times`.
llvm::Expected<ObjectCode>
compileToObject(mlir::ModuleOp llvmModule,
                const llvm::StringMap<HostSignature> &signatures,
                CompileTimes &times);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_LOWERING_H
