//===- LowerIndexExpr.cpp - Index expressions as loop nests ---------------===//
//
// Every index variable ranges over a hierarchy of levels (a set, then block
// ranges). The loop nest binds one level at a time:
//  - result variables first: the outermost level is an scf.parallel loop,
//  - then summed variables, accumulated in loop-carried scalars; a scalar
//    result sums its outermost level with scf.parallel + scf.reduce,
//  - the set level of a variable v that a matrix input A(u, v) pairs with a
//    bound variable u follows A's sparsity: the blocks of row u of the BCSR
//    pattern (rowptr/colidx), the endpoints of edge u for an incidence
//    matrix, or v = u for a diagonal matrix,
//  - other levels are dense loops over the set or range.
// `simit.index_sum` inside the body sums its variables at that point of the
// body (the fused form). Index expressions without sets are unrolled over
// their static ranges.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

namespace {
/// Whether the body multiplies or divides two values that both come from
/// matrix inputs.
bool multipliesMatrices(IndexExprOp op) {
  Block &body = op.getBody().front();
  auto fromMatrix = [&](Value v) {
    // The values a body computes from its arguments, seen through one
    // level of arithmetic.
    auto isMatrixArg = [&](Value x) {
      auto arg = dyn_cast<BlockArgument>(x);
      return arg && arg.getOwner() == &body &&
             op.getInputIndexList(arg.getArgNumber()).size() == 2;
    };
    if (isMatrixArg(v))
      return true;
    Operation *def = v.getDefiningOp();
    return def && llvm::any_of(def->getOperands(), isMatrixArg);
  };
  WalkResult walk = body.walk([&](Operation *inner) {
    if (isa<arith::MulFOp, arith::DivFOp, arith::MulIOp, arith::DivSIOp>(
            inner) &&
        fromMatrix(inner->getOperand(0)) && fromMatrix(inner->getOperand(1)))
      return WalkResult::interrupt();
    return WalkResult::advance();
  });
  return walk.wasInterrupted();
}

class IndexExprLowering {
public:
  IndexExprLowering(FunctionLowering &l, IndexExprOp op)
      : l(l), b(l.b), op(op), loc(op.getLoc()),
        scalarType(getComponentType(op.getType())) {}

  LogicalResult lower();

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
      return Storage::incidence(storage.edges, storage.rows,
                                storage.cardinality);
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

  /// The level indices of a tensor's components in level-major order (all
  /// dimensions' outer levels, then their first block levels, ...).
  SmallVector<Value> levelMajor(Type type, ArrayRef<int64_t> vars);
  Value extent(unsigned v, unsigned i);
  /// Reads the component of input `i` at the bound variables.
  FailureOr<Value> access(unsigned i);
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
  /// The sum over `vars` of `body` (nested loops, loop-carried scalar).
  FailureOr<Value> sum(SmallVector<unsigned> vars,
                       function_ref<FailureOr<Value>()> body,
                       bool parallelTop);
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
  DenseMap<unsigned, SmallVector<Value>> bound;
  /// Block positions of matrix operands bound by a pattern loop.
  DenseMap<unsigned, Value> positions;
  /// The operands whose position comes from a union's gather map, so may
  /// be -1 (no block there).
  llvm::SmallDenseSet<unsigned> gathered;
  /// The swapped variable lists of transposed incidences, by operand.
  SmallVector<SmallVector<int64_t, 2>> swappedLists;
  /// Variables summed by a simit.index_sum in the body.
  llvm::SmallDenseSet<unsigned> nestedVars;
  bool failedInside = false;
};
} // namespace

Value IndexExprLowering::extent(unsigned v, unsigned i) {
  Attribute lvl = level(v, i);
  if (auto set = dyn_cast<StringAttr>(lvl))
    return l.getSetSize(set);
  return l.indexConstant(cast<IntegerAttr>(lvl).getInt());
}

