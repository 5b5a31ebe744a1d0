//===- SourcePosition.h - Source positions in run-time messages -*- C++ -*-===//
//
// Messages that lowered code reports at run time (--check-numerics, failed
// solves, failed run-time checks) name the statement by its source position.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SOURCEPOSITION_H
#define SIMIT_DIALECT_SIMIT_IR_SOURCEPOSITION_H

#include "mlir/IR/Operation.h"

#include <string>

namespace mlir {
namespace simit {

/// " (<file>:<line>:<col>)" for an op at a source position (the file's
/// name without its folder), else "".
std::string sourcePositionSuffix(Operation *op);
std::string sourcePositionSuffix(Location loc);

} // namespace simit
} // namespace mlir

#endif // SIMIT_DIALECT_SIMIT_IR_SOURCEPOSITION_H
