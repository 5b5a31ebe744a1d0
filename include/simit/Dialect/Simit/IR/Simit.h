//===- Simit.h - The simit dialect ------------------------------*- C++ -*-===//
//
// The one header a user of the dialect includes: the dialect, its types,
// attributes and operations, and the type queries the verifiers share.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMIT_H
#define SIMIT_DIALECT_SIMIT_IR_SIMIT_H

#include "mlir/Bytecode/BytecodeOpInterface.h"
#include "mlir/IR/BuiltinAttributes.h"
#include "mlir/IR/BuiltinTypes.h"
#include "mlir/IR/Dialect.h"
#include "mlir/IR/OpDefinition.h"
#include "mlir/IR/OpImplementation.h"
#include "mlir/IR/SymbolTable.h"
#include "mlir/Interfaces/ControlFlowInterfaces.h"
#include "mlir/Interfaces/InferTypeOpInterface.h"
#include "mlir/Interfaces/SideEffectInterfaces.h"

#include "simit/Dialect/Simit/IR/SimitDialect.h.inc"

#include "simit/Dialect/Simit/IR/SimitEnums.h.inc"

#define GET_ATTRDEF_CLASSES
#include "simit/Dialect/Simit/IR/SimitAttrs.h.inc"

#define GET_TYPEDEF_CLASSES
#include "simit/Dialect/Simit/IR/SimitTypes.h.inc"

namespace mlir {
namespace simit {

/// Whether `type` is a Simit scalar: a float, an integer or a complex.
bool isScalarType(Type type);

/// Whether `type` is a builtin ranked tensor or a SystemTensorType.
bool isTensorType(Type type);

/// Whether `type` is a scalar or a tensor.
bool isTensorOrScalarType(Type type);

/// The number of outer dimensions of a tensor (0 for a scalar).
unsigned getTensorOrder(Type type);

/// The innermost scalar type of a tensor (the type itself for a scalar).
Type getComponentType(Type type);

/// The shape of a local tensor's components: the builtin shape, or the
/// integer dimensions of a `!simit.tensor` followed by its block's; empty
/// for a scalar.
SmallVector<int64_t> getLocalShape(Type type);

/// The block of a tensor: what one index per outer dimension selects. The
/// component type for builtin tensors and unblocked system tensors.
Type getBlockType(Type type);

/// The levels of dimension `dim` of a tensor, from the outer dimension
/// inwards through nested blocks: StringAttr for a set, IntegerAttr (i64)
/// for a range.
SmallVector<Attribute> getDimensionHierarchy(Type type, unsigned dim);

/// Whether a tensor has a set dimension at any level.
bool hasSetDimension(Type type);

} // namespace simit
} // namespace mlir

#define GET_OP_CLASSES
#include "simit/Dialect/Simit/IR/SimitOps.h.inc"

namespace mlir {
namespace simit {

/// The first write, and the result it writes, of the element function of a
/// `simit.map` or `simit.assemble` into a set dimension of one of its
/// results at a position other than its element, its endpoints or (through
/// a grid) points near it (language.md 8.3); none when every write is
/// indexed so. The maps' verifier rejects such writes; front ends report
/// them at the write.
std::optional<std::pair<InsertOp, unsigned>>
findUnindexedResultWrite(Operation *mapLike);

} // namespace simit
} // namespace mlir

#endif // SIMIT_DIALECT_SIMIT_IR_SIMIT_H
