//===--- CompiledModule.h - JIT-loaded code shared by Functions -----------===//
//
// The machine code of one lowered module, linked into a JIT, and the host
// ABI of each of its exported functions. Every Function compiled from a
// Program holds it, so the code lives as long as the last Function does.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ENGINE_COMPILEDMODULE_H
#define SIMIT_LIB_ENGINE_COMPILEDMODULE_H

#include "simit/Engine/HostABI.h"
#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ExecutionEngine/Orc/LLJIT.h"

#include <memory>

namespace simit {

/// How the lowered function receives a memref argument: as its exploded
/// descriptor (allocated and aligned pointers, offset, sizes, strides; the
/// default of MLIR's func-to-llvm) or as a bare pointer to the data.
enum class MemRefConvention { Descriptor, BarePointer };

struct CompiledFunction {
  HostSignature signature;
  MemRefConvention convention = MemRefConvention::Descriptor;
  /// The packed entry point `_mlir_<name>(void **args)` once loaded.
  void (*entry)(void **) = nullptr;
};

class CompiledModule {
public:
  CompiledModule() = default;
  CompiledModule(const CompiledModule &) = delete;
  CompiledModule &operator=(const CompiledModule &) = delete;
  /// Runs the module's destructors (finalize), e.g. unloading its kernels,
  /// before its code goes.
  ~CompiledModule();

  std::unique_ptr<llvm::orc::LLJIT> jit;
  /// `_simit_module_fini` once the module's constructors have run.
  void (*finalize)(void **) = nullptr;
  llvm::StringMap<CompiledFunction> functions;
  /// The threads its parallel regions run on (1: it has none).
  int threads = 1;
  /// The solver of the Program that compiled the module.
  std::shared_ptr<SolveSession> solver;
};

} // namespace simit

#endif // SIMIT_LIB_ENGINE_COMPILEDMODULE_H