SmallVector<Value> IndexExprLowering::levelMajor(Type type,
                                                 ArrayRef<int64_t> vars) {
  SmallVector<Value> indices;
  unsigned maxLevels = 0;
  for (int64_t v : vars)
    maxLevels = std::max(maxLevels, numLevels(v));
  for (unsigned lvl = 0; lvl < maxLevels; ++lvl)
    for (int64_t v : vars)
      if (lvl < numLevels(v))
        indices.push_back(bound[v][lvl]);
  return indices;
}

FailureOr<Value> IndexExprLowering::access(unsigned i) {
  Value input = op.getInputs()[i];
  Value lowered = l.lookup(input);
  Type type = input.getType();
  ArrayRef<int64_t> vars = op.getInputIndexList(i);
  if (vars.empty())
    return lowered;
  SmallVector<Value> indices = levelMajor(type, vars);
  if (!hasSetDimension(type)) {
    // A flat vector: row-major over the level-major extents.
    SmallVector<int64_t> extents;
    unsigned maxLevels = 0;
    for (int64_t v : vars)
      maxLevels = std::max(maxLevels, numLevels(v));
    for (unsigned lvl = 0; lvl < maxLevels; ++lvl)
      for (int64_t v : vars)
        if (lvl < numLevels(v))
          extents.push_back(cast<IntegerAttr>(level(v, lvl)).getInt());
    Value flat = l.indexConstant(0);
    for (auto [index, size] : llvm::zip(indices, extents)) {
      flat = arith::MulIOp::create(b, loc, flat, l.indexConstant(size));
      flat = arith::AddIOp::create(b, loc, flat, index);
    }
    return l.component(type, lowered, flat);
  }
  Storage storage = storageOf(i);
  if (!storage.isMatrix())
    return memref::LoadOp::create(b, loc, lowered, indices).getResult();
  // Matrices: the outer pair of indices becomes a block position.
  Value row = indices[0], col = indices[1];
  SmallVector<Value> inner(indices.begin() + 2, indices.end());
  if (Value position = positions.lookup(i)) {
    if (!gathered.contains(i)) {
      inner.insert(inner.begin(), position);
      return memref::LoadOp::create(b, loc, lowered, inner).getResult();
    }
    // A union member without this block reads zero (at a valid position).
    Value present = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                          position, l.indexConstant(0));
    inner.insert(inner.begin(),
                 arith::SelectOp::create(b, loc, present, position,
                                         l.indexConstant(0)));
    Value value = memref::LoadOp::create(b, loc, lowered, inner);
    return arith::SelectOp::create(b, loc, present, value,
                                   l.zeroOf(scalarType))
        .getResult();
  }
  if (storage.kind == Storage::Kind::Diagonal) {
    // Off the diagonal the block is zero; rows are in range either way.
    inner.insert(inner.begin(), row);
    Value value = memref::LoadOp::create(b, loc, lowered, inner);
    Value onDiagonal = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                             row, col);
    return arith::SelectOp::create(b, loc, onDiagonal, value,
                                   l.zeroOf(scalarType))
        .getResult();
  }
  // Row and column are the input's own: read it in its own orientation.
  if (storage.kind == Storage::Kind::Incidence)
    return l.sumIncidenceBlocks(loc, l.storageOf(input), row, col, scalarType,
                                [&](Value position) {
                                  SmallVector<Value> at(inner);
                                  at.insert(at.begin(), position);
                                  return memref::LoadOp::create(b, loc,
                                                                lowered, at)
                                      .getResult();
                                });
  // Elsewhere a search of the row (a diagonal result read from a
  // pattern): zero where the matrix has no block.
  Value position = l.findBlock(loc, storage, row, col);
  Value present = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                        position, l.indexConstant(0));
  inner.insert(inner.begin(), arith::SelectOp::create(b, loc, present, position,
                                                      l.indexConstant(0)));
  Value value = memref::LoadOp::create(b, loc, lowered, inner);
  return arith::SelectOp::create(b, loc, present, value, l.zeroOf(scalarType))
      .getResult();
}

