//===- LowerMatrixBlocks.cpp - Reading and writing one matrix block -------===//
//
// `A(r, c)` on an assembled system matrix outside a map (simit.extract and
// simit.insert with two element indices). The block's position follows the
// matrix's storage: a diagonal matrix holds (r, r) at r; a pattern matrix
// holds (r, c) at the k of row r's blocks (rowptr[r] .. rowptr[r+1]) with
// colidx[k] == c, found by a scan of the row. A block outside the storage is
// zero when read; writing one is a runtime error (cf.assert), since the
// matrix has no place for it.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "simit/Dialect/Simit/IR/SourcePosition.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// Whether `value` is defined in the builder's insertion block or one
/// enclosing it (so it can be used at the insertion point).
static bool isVisible(OpBuilder &b, Value value) {
  Block *defining = value.getParentBlock();
  for (Block *block = b.getInsertionBlock(); block;
       block = block->getParentOp() ? block->getParentOp()->getBlock()
                                    : nullptr)
    if (block == defining)
      return true;
  return false;
}

Value FunctionLowering::findBlock(Location loc, const Storage &storage,
                                  Value row, Value col) {
  FunctionLowering &l = *this;
  // Patterns do not change while the function runs: a scan done earlier
  // (the read of `A(q,q) = 1 + A(q,q)`) serves the write too.
  for (auto &[s, r, c, position] : l.blockPositions)
    if (s == storage && r == row && c == col && isVisible(b, position))
      return position;
  if (storage.kind == Storage::Kind::DenseMatrix)
    return arith::AddIOp::create(
        b, loc, arith::MulIOp::create(b, loc, row, getSetSize(storage.cols)),
        col);
  Value none = l.indexConstant(-1);
  if (storage.kind == Storage::Kind::Diagonal) {
    Value onDiagonal =
        arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq, row, col);
    return arith::SelectOp::create(b, loc, onDiagonal, row, none);
  }
  if (storage.kind == Storage::Kind::Incidence) {
    // The edge's first block at the endpoint (an edge may name it twice).
    Value endpoint = storage.transposed ? row : col;
    SmallVector<std::pair<Value, Value>> blocks;
    forEachEdgeBlock(loc, storage, storage.transposed ? col : row,
                     [&](Value at, Value position) {
                       blocks.push_back({at, position});
                     });
    Value found = none;
    for (auto [at, position] : llvm::reverse(blocks))
      found = arith::SelectOp::create(
          b, loc,
          arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq, at,
                                endpoint),
          position, found);
    return found;
  }
  if (storage.kind == Storage::Kind::Stencil) {
    // The first offset whose point is the column, as writes choose.
    Value found = none;
    for (int64_t k = storage.offsets.size(); k-- > 0;) {
      Value kv = indexConstant(k);
      Value match = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                          stencilColumn(storage, row, kv), col);
      found = arith::SelectOp::create(b, loc, match,
                                      stencilBlock(storage, row, kv), found);
    }
    return found;
  }
  Value rowPtr = l.rowPointers(storage);
  Value colIdx = l.columnIndices(storage);
  auto load = [&](Value array, Value index) -> Value {
    return arith::IndexCastOp::create(
        b, loc, b.getIndexType(),
        memref::LoadOp::create(b, loc, array, ValueRange{index}));
  };
  Value next = arith::AddIOp::create(b, loc, row, l.indexConstant(1));
  // Columns are unique within a row: at most one k matches.
  auto scan = scf::ForOp::create(
      b, loc, load(rowPtr, row), load(rowPtr, next), l.indexConstant(1),
      ValueRange{none},
      [&](OpBuilder &nb, Location, Value k, ValueRange found) {
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
        Value match = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                            load(colIdx, k), col);
        scf::YieldOp::create(
            b, loc,
            ValueRange{arith::SelectOp::create(b, loc, match, k, found[0])});
      });
  l.blockPositions.emplace_back(storage, row, col, scan.getResult(0));
  return scan.getResult(0);
}

void FunctionLowering::forEachEdgeBlock(
    Location loc, const Storage &storage, Value edge,
    function_ref<void(Value endpoint, Value position)> body) {
  Value ends = incidenceEndpoints(storage);
  Value first =
      arith::MulIOp::create(b, loc, edge, indexConstant(storage.cardinality));
  for (int64_t k = 0; k < storage.cardinality; ++k) {
    Value kv = indexConstant(k);
    body(arith::IndexCastOp::create(
             b, loc, b.getIndexType(),
             memref::LoadOp::create(b, loc, ends, ValueRange{edge, kv})),
         arith::AddIOp::create(b, loc, first, kv));
  }
}

