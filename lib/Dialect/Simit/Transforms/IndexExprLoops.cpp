//===- IndexExprLoops.cpp - The loops of an index expression --------------===//
//
// How IndexExprLowering (IndexExprLowering.h) binds one level at a time:
// which variable's level comes next and which storage its loop follows,
// the loop itself (over a set, a range, a pattern row, a stencil's offsets
// or an edge's endpoints), reads of operands at the bound blocks, and sums.
//
//===----------------------------------------------------------------------===//

#include "IndexExprLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

Value IndexExprLowering::extent(unsigned v, unsigned i) {
  Attribute lvl = level(v, i);
  if (auto set = dyn_cast<StringAttr>(lvl))
    return l.getSetSize(set);
  return l.indexConstant(cast<IntegerAttr>(lvl).getInt());
}

SmallVector<std::pair<int64_t, unsigned>>
IndexExprLowering::levelMajorOrder(ArrayRef<int64_t> vars) {
  SmallVector<std::pair<int64_t, unsigned>> order;
  unsigned maxLevels = 0;
  for (int64_t v : vars)
    maxLevels = std::max(maxLevels, numLevels(v));
  for (unsigned lvl = 0; lvl < maxLevels; ++lvl)
    for (int64_t v : vars)
      if (lvl < numLevels(v))
        order.push_back({v, lvl});
  return order;
}

SmallVector<Value> IndexExprLowering::levelMajor(ArrayRef<int64_t> vars) {
  return llvm::map_to_vector(levelMajorOrder(vars), [&](auto vl) {
    return bound[vl.first][vl.second];
  });
}

SmallVector<int64_t>
IndexExprLowering::levelMajorExtents(ArrayRef<int64_t> vars) {
  return llvm::map_to_vector(levelMajorOrder(vars), [&](auto vl) {
    return cast<IntegerAttr>(level(vl.first, vl.second)).getInt();
  });
}

