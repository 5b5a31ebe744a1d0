//===--- RuntimeSymbols.h - Host functions JIT-compiled code calls --------===//

#ifndef SIMIT_LIB_ENGINE_RUNTIMESYMBOLS_H
#define SIMIT_LIB_ENGINE_RUNTIMESYMBOLS_H

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/ExecutionEngine/Orc/Core.h"
#include "llvm/ExecutionEngine/Orc/Mangling.h"

namespace simit {

/// The runtime functions of simit/ABI/RuntimeFunctions.h under the names
/// lowered code calls them by (simit/ABI/RuntimeFunctionNames.h).
llvm::orc::SymbolMap runtimeSymbolMap(llvm::orc::MangleAndInterner interner);

/// Calls `add` with the name and address of each function the host code of
/// simit-gpu-pipeline calls (the mgpu* functions, lib/ABI/GPUFunctions.cpp).
void addGPURuntimeSymbols(
    llvm::function_ref<void(llvm::StringRef, void *)> add);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_RUNTIMESYMBOLS_H
