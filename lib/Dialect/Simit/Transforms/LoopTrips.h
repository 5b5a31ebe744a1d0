//===- LoopTrips.h - Trip counts of loop dimensions -------------*- C++ -*-===//
//
// The number of iterations of one dimension of an scf loop, as IR: the
// passes that cut set loops into chunks, map them to GPU grids or decide
// whether they are worth threads all need it.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_LOOPTRIPS_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_LOOPTRIPS_H

#include "mlir/IR/Builders.h"

namespace mlir {
namespace simit {

/// max(ceil((ub - lb) / step), 0), folded where the bounds are constants.
Value tripCount(OpBuilder &b, Location loc, Value lb, Value ub, Value step);

} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_LOOPTRIPS_H
