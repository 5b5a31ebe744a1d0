//===- StorageAnalysis.h - Storage of system matrices, as data flow -*- C++ -*-===//
//
// The forward data-flow analysis of simit-assign-storage: the lattice of
// `#simit.storage` encodings (nothing known yet, an encoding, or
// unsupported with a reason) and the storage rules of the simit ops.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_STORAGEANALYSIS_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_STORAGEANALYSIS_H

#include "simit/Dialect/Simit/IR/SimitStorage.h"

#include "mlir/Analysis/DataFlow/SparseAnalysis.h"
#include "mlir/Dialect/Func/IR/FuncOps.h"

namespace mlir {
namespace simit {

/// Whether values of `type` get a storage encoding: matrices over two sets
/// and slots holding them.
bool holdsSetMatrix(Type type);

/// simit-assign-storage on one function that is not an element function:
/// gives every matrix value its storage, with `simit.convert` where a use
/// needs another; reports, and fails on, matrices that have none.
LogicalResult assignStorage(func::FuncOp function);

/// Whether some matrix value of `function` has no storage encoding yet.
bool needsStorageAssignment(func::FuncOp function);

/// What a storage rule gives one result: an encoding, or the reason there
/// is none (an empty reason means success).
struct StorageRule {
  StorageAttr encoding;
  std::string unsupported;

  static StorageRule of(StorageAttr encoding) { return {encoding, {}}; }
  static StorageRule error(const Twine &reason) { return {{}, reason.str()}; }
};

/// The storage of result `result` (a matrix over two sets) of a
/// `simit.map` or `simit.assemble`, from the mapped set's type (and, through
/// a grid, the offsets the element function writes).
StorageRule getMapResultStorage(Operation *map, unsigned result);

/// The storage of an index expression's matrix result, from its body read
/// as a path expression over the inputs' storage (null for inputs that are
/// not matrices over two sets).
StorageRule getIndexExprStorage(IndexExprOp op, ArrayRef<StorageAttr> inputs);

/// The storage of one value: nothing known yet, an encoding (with the op it
/// comes from, for diagnostics), or unsupported (with the op where that
/// arose and why).
class StorageLattice : public dataflow::AbstractSparseLattice {
public:
  MLIR_DEFINE_EXPLICIT_INTERNAL_INLINE_TYPE_ID(StorageLattice)
  using AbstractSparseLattice::AbstractSparseLattice;

  bool isUninitialized() const { return !encoding && !origin; }
  bool isUnsupported() const { return origin != nullptr; }
  StorageAttr getEncoding() const { return encoding; }
  Operation *getProducer() const { return producer; }
  Operation *getOrigin() const { return origin; }
  StringRef getReason() const { return reason; }

  /// Joins `rhs` into this storage.
  ChangeResult join(const AbstractSparseLattice &rhs) override;
  /// Joins `encoding`, which `from` produced.
  ChangeResult join(StorageAttr encoding, Operation *from);
  /// Makes this storage unsupported, because of `reason` at `at`.
  ChangeResult markUnsupported(Operation *at, StringRef why);
  void print(raw_ostream &os) const override;

private:
  StorageAttr encoding;
  Operation *producer = nullptr;
  Operation *origin = nullptr;
  std::string reason;
  /// How often a loop-carried value or a slot widened.
  unsigned growth = 0;
};

/// Computes the storage of every matrix over two sets in a function (not an
/// element function) by the rules of docs/storage.md.
class StorageAnalysis
    : public dataflow::SparseForwardDataFlowAnalysis<StorageLattice> {
public:
  using SparseForwardDataFlowAnalysis::SparseForwardDataFlowAnalysis;

  LogicalResult visitOperation(Operation *op,
                               ArrayRef<const StorageLattice *> operands,
                               ArrayRef<StorageLattice *> results) override;
  /// Calls of host functions (the only calls left after inlining) follow
  /// the rule of visitOperation.
  void visitExternalCall(CallOpInterface call,
                         ArrayRef<const StorageLattice *> arguments,
                         ArrayRef<StorageLattice *> results) override;
  void setToEntryState(StorageLattice *lattice) override;
};

} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_STORAGEANALYSIS_H
