//===- SimitMapOps.cpp - Verification of simit.map and simit.assemble -----===//
//
// A map calls an element function once per element of a set. Its verifier
// matches the call against the function's signature and checks the rule
// that makes assembly coordinate-free: inside the function, every write to
// a result is indexed on set dimensions only by the function's own element,
// its endpoints or (for grid stencils) grid points near the element.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/SimitStorage.h"

#include "SetChecks.h"
#include "mlir/Interfaces/FunctionInterfaces.h"
#include "mlir/Interfaces/LoopLikeInterface.h"
#include "llvm/ADT/DenseSet.h"

using namespace mlir;
using namespace mlir::simit;

namespace {
/// The values an element function may use to index a set dimension of a
/// result, and the search for writes to results that use anything else.
class ResultWriteChecker {
public:
  ResultWriteChecker(Value element, Value endpoints)
      : element(element), endpoints(endpoints) {}

  /// The first simit.insert that writes into a set dimension of `result`
  /// (a value returned by the function, or flowing into one) with an index
  /// that is not allowed; null if every write is allowed.
  InsertOp findBadWrite(Value result);

private:
  bool isAllowedIndex(Value index) const;
  /// Adds the values `value` is computed from that may carry writes.
  void pushSources(Value value);
  void push(Value value);

  Value element, endpoints;
  SmallVector<Value> worklist;
  llvm::DenseSet<Value> visited;
};
} // namespace

/// Whether a value of `type` can carry writes to a set dimension.
static bool mayHoldSetDimension(Type type) {
  if (auto ref = dyn_cast<RefType>(type))
    type = ref.getValueType();
  return hasSetDimension(type);
}

bool ResultWriteChecker::isAllowedIndex(Value index) const {
  if (index == element)
    return true;
  if (auto component = index.getDefiningOp<TupleGetOp>())
    return endpoints && component.getTuple() == endpoints;
  if (auto point = index.getDefiningOp<GridPointOp>())
    return isAllowedIndex(point.getPoint());
  return false;
}

void ResultWriteChecker::push(Value value) {
  if (mayHoldSetDimension(value.getType()) && visited.insert(value).second)
    worklist.push_back(value);
}

void ResultWriteChecker::pushSources(Value value) {
  if (auto argument = dyn_cast<BlockArgument>(value)) {
    auto loop = dyn_cast<LoopLikeOpInterface>(argument.getOwner()->getParentOp());
    if (!loop)
      return;
    for (auto [iterArg, init, yielded] :
         llvm::zip(loop.getRegionIterArgs(), loop.getInits(),
                   loop.getYieldedValues())) {
      if (iterArg != argument)
        continue;
      push(init);
      push(yielded);
    }
    return;
  }

  Operation *op = value.getDefiningOp();
  if (auto insert = dyn_cast<InsertOp>(op)) {
    push(insert.getTensor());
    return;
  }
  if (auto load = dyn_cast<LoadOp>(op)) {
    // A slot holds whatever was stored into it.
    for (Operation *user : load.getRef().getUsers())
      if (auto store = dyn_cast<StoreOp>(user))
        push(store.getValue());
    return;
  }
  if (op->getNumRegions() != 0) {
    // Results of control flow (scf.if, scf.for, ...) are what their regions
    // yield at the same position, or the loop's initial value.
    unsigned position = cast<OpResult>(value).getResultNumber();
    for (Region &region : op->getRegions())
      for (Block &block : region)
        if (Operation *terminator = block.getTerminator();
            terminator && terminator->getNumOperands() == op->getNumResults())
          push(terminator->getOperand(position));
    if (auto loop = dyn_cast<LoopLikeOpInterface>(op))
      if (loop.getInits().size() == op->getNumResults())
        push(loop.getInits()[position]);
    return;
  }
  // Any other operation (simit.add, ...) combines its operands.
  for (Value operand : op->getOperands())
    push(operand);
}

