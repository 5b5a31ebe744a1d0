//===- ElementLoopVectorizer.h - One element loop across lanes -*- C++ -*-===//
//
// The rewriter of one element loop behind simit-vectorize-element-loops:
// planning (which ops run across lanes) in VectorizeElementLoops.cpp, the
// rewrite in ElementLoopRewrite.cpp.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_ELEMENTLOOPVECTORIZER_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_ELEMENTLOOPVECTORIZER_H

#include "mlir/Dialect/MemRef/IR/MemRef.h"
#include "mlir/Dialect/SCF/IR/SCF.h"
#include "mlir/IR/IRMapping.h"
#include "llvm/ADT/SetVector.h"

#include <map>
#include <tuple>

namespace mlir {
namespace simit {
namespace element_vectorize {

/// The scalar type of one component of `type` (a scalar or a vector of
/// scalars), or null when it is neither.
Type componentType(Type type);
int64_t componentCount(Type type);
bool allConstantIndices(ValueRange indices);
/// The linear position of constant `indices` in a memref of `shape`.
int64_t linearPosition(ArrayRef<int64_t> shape, ValueRange indices);
/// The linear position in `type` of the first component at the leading
/// `position` (a vector.extract's or vector.insert's).
int64_t firstComponent(VectorType type, ArrayRef<int64_t> position);
/// The memref a view (subview, cast, ...) looks into, through every view.
Value viewRoot(Value memref);

/// Rewrites one loop. Ops of its body are either vector ops, run once for
/// `lanes` elements (a value that differs between elements becomes one
/// vector<lanes x T> per component, a value that does not stays as it was),
/// or lane ops, run for each element in order after the vector ops.
class ElementLoopVectorizer {
public:
  ElementLoopVectorizer(scf::ParallelOp loop, unsigned vectorBits,
                        int64_t minVectorOps)
      : loop(loop), body(loop.getBody()), iv(loop.getInductionVars()[0]),
        vectorBits(vectorBits), minVectorOps(minVectorOps) {}

  /// Classifies the body's ops; false when the loop is not worth
  /// vectorising.
  bool plan();
  void rewrite();

private:
  // Planning.
  void findPromotableAllocas();
  bool isPromotedAccess(Operation *op, Value &alloca) const;
  void findWrittenMemrefs();
  bool isReadOnlyLoad(Operation *op) const;
  bool canWiden(Operation *op) const;
  bool usesAny(Operation *op, const DenseSet<Value> &values) const;
  bool classify(Value &demote);

  // Rewriting.
  ArrayRef<Value> wide(OpBuilder &b, Value value);
  Value broadcastScalar(OpBuilder &b, Value scalar);
  void widen(OpBuilder &b, Operation *op);
  void widenAllocaAccess(OpBuilder &b, Operation *op, Value alloca);
  Value laneScalar(OpBuilder &b, Value value, int64_t lane);
  SmallVector<Value> laneIndices(OpBuilder &b, ValueRange indices,
                                 int64_t lane);
  std::pair<Value, Value> blocksSource(OpBuilder &b, Value memref,
                                       int64_t blockSize);
  Value elementBlockComponent(OpBuilder &b, memref::LoadOp load);
  void gather(OpBuilder &b, memref::LoadOp load);
  void prefetchLanes(OpBuilder &b, memref::PrefetchOp prefetch);
  /// Where the lane phase finds a value: its components from `offset` on
  /// in `memref`, [lane][component] when transposed, else
  /// [component][lane].
  struct LaneBuffer {
    Value memref;
    bool transposed;
    int64_t offset;
  };
  void storeForLanes(OpBuilder &b, ArrayRef<Value> values);
  void loadForLane(OpOperand &read);
  VectorType laneType(Type component) const {
    return VectorType::get({lanes}, component);
  }

  scf::ParallelOp loop;
  Block *body;
  Value iv;
  unsigned vectorBits;
  int64_t minVectorOps;
  int64_t lanes = 0;

  /// Allocas of local tensors held as values; a fill loop (an scf.parallel
  /// storing one value to every component) counts as an access.
  DenseSet<Value> promoted;
  /// Roots of the memrefs the body may write (other than promoted allocas).
  DenseSet<Value> writtenRoots;
  DenseSet<Operation *> laneOps;
  DenseSet<Operation *> prefetches;
  SetVector<Value> needed;
  /// Values (results of vector ops, and the induction variable) that differ
  /// between elements.
  DenseSet<Value> varying;

  IRMapping uniform;
  DenseMap<Value, SmallVector<Value>> components;
  DenseMap<Value, SmallVector<Value>> allocaState;
  /// The element of the vector loop's first lane, the set's last element
  /// (lanes past it repeat it), and how many lanes hold elements.
  Value base, lastElement, elementsInLanes;
  /// Scalars of varying index values, per lane (laneScalar()).
  DenseMap<Value, SmallVector<Value>> laneScalars;
  /// Loads already made, by memref and indices.
  std::map<SmallVector<const void *>, Value> gathered;
  /// The blocks of all lanes of an element field (elementBlockComponent()).
  DenseMap<Value, Value> elementBlocks;
  /// The lane phase: its induction variable, the buffers it reads, and the
  /// loads of their components already made in each block.
  Value lane;
  DenseMap<Value, LaneBuffer> laneBuffers;
  DenseMap<std::tuple<Block *, Value, int64_t>, Value> laneLoads;
};

} // namespace element_vectorize
} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_ELEMENTLOOPVECTORIZER_H
