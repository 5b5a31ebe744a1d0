//===- LowerGridStencils.cpp - Maps through grids, stencil matrices -------===//
//
// A grid over a point set of extents (n0, ..., n(d-1)) numbers the point of
// coordinate (c0, ..., c(d-1)) (c0 * n1 + c1) * n2 + ...; edge p * d + a
// joins point p to its periodic successor along axis a (Set::makeGrid).
// Neighbours and edges are therefore computed from a point's coordinates and
// the extents (the `grid_dims` binding), without index arrays.
//
// A matrix assembled by a map through a grid is stored as one dense array of
// blocks per stencil offset: block k * |P| + r is (r, r + offset k). The
// offsets are the column indices `P[o]` the element function writes at.
// On a grid that is small against the offsets two offsets can name the same
// point; the write goes to the first such offset, so every location has one
// block and the others stay zero (reads sum all blocks of a row).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// The offset of grid point `index` from the point `isPoint` accepts:
/// the sum of the offsets of the grid_point chain leading to it.
static std::optional<SmallVector<int64_t>>
pointOffset(Value index, unsigned rank, function_ref<bool(Value)> isPoint) {
  SmallVector<int64_t> offset(rank, 0);
  while (!isPoint(index)) {
    auto point = index.getDefiningOp<GridPointOp>();
    if (!point)
      return std::nullopt;
    for (auto [total, o] : llvm::zip(offset, point.getOffsets()))
      total += o;
    index = point.getPoint();
  }
  return offset;
}

/// The extent of axis `axis` of the grid (an index).
static Value extentOf(FunctionLowering &l, Location loc, Value dims,
                      unsigned axis) {
  Value extent = memref::LoadOp::create(l.b, loc, dims,
                                        ValueRange{l.indexConstant(axis)});
  return arith::IndexCastOp::create(l.b, loc, l.b.getIndexType(), extent);
}

/// The point at `offset` (index values, any sign) from `point`, wrapping
/// around each axis.
static Value neighbour(FunctionLowering &l, Location loc, StringAttr grid,
                       Value point, ArrayRef<Value> offset) {
  OpBuilder &b = l.b;
  unsigned rank = offset.size();
  Value dims = l.getGridDims(grid, rank);
  SmallVector<Value> extents;
  for (unsigned a = 0; a < rank; ++a)
    extents.push_back(extentOf(l, loc, dims, a));
  // Coordinates from the last axis to the first.
  SmallVector<Value> coordinates(rank);
  Value rest = point;
  for (unsigned a = rank; a-- > 0;) {
    coordinates[a] = arith::RemUIOp::create(b, loc, rest, extents[a]);
    rest = arith::DivUIOp::create(b, loc, rest, extents[a]);
  }
  Value result = l.indexConstant(0);
  for (unsigned a = 0; a < rank; ++a) {
    Value c = coordinates[a];
    std::optional<int64_t> constant = getConstantIntValue(offset[a]);
    if (!constant || *constant != 0) {
      // ((c + o) rem n + n) rem n is in [0, n) for negative o as well.
      Value moved = arith::AddIOp::create(b, loc, c, offset[a]);
      moved = arith::RemSIOp::create(b, loc, moved, extents[a]);
      moved = arith::AddIOp::create(b, loc, moved, extents[a]);
      c = arith::RemSIOp::create(b, loc, moved, extents[a]);
    }
    result = arith::MulIOp::create(b, loc, result, extents[a]);
    result = arith::AddIOp::create(b, loc, result, c);
  }
  return result;
}

static SmallVector<Value> indexConstants(FunctionLowering &l,
                                         ArrayRef<int64_t> values) {
  return llvm::map_to_vector(
      values, [&](int64_t v) { return l.indexConstant(v); });
}

Value FunctionLowering::getGridDims(StringAttr grid, unsigned rank) {
  return getBinding(BindingKind::GridDims, {grid.getValue()},
                    MemRefType::get({rank}, b.getI32Type()));
}