std::optional<IndexExprLowering::Choice>
IndexExprLowering::choose(ArrayRef<unsigned> vars) {
  // A set level that a bound variable's matrix row gives comes first. A
  // matrix result leads: its storage holds every nonzero of the body.
  // Otherwise, among the matrices pairing the same variables, the largest
  // sparsity leads (an edge pattern holds a diagonal).
  unsigned result = op.getInputs().size();
  for (unsigned v : vars) {
    if (isSetBound(v) || !isa<StringAttr>(level(v, 0)))
      continue;
    int best = -1;
    unsigned partner = 0;
    std::optional<Storage> joined;
    for (unsigned n = 0; n < numMatrixOperands(); ++n) {
      unsigned o = (result + n) % numMatrixOperands();
      if (best == static_cast<int>(result))
        break;
      Storage storage = storageOf(o);
      ArrayRef<int64_t> list = indexList(o);
      if (!storage.isMatrix() || list.size() != 2 || list[0] == list[1])
        continue;
      // A(u, v) couples v along its rows; A(v, u), read transposed, along
      // the rows of its transpose.
      bool transposed = list[0] == v;
      if ((!transposed && list[1] != v) ||
          !isSetBound(transposed ? list[1] : list[0]))
        continue;
      unsigned u = transposed ? list[1] : list[0];
      if (best >= 0 && u != partner)
        continue;
      std::optional<Storage> own =
          transposed ? transposedStorage(storage) : storage;
      if (!own)
        continue;
      if (best < 0) {
        best = o;
        partner = u;
        joined = own;
        continue;
      }
      // Operands that do not combine are read by search-free means only
      // when the loop's storage holds them; access() says otherwise.
      if (std::optional<Storage> both = joinStorages(*joined, *own))
        joined = both;
    }
    if (best >= 0)
      return Choice{v, 0, best, partner, *joined};
  }
  for (unsigned v : vars)
    if (!isSetBound(v) && isa<StringAttr>(level(v, 0)))
      return Choice{v, 0};
  for (unsigned v : vars)
    for (unsigned i = 0; i < numLevels(v); ++i)
      if (!bound.count(v) || !bound[v][i])
        return Choice{v, i};
  return std::nullopt;
}

void IndexExprLowering::unbind(const Choice &choice) {
  bound[choice.var][choice.levelIndex] = Value();
  if (choice.coupledBy >= 0)
    for (unsigned o = 0; o < numMatrixOperands(); ++o)
      if (indexList(o).size() == 2 &&
          llvm::is_contained(indexList(o), choice.var)) {
        positions.erase(o);
        gathered.erase(o);
      }
}

