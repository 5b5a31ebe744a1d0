//===--- Lowering.h - From the simit dialect to JIT-compiled code ---------===//

#ifndef SIMIT_LIB_ENGINE_LOWERING_H
#define SIMIT_LIB_ENGINE_LOWERING_H

#include "ObjectCode.h"

#include "simit/Engine/Program.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/BuiltinOps.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/Support/Error.h"

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
  /// The host ABI of every function carrying `simit.bindings`, read just
  /// before the function became an llvm.func.
  llvm::StringMap<HostSignature> signatures;
  /// The module right after convert-simit-to-loops (empty when the input
  /// was already loops).
  std::string loopsText;
};

/// Lowers `module` in place to the LLVM dialect. Errors carry the MLIR
/// diagnostics with their locations.
/// Runs simit-cpu-pipeline with `options` (the JIT always uses the
/// runtime allocator).
llvm::Error
lowerToLLVM(mlir::ModuleOp module, LoweringResult &result,
            mlir::simit::SimitCpuPipelineOptions options = {});

/// Compiles a module in the LLVM dialect at -O3 for the host (hostTarget())
/// into an object with a packed entry point for every function in
/// `signatures`; records the time of LLVM's optimization and code
/// generation in `times`.
llvm::Expected<ObjectCode>
compileToObject(mlir::ModuleOp llvmModule,
                const llvm::StringMap<HostSignature> &signatures,
                CompileTimes &times);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_LOWERING_H
