//===- Passes.h - Passes on the simit dialect -------------------*- C++ -*-===//

#ifndef SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_H
#define SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_H

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/IR/BuiltinOps.h"
#include "mlir/Pass/Pass.h"

namespace mlir {
namespace simit {

#define GEN_PASS_DECL
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"

#define GEN_PASS_REGISTRATION
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"

} // namespace simit
} // namespace mlir

#endif // SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_H