SmallVector<Value>
IndexExprLowering::emitLoop(const Choice &choice, ValueRange inits,
                            bool parallel,
                            function_ref<SmallVector<Value>(ValueRange)> inner) {
  unsigned v = choice.var;
  if (!bound.count(v))
    bound[v].assign(numLevels(v), Value());
  Value lb = l.indexConstant(0), ub = extent(v, choice.levelIndex);
  Value rowPtr, colIdx, row;
  if (choice.coupledBy >= 0) {
    const Storage &storage = choice.storage;
    row = bound[choice.partner][0];
    if (storage.kind == Storage::Kind::Diagonal) {
      // v = u: no loop, the diagonal block is the row's.
      bound[v][0] = row;
      for (unsigned o = 0; o < numMatrixOperands(); ++o)
        if (indexList(o).size() == 2 && indexList(o)[1] == v &&
            indexList(o)[0] == choice.partner && storageOf(o) == storage)
          positions[o] = row;
      // Without a loop the results are the inner values themselves.
      SmallVector<Value> results = inner(inits);
      unbind(choice);
      return results;
    }
    if (storage.kind == Storage::Kind::Stencil) {
      // One block per stencil offset; the column follows from the row.
      ub = l.indexConstant(storage.offsets.size());
    } else if (storage.kind == Storage::Kind::Incidence) {
      // Row u (an edge) has a block per endpoint k: column endpoints[u, k].
      colIdx = l.getEndpoints(storage.edges, storage.cardinality);
      ub = l.indexConstant(storage.cardinality);
    } else {
      rowPtr = l.rowPointers(storage);
      colIdx = l.columnIndices(storage);
      Value next = arith::AddIOp::create(b, loc, row, l.indexConstant(1));
      lb = arith::IndexCastOp::create(
          b, loc, b.getIndexType(),
          memref::LoadOp::create(b, loc, rowPtr, ValueRange{row}));
      ub = arith::IndexCastOp::create(
          b, loc, b.getIndexType(),
          memref::LoadOp::create(b, loc, rowPtr, ValueRange{next}));
    }
  }
  auto bindAt = [&](OpBuilder &nb, Value iv) {
    OpBuilder::InsertionGuard guard(b);
    if (choice.coupledBy < 0) {
      bound[v][choice.levelIndex] = iv;
      return;
    }
    b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
    const Storage &storage = choice.storage;
    Value position = iv;
    if (storage.kind == Storage::Kind::Stencil) {
      bound[v][0] = l.stencilColumn(storage, row, iv);
      position = l.stencilBlock(storage, row, iv);
    } else if (storage.kind == Storage::Kind::Incidence) {
      bound[v][0] = arith::IndexCastOp::create(
          b, loc, b.getIndexType(),
          memref::LoadOp::create(b, loc, colIdx, ValueRange{row, iv}));
      position = arith::AddIOp::create(
          b, loc,
          arith::MulIOp::create(b, loc, row,
                                l.indexConstant(storage.cardinality)),
          iv);
    } else {
      bound[v][0] = arith::IndexCastOp::create(
          b, loc, b.getIndexType(),
          memref::LoadOp::create(b, loc, colIdx, ValueRange{iv}));
    }
    for (unsigned o = 0; o < numMatrixOperands(); ++o) {
      ArrayRef<int64_t> list = indexList(o);
      if (list.size() != 2 || list[0] == list[1] ||
          !llvm::is_contained(list, v))
        continue;
      // Only a matrix that pairs v with the loop's row variable is read at
      // this row's blocks.
      bool transposed = list[0] == v;
      if ((transposed ? list[1] : list[0]) != choice.partner)
        continue;
      Storage own = storageOf(o);
      if (!transposed && own == storage) {
        positions[o] = position;
        continue;
      }
      // Another pattern or union over the same sets: its block at this
      // position (for a transposed read, the block at the mirrored
      // position), or -1, from a gather map built once per binding.
      auto gatherable = [](const Storage &s) {
        return s.kind == Storage::Kind::Pattern ||
               s.kind == Storage::Kind::Union;
      };
      std::optional<Storage> read = transposed ? transposedStorage(own) : own;
      if (!gatherable(storage) || !gatherable(own) || !read ||
          read->rows != storage.rows || read->cols != storage.cols)
        continue;
      positions[o] = arith::IndexCastOp::create(
          b, loc, b.getIndexType(),
          memref::LoadOp::create(b, loc,
                                 l.gatherMap(storage, own, transposed),
                                 ValueRange{iv}));
      gathered.insert(o);
    }
    nb.setInsertionPoint(b.getInsertionBlock(), b.getInsertionPoint());
  };
  Value step = l.indexConstant(1);
  if (parallel) {
    auto loop = scf::ParallelOp::create(
        b, loc, ValueRange{lb}, ValueRange{ub}, ValueRange{step}, inits,
        [&](OpBuilder &nb, Location, ValueRange ivs, ValueRange) {
          bindAt(nb, ivs[0]);
          OpBuilder::InsertionGuard guard(b);
          b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
          SmallVector<Value> results = inner({});
          if (inits.empty()) {
            scf::ReduceOp::create(b, loc);
            return;
          }
          auto reduce = scf::ReduceOp::create(b, loc, results);
          for (Region &region : reduce.getReductions()) {
            Block &block = region.front();
            OpBuilder rb = OpBuilder::atBlockEnd(&block);
            Value s = arith::AddFOp::create(rb, loc, block.getArgument(0),
                                            block.getArgument(1));
            scf::ReduceReturnOp::create(rb, loc, s);
          }
        });
    unbind(choice);
    return SmallVector<Value>(loop.getResults());
  }
  auto loop = scf::ForOp::create(
      b, loc, lb, ub, step, inits,
      [&](OpBuilder &nb, Location, Value iv, ValueRange args) {
        bindAt(nb, iv);
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
        SmallVector<Value> results = inner(args);
        scf::YieldOp::create(b, loc, results);
      });
  unbind(choice);
  return SmallVector<Value>(loop.getResults());
}

