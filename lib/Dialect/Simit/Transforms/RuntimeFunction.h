//===- RuntimeFunction.h - Declarations of runtime functions ----*- C++ -*-===//
//
// Passes that call the Simit runtime declare its functions in the module
// they rewrite, once, whichever pass comes first, by the names of
// simit/ABI/RuntimeFunctionNames.h.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_RUNTIMEFUNCTION_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_RUNTIMEFUNCTION_H

#include "simit/ABI/RuntimeFunctionNames.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/IR/BuiltinOps.h"

namespace mlir {
namespace simit {

/// The name lowered code calls `function` of the runtime by.
constexpr StringRef runtimeName(::simit::abi::RuntimeFunction function) {
  return ::simit::abi::runtimeFunctionName(function);
}

/// The runtime function a failed assertion calls (simit-lower-assertions).
constexpr StringRef kRuntimeFail =
    runtimeName(::simit::abi::RuntimeFunction::Fail);

/// The private declaration `name : type` in `module`, made at its end if
/// missing; null (with an error on the existing symbol) when `name` is
/// declared with another type.
func::FuncOp declareRuntimeFunction(ModuleOp module, StringRef name,
                                    FunctionType type);

} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_RUNTIMEFUNCTION_H
