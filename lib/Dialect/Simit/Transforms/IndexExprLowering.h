//===- IndexExprLowering.h - Index expressions as loop nests -----*- C++ -*-===//
//
// The state of lowering one simit.index_expr to a loop nest: which levels
// of which variables are bound, at which block positions the matrix
// operands are read, and the storage the loops follow. The loop machinery
// (choosing the next level, emitting its loop, reading operands, sums) is
// in IndexExprLoops.cpp; the driver in LowerIndexExpr.cpp.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_INDEXEXPRLOWERING_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_INDEXEXPRLOWERING_H

#include "LoopsLowering.h"

namespace mlir {
namespace simit {
namespace loops {

/// Whether the body multiplies or divides two values that both come from
/// matrix inputs.
bool multipliesMatrices(IndexExprOp op);
/// The variables whose sum (or, for the result's and the top-level summed
/// variables, the body) can be nonzero where every sparse matrix input
/// (`isSparseInput`) is zero: no matrix's sparsity bounds their loops.
llvm::SmallDenseSet<unsigned>
varsNonzeroOutsideMatrices(IndexExprOp op,
                           function_ref<bool(unsigned)> isSparseInput);

class IndexExprLowering {
public:
  IndexExprLowering(FunctionLowering &l, IndexExprOp op)
      : l(l), b(l.b), op(op), loc(op.getLoc()),
        scalarType(getComponentType(op.getType())) {}

  /// Lowers the expression. With `at`, the read of the result's one block
  /// (FunctionLowering::blockRead), maps `at` to that block alone where its
  /// row's sums allow (y = A x), else lowers the whole result.
  LogicalResult lower(ExtractOp at = nullptr);

private:
  /// A local tensor result of sums over sets: one sum per component.
  LogicalResult lowerLocalResultOfSums(ArrayRef<unsigned> summed,
                                       function_ref<FailureOr<Value>()> body);

private:
  unsigned numLevels(unsigned v) { return op.getDomain(v).size(); }
  Attribute level(unsigned v, unsigned i) { return op.getDomain(v)[i]; }
  bool isBound(unsigned v) {
    auto it = bound.find(v);
    return it != bound.end() && llvm::all_of(it->second, [](Value x) {
             return bool(x);
           });
  }
  bool isSetBound(unsigned v) {
    auto it = bound.find(v);
    return it != bound.end() && it->second[0];
  }
  /// The storage of input `i` (or of the result for i == number of inputs)
  /// as the loops follow it: a transposed incidence H(v, e) is followed as
  /// the incidence G(e, v) it is stored as (indexList swaps its variables;
  /// access() still reads each block in H's orientation).
  Storage storageOf(unsigned i) {
    Storage storage = i == op.getInputs().size()
                          ? resultStorage
                          : l.storageOf(op.getInputs()[i]);
    if (storage.kind == Storage::Kind::Incidence && storage.transposed)
      return Storage::incidenceTransposed(storage);
    return storage;
  }
  /// The variables of input `i` (or of the result) in storageOf's order.
  ArrayRef<int64_t> indexList(unsigned i) {
    if (i < swappedLists.size() && !swappedLists[i].empty())
      return swappedLists[i];
    if (i == op.getInputs().size())
      return op.getResultIndices();
    return op.getInputIndexList(i);
  }
  unsigned numMatrixOperands() { return op.getInputs().size() + 1; }