FailureOr<Value>
IndexExprLowering::sum(SmallVector<unsigned> vars,
                       function_ref<FailureOr<Value>()> body,
                       bool parallelTop) {
  std::optional<Choice> choice = choose(vars);
  if (!choice)
    return body();
  Value zero = l.zeroOf(scalarType);
  bool failedBody = false;
  auto accumulate = [&](Value acc, Value term) -> Value {
    if (isa<FloatType>(scalarType))
      return arith::AddFOp::create(b, loc, acc, term);
    return arith::AddIOp::create(b, loc, acc, term);
  };
  if (parallelTop && choice->coupledBy < 0 && isa<FloatType>(scalarType)) {
    SmallVector<Value> results = emitLoop(*choice, {zero}, true, [&](ValueRange) {
      FailureOr<Value> term = sum(vars, body, false);
      if (failed(term)) {
        failedBody = true;
        return SmallVector<Value>{zero};
      }
      return SmallVector<Value>{*term};
    });
    if (failedBody)
      return failure();
    return results[0];
  }
  SmallVector<Value> results = emitLoop(*choice, {zero}, false, [&](ValueRange args) {
    FailureOr<Value> term = sum(vars, body, false);
    if (failed(term)) {
      failedBody = true;
      return SmallVector<Value>{args[0]};
    }
    return SmallVector<Value>{accumulate(args[0], *term)};
  });
  if (failedBody)
    return failure();
  return results[0];
}

FailureOr<Value> IndexExprLowering::evaluate(Block &block) {
  for (Operation &inner : block) {
    // Inputs are read where they are used, with the variables bound there.
    for (Value operand : inner.getOperands()) {
      auto arg = dyn_cast<BlockArgument>(operand);
      if (!arg || arg.getOwner() != &op.getBody().front())
        continue;
      FailureOr<Value> value = access(arg.getArgNumber());
      if (failed(value))
        return failure();
      l.map(arg, *value);
    }
    if (auto yield = dyn_cast<YieldOp>(inner))
      return l.lookup(yield.getValue());
    if (auto nested = dyn_cast<IndexSumOp>(inner)) {
      SmallVector<unsigned> vars(nested.getVars().begin(),
                                 nested.getVars().end());
      FailureOr<Value> value =
          sum(vars, [&]() { return evaluate(nested.getBody().front()); },
              false);
      if (failed(value))
        return failure();
      l.map(nested.getResult(), *value);
      continue;
    }
    if (auto yield = dyn_cast<IndexSumYieldOp>(inner))
      return l.lookup(yield.getValue());
    if (failed(l.lowerOp(&inner)))
      return failure();
  }
  return op.emitError("index expression body without a terminator");
}

