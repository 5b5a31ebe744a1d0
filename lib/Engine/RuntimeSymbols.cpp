//===--- RuntimeSymbols.cpp - Runtime functions bound in every JIT --------===//
//
// The names come from the one list of simit/ABI/RuntimeFunctionNames.h that
// the lowering declares its calls by; the addresses are the functions of
// simit/ABI/RuntimeFunctions.h the list names.
//
//===----------------------------------------------------------------------===//

#include "RuntimeSymbols.h"

#include "simit/ABI/RuntimeFunctionNames.h"
#include "simit/ABI/RuntimeFunctions.h"

// The symbol the JIT binds for a function of each interface, and its
// definition in the runtime.
#define SIMIT_RUNTIME_SYMBOL_Plain(symbol) #symbol
#define SIMIT_RUNTIME_SYMBOL_CInterface(symbol) "_mlir_ciface_" #symbol
#define SIMIT_RUNTIME_ADDRESS_Plain(symbol) &symbol
#define SIMIT_RUNTIME_ADDRESS_CInterface(symbol) &_mlir_ciface_##symbol

llvm::orc::SymbolMap
simit::runtimeSymbolMap(llvm::orc::MangleAndInterner interner) {
  llvm::orc::SymbolMap symbols;
  auto add = [&](llvm::StringRef name, void *address) {
    symbols[interner(name)] = {llvm::orc::ExecutorAddr::fromPtr(address),
                               llvm::JITSymbolFlags::Exported};
  };
#define SIMIT_ADD_RUNTIME_FUNCTION(Id, symbol, Interface)                      \
  add(SIMIT_RUNTIME_SYMBOL_##Interface(symbol),                                \
      reinterpret_cast<void *>(SIMIT_RUNTIME_ADDRESS_##Interface(symbol)));
  SIMIT_RUNTIME_FUNCTIONS(SIMIT_ADD_RUNTIME_FUNCTION)
#undef SIMIT_ADD_RUNTIME_FUNCTION
  addGPURuntimeSymbols(add);
  return symbols;
}

void simit::addGPURuntimeSymbols(
    llvm::function_ref<void(llvm::StringRef, void *)> add) {
#define SIMIT_ADD_GPU_RUNTIME_FUNCTION(Id, symbol)                             \
  add(#symbol, reinterpret_cast<void *>(&symbol));
  SIMIT_GPU_RUNTIME_FUNCTIONS(SIMIT_ADD_GPU_RUNTIME_FUNCTION)
#undef SIMIT_ADD_GPU_RUNTIME_FUNCTION
}