InsertOp ResultWriteChecker::findBadWrite(Value result) {
  push(result);
  while (!worklist.empty()) {
    Value value = worklist.pop_back_val();
    if (auto insert = value.getDefiningOp<InsertOp>()) {
      auto tensorType = dyn_cast<SystemTensorType>(insert.getTensor().getType());
      for (auto [dim, index] : llvm::enumerate(insert.getIndices()))
        if (tensorType && isa<StringAttr>(tensorType.getDims()[dim]) &&
            !isAllowedIndex(index))
          return insert;
    }
    pushSources(value);
  }
  return {};
}

/// Checks a map or assembly of `callee` over `set` (through `grid`).
static LogicalResult verifyMapLike(Operation *op,
                                   SymbolTableCollection &symbolTable,
                                   FlatSymbolRefAttr callee, ValueRange extras,
                                   SetType set, Value grid,
                                   TypeRange resultTypes) {
  auto function =
      symbolTable.lookupNearestSymbolFrom<FunctionOpInterface>(op, callee);
  if (!function)
    return op->emitOpError() << "'" << callee << "' does not name a function";
  ArrayRef<Type> params = function.getArgumentTypes();

  // Parameters: extra arguments, the element, the endpoint tuple (edge sets,
  // when the function has a parameter for it), the grid.
  unsigned numExtras = extras.size();
  if (params.size() < numExtras + 1)
    return op->emitOpError()
           << callee << " has " << params.size() << " parameters but the map "
           << "passes " << numExtras << " extra arguments and the element";
  for (auto [i, extra] : llvm::enumerate(extras)) {
    Type type = extra.getType();
    if (!isTensorOrScalarType(type) && !isa<simit::OpaqueType>(type))
      return op->emitOpError() << "extra argument #" << i
                               << " must be a tensor, a scalar or an opaque "
                                  "handle, got "
                               << type;
    // Element functions read matrix arguments in any storage.
    if (!isSameUpToStorage(type, params[i]))
      return op->emitOpError()
             << "passes extra argument #" << i << " of type " << extra.getType()
             << " but " << callee << " expects " << params[i];
  }
  if (params[numExtras] != set.getElementType())
    return op->emitOpError()
           << callee << " takes " << params[numExtras]
           << " as its element parameter but set '" << set.getName().getValue()
           << "' holds " << set.getElementType();
  unsigned numPassed = numExtras + 1;
  if (grid) {
    auto gridType = cast<SetType>(grid.getType());
    if (!gridType.isGrid() || gridType.getEndpoint(0) != set.getName())
      return op->emitOpError() << "'through' set '"
                               << gridType.getName().getValue()
                               << "' is not a grid over the mapped set '"
                               << set.getName().getValue() << "'";
    if (params.size() != numPassed + 1 || params[numPassed] != gridType)
      return op->emitOpError() << callee << " must take the grid " << gridType
                               << " as its last parameter";
    ++numPassed;
  } else if (set.getCardinality() != 0 && params.size() > numPassed) {
    auto tuple = dyn_cast<simit::TupleType>(params[numPassed]);
    if (!tuple)
      return op->emitOpError() << callee << " takes " << params[numPassed]
                               << " where the map passes the endpoint tuple";
    if (failed(verifyEndpointTuple(op, set, tuple)))
      return failure();
    ++numPassed;
  }
  if (params.size() != numPassed)
    return op->emitOpError() << callee << " has " << params.size()
                             << " parameters but the map passes " << numPassed;

  // Results: the function's, over the set, its endpoint sets or ranges. The
  // function returns one element's contributions, which have no storage;
  // the map's results may carry the encoding simit-assign-storage gives them.
  ArrayRef<Type> functionResults = function.getResultTypes();
  if (functionResults.size() != resultTypes.size() ||
      !llvm::all_of(llvm::zip(functionResults, resultTypes), [](auto types) {
        return isSameUpToStorage(std::get<0>(types), std::get<1>(types));
      }))
    return op->emitOpError() << "result types must be the result types of "
                             << callee;
  for (auto [i, type] : llvm::enumerate(resultTypes)) {
    for (unsigned dim = 0, e = getTensorOrder(type); dim < e; ++dim) {
      for (Attribute level : getDimensionHierarchy(type, dim)) {
        auto setName = dyn_cast<StringAttr>(level);
        if (!setName || setName == set.getName() ||
            llvm::is_contained(set.getEndpoints(), setName))
          continue;
        return op->emitOpError()
               << "result #" << i << " has dimension '" << setName.getValue()
               << "', which is neither the mapped set '"
               << set.getName().getValue() << "' nor one of its endpoint sets";
      }
    }
  }

  // Writes to results, indexed only by the element and its endpoints.
  if (std::optional<std::pair<InsertOp, unsigned>> bad =
          findUnindexedResultWrite(op)) {
    InFlightDiagnostic diag =
        op->emitOpError()
        << callee << " writes result #" << bad->second
        << " at a set position not indexed by its element or endpoints; "
           "an element function writes only to locations indexed by its "
           "own element and endpoints";
    diag.attachNote(bad->first.getLoc()) << "see the write here";
    return diag;
  }
  return success();
}