LogicalResult IndexExprLowering::lowerLocal() {
  // Everything is static: unroll every variable's range.
  unsigned numVars = op.getIndexVars().size();
  SmallVector<int64_t> extents(numVars, 1);
  for (unsigned v = 0; v < numVars; ++v)
    for (Attribute lvl : op.getDomain(v))
      extents[v] *= cast<IntegerAttr>(lvl).getInt();
  ArrayRef<int64_t> resultVars = op.getResultIndices();
  SmallVector<unsigned> summed;
  for (unsigned v = 0; v < numVars; ++v)
    if (!llvm::is_contained(resultVars, v) && !nestedVars.contains(v))
      summed.push_back(v);
  auto bindValue = [&](unsigned v, int64_t value) {
    SmallVector<Value> levels(numLevels(v));
    for (int64_t i = numLevels(v) - 1; i >= 0; --i) {
      int64_t size = cast<IntegerAttr>(level(v, i)).getInt();
      levels[i] = l.indexConstant(value % size);
      value /= size;
    }
    bound[v] = levels;
  };
  auto forEach = [&](ArrayRef<unsigned> vars,
                     function_ref<LogicalResult()> f) -> LogicalResult {
    int64_t total = 1;
    for (unsigned v : vars)
      total *= extents[v];
    for (int64_t flat = 0; flat < total; ++flat) {
      int64_t rest = flat;
      for (unsigned v : llvm::reverse(vars)) {
        bindValue(v, rest % extents[v]);
        rest /= extents[v];
      }
      if (failed(f()))
        return failure();
    }
    return success();
  };
  SmallVector<unsigned> free(resultVars.begin(), resultVars.end());
  // Components in level-major order of the result are produced by
  // enumerating the result's level-major indices.
  int64_t n = numComponents(op.getType());
  SmallVector<Value> components(n);
  auto resultPosition = [&]() {
    SmallVector<int64_t> extentsLM;
    SmallVector<Value> indices = levelMajor(op.getType(), resultVars);
    unsigned maxLevels = 0;
    for (int64_t v : resultVars)
      maxLevels = std::max(maxLevels, numLevels(v));
    for (unsigned lvl = 0; lvl < maxLevels; ++lvl)
      for (int64_t v : resultVars)
        if (lvl < numLevels(v))
          extentsLM.push_back(cast<IntegerAttr>(level(v, lvl)).getInt());
    int64_t flat = 0;
    for (auto [index, size] : llvm::zip(indices, extentsLM))
      flat = flat * size +
             cast<arith::ConstantIndexOp>(index.getDefiningOp()).value();
    return flat;
  };
  LogicalResult result = forEach(free, [&]() -> LogicalResult {
    Value total;
    LogicalResult inner = forEach(summed, [&]() -> LogicalResult {
      FailureOr<Value> term = evaluate(op.getBody().front());
      if (failed(term))
        return failure();
      total = !total ? *term
              : isa<FloatType>(scalarType)
                  ? arith::AddFOp::create(b, loc, total, *term).getResult()
                  : arith::AddIOp::create(b, loc, total, *term).getResult();
      return success();
    });
    if (failed(inner))
      return failure();
    components[free.empty() ? 0 : resultPosition()] = total;
    return success();
  });
  if (failed(result))
    return failure();
  l.map(op, l.fromComponents(l.convertType(op.getType()), components));
  return success();
}

Value IndexExprLowering::inPlaceTarget() {
  if (resultStorage.isMatrix() || !op->hasOneUse())
    return nullptr;
  Operation *next = op->getNextNode();
  if (!next || *op->getUsers().begin() != next)
    return nullptr;
  Value target;
  if (auto store = dyn_cast<StoreOp>(next)) {
    target = l.lookup(store.getRef());
  } else if (auto write = dyn_cast<FieldWriteOp>(next)) {
    auto set = cast<SetType>(write.getSet().getType());
    target = l.getField(set.getName(), write.getFieldAttr(),
                        set.getElement().getFieldType(write.getField()));
  }
  if (!target || target.getType() != l.convertType(op.getType()))
    return nullptr;
  for (auto [i, input] : llvm::enumerate(op.getInputs()))
    if (l.lookup(input) == target &&
        op.getInputIndexList(i) != op.getResultIndices())
      return nullptr;
  return target;
}

