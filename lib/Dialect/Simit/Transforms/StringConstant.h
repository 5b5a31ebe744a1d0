//===- StringConstant.h - C strings for runtime calls -----------*- C++ -*-===//
//
// Runtime functions take messages and names as C strings: one internal
// constant global per distinct text, shared by every pass that calls them.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_STRINGCONSTANT_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_STRINGCONSTANT_H

#include "mlir/IR/Builders.h"
#include "mlir/IR/BuiltinOps.h"

namespace mlir {
namespace simit {

/// An !llvm.ptr to a NUL-terminated copy of `text` in `module`
/// (global simit_str_<hash of text>, made on first use).
Value createStringConstant(OpBuilder &b, ModuleOp module, Location loc,
                           StringRef text);

} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_STRINGCONSTANT_H