FailureOr<Value> IndexExprLowering::access(unsigned i) {
  Value input = op.getInputs()[i];
  Value lowered = l.lookup(input);
  Type type = input.getType();
  ArrayRef<int64_t> vars = op.getInputIndexList(i);
  if (vars.empty())
    return lowered;
  SmallVector<Value> indices = levelMajor(vars);
  if (!hasSetDimension(type)) {
    // A flat vector: row-major over the level-major extents.
    Value flat = l.indexConstant(0);
    for (auto [index, size] : llvm::zip(indices, levelMajorExtents(vars))) {
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
  Value loopPosition = positions.lookup(i);
  if (entrywiseIncidences && storage.kind == Storage::Kind::Incidence)
    return incidenceEntry(i, row, col, inner, loopPosition);
  if (entrywiseStencils) {
    FailureOr<Value> entry = storage.kind == Storage::Kind::Stencil
                                 ? stencilEntry(i, row, col, inner)
                                 : blockAt(i, row, col, inner);
    if (failed(entry))
      return failure();
    // Inside a loop over a stencil, at the first block naming the column.
    for (int64_t v : vars)
      if (Value first = stencilFirsts.lookup(v))
        entry = arith::SelectOp::create(b, loc, first, *entry,
                                        l.zeroOf(scalarType))
                    .getResult();
    return entry;
  }
  return blockAt(i, row, col, inner);
}

Value IndexExprLowering::stencilEntry(unsigned i, Value row, Value col,
                                      ArrayRef<Value> inner) {
  Value lowered = l.lookup(op.getInputs()[i]);
  return l.sumStencilBlocks(loc, storageOf(i), row, col, scalarType,
                            [&](Value position) {
                              SmallVector<Value> at(inner);
                              at.insert(at.begin(), position);
                              return memref::LoadOp::create(b, loc, lowered,
                                                            at)
                                  .getResult();
                            });
}

FailureOr<Value> IndexExprLowering::blockAt(unsigned i, Value row, Value col,
                                            SmallVector<Value> inner) {
  Value input = op.getInputs()[i];
  Value lowered = l.lookup(input);
  Storage storage = storageOf(i);
  Value loopPosition = positions.lookup(i);
  if (loopPosition) {
    if (!gathered.contains(i)) {
      inner.insert(inner.begin(), loopPosition);
      return memref::LoadOp::create(b, loc, lowered, inner).getResult();
    }
    // A union member without this block reads zero (at a valid position).
    Value present = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                          loopPosition, l.indexConstant(0));
    inner.insert(inner.begin(),
                 arith::SelectOp::create(b, loc, present, loopPosition,
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
  if (storage.kind == Storage::Kind::Incidence)
    return incidenceEntry(i, row, col, inner, Value());
  if (storage.kind == Storage::Kind::DenseMatrix) {
    inner.insert(inner.begin(), l.findBlock(loc, storage, row, col));
    return memref::LoadOp::create(b, loc, lowered, inner).getResult();
  }
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

Value IndexExprLowering::incidenceEntry(unsigned i, Value row, Value col,
                                        ArrayRef<Value> inner,
                                        Value loopPosition) {
  // Row and column are the input's own: read it in its own orientation.
  Value input = op.getInputs()[i];
  Value lowered = l.lookup(input);
  const Storage storage = l.storageOf(input);
  Value entry = l.sumIncidenceBlocks(
      loc, storage, row, col, scalarType, [&](Value position) {
        SmallVector<Value> at(inner);
        at.insert(at.begin(), position);
        return memref::LoadOp::create(b, loc, lowered, at).getResult();
      });
  if (!loopPosition)
    return entry;
  // A loop over the incidence's blocks visits an entry once per block of
  // its edge at the endpoint: the entry counts at the first.
  Value isFirst = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                        l.findBlock(loc, storage, row, col),
                                        loopPosition);
  return arith::SelectOp::create(b, loc, isFirst, entry, l.zeroOf(scalarType));
}

std::optional<IndexExprLowering::Choice>
IndexExprLowering::choose(ArrayRef<unsigned> vars) {
  // A set level that a bound variable's matrix row gives comes first. A
  // matrix result leads: its storage holds every nonzero of the body.
  // Otherwise, among the matrices pairing the same variables, the largest
  // sparsity leads (an edge pattern holds a diagonal).
  unsigned result = op.getInputs().size();
  for (unsigned v : vars) {
    if (denseVars.contains(v) || isSetBound(v) || !isa<StringAttr>(level(v, 0)))
      continue;
    int best = -1;
    unsigned partner = 0;
    std::optional<Storage> joined;
    // Whether the loop's storage holds every matrix pairing v with the
    // partner: one that it does not hold (a product read transposed, or
    // storages that do not join) could add values the loop never visits.
    bool holdsAll = true;
    for (unsigned n = 0; n < numMatrixOperands(); ++n) {
      unsigned o = (result + n) % numMatrixOperands();
      if (best == static_cast<int>(result))
        break;
      Storage storage = storageOf(o);
      ArrayRef<int64_t> list = indexList(o);
      // A dense matrix has every block: it couples nothing, and its
      // variables run over their whole sets.
      if (!storage.isMatrix() || storage.kind == Storage::Kind::DenseMatrix ||
          list.size() != 2 || list[0] == list[1])
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
      if (!own) {
        holdsAll = false;
        continue;
      }
      if (best < 0) {
        best = o;
        partner = u;
        joined = own;
        continue;
      }
      // The others are read by position, gather map or search (access()).
      if (std::optional<Storage> both = joinStorages(*joined, *own))
        joined = both;
      else
        holdsAll = false;
    }
    // Otherwise v runs over its whole set, every matrix read by search.
    if (best >= 0 && !holdsAll && best != static_cast<int>(result))
      return Choice{v, 0};
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
  stencilFirsts.erase(choice.var);
  if (choice.coupledBy >= 0)
    for (unsigned o = 0; o < numMatrixOperands(); ++o)
      if (indexList(o).size() == 2 &&
          llvm::is_contained(indexList(o), choice.var)) {
        positions.erase(o);
        gathered.erase(o);
      }
}

void IndexExprLowering::prefetchAhead(unsigned i, Value position) {
  // The rows' blocks lie one after the other: the hardware's prefetcher
  // follows the stream, but a read that waits for each row's blocks (and
  // the index loads before them) keeps fewer lines in flight than the
  // memory allows.
  Value values = l.lookup(op.getInputs()[i]);
  auto type = cast<MemRefType>(values.getType());
  int64_t blockBytes = componentBytes(type.getElementType());
  for (int64_t d = 1; d < type.getRank(); ++d)
    blockBytes *= type.getDimSize(d);
  int64_t distance = llvm::divideCeil(l.prefetchMatrixBytes,
                                      std::max<int64_t>(1, blockBytes));
  Value last = arith::SubIOp::create(
      b, loc, memref::DimOp::create(b, loc, values, 0), l.indexConstant(1));
  Value ahead = arith::MinSIOp::create(
      b, loc,
      arith::AddIOp::create(b, loc, position, l.indexConstant(distance)),
      last);
  l.prefetchBlock(loc, values, ahead, /*isWrite=*/false);
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
      colIdx = l.incidenceEndpoints(storage);
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
      if (entrywiseStencils)
        stencilFirsts[v] = arith::CmpIOp::create(
            b, loc, arith::CmpIPredicate::eq,
            l.findBlock(loc, storage, row, bound[v][0]), position);
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
        if (rowPtr && o < op.getInputs().size() && l.prefetchMatrixBytes > 0)
          prefetchAhead(o, position);
        continue;
      }
      // Another pattern or union over the same sets: its block at this
      // position (for a transposed read, the block at the mirrored
      // position), or -1, from a gather map built once per binding.
      std::optional<Storage> read = transposed ? transposedStorage(own) : own;
      if (!storage.hasGatherMaps() || !own.hasGatherMaps() || !read ||
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

FailureOr<Value> IndexExprLowering::sum(SmallVector<unsigned> vars,
                                        function_ref<FailureOr<Value>()> body,
                                        bool parallelTop, Type type) {
  std::optional<Choice> choice = choose(vars);
  if (!choice)
    return body();
  if (!type)
    type = scalarType;
  Value zero = l.zeroOf(type);
  bool failedBody = false;
  if (parallelTop && choice->coupledBy < 0 && isa<FloatType>(type)) {
    SmallVector<Value> results =
        emitLoop(*choice, {zero}, true, [&](ValueRange) {
          FailureOr<Value> term = sum(vars, body, false, type);
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
  SmallVector<Value> results =
      emitLoop(*choice, {zero}, false, [&](ValueRange args) {
        FailureOr<Value> term = sum(vars, body, false, type);
        if (failed(term)) {
          failedBody = true;
          return SmallVector<Value>{args[0]};
        }
        return SmallVector<Value>{add(args[0], *term)};
      });
  if (failedBody)
    return failure();
  return results[0];
}