LogicalResult IndexExprLowering::lower() {
  op.walk([&](IndexSumOp nested) {
    for (int64_t v : nested.getVars())
      nestedVars.insert(v);
  });
  bool system = hasSetDimension(op.getType()) ||
                llvm::any_of(op.getInputs().getTypes(), hasSetDimension);
  if (!system)
    return lowerLocal();

  unsigned numVars = op.getIndexVars().size();
  for (unsigned v = 0; v < numVars; ++v)
    for (unsigned i = 1; i < numLevels(v); ++i)
      if (!isa<IntegerAttr>(level(v, i)))
        return op.emitError("index variables whose inner levels are sets are "
                            "not supported by the loop lowering");
  for (auto [i, input] : llvm::enumerate(op.getInputs())) {
    auto type = dyn_cast<SystemTensorType>(input.getType());
    if (type && type.isSystem() && type.getOrder() == 2 &&
        isa<StringAttr>(type.getDims()[0]) &&
        isa<StringAttr>(type.getDims()[1]) &&
        !l.storageOf(input).isMatrix())
      return op.emitError("input #")
             << i << " is a system matrix of unknown sparsity";
  }

  // An incidence holds a block per (edge, endpoint position); an edge
  // naming one endpoint twice has two blocks in one column, which sum to
  // the entry. Sums and scalings of the blocks are right; products and
  // quotients of two matrices' blocks are not.
  for (Value input : op.getInputs()) {
    Storage s = l.storageOf(input);
    if (s.kind == Storage::Kind::Incidence && multipliesMatrices(op))
      return op.emitError("element-wise products and quotients of matrices "
                          "stored as ")
             << s.describe() << " are not supported by the loop lowering yet";
  }
  // Inputs, then the result.
  swappedLists.resize(op.getInputs().size() + 1);
  for (auto [i, input] : llvm::enumerate(op.getInputs())) {
    Storage s = l.storageOf(input);
    if (s.kind == Storage::Kind::Incidence && s.transposed)
      swappedLists[i] = {op.getInputIndexList(i)[1], op.getInputIndexList(i)[0]};
  }

  ArrayRef<int64_t> resultVars = op.getResultIndices();
  SmallVector<unsigned> summed;
  for (unsigned v = 0; v < numVars; ++v)
    if (!llvm::is_contained(resultVars, v) && !nestedVars.contains(v))
      summed.push_back(v);
  auto body = [&]() { return evaluate(op.getBody().front()); };

  // A scalar: one sum.
  if (resultVars.empty()) {
    FailureOr<Value> total = sum(summed, body, /*parallelTop=*/true);
    if (failed(total))
      return failure();
    l.map(op, *total);
    return success();
  }

  auto type = dyn_cast<SystemTensorType>(op.getType());
  if (!type || !type.isSystem())
    return op.emitError("an index expression over sets must produce a "
                        "system tensor or a scalar");
  // A matrix result is stored as its type says (simit-assign-storage reads
  // the body as a path expression, so the storage holds every nonzero); a
  // vector result is dense.
  if (type.getOrder() == 2 && isa<StringAttr>(type.getDims()[0]) &&
      isa<StringAttr>(type.getDims()[1])) {
    if (!summed.empty())
      return op.emitError("products of system matrices are not supported by "
                          "the loop lowering");
    resultStorage = l.storageOf(op);
    if (!resultStorage.isMatrix())
      return op.emitError("a system matrix result needs a sparse input");
    // A transposed incidence result is written edge by edge, as the
    // incidence it transposes: the edge variable's loop comes first.
    if (resultStorage.kind == Storage::Kind::Incidence &&
        resultStorage.transposed)
      swappedLists.back() = {resultVars[1], resultVars[0]};
  }
  ArrayRef<int64_t> resultOrder = indexList(op.getInputs().size());
  SmallVector<unsigned> free(resultOrder.begin(), resultOrder.end());
  bool sparseSum =
      !resultStorage.isMatrix() && llvm::any_of(summed, [&](unsigned v) {
        return isa<StringAttr>(level(v, 0));
      });
  // A sum over a set into a blocked vector (y = A x, y = A' x) runs each
  // row's blocks once: for the row, for its blocks, for the block's
  // components, add into the (zeroed) result at the row, or at the block's
  // column when A is read transposed. Otherwise every result component is
  // written once by the loop nest.
  Value output = inPlaceTarget();
  if (output && sparseSum)
    l.fill(loc, output, l.zeroOf(scalarType));
  if (!output)
    output = l.allocSystem(loc, type, resultStorage, sparseSum);
  if (sparseSum) {
    SmallVector<unsigned> all(free);
    llvm::append_range(all, summed);
    // A result variable that is the column of a matrix read transposed
    // (y(j) = A(i, j) x(i)) is not looped over: the loop runs over A's
    // rows i, binds j from each row's blocks and adds into y(j).
    auto transposedRow = [&](unsigned v) -> std::optional<unsigned> {
      for (unsigned o = 0; o < op.getInputs().size(); ++o) {
        ArrayRef<int64_t> list = indexList(o);
        if (storageOf(o).isMatrix() && list.size() == 2 && list[1] == v &&
            list[0] != v && !isSetBound(list[0]) &&
            !llvm::is_contained(free, list[0]))
          return list[0];
      }
      return std::nullopt;
    };
    std::function<LogicalResult(bool)> loopAll =
        [&](bool outermost) -> LogicalResult {
      std::optional<Choice> choice;
      for (unsigned v : free)
        if (!isSetBound(v) && isa<StringAttr>(level(v, 0))) {
          std::optional<unsigned> row = transposedRow(v);
          choice = row ? Choice{*row, 0} : choose({v});
          break;
        }
      if (!choice)
        choice = choose(all);
      if (!choice) {
        FailureOr<Value> value = evaluate(op.getBody().front());
        if (failed(value))
          return failure();
        SmallVector<Value> indices = levelMajor(type, resultVars);
        Value old = memref::LoadOp::create(b, loc, output, indices);
        Value sum = isa<FloatType>(scalarType)
                        ? arith::AddFOp::create(b, loc, old, *value).getResult()
                        : arith::AddIOp::create(b, loc, old, *value).getResult();
        memref::StoreOp::create(b, loc, sum, output, indices);
        return success();
      }
      bool parallel = outermost && choice->coupledBy < 0 &&
                      llvm::is_contained(free, choice->var);
      LogicalResult inner = success();
      emitLoop(*choice, {}, parallel, [&](ValueRange) {
        if (failed(loopAll(false)))
          inner = failure();
        return SmallVector<Value>{};
      });
      return inner;
    };
    if (failed(loopAll(true)))
      return failure();
    l.map(op, output);
    return success();
  }

  // Loops over the result's levels, then the sum, then the store.
  unsigned resultOperand = op.getInputs().size();
  std::function<LogicalResult(bool)> loopFree =
      [&](bool outermost) -> LogicalResult {
    std::optional<Choice> choice = choose(free);
    if (!choice) {
      FailureOr<Value> value = sum(summed, body, false);
      if (failed(value))
        return failure();
      SmallVector<Value> indices = levelMajor(type, resultVars);
      if (resultStorage.isMatrix()) {
        indices.erase(indices.begin(), indices.begin() + 2);
        indices.insert(indices.begin(), positions.lookup(resultOperand));
      }
      memref::StoreOp::create(b, loc, *value, output, indices);
      return success();
    }
    LogicalResult inner = success();
    emitLoop(*choice, {}, outermost && choice->coupledBy < 0,
             [&](ValueRange) {
               if (failed(loopFree(false)))
                 inner = failure();
               return SmallVector<Value>{};
             });
    return inner;
  };
  if (failed(loopFree(true)))
    return failure();
  l.map(op, output);
  return success();
}

LogicalResult FunctionLowering::lowerIndexExpr(IndexExprOp op) {
  // The loop nests sum with arith on floats and integers only.
  if (isa<ComplexType>(getComponentType(op.getType())))
    return op.emitError("index expressions on complex tensors are not "
                        "supported by the loop lowering yet");
  return IndexExprLowering(*this, op).lower();
}