Value FunctionLowering::sumIncidenceBlocks(Location loc,
                                           const Storage &storage, Value row,
                                           Value col, Type scalar,
                                           function_ref<Value(Value)> read) {
  Value endpoint = storage.transposed ? row : col;
  Value sum = zeroOf(scalar);
  forEachEdgeBlock(
      loc, storage, storage.transposed ? col : row,
      [&](Value at, Value position) {
        Value match = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                            at, endpoint);
        Value value = arith::SelectOp::create(b, loc, match, read(position),
                                              zeroOf(scalar));
        sum = addNumbers(b, loc, sum, value);
      });
  return sum;
}

SmallVector<Value> FunctionLowering::readMatrixBlock(Location loc,
                                                    const Storage &storage,
                                                    Value array, Value row,
                                                    Value col, int64_t n) {
  auto type = cast<MemRefType>(array.getType());
  Type scalar = type.getElementType();
  auto load = [&](Value position, int64_t c) -> Value {
    return memref::LoadOp::create(b, loc, array,
                                  blockIndices(type, {position}, c));
  };
  SmallVector<Value> components;
  // Entries that several blocks share (an edge naming an endpoint twice,
  // stencil offsets naming one point) are their sums.
  if (storage.kind == Storage::Kind::Incidence ||
      storage.kind == Storage::Kind::Stencil) {
    for (int64_t c = 0; c < n; ++c) {
      auto read = [&](Value position) { return load(position, c); };
      components.push_back(
          storage.kind == Storage::Kind::Incidence
              ? sumIncidenceBlocks(loc, storage, row, col, scalar, read)
              : sumStencilBlocks(loc, storage, row, col, scalar, read));
    }
    return components;
  }
  Value position = findBlock(loc, storage, row, col);
  Value found = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                      position, indexConstant(0));
  SmallVector<Type> types(n, scalar);
  auto branch = scf::IfOp::create(b, loc, types, found,
                                  /*withElseRegion=*/true);
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPointToStart(branch.thenBlock());
  for (int64_t c = 0; c < n; ++c)
    components.push_back(load(position, c));
  scf::YieldOp::create(b, loc, components);
  // Blocks outside the storage are zero.
  b.setInsertionPointToStart(branch.elseBlock());
  scf::YieldOp::create(b, loc, SmallVector<Value>(n, zeroOf(scalar)));
  return SmallVector<Value>(branch.getResults());
}

Value FunctionLowering::sumStencilBlocks(Location loc, const Storage &storage,
                                         Value row, Value col, Type scalar,
                                         function_ref<Value(Value)> read) {
  Value sum = zeroOf(scalar);
  for (int64_t k = 0, n = storage.offsets.size(); k < n; ++k) {
    Value kv = indexConstant(k);
    Value match = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                        stencilColumn(storage, row, kv), col);
    Value value = arith::SelectOp::create(
        b, loc, match, read(stencilBlock(storage, row, kv)), zeroOf(scalar));
    sum = addNumbers(b, loc, sum, value);
  }
  return sum;
}