LogicalResult FunctionLowering::lowerGridAccess(Operation *op) {
  Location loc = op->getLoc();
  if (!element)
    return op->emitError("grid reads are only supported in functions mapped "
                         "through the grid");
  if (auto point = dyn_cast<GridPointOp>(op)) {
    SetType grid = point.getGrid().getType();
    Value lowered = neighbour(*this, loc, grid.getName(),
                              lookup(point.getPoint()),
                              indexConstants(*this, point.getOffsets()));
    map(point, lowered);
    elementSets[point] = grid.getEndpoint(0);
    return success();
  }
  auto edge = cast<GridEdgeOp>(op);
  SetType grid = edge.getGrid().getType();
  // The edge leaving q in direction -e_a is the one leaving q - e_a in
  // direction +e_a.
  SmallVector<int64_t> from(edge.getOffsets());
  ArrayRef<int64_t> dir = edge.getDir();
  unsigned axis = llvm::find_if(dir, [](int64_t s) { return s != 0; }) -
                  dir.begin();
  if (dir[axis] < 0)
    --from[axis];
  Value start = neighbour(*this, loc, grid.getName(), lookup(edge.getPoint()),
                          indexConstants(*this, from));
  Value number = arith::AddIOp::create(
      b, loc,
      arith::MulIOp::create(b, loc, start,
                            indexConstant(grid.getGridRank())),
      indexConstant(axis));
  map(edge, number);
  elementSets[edge] = grid.getName();
  return success();
}

/// The grid rank of a stencil storage (it always holds offset 0).
static unsigned rankOf(const Storage &storage) {
  return cast<DenseI64ArrayAttr>(storage.offsets[0]).size();
}

FailureOr<Value> FunctionLowering::stencilBlockAt(Operation *access,
                                                  ValueRange indices,
                                                  const Storage &storage) {
  Location loc = access->getLoc();
  Value point = element->element;
  auto isPoint = [&](Value v) { return lookup(v) == point; };
  unsigned rank = rankOf(storage);
  std::optional<SmallVector<int64_t>> offset;
  if (indices.size() == 2 && isPoint(indices[0]))
    offset = pointOffset(indices[1], rank, isPoint);
  if (!offset)
    return access->emitError("a matrix assembled through a grid can only be "
                             "written and read at (p, p) and (p, P[offset]) "
                             "of the mapped point p");
  auto offsets = llvm::map_to_vector(storage.offsets, [](Attribute a) {
    return cast<DenseI64ArrayAttr>(a).asArrayRef();
  });
  // The stencil holds the offsets the function writes (simit-assign-storage).
  unsigned k = llvm::find(offsets, ArrayRef<int64_t>(*offset)) -
               offsets.begin();
  if (k == offsets.size())
    return access->emitError("this reads a block of a matrix assembled "
                             "through a grid at an offset the function "
                             "never writes");
  // The first offset that names the same point: offsets o and o' do when
  // o - o' is a multiple of the extent along every axis.
  Value dims = getGridDims(storage.edges, rank);
  Value block = indexConstant(k);
  Value zero = indexConstant(0);
  for (unsigned j = k; j-- > 0;) {
    Value same = arith::ConstantIntOp::create(b, loc, 1, 1);
    for (unsigned a = 0; a < rank; ++a) {
      int64_t difference = offsets[j][a] - offsets[k][a];
      if (difference == 0)
        continue;
      Value rem = arith::RemSIOp::create(b, loc, indexConstant(difference),
                                         extentOf(*this, loc, dims, a));
      same = arith::AndIOp::create(
          b, loc, same,
          arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq, rem, zero));
    }
    block = arith::SelectOp::create(b, loc, same, indexConstant(j), block);
  }
  return stencilBlock(storage, point, block);
}

Value FunctionLowering::stencilBlock(const Storage &storage, Value row,
                                     Value k) {
  Location loc = function.getLoc();
  Value rows = getSetSize(storage.rows);
  return arith::AddIOp::create(b, loc,
                               arith::MulIOp::create(b, loc, k, rows), row);
}

Value FunctionLowering::stencilColumn(const Storage &storage, Value row,
                                      Value k) {
  Location loc = function.getLoc();
  // Offset k along each axis, from a constant table.
  SmallVector<Value> offset;
  for (unsigned a = 0, rank = rankOf(storage); a < rank; ++a) {
    SmallVector<int64_t> column = llvm::map_to_vector(
        storage.offsets, [&](Attribute o) {
          return cast<DenseI64ArrayAttr>(o)[a];
        });
    auto type = VectorType::get({static_cast<int64_t>(column.size())},
                                b.getI64Type());
    Value table = arith::ConstantOp::create(
        b, loc, DenseIntElementsAttr::get(type, ArrayRef<int64_t>(column)));
    Value entry =
        vector::ExtractOp::create(b, loc, table, ArrayRef<OpFoldResult>{k});
    offset.push_back(
        arith::IndexCastOp::create(b, loc, b.getIndexType(), entry));
  }
  return neighbour(*this, loc, storage.edges, row, offset);
}
