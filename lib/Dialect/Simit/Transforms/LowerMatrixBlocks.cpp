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

/// The position of block (row, col) in a matrix stored as `storage`, or -1.
static Value findBlock(FunctionLowering &l, Location loc,
                       const Storage &storage, Value row, Value col) {
  OpBuilder &b = l.b;
  // Patterns do not change while the function runs: a scan done earlier
  // (the read of `A(q,q) = 1 + A(q,q)`) serves the write too.
  for (auto &[s, r, c, position] : l.blockPositions)
    if (s == storage && r == row && c == col && isVisible(b, position))
      return position;
  Value none = l.indexConstant(-1);
  if (storage.kind == Storage::Kind::Diagonal) {
    Value onDiagonal =
        arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq, row, col);
    return arith::SelectOp::create(b, loc, onDiagonal, row, none);
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

LogicalResult FunctionLowering::lowerMatrixBlockAccess(Operation *op) {
  Location loc = op->getLoc();
  auto extract = dyn_cast<ExtractOp>(op);
  auto insert = dyn_cast<InsertOp>(op);
  Value matrix = extract ? extract.getTensor() : insert.getTensor();
  ValueRange indices = extract ? extract.getIndices() : insert.getIndices();
  Storage storage = storages.lookup(matrix);
  if (!storage.isMatrix())
    return op->emitError("a block of a system matrix of unknown sparsity "
                         "cannot be ")
           << (extract ? "read" : "written") << " by the loop lowering";
  if (storage.kind == Storage::Kind::Incidence)
    return op->emitError("blocks of a matrix stored as ")
           << storage.describe()
           << " cannot be accessed one at a time by the loop lowering";
  if (indices.size() != 2)
    return op->emitError("a block of a system matrix needs two indices");
  Value row = lookup(indices[0]), col = lookup(indices[1]);
  Value array = lookup(matrix);
  auto type = cast<MemRefType>(array.getType());
  Value position = findBlock(*this, loc, storage, row, col);
  Value found = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                      position, indexConstant(0));

  if (extract) {
    Type resultType = convertType(extract.getType());
    int64_t n = numComponents(extract.getType());
    auto branch = scf::IfOp::create(b, loc, TypeRange{resultType}, found,
                                    /*withElseRegion=*/true);
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(branch.thenBlock());
    SmallVector<Value> components;
    for (int64_t c = 0; c < n; ++c)
      components.push_back(memref::LoadOp::create(
          b, loc, array, blockIndices(type, {position}, c)));
    scf::YieldOp::create(b, loc, fromComponents(resultType, components));
    // Blocks outside the storage are zero.
    b.setInsertionPointToStart(branch.elseBlock());
    SmallVector<Value> zeros(n, zeroOf(type.getElementType()));
    scf::YieldOp::create(b, loc, fromComponents(resultType, zeros));
    map(extract, branch.getResult(0));
    return success();
  }

  cf::AssertOp::create(b, loc, found,
                       "writing a block that is not in the sparsity of " +
                           storage.describe());
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
  storages[insert] = storage;
  map(insert, target);
  return success();
}
