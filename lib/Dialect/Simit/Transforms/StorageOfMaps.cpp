//===- StorageOfMaps.cpp - Storage of assembled matrices ------------------===//
//
// An assembled matrix is stored by where its set can write, read from the
// set type and not from the writes, so that all assemblies of one set share
// one index: the diagonal of the mapped set, the pattern of an edge set over
// the endpoint positions of its rows and columns, the incidence of an edge
// set (or its transpose) when the edges are the rows (or columns). Through
// a grid the offsets the element function writes at make the stencil.
//
//===----------------------------------------------------------------------===//

#include "StorageAnalysis.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/Dialect/SCF/IR/SCF.h"
#include "mlir/IR/SymbolTable.h"
#include "llvm/ADT/SetVector.h"

using namespace mlir;
using namespace mlir::simit;

/// The endpoint positions of `edges` whose endpoint set is `set`.
static SmallVector<int64_t> positionsOf(SetType edges, StringAttr set) {
  SmallVector<int64_t> positions;
  for (unsigned i = 0, e = edges.getCardinality(); i < e; ++i)
    if (edges.getEndpoint(i) == set)
      positions.push_back(i);
  return positions;
}

/// The inserts of `callee` that write its result `result`: those a returned
/// value is built from through inserts, slots, loops and branches.
static FailureOr<SmallVector<InsertOp>> writesOf(func::FuncOp callee,
                                                 unsigned result) {
  auto ret = cast<func::ReturnOp>(callee.front().getTerminator());
  SmallVector<InsertOp> writes;
  SmallVector<Value> work{ret.getOperand(result)};
  DenseSet<Value> seen;
  while (!work.empty()) {
    Value v = work.pop_back_val();
    if (!seen.insert(v).second)
      continue;
    if (auto arg = dyn_cast<BlockArgument>(v)) {
      auto loop = dyn_cast<scf::ForOp>(arg.getOwner()->getParentOp());
      if (!loop || arg == loop.getInductionVar())
        return failure();
      unsigned i = arg.getArgNumber() - 1;
      work.append({loop.getInitArgs()[i], loop.getYieldedValues()[i]});
      continue;
    }
    Operation *def = v.getDefiningOp();
    if (auto insert = dyn_cast<InsertOp>(def)) {
      writes.push_back(insert);
      work.push_back(insert.getTensor());
    } else if (auto load = dyn_cast<LoadOp>(def)) {
      work.push_back(load.getRef());
    } else if (isa<AllocOp>(def)) {
      for (Operation *user : v.getUsers())
        if (auto store = dyn_cast<StoreOp>(user))
          work.push_back(store.getValue());
    } else if (auto loop = dyn_cast<scf::ForOp>(def)) {
      unsigned i = cast<OpResult>(v).getResultNumber();
      work.append({loop.getInitArgs()[i], loop.getYieldedValues()[i]});
    } else if (auto branch = dyn_cast<scf::IfOp>(def)) {
      unsigned i = cast<OpResult>(v).getResultNumber();
      work.push_back(branch.thenYield().getOperand(i));
      if (!branch.getElseRegion().empty())
        work.push_back(branch.elseYield().getOperand(i));
    } else if (!isa<ZerosOp>(def)) {
      return failure();
    }
  }
  return writes;
}

/// The offset from `point` of the grid point `index`: the sum of the
/// offsets of the `simit.grid_point` chain leading to it.
static std::optional<SmallVector<int64_t>>
offsetFrom(Value point, Value index, unsigned rank) {
  SmallVector<int64_t> offset(rank, 0);
  while (index != point) {
    auto neighbour = index.getDefiningOp<GridPointOp>();
    if (!neighbour)
      return std::nullopt;
    for (auto [total, o] : llvm::zip(offset, neighbour.getOffsets()))
      total += o;
    index = neighbour.getPoint();
  }
  return offset;
}

/// The stencil of result `result` of `map` through `grid`: the offsets at
/// which the element function writes, each at (p, P[offset]) of its point p.
static StorageRule stencilStorage(Operation *map, SetType grid,
                                  unsigned result) {
  auto callee = SymbolTable::lookupNearestSymbolFrom<func::FuncOp>(
      map, map->getAttrOfType<FlatSymbolRefAttr>("callee"));
  if (!callee || callee.isExternal())
    return StorageRule::error("the element function of this map has no body");
  // The element parameter comes just before the grid, the last one.
  Value point = callee.getArgument(callee.getNumArguments() - 2);
  unsigned rank = grid.getGridRank();
  FailureOr<SmallVector<InsertOp>> writes = writesOf(callee, result);
  if (failed(writes))
    return StorageRule::error("cannot trace result " + Twine(result) +
                              " of '" + callee.getSymName() +
                              "' to the writes that make it");
  SmallVector<SmallVector<int64_t>> offsets{SmallVector<int64_t>(rank, 0)};
  for (InsertOp write : *writes) {
    std::optional<SmallVector<int64_t>> offset;
    if (write.getIndices().size() == 2 && write.getIndices()[0] == point)
      offset = offsetFrom(point, write.getIndices()[1], rank);
    if (!offset)
      return StorageRule::error(
          "cannot store result " + Twine(result) +
          " as a grid stencil: a matrix assembled through a grid can only be "
          "written at (p, p) and (p, P[offset]) of the mapped point p");
    offsets.push_back(std::move(*offset));
  }
  return StorageRule::of(storage::stencil(grid.getName(), offsets));
}

StorageRule mlir::simit::getMapResultStorage(Operation *map, unsigned result) {
  auto type = cast<SystemTensorType>(map->getResult(result).getType());
  auto rows = cast<StringAttr>(type.getDims()[0]);
  auto cols = cast<StringAttr>(type.getDims()[1]);
  auto [set, grid] = [&]() -> std::pair<SetType, SetType> {
    auto setAndGrid = [](auto op) -> std::pair<SetType, SetType> {
      Value grid = op.getGrid();
      return {op.getSet().getType(),
              grid ? cast<SetType>(grid.getType()) : SetType()};
    };
    if (auto assemble = dyn_cast<AssembleOp>(map))
      return setAndGrid(assemble);
    return setAndGrid(cast<MapOp>(map));
  }();
  StringAttr name = set.getName();
  if (set.getCardinality() == 0) {
    if (rows != name || cols != name)
      return StorageRule::error("a matrix assembled from vertex set '" +
                                name.getValue() +
                                "' must be over that set (its diagonal)");
    if (grid)
      return stencilStorage(map, grid, result);
    return StorageRule::of(storage::diag(name));
  }
  if (rows == name && cols == name)
    return StorageRule::of(storage::diag(name));
  SmallVector<int64_t> rowPositions = positionsOf(set, rows);
  SmallVector<int64_t> colPositions = positionsOf(set, cols);
  if (rows == name && !colPositions.empty())
    return StorageRule::of(storage::incidence(name, colPositions));
  if (cols == name && !rowPositions.empty())
    return StorageRule::of(
        storage::transpose(storage::incidence(name, rowPositions)));
  if (rowPositions.empty() || colPositions.empty())
    return StorageRule::error("a matrix assembled from edge set '" +
                              name.getValue() +
                              "' must be over the edge set or its endpoint "
                              "sets");
  return StorageRule::of(storage::pattern(name, rowPositions, colPositions));
}
