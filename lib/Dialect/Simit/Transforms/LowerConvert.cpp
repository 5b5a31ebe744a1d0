//===- LowerConvert.cpp - A matrix moved to a larger storage --------------===//
//
// simit-assign-storage ties the values that a variable, a loop or a branch
// carries to one storage and widens the others with `simit.convert`: the
// result holds every block of the source, so the lowering zero-fills it
// and adds each source block at its place. The loop runs over the rows,
// whose blocks no other row writes. Between patterns and unions of edge
// sets the place comes from a gather map built once per binding; otherwise
// from a search of the row (findBlock).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

LogicalResult FunctionLowering::lowerConvert(ConvertOp op) {
  Location loc = op.getLoc();
  Value source = lookup(op.getSource());
  // A use declared without storage (a runtime function's operand) reads
  // the matrix as it is stored.
  if (!getStorage(op.getType())) {
    map(op, source);
    alias(op, op.getSource());
    return success();
  }
  // A host function's matrix gets its storage after the call, which
  // lowered it as that storage.
  if (op.getSource().getDefiningOp<func::CallOp>() &&
      !getStorage(op.getSource().getType())) {
    map(op, source);
    return success();
  }
  Storage from = storageOf(op.getSource()), to = storageOf(op);
  if (op.getRestrict())
    return op.emitError("restricting a matrix stored as ")
           << from.describe() << " to " << to.describe()
           << " is not supported by the loop lowering";
  auto type = cast<MemRefType>(source.getType());
  if (from == to) {
    Value copy = memref::AllocOp::create(
        b, loc, type,
        ValueRange{memref::DimOp::create(b, loc, source, 0).getResult()});
    memref::CopyOp::create(b, loc, source, copy);
    map(op, copy);
    return success();
  }
  bool fromBCSR = from.isBCSR(), fromStencil =
                                     from.kind == Storage::Kind::Stencil;
  if ((!fromBCSR && !fromStencil && from.kind != Storage::Kind::Diagonal) ||
      (!to.isBCSR() && to.kind != Storage::Kind::Stencil &&
       to.kind != Storage::Kind::Diagonal))
    return op.emitError("converting a matrix stored as ")
           << from.describe() << " to " << to.describe()
           << " is not supported by the loop lowering";
  Value gather =
      from.hasGatherMaps() && to.hasGatherMaps() ? gatherMap(to, from)
                                                 : Value();
  Value target = allocSystem(loc, op.getType(), to);
  auto targetType = cast<MemRefType>(target.getType());
  int64_t components = 1;
  for (int64_t d : targetType.getShape().drop_front())
    components *= d;

  // Adds source block `position` at target block `place` (-1: none).
  auto addBlock = [&](Value position, Value place) {
    Value present = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                          place, indexConstant(0));
    auto branch = scf::IfOp::create(b, loc, present);
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(branch.thenBlock());
    for (int64_t c = 0; c < components; ++c) {
      SmallVector<Value> at = blockIndices(targetType, {place}, c);
      Value old = memref::LoadOp::create(b, loc, target, at);
      Value add = memref::LoadOp::create(
          b, loc, source, blockIndices(type, {position}, c));
      Value sum = addNumbers(b, loc, old, add);
      memref::StoreOp::create(b, loc, sum, target, at);
    }
  };
  auto toIndex = [&](Value i32) -> Value {
    return arith::IndexCastOp::create(b, loc, b.getIndexType(), i32);
  };

  auto rows = scf::ParallelOp::create(
      b, loc, ValueRange{indexConstant(0)},
      ValueRange{getSetSize(from.rows)}, ValueRange{indexConstant(1)},
      [](OpBuilder &, Location, ValueRange) {});
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPoint(rows.getBody()->getTerminator());
  Value row = rows.getInductionVars()[0];
  auto rowRange = [&](const Storage &s) -> std::pair<Value, Value> {
    Value rowPtr = rowPointers(s);
    Value next = arith::AddIOp::create(b, loc, row, indexConstant(1));
    return {toIndex(memref::LoadOp::create(b, loc, rowPtr, ValueRange{row})),
            toIndex(memref::LoadOp::create(b, loc, rowPtr, ValueRange{next}))};
  };
  auto loopOver = [&](std::pair<Value, Value> range) {
    auto loop = scf::ForOp::create(b, loc, range.first, range.second,
                                   indexConstant(1));
    b.setInsertionPoint(loop.getBody()->getTerminator());
    return loop.getInductionVar();
  };
  if (from.kind == Storage::Kind::Diagonal) {
    addBlock(row, findBlock(loc, to, row, row));
  } else if (gather) {
    // The gather map goes from the target's positions to the source's
    // (-1 where the source has no block).
    Value place = loopOver(rowRange(to));
    Value position =
        toIndex(memref::LoadOp::create(b, loc, gather, ValueRange{place}));
    Value present = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                          position, indexConstant(0));
    addBlock(position, arith::SelectOp::create(b, loc, present, place,
                                               indexConstant(-1)));
  } else if (fromStencil) {
    Value k = loopOver({indexConstant(0), indexConstant(from.offsets.size())});
    addBlock(stencilBlock(from, row, k),
             findBlock(loc, to, row, stencilColumn(from, row, k)));
  } else {
    Value k = loopOver(rowRange(from));
    Value column = toIndex(
        memref::LoadOp::create(b, loc, columnIndices(from), ValueRange{k}));
    addBlock(k, findBlock(loc, to, row, column));
  }
  map(op, target);
  return success();
}