LogicalResult FunctionLowering::lowerMatrixBlockAccess(Operation *op) {
  Location loc = op->getLoc();
  auto extract = dyn_cast<ExtractOp>(op);
  auto insert = dyn_cast<InsertOp>(op);
  Value matrix = extract ? extract.getTensor() : insert.getTensor();
  ValueRange indices = extract ? extract.getIndices() : insert.getIndices();
  Storage storage = storageOf(matrix);
  if (!storage.isMatrix())
    return op->emitError("a block of a system matrix of unknown sparsity "
                         "cannot be ")
           << (extract ? "read" : "written") << " by the loop lowering";
  if (indices.size() != 2)
    return op->emitError("a block of a system matrix needs two indices");
  Value row = lookup(indices[0]), col = lookup(indices[1]);
  Value array = lookup(matrix);
  auto type = cast<MemRefType>(array.getType());
  if (extract) {
    map(extract,
        fromComponents(convertType(extract.getType()),
                       readMatrixBlock(loc, storage, array, row, col,
                                       numComponents(extract.getType()))));
    return success();
  }

  Value position = findBlock(loc, storage, row, col);
  Value found = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                      position, indexConstant(0));
  cf::AssertOp::create(b, loc, found,
                       "writing a block outside the storage of the matrix, " +
                           storage.describe() + sourcePositionSuffix(loc));
  // `A(r, c) = v` on a variable (load, insert, store back) writes the
  // variable's array in place; otherwise the matrix is copied first.
  auto load = matrix.getDefiningOp<LoadOp>();
  auto store = insert->hasOneUse()
                   ? dyn_cast<StoreOp>(*insert->getUsers().begin())
                   : StoreOp();
  Value target = array;
  if (!load || !store || store.getRef() != load.getRef() ||
      array != lookup(load.getRef())) {
    target = memref::AllocOp::create(
        b, loc, type,
        ValueRange{memref::DimOp::create(b, loc, array, 0).getResult()});
    memref::CopyOp::create(b, loc, array, target);
  }
  Value value = lookup(insert.getValue());
  for (int64_t c = 0, n = numComponents(insert.getValue().getType()); c < n;
       ++c)
    memref::StoreOp::create(b, loc,
                            component(insert.getValue().getType(), value, c),
                            target, blockIndices(type, {position}, c));
  // An entry that several blocks share (stencil offsets naming one point,
  // an edge naming an endpoint twice) is their sum: the value stays in the
  // first (findBlock's) and the others there become zero.
  auto zeroIfOtherThere = [&](Value block, Value there) {
    Value other = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::ne,
                                        block, position);
    auto branch = scf::IfOp::create(
        b, loc, TypeRange{}, arith::AndIOp::create(b, loc, other, there),
        /*withElseRegion=*/false);
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(branch.thenBlock());
    for (int64_t c = 0, n = numComponents(insert.getValue().getType()); c < n;
         ++c)
      memref::StoreOp::create(b, loc, zeroOf(type.getElementType()), target,
                              blockIndices(type, {block}, c));
  };
  if (storage.kind == Storage::Kind::Stencil)
    for (int64_t k = 0, n = storage.offsets.size(); k < n; ++k) {
      Value kv = indexConstant(k);
      zeroIfOtherThere(stencilBlock(storage, row, kv),
                       arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                             stencilColumn(storage, row, kv),
                                             col));
    }
  if (storage.kind == Storage::Kind::Incidence)
    forEachEdgeBlock(loc, storage, storage.transposed ? col : row,
                     [&](Value at, Value block) {
                       zeroIfOtherThere(
                           block, arith::CmpIOp::create(
                                      b, loc, arith::CmpIPredicate::eq, at,
                                      storage.transposed ? row : col));
                     });
  map(insert, target);
  return success();
}

