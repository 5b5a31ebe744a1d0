//===- SimitStorage.h - Storage encodings of system matrices ----*- C++ -*-===//
//
// The C++ API of `#simit.storage`: canonicalising builders, the structural
// containment order and the join, and queries on types. The builders are
// the only way to make an encoding: equal storage is one attribute, so
// encodings compare by pointer.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITSTORAGE_H
#define SIMIT_DIALECT_SIMIT_IR_SIMITSTORAGE_H

#include "simit/Dialect/Simit/IR/Simit.h"

namespace mlir {
namespace simit {

/// The encoding of `type`: null unless it is a `!simit.tensor` carrying one.
StorageAttr getStorage(Type type);

/// `type` (a `!simit.tensor`) with `encoding` (null: none).
Type withStorage(Type type, StorageAttr encoding);

/// Whether `a` and `b` are one type up to their storage encodings.
bool isSameUpToStorage(Type a, Type b);

namespace storage {

/// Builders. Each returns the canonical encoding of what it describes.
StorageAttr dense(MLIRContext *ctx);
StorageAttr empty(MLIRContext *ctx);
StorageAttr diag(StringAttr set);
/// Positions are endpoint positions of `edges`; they are sorted and made
/// unique.
StorageAttr pattern(StringAttr edges, ArrayRef<int64_t> rows,
                    ArrayRef<int64_t> cols);
StorageAttr incidence(StringAttr edges, ArrayRef<int64_t> cols);
/// The offsets (one per written neighbour, each of the grid's rank) are
/// sorted and made unique; offset 0 is added.
StorageAttr stencil(StringAttr grid, ArrayRef<SmallVector<int64_t>> offsets);
/// Matrix result number `call` of the host function calls of a function,
/// one of `function` (an `extern func`): a pattern known only at run time.
StorageAttr host(StringAttr function, int64_t call);
/// transpose(transpose(X)) = X, transpose(diag) = diag, transpose(empty) =
/// empty, transpose(dense) = dense, and rank-one terms stay outermost.
StorageAttr transpose(StorageAttr x);
/// Flattened, sorted and without duplicates, empty members or members
/// another contains; stencils of one grid merge; a member `dense` makes it
/// `dense`. No member gives `empty`, one member is that member.
StorageAttr unionOf(ArrayRef<StorageAttr> members);
/// Flattened; diagonal factors drop out, an empty factor makes it empty, a
/// dense one dense, and transpose(incidence(E, P)) then incidence(E, Q) is
/// pattern(E, P, Q).
StorageAttr product(ArrayRef<StorageAttr> factors);
/// `x` plus `rank` rank-one terms; `lowrank(lowrank(X, a), b)` is
/// `lowrank(X, a + b)`, and rank 0 is `x`.
StorageAttr lowRank(StorageAttr x, int64_t rank);

/// `x` if it is a host function's matrix (`host`), else the first such
/// among its members (of a union, product, transpose or lowrank), else
/// null: a pattern known only at run time is part of `x`.
StorageAttr findHost(StorageAttr x);

/// Whether `outer` stores every block `inner` stores, for encodings of
/// matrices over the same two sets. Structural and conservative: a false
/// "no" costs an index, never correctness. Equality; `empty` is below and
/// `dense` above everything; a square pattern or a stencil contains the
/// diagonal; positions and offsets by subset; a union contains what one of
/// its members contains, and a union is contained when all its members
/// are; transpose and lowrank are monotone.
bool contains(StorageAttr outer, StorageAttr inner);

/// The smallest encoding found that contains both: one of them when it
/// contains the other (no new index), else their union.
StorageAttr join(StorageAttr a, StorageAttr b);

} // namespace storage
} // namespace simit
} // namespace mlir

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITSTORAGE_H