std::optional<std::pair<InsertOp, unsigned>>
mlir::simit::findUnindexedResultWrite(Operation *mapLike) {
  auto callee = mapLike->getAttrOfType<FlatSymbolRefAttr>("callee");
  auto function =
      callee ? SymbolTable::lookupNearestSymbolFrom<FunctionOpInterface>(
                   mapLike, callee)
             : FunctionOpInterface();
  if (!function || function.getFunctionBody().empty())
    return std::nullopt;
  bool throughGrid;
  unsigned numExtras;
  if (auto map = dyn_cast<MapOp>(mapLike)) {
    throughGrid = static_cast<bool>(map.getGrid());
    numExtras = map.getExtras().size();
  } else {
    auto assemble = cast<AssembleOp>(mapLike);
    throughGrid = static_cast<bool>(assemble.getGrid());
    numExtras = assemble.getExtras().size();
  }
  Region &body = function.getFunctionBody();
  if (body.getNumArguments() <= numExtras)
    return std::nullopt;
  Value element = body.getArgument(numExtras);
  // The endpoint tuple follows the element (a grid point's neighbours are
  // reached through the grid instead).
  Value endpoints;
  if (!throughGrid && body.getNumArguments() > numExtras + 1 &&
      isa<TupleType>(body.getArgument(numExtras + 1).getType()))
    endpoints = body.getArgument(numExtras + 1);
  for (Block &block : body) {
    Operation *terminator = block.getTerminator();
    if (!terminator || !terminator->hasTrait<OpTrait::ReturnLike>())
      continue;
    for (auto [i, result] : llvm::enumerate(terminator->getOperands())) {
      ResultWriteChecker checker(element, endpoints);
      if (InsertOp bad = checker.findBadWrite(result))
        return std::make_pair(bad, static_cast<unsigned>(i));
    }
  }
  return std::nullopt;
}

LogicalResult MapOp::verifySymbolUses(SymbolTableCollection &symbolTable) {
  return verifyMapLike(*this, symbolTable, getCalleeAttr(), getExtras(),
                       getSet().getType(), getGrid(), getResultTypes());
}

LogicalResult AssembleOp::verifySymbolUses(SymbolTableCollection &symbolTable) {
  return verifyMapLike(*this, symbolTable, getCalleeAttr(), getExtras(),
                       getSet().getType(), getGrid(), getResultTypes());
}

LogicalResult MapOp::verify() {
  std::optional<ArrayRef<int64_t>> inits = getResultInits();
  if (!inits)
    return success();
  if (inits->size() != getResults().size())
    return emitOpError() << "has " << inits->size() << " result_inits for "
                         << getResults().size() << " results";
  for (auto [i, extra] : llvm::enumerate(*inits)) {
    if (extra == -1)
      continue;
    if (extra < 0 || extra >= static_cast<int64_t>(getExtras().size()))
      return emitOpError() << "result_inits[" << i << "] = " << extra
                           << " names no extra argument";
    if (getExtras()[extra].getType() != getResult(i).getType())
      return emitOpError() << "result #" << i << " starts from extra argument #"
                           << extra << " of another type";
  }
  return success();
}

LogicalResult AssembleOp::verify() {
  if (getResults().empty())
    return emitOpError() << "assembles at least one result; use simit.map to "
                            "apply a function without results";
  return success();
}
