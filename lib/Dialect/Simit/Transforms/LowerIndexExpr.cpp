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

#include "IndexExprLowering.h"

#include "mlir/Dialect/Vector/IR/VectorOps.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

LogicalResult IndexExprLowering::lowerLocalResultOfSums(
    ArrayRef<unsigned> summed, function_ref<FailureOr<Value>()> body) {
  // A local tensor summed over sets (`w = R' * x` of a matrix[V,2]): one
  // sum per component, its result variables bound to the component's
  // indices, in row-major order.
  ArrayRef<int64_t> resultVars = op.getResultIndices();
  SmallVector<int64_t> extents;
  for (int64_t v : resultVars) {
    auto range =
        numLevels(v) == 1 ? dyn_cast<IntegerAttr>(level(v, 0)) : IntegerAttr();
    if (!range)
      return op.emitError("an index expression over sets must produce a "
                          "system tensor, a scalar or an unblocked local "
                          "tensor");
    extents.push_back(range.getInt());
  }
  int64_t total = 1;
  for (int64_t extent : extents)
    total *= extent;
  SmallVector<Value> components;
  for (int64_t flat = 0; flat < total; ++flat) {
    int64_t rest = flat;
    for (int64_t d = resultVars.size() - 1; d >= 0; --d) {
      bound[resultVars[d]] = {l.indexConstant(rest % extents[d])};
      rest /= extents[d];
    }
    FailureOr<Value> component =
        sum(SmallVector<unsigned>(summed), body, /*parallelTop=*/true);
    if (failed(component))
      return failure();
    components.push_back(*component);
  }
  for (int64_t v : resultVars)
    bound.erase(v);
  l.map(op, l.fromComponents(l.convertType(op.getType()), components));
  return success();
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
      FailureOr<Value> value = sum(
          vars, [&]() { return evaluate(nested.getBody().front()); }, false,
          nested.getResult().getType());
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
    int64_t flat = 0;
    for (auto [index, size] :
         llvm::zip(levelMajor(resultVars), levelMajorExtents(resultVars)))
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
      total = total ? add(total, *term) : *term;
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

Value IndexExprLowering::add(Value lhs, Value rhs) {
  return addNumbers(b, loc, lhs, rhs);
}

std::optional<unsigned> IndexExprLowering::accumulatedRowVar(
    ArrayRef<unsigned> free, ArrayRef<unsigned> all,
    function_ref<bool(unsigned)> readsTransposed) {
  // The one result variable over a set, not a transposed read's column:
  // its loop comes first and every term of its row lands in that row.
  std::optional<unsigned> row;
  for (unsigned v : free) {
    if (!isa<StringAttr>(level(v, 0)))
      continue;
    if (row || readsTransposed(v))
      return std::nullopt;
    row = v;
  }
  if (!row)
    return std::nullopt;
  // The static levels are unrolled inside the row; beyond this many terms
  // per block the body would outgrow the registers it is meant to use.
  constexpr int64_t kMaxUnrolledTerms = 256;
  int64_t terms = 1;
  for (unsigned v : all)
    for (unsigned i = 0; i < numLevels(v); ++i)
      if (auto size = dyn_cast<IntegerAttr>(level(v, i)))
        terms *= size.getInt();
  if (terms > kMaxUnrolledTerms)
    return std::nullopt;
  return row;
}

SmallVector<std::pair<int64_t, unsigned>>
IndexExprLowering::rowComponentLevels(unsigned rowVar) {
  SmallVector<std::pair<int64_t, unsigned>> levels;
  for (auto vl : levelMajorOrder(op.getResultIndices()))
    if (vl.first != rowVar || vl.second != 0)
      levels.push_back(vl);
  return levels;
}

LogicalResult
IndexExprLowering::forEachStaticValue(const Choice &choice,
                                      function_ref<LogicalResult()> body) {
  unsigned v = choice.var;
  if (!bound.count(v))
    bound[v].assign(numLevels(v), Value());
  int64_t size = cast<IntegerAttr>(level(v, choice.levelIndex)).getInt();
  for (int64_t k = 0; k < size; ++k) {
    bound[v][choice.levelIndex] = l.indexConstant(k);
    if (failed(body()))
      return failure();
  }
  bound[v][choice.levelIndex] = Value();
  return success();
}

std::optional<int64_t>
IndexExprLowering::termsPerInnermostIteration(const Choice &loop,
                                              ArrayRef<unsigned> all) {
  // Set levels are chosen before static ones: the loop is innermost when
  // no other variable's set level is left, and its body unrolls every
  // static level that is not bound yet.
  int64_t terms = 1;
  for (unsigned v : all) {
    if (v != loop.var && !isSetBound(v) && isa<StringAttr>(level(v, 0)))
      return std::nullopt;
    for (unsigned i = 0; i < numLevels(v); ++i)
      if (auto size = dyn_cast<IntegerAttr>(level(v, i)))
        if (!bound.count(v) || !bound[v][i])
          terms *= size.getInt();
  }
  return terms;
}

FailureOr<SmallVector<Value>>
IndexExprLowering::sumTermsApart(const Choice &loop, SmallVector<Value> sums,
                                 int64_t terms, ArrayRef<unsigned> all,
                                 function_ref<int64_t()> componentOf) {
  // Term k of every iteration (a block's entry (i, j) for y = A x) has a
  // sum of its own, a lane of loop-carried vectors of power-of-two sizes
  // up to kTermLanes (9 terms: 4 + 4 + 1), each a machine register: an
  // iteration's terms are added with one vector addition per chunk, whose
  // operands the SLP vectoriser builds with vector loads and
  // multiplications, and the loop's chain of dependent additions is one
  // per iteration. Each component then adds its terms' sums in term order:
  // a fixed order, so results do not depend on threads.
  SmallVector<int64_t> chunks;
  for (int64_t left = terms; left > 0;)
    chunks.push_back(std::min(kTermLanes, int64_t(1) << llvm::Log2_64(left))),
        left -= chunks.back();
  SmallVector<Value> zeros;
  for (int64_t size : chunks) {
    Type type = size == 1 ? scalarType : VectorType::get({size}, scalarType);
    zeros.push_back(arith::ConstantOp::create(
        b, loc, type, cast<TypedAttr>(b.getZeroAttr(type))));
  }
  SmallVector<int64_t> componentOfTerm;
  bool failedInner = false;
  SmallVector<Value> accumulated =
      emitLoop(loop, zeros, /*parallel=*/false, [&](ValueRange args) {
        SmallVector<Value> termValues;
        std::function<LogicalResult()> unroll = [&]() -> LogicalResult {
          std::optional<Choice> choice = choose(all);
          if (!choice) {
            FailureOr<Value> term = evaluate(op.getBody().front());
            if (failed(term))
              return failure();
            componentOfTerm.push_back(componentOf());
            termValues.push_back(*term);
            return success();
          }
          return forEachStaticValue(*choice, unroll);
        };
        if (failed(unroll()) ||
            termValues.size() != static_cast<size_t>(terms)) {
          failedInner = true;
          return SmallVector<Value>(args);
        }
        SmallVector<Value> next;
        ArrayRef<Value> rest(termValues);
        for (auto [size, sum] : llvm::zip(chunks, args)) {
          Value chunk =
              size == 1 ? rest.front()
                        : vector::FromElementsOp::create(b, loc, sum.getType(),
                                                         rest.take_front(size));
          next.push_back(add(sum, chunk));
          rest = rest.drop_front(size);
        }
        return next;
      });
  if (failedInner)
    return failure();
  size_t k = 0;
  for (auto [size, sum] : llvm::zip(chunks, accumulated))
    for (int64_t lane = 0; lane < size; ++lane, ++k) {
      Value term =
          size == 1 ? sum : vector::ExtractOp::create(b, loc, sum, lane);
      sums[componentOfTerm[k]] = add(sums[componentOfTerm[k]], term);
    }
  return sums;
}

FailureOr<SmallVector<Value>>
IndexExprLowering::rowSums(unsigned rowVar, ArrayRef<unsigned> all) {
  SmallVector<std::pair<int64_t, unsigned>> componentLevels =
      rowComponentLevels(rowVar);
  int64_t numComponents = 1;
  for (auto [v, lvl] : componentLevels)
    numComponents *= cast<IntegerAttr>(level(v, lvl)).getInt();
  auto componentOf = [&]() {
    int64_t flat = 0;
    for (auto [v, lvl] : componentLevels)
      flat =
          flat * cast<IntegerAttr>(level(v, lvl)).getInt() +
          cast<arith::ConstantIndexOp>(bound[v][lvl].getDefiningOp()).value();
    return flat;
  };

  // Sums in the order of the loop nest the terms would otherwise be added
  // to memory in: set levels as loops carrying the sums, static levels
  // unrolled (their positions become constants).
  std::function<FailureOr<SmallVector<Value>>(SmallVector<Value>)> sumTerms =
      [&](SmallVector<Value> sums) -> FailureOr<SmallVector<Value>> {
    std::optional<Choice> choice = choose(all);
    if (!choice) {
      FailureOr<Value> term = evaluate(op.getBody().front());
      if (failed(term))
        return failure();
      int64_t component = componentOf();
      sums[component] = add(sums[component], *term);
      return sums;
    }
    if (choice->coupledBy < 0 &&
        isa<IntegerAttr>(level(choice->var, choice->levelIndex))) {
      if (failed(forEachStaticValue(*choice, [&]() -> LogicalResult {
            FailureOr<SmallVector<Value>> next = sumTerms(std::move(sums));
            if (failed(next))
              return failure();
            sums = std::move(*next);
            return success();
          })))
        return failure();
      return sums;
    }
    if (std::optional<int64_t> terms = termsPerInnermostIteration(*choice, all);
        terms && *terms > numComponents && *terms <= kMaxTermAccumulators &&
        isa<FloatType, IntegerType>(scalarType))
      return sumTermsApart(*choice, std::move(sums), *terms, all, componentOf);
    bool failedInner = false;
    SmallVector<Value> results =
        emitLoop(*choice, sums, /*parallel=*/false, [&](ValueRange args) {
          FailureOr<SmallVector<Value>> next =
              sumTerms(SmallVector<Value>(args));
          if (failed(next)) {
            failedInner = true;
            return SmallVector<Value>(args);
          }
          return *next;
        });
    if (failedInner)
      return failure();
    return results;
  };
  return sumTerms(SmallVector<Value>(numComponents, l.zeroOf(scalarType)));
}

LogicalResult IndexExprLowering::accumulateRow(unsigned rowVar,
                                               ArrayRef<unsigned> all,
                                               Value output) {
  FailureOr<SmallVector<Value>> sums = rowSums(rowVar, all);
  if (failed(sums))
    return failure();
  // One store per component of the row.
  SmallVector<std::pair<int64_t, unsigned>> componentLevels =
      rowComponentLevels(rowVar);
  for (auto [component, value] : llvm::enumerate(*sums)) {
    int64_t rest = component;
    for (auto [v, lvl] : llvm::reverse(componentLevels)) {
      int64_t size = cast<IntegerAttr>(level(v, lvl)).getInt();
      bound[v][lvl] = l.indexConstant(rest % size);
      rest /= size;
    }
    memref::StoreOp::create(b, loc, value, output,
                            levelMajor(op.getResultIndices()));
  }
  for (auto [v, lvl] : componentLevels)
    bound[v][lvl] = Value();
  return success();
}

LogicalResult IndexExprLowering::lower(ExtractOp at) {
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
  // the entry. Sums and scalings of the blocks are right position by
  // position; products and quotients of two matrices' blocks are computed
  // on the entries.
  entrywiseIncidences =
      multipliesMatrices(op) && llvm::any_of(op.getInputs(), [&](Value in) {
        return l.storageOf(in).kind == Storage::Kind::Incidence;
      });
  denseVars = varsNonzeroOutsideMatrices(op, [&](unsigned i) {
    Storage s = l.storageOf(op.getInputs()[i]);
    return s.isMatrix() && s.kind != Storage::Kind::DenseMatrix &&
           op.getInputIndexList(i).size() == 2;
  });
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

  // A loop over a stencil on a grid narrower than its offsets visits an
  // entry once per offset naming its column: block by block is right only
  // when every matrix is that stencil, read as the result is written (not
  // transposed: the transposed entry lands at another offset, which may
  // name the same column as one the loop also writes), and the body adds
  // and scales them.
  auto decideEntrywiseStencils = [&] {
    SmallVector<Storage> matrixStorages;
    // The order the loops bind variables in: the result's set variables, or
    // for sums into a scalar or a local tensor the top-level summed ones
    // (nested sums' variables come after all of them).
    SmallVector<int64_t> order;
    for (int64_t v : resultVars)
      if (isa<StringAttr>(level(v, 0)))
        order.push_back(v);
    if (order.empty())
      order.assign(summed.begin(), summed.end());
    auto position = [&](int64_t v) {
      return static_cast<size_t>(llvm::find(order, v) - order.begin());
    };
    bool transposesMatrix = false;
    for (auto [i, in] : llvm::enumerate(op.getInputs())) {
      if (!l.storageOf(in).isMatrix())
        continue;
      matrixStorages.push_back(l.storageOf(in));
      // Read transposed: its column is bound before its row (or its row by
      // a nested sum), as A(j, i) in C(i, j) = A(j, i), in y(i) = sum_j
      // A(j, i) x(j) and in x' (A' x).
      ArrayRef<int64_t> list = op.getInputIndexList(i);
      transposesMatrix |=
          list.size() == 2 && position(list[1]) < position(list[0]);
    }
    if (resultStorage.isMatrix())
      matrixStorages.push_back(resultStorage);
    entrywiseStencils = llvm::any_of(matrixStorages,
                                     [](const Storage &s) {
                                       return s.kind == Storage::Kind::Stencil;
                                     }) &&
                        (multipliesMatrices(op) || transposesMatrix ||
                         llvm::any_of(matrixStorages, [&](const Storage &s) {
                           return s != matrixStorages.front();
                         }));
  };
  // A scalar: one sum.
  if (resultVars.empty()) {
    decideEntrywiseStencils();
    FailureOr<Value> total = sum(summed, body, /*parallelTop=*/true);
    if (failed(total))
      return failure();
    l.map(op, *total);
    return success();
  }

  auto type = dyn_cast<SystemTensorType>(op.getType());
  if (!type || !type.isSystem()) {
    decideEntrywiseStencils();
    return lowerLocalResultOfSums(summed, body);
  }
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
  decideEntrywiseStencils();
  ArrayRef<int64_t> resultOrder = indexList(op.getInputs().size());
  SmallVector<unsigned> free(resultOrder.begin(), resultOrder.end());
  bool sparseSum =
      !resultStorage.isMatrix() && llvm::any_of(summed, [&](unsigned v) {
        return isa<StringAttr>(level(v, 0));
      });
  // A sum over a set into a blocked vector (y = A x, y = A' x) runs each
  // row's blocks once: for the row, for its blocks, for the block's
  // components. Where the row is the result's own (y = A x), the row's
  // components are summed in loop-carried values and stored once, so the
  // result needs no zero fill (accumulateRows); where the column of a
  // matrix read transposed is the result's (y = A' x), each term is added
  // into the zeroed result at the block's column. Otherwise every result
  // component is written once by the loop nest.
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
    std::optional<unsigned> rowVar = accumulatedRowVar(free, all, [&](
                                         unsigned v) {
      return transposedRow(v).has_value();
    });
    // Block p alone of y = A x, read there and nowhere else: row p's sums.
    if (rowVar && at) {
      bound[*rowVar].assign(numLevels(*rowVar), Value());
      bound[*rowVar][0] = l.lookup(at.getIndices()[0]);
      FailureOr<SmallVector<Value>> sums = rowSums(*rowVar, all);
      if (failed(sums))
        return failure();
      l.map(at, sums->size() == 1 && !isa<ShapedType>(at.getType())
                    ? sums->front()
                    : l.fromComponents(l.convertType(at.getType()), *sums));
      return success();
    }
    Value output = inPlaceTarget();
    if (output && !rowVar)
      l.fill(loc, output, l.zeroOf(scalarType));
    if (!output)
      output = l.allocSystem(loc, type, resultStorage, !rowVar);
    if (rowVar) {
      LogicalResult rows = success();
      emitLoop(Choice{*rowVar, 0}, {}, /*parallel=*/true, [&](ValueRange) {
        if (failed(accumulateRow(*rowVar, all, output)))
          rows = failure();
        return SmallVector<Value>{};
      });
      if (failed(rows))
        return failure();
      l.map(op, output);
      return success();
    }
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
        SmallVector<Value> indices = levelMajor(resultVars);
        Value old = memref::LoadOp::create(b, loc, output, indices);
        memref::StoreOp::create(b, loc, add(old, *value), output, indices);
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

  Value output = inPlaceTarget();
  if (!output)
    output = l.allocSystem(loc, type, resultStorage, false);
  // Loops over the result's levels, then the sum, then the store.
  unsigned resultOperand = op.getInputs().size();
  std::function<LogicalResult(bool)> loopFree =
      [&](bool outermost) -> LogicalResult {
    std::optional<Choice> choice = choose(free);
    if (!choice) {
      FailureOr<Value> value = sum(summed, body, false);
      if (failed(value))
        return failure();
      SmallVector<Value> indices = levelMajor(resultVars);
      Value stored = *value;
      if (resultStorage.isMatrix()) {
        Value position = positions.lookup(resultOperand);
        // A dense result's loops run over whole sets, not its blocks.
        if (resultStorage.kind == Storage::Kind::DenseMatrix)
          position = l.findBlock(loc, resultStorage, indices[0], indices[1]);
        // An entry of an incidence is its edge's first block at the
        // endpoint; the edge's other blocks there are zero.
        if (entrywiseIncidences &&
            resultStorage.kind == Storage::Kind::Incidence) {
          Value first =
              l.findBlock(loc, resultStorage, indices[0], indices[1]);
          Value isFirst = arith::CmpIOp::create(
              b, loc, arith::CmpIPredicate::eq, first, position);
          stored = arith::SelectOp::create(b, loc, isFirst, stored,
                                           l.zeroOf(scalarType));
        }
        indices.erase(indices.begin(), indices.begin() + 2);
        indices.insert(indices.begin(), position);
      }
      memref::StoreOp::create(b, loc, stored, output, indices);
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

ExtractOp FunctionLowering::blockRead(IndexExprOp op) {
  auto read = dyn_cast_or_null<ExtractOp>(op->getNextNode());
  if (!read || !op->hasOneUse() || read.getTensor() != op.getResult() ||
      !hasSetDimension(op.getType()) || getTensorOrder(op.getType()) != 1)
    return nullptr;
  return read;
}

LogicalResult FunctionLowering::lowerIndexExpr(IndexExprOp op, ExtractOp at) {
  // Lowered with its block read, right after it (blockRead).
  if (!at && blockRead(op))
    return success();
  return IndexExprLowering(*this, op).lower(at);
}
