//===- SetChecks.h - Checks of values against named sets -------*- C++ -*-===//
//
// Types refer to sets by name (tensor dimensions, endpoints), so verifiers
// that need a set's element type look the name up among the sets visible
// from an operation.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_IR_SETCHECKS_H
#define SIMIT_LIB_DIALECT_SIMIT_IR_SETCHECKS_H

#include "simit/Dialect/Simit/IR/Simit.h"

namespace mlir {
namespace simit {

/// The type of the set called `name` visible from `from`: a set-typed
/// argument of an enclosing function, or a simit.extern of an enclosing
/// symbol table. Null when no such set is declared (the name may belong to
/// a set the surrounding IR does not show).
SetType lookupSetByName(Operation *from, StringAttr name);

/// Checks that `elementType` is the element type of the set called `name`
/// when that set can be found; `what` describes the value for the message.
LogicalResult verifyElementOfSet(Operation *op, Type elementType,
                                 StringAttr name, const Twine &what);

/// Checks that `tuple` can hold the endpoints of an element of `set`: one
/// component per endpoint, named unless the set is homogeneous, and each of
/// the element type of its endpoint set when that set can be found.
LogicalResult verifyEndpointTuple(Operation *op, SetType set, TupleType tuple);

} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_IR_SETCHECKS_H