  /// The (variable, level) pairs of `vars` in level-major order (all
  /// variables' outer levels, then their first block levels, ...): the
  /// order of a tensor's component indices.
  SmallVector<std::pair<int64_t, unsigned>>
  levelMajorOrder(ArrayRef<int64_t> vars);
  /// The bound level indices of `vars` in level-major order.
  SmallVector<Value> levelMajor(ArrayRef<int64_t> vars);
  /// The extents of `vars`' levels (static ranges) in level-major order.
  SmallVector<int64_t> levelMajorExtents(ArrayRef<int64_t> vars);
  Value extent(unsigned v, unsigned i);
  /// Reads the component of input `i` at the bound variables.
  FailureOr<Value> access(unsigned i);
  /// The component of matrix input `i` at block (row, col) and indices
  /// `inner` within it: at the loop's position when it has one, else found
  /// by its storage (zero outside it).
  FailureOr<Value> blockAt(unsigned i, Value row, Value col,
                           SmallVector<Value> inner);
  /// The entry (row, col) of incidence input `i` at block indices
  /// `inner`: the sum of the edge's blocks at the endpoint. `loopPosition`,
  /// when the loop runs over the incidence's blocks, is the block's
  /// position: the entry is read at the edge's first block there, zero at
  /// the others.
  Value incidenceEntry(unsigned i, Value row, Value col, ArrayRef<Value> inner,
                       Value loopPosition);
  /// The entry (row, col) of stencil input `i` at block indices `inner`:
  /// the sum of its blocks whose offset names that column (on a grid
  /// narrower than the offsets, several do).
  Value stencilEntry(unsigned i, Value row, Value col, ArrayRef<Value> inner);
  /// Picks how to bind the next level of one of `vars`: returns the variable
  /// and whether a matrix couples it (then the loop runs over its pattern).
  struct Choice {
    unsigned var;
    unsigned levelIndex;
    int coupledBy = -1; // an operand that couples the variable
    unsigned partner = 0;
    /// The sparsity the loop follows: the coupling operands' join (a
    /// union of their patterns when none holds the others).
    Storage storage;
  };
  std::optional<Choice> choose(ArrayRef<unsigned> vars);
  /// Emits the loop for `choice`, calls `inner` inside it with the builder
  /// in the body; returns the loop's results.
  SmallVector<Value>
  emitLoop(const Choice &choice, ValueRange inits, bool parallel,
           function_ref<SmallVector<Value>(ValueRange)> inner);
  void unbind(const Choice &choice);
  /// Prefetches the block of matrix input `i` that lies
  /// FunctionLowering::prefetchMatrixBytes after block `position`.
  void prefetchAhead(unsigned i, Value position);
  /// The sum over `vars` of `body` (nested loops, loop-carried scalar) of
  /// numbers of `type` (default: the result's components; a nested
  /// simit.index_sum's own, such as the complex row sums of a norm).
  FailureOr<Value> sum(SmallVector<unsigned> vars,
                       function_ref<FailureOr<Value>()> body, bool parallelTop,
                       Type type = {});
  /// lhs + rhs in the scalar type (addf or addi).
  Value add(Value lhs, Value rhs);
  /// The result variable whose row a sum over a set (y = A x) can
  /// accumulate in loop-carried values: the only result variable over a
  /// set, not the column of a matrix read transposed (`readsTransposed`),
  /// with few enough static components per term to unroll.
  std::optional<unsigned>
  accumulatedRowVar(ArrayRef<unsigned> free, ArrayRef<unsigned> all,
                    function_ref<bool(unsigned)> readsTransposed);
  /// The result's levels but `rowVar`'s set level, in level-major order:
  /// those of a row's components.
  SmallVector<std::pair<int64_t, unsigned>> rowComponentLevels(unsigned rowVar);
  /// With `rowVar`'s set level bound: the sums of the row's terms over the
  /// other variables `all` in loop-carried values, static levels unrolled,
  /// one per component in rowComponentLevels' order.
  FailureOr<SmallVector<Value>> rowSums(unsigned rowVar,
                                        ArrayRef<unsigned> all);
  /// Binds `choice`'s static level to each of its values in turn, calling
  /// `body` for each, and unbinds it after.
  LogicalResult forEachStaticValue(const Choice &choice,
                                   function_ref<LogicalResult()> body);
  /// The terms one iteration of `loop` adds when its body has no loop of
  /// its own (its static levels unrolled), else nullopt.
  std::optional<int64_t> termsPerInnermostIteration(const Choice &loop,
                                                    ArrayRef<unsigned> all);
  /// rowSums' innermost loop with a loop-carried sum per term of its body
  /// (`terms` of them), added to `sums` at the components `componentOf`
  /// names after the loop.
  FailureOr<SmallVector<Value>>
  sumTermsApart(const Choice &loop, SmallVector<Value> sums, int64_t terms,
                ArrayRef<unsigned> all, function_ref<int64_t()> componentOf);
  /// The most terms an innermost loop sums apart: a 3x3 block's.
  static constexpr int64_t kMaxTermAccumulators = 9;
  /// Lanes of each loop-carried vector of sumTermsApart: 256 bits of
  /// doubles. With 512 (8 + 1 for a 3x3 block) the product alone was as
  /// fast, but springs-bunny's CG loop took 17 % longer, not 14 % less.
  static constexpr int64_t kTermLanes = 4;
  /// Inside the loop over `rowVar`'s set: stores each component of the
  /// row's sums into `output` once.
  LogicalResult accumulateRow(unsigned rowVar, ArrayRef<unsigned> all,
                              Value output);
  /// Evaluates the body with the bound variables: the scalar it yields.
  FailureOr<Value> evaluate(Block &block);
  LogicalResult lowerLocal();
  /// The array the result may be computed into directly: that of the
  /// variable or field the next operation stores the result to, when every
  /// input reading that array reads it at the result's own position.
  Value inPlaceTarget();

  FunctionLowering &l;
  OpBuilder &b;
  IndexExprOp op;
  Location loc;
  Type scalarType;
  Storage resultStorage;
  /// The variables whose terms can be nonzero outside the sparse matrices'
  /// blocks: each runs over its whole set.
  llvm::SmallDenseSet<unsigned> denseVars;
  DenseMap<unsigned, SmallVector<Value>> bound;
  /// Block positions of matrix operands bound by a pattern loop.
  DenseMap<unsigned, Value> positions;
  /// The operands whose position comes from a union's gather map, so may
  /// be -1 (no block there).
  llvm::SmallDenseSet<unsigned> gathered;
  /// The swapped variable lists of transposed incidences, by operand.
  SmallVector<SmallVector<int64_t, 2>> swappedLists;
  /// Whether the body multiplies or divides matrix entries and an input is
  /// an incidence: incidences are then read as entries (the sum of an
  /// edge's blocks at the endpoint), not block by block, and an incidence
  /// result keeps each entry in the edge's first block there.
  bool entrywiseIncidences = false;
  /// Whether a stencil meets a matrix of another storage or the body
  /// multiplies matrix entries: a loop over a stencil then visits an entry
  /// once per offset naming its column, so matrices are read as entries
  /// (stencilEntry for stencils), counted at the first such offset only
  /// (`stencilFirsts`).
  bool entrywiseStencils = false;
  /// Per variable bound by a loop over a stencil (entrywiseStencils):
  /// whether the loop's block is the first of its row naming its column.
  DenseMap<unsigned, Value> stencilFirsts;
  /// Variables summed by a simit.index_sum in the body.
  llvm::SmallDenseSet<unsigned> nestedVars;
  bool failedInside = false;
};

} // namespace loops
} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_INDEXEXPRLOWERING_H