LogicalResult FunctionLowering::lowerMatrixSlice(SliceOp op) {
  Location loc = op.getLoc();
  auto type = dyn_cast<SystemTensorType>(op.getTensor().getType());
  ArrayRef<bool> kept = op.getKept();
  if (!type || type.getOrder() != 2 || kept.size() != 2 || kept[0] == kept[1])
    return op.emitError("slices of system tensors are supported as rows "
                        "A(p, :) and columns A(:, q) of matrices");
  Storage storage = storageOf(op.getTensor());
  Value matrix = lookup(op.getTensor());
  Value index = lookup(op.getIndices()[0]);
  bool row = kept[1];
  // The result: a zero-filled vector over the kept dimension's set.
  Value result = allocSystem(loc, op.getType(), Storage::dense());
  Type scalar = type.getComponentType();
  auto matrixType = cast<MemRefType>(matrix.getType());
  auto resultType = cast<MemRefType>(result.getType());
  // Block `from` of the matrix to block `to` of the result, each component.
  auto copy = [&](Value from, Value to, bool add) {
    for (int64_t c = 0, n = numComponents(getBlockType(type)); c < n; ++c) {
      SmallVector<Value> at = blockIndices(resultType, {to}, c);
      Value value = memref::LoadOp::create(
          b, loc, matrix, blockIndices(matrixType, {from}, c));
      if (add)
        value = addNumbers(b, loc, memref::LoadOp::create(b, loc, result, at),
                           value);
      memref::StoreOp::create(b, loc, value, result, at);
    }
  };
  auto forEach = [&](Value lb, Value ub, function_ref<void(Value)> body) {
    scf::ForOp::create(b, loc, lb, ub, indexConstant(1), ValueRange{},
                       [&](OpBuilder &nb, Location, Value iv, ValueRange) {
                         OpBuilder::InsertionGuard guard(b);
                         b.setInsertionPoint(nb.getInsertionBlock(),
                                             nb.getInsertionPoint());
                         body(iv);
                         scf::YieldOp::create(b, loc);
                       });
  };
  auto asIndex = [&](Value v) -> Value {
    return arith::IndexCastOp::create(b, loc, b.getIndexType(), v);
  };
  bool incidence = storage.kind == Storage::Kind::Incidence;
  bool stencil = storage.kind == Storage::Kind::Stencil;
  bool dense = storage.kind == Storage::Kind::DenseMatrix;
  if (!isa<FloatType, IntegerType, ComplexType>(scalar) ||
      !(storage.kind == Storage::Kind::Diagonal || storage.isBCSR() ||
        incidence || stencil || dense))
    return op.emitError("this slice of a matrix stored as ")
           << storage.describe() << " is not supported by the loop lowering";

  if (storage.kind == Storage::Kind::Diagonal) {
    copy(index, index, /*add=*/false);
  } else if (dense) {
    // Block r * |cols| + c is (r, c).
    Value cols = getSetSize(storage.cols);
    forEach(indexConstant(0), getSetSize(row ? storage.cols : storage.rows),
            [&](Value i) {
              Value r = row ? index : i, c = row ? i : index;
              copy(arith::AddIOp::create(
                       b, loc, arith::MulIOp::create(b, loc, r, cols), c),
                   i, /*add=*/false);
            });
  } else if (stencil && row) {
    // Row p: its block per offset at the offset's point (offsets naming
    // one point add).
    for (int64_t k = 0, n = storage.offsets.size(); k < n; ++k)
      copy(stencilBlock(storage, index, indexConstant(k)),
           stencilColumn(storage, index, indexConstant(k)), /*add=*/true);
  } else if (stencil) {
    // Column q: every row's blocks whose offset names q.
    forEach(indexConstant(0), getSetSize(storage.rows), [&](Value r) {
      for (int64_t k = 0, n = storage.offsets.size(); k < n; ++k) {
        Value kv = indexConstant(k);
        Value match = arith::CmpIOp::create(
            b, loc, arith::CmpIPredicate::eq, stencilColumn(storage, r, kv),
            index);
        auto branch = scf::IfOp::create(b, loc, TypeRange{}, match,
                                        /*withElseRegion=*/false);
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPointToStart(branch.thenBlock());
        copy(stencilBlock(storage, r, kv), r, /*add=*/true);
      }
    });
  } else if (incidence && row == storage.transposed) {
    // A row of a transposed incidence (a vertex's) or a column of an
    // incidence: the blocks of every edge naming the vertex, at the edge.
    forEach(indexConstant(0), getSetSize(storage.edges), [&](Value e) {
      forEachEdgeBlock(loc, storage, e, [&](Value at, Value block) {
        Value match = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                            at, index);
        auto branch = scf::IfOp::create(b, loc, TypeRange{}, match,
                                        /*withElseRegion=*/false);
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPointToStart(branch.thenBlock());
        copy(block, e, /*add=*/true);
      });
    });
  } else if (incidence) {
    // A row of an incidence or a column of a transposed one: edge `index`'s
    // block per endpoint k, at endpoints[index, k]; an edge may name one
    // endpoint twice.
    forEachEdgeBlock(loc, storage, index, [&](Value at, Value block) {
      copy(block, at, /*add=*/true);
    });
  } else if (row) {
    Value rowPtr = rowPointers(storage), colIdx = columnIndices(storage);
    Value next = arith::AddIOp::create(b, loc, index, indexConstant(1));
    forEach(asIndex(memref::LoadOp::create(b, loc, rowPtr, ValueRange{index})),
            asIndex(memref::LoadOp::create(b, loc, rowPtr, ValueRange{next})),
            [&](Value k) {
              copy(k,
                   asIndex(memref::LoadOp::create(b, loc, colIdx,
                                                  ValueRange{k})),
                   /*add=*/false);
            });
  } else {
    // Column q: row r's block (r, q), found in its row, or zero.
    forEach(indexConstant(0), getSetSize(storage.rows), [&](Value r) {
      Value position = findBlock(loc, storage, r, index);
      Value found = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                          position, indexConstant(0));
      auto branch = scf::IfOp::create(b, loc, TypeRange{}, found,
                                      /*withElseRegion=*/false);
      OpBuilder::InsertionGuard guard(b);
      b.setInsertionPointToStart(branch.thenBlock());
      copy(position, r, /*add=*/false);
    });
  }
  map(op, result);
  return success();
}
