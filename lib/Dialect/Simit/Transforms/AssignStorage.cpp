//===- AssignStorage.cpp - Storage encodings into the types ---------------===//
//
// Runs StorageAnalysis on every function that is not an element function,
// reports what has no storage, and otherwise writes the encodings into the
// types of results, block arguments and slots, with a `simit.convert` on
// every operand whose storage differs from what its use needs (the types an
// op, a slot or a loop ties together must be equal).
//
//===----------------------------------------------------------------------===//

#include "StorageAnalysis.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Analysis/DataFlow/ConstantPropagationAnalysis.h"
#include "mlir/Analysis/DataFlow/DeadCodeAnalysis.h"
#include "mlir/Analysis/DataFlowFramework.h"
#include "llvm/ADT/MapVector.h"
#include "llvm/ADT/TypeSwitch.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITASSIGNSTORAGE
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

/// Reports every place where storage became unsupported, once, with notes
/// at the ops the operands' storage comes from. Fails if there is one.
static LogicalResult reportUnsupported(func::FuncOp function,
                                       DataFlowSolver &solver) {
  llvm::MapVector<Operation *, const StorageLattice *> origins;
  bool returnsMatrix = false;
  auto collect = [&](Value value) {
    if (!holdsSetMatrix(value.getType()))
      return;
    const auto *lattice = solver.lookupState<StorageLattice>(value);
    if (lattice && lattice->isUnsupported())
      origins.insert({lattice->getOrigin(), lattice});
  };
  function.walk([&](Operation *op) {
    for (Value result : op->getResults())
      collect(result);
    for (Region &region : op->getRegions())
      for (Block &block : region)
        for (Value arg : block.getArguments())
          collect(arg);
    if (auto ret = dyn_cast<func::ReturnOp>(op)) {
      if (llvm::any_of(ret.getOperandTypes(), holdsSetMatrix)) {
        ret.emitError("exported functions cannot return system matrices");
        returnsMatrix = true;
      }
    }
  });
  for (auto [origin, lattice] : origins) {
    InFlightDiagnostic diag = origin->emitError(lattice->getReason());
    DenseSet<Operation *> noted;
    for (Value operand : origin->getOperands()) {
      const auto *source = solver.lookupState<StorageLattice>(operand);
      if (!source || !source->getEncoding() || !source->getProducer() ||
          !noted.insert(source->getProducer()).second)
        continue;
      diag.attachNote(source->getProducer()->getLoc())
          << "'" << source->getEncoding().str() << "' comes from here";
    }
  }
  return failure(!origins.empty() || returnsMatrix);
}

/// The type `value` has with `encoding`.
static Type typeWith(Value value, StorageAttr encoding) {
  if (auto ref = dyn_cast<RefType>(value.getType()))
    return RefType::get(ref.getContext(),
                        withStorage(ref.getValueType(), encoding));
  return withStorage(value.getType(), encoding);
}

/// Gives every matrix value of `function` the type of its storage. Values
/// the analysis never reached (dead code) are empty.
static void retype(func::FuncOp function, DataFlowSolver &solver) {
  StorageAttr empty = storage::empty(function.getContext());
  auto encodingOf = [&](Value value) {
    const auto *lattice = solver.lookupState<StorageLattice>(value);
    return lattice && lattice->getEncoding() ? lattice->getEncoding() : empty;
  };
  auto assign = [&](Value value) {
    if (holdsSetMatrix(value.getType()))
      value.setType(typeWith(value, encodingOf(value)));
  };
  // A loop's results and the block arguments they come from share a type.
  auto tie = [&](Value a, Value b) {
    if (!holdsSetMatrix(a.getType()))
      return;
    StorageAttr joined = storage::join(encodingOf(a), encodingOf(b));
    a.setType(typeWith(a, joined));
    b.setType(typeWith(b, joined));
  };
  function.walk([&](Operation *op) {
    for (Value result : op->getResults())
      assign(result);
    for (Region &region : op->getRegions())
      for (Block &block : region)
        for (Value arg : block.getArguments())
          assign(arg);
    if (auto loop = dyn_cast<scf::ForOp>(op))
      for (auto [arg, result] :
           llvm::zip(loop.getRegionIterArgs(), loop.getResults()))
        tie(arg, result);
    else if (auto loop = dyn_cast<scf::WhileOp>(op))
      for (auto [arg, result] :
           llvm::zip(loop.getAfterArguments(), loop.getResults()))
        tie(arg, result);
  });
}

/// Makes `operand` have type `expected` (equal up to storage): a widening
/// `simit.convert`, or a restricting one where `mayRestrict`.
static LogicalResult require(OpOperand &operand, Type expected,
                             bool mayRestrict = false) {
  Value value = operand.get();
  if (value.getType() == expected || !holdsSetMatrix(expected))
    return success();
  StorageAttr from = getStorage(value.getType());
  StorageAttr to = getStorage(expected);
  OpBuilder builder(operand.getOwner());
  // A use declared without storage (a runtime intrinsic) forgets it.
  bool widens = !to || storage::contains(to, from);
  if (!widens && !mayRestrict)
    return operand.getOwner()->emitError("operand #")
           << operand.getOperandNumber() << " stored as '" << from.str()
           << "' does not fit the storage '" << to.str() << "' of its use";
  operand.set(
      ConvertOp::create(builder, value.getLoc(), expected, value, !widens));
  return success();
}

/// Requires each of `operands` to have the matching type of `types`.
static LogicalResult requireAll(MutableArrayRef<OpOperand> operands,
                                TypeRange types) {
  for (auto [operand, type] : llvm::zip_equal(operands, types))
    if (failed(require(operand, type)))
      return failure();
  return success();
}

/// Inserts the conversions the uses of `op`'s operands need.
static LogicalResult convertOperands(Operation *op) {
  return TypeSwitch<Operation *, LogicalResult>(op)
      .Case<AddOp, SubOp, NegOp>([&](Operation *op) {
        for (OpOperand &operand : op->getOpOperands())
          if (failed(require(operand, op->getResult(0).getType())))
            return failure();
        return success();
      })
      .Case([&](MulOp mul) {
        return failure(
            failed(require(mul.getLhsMutable(), mul.getType(), true)) ||
            failed(require(mul.getRhsMutable(), mul.getType(), true)));
      })
      .Case([&](DivOp div) {
        return failure(
            failed(require(div.getLhsMutable(), div.getType())) ||
            failed(require(div.getRhsMutable(), div.getType(), true)));
      })
      .Case([&](ScaleOp scale) {
        return require(scale.getTensorMutable(), scale.getType());
      })
      .Case([&](InsertOp insert) {
        return require(insert.getTensorMutable(), insert.getType());
      })
      .Case([&](StoreOp store) {
        return require(store.getValueMutable(),
                       store.getRef().getType().getValueType());
      })
      .Case([&](func::CallOp call) {
        auto callee = SymbolTable::lookupNearestSymbolFrom<func::FuncOp>(
            call, call.getCalleeAttr());
        if (!callee)
          return success();
        return requireAll(call->getOpOperands(),
                          callee.getFunctionType().getInputs());
      })
      .Case([&](scf::ForOp loop) {
        return requireAll(loop.getInitArgsMutable(),
                          ValueRange(loop.getRegionIterArgs()).getTypes());
      })
      .Case([&](scf::WhileOp loop) {
        return requireAll(loop.getInitsMutable(),
                          ValueRange(loop.getBeforeArguments()).getTypes());
      })
      .Case([&](scf::ConditionOp condition) {
        auto loop = cast<scf::WhileOp>(condition->getParentOp());
        return requireAll(condition.getArgsMutable(),
                          ValueRange(loop.getAfterArguments()).getTypes());
      })
      .Case([&](scf::YieldOp yield) {
        Operation *parent = yield->getParentOp();
        if (auto loop = dyn_cast<scf::WhileOp>(parent))
          return requireAll(yield.getResultsMutable(),
                            ValueRange(loop.getBeforeArguments()).getTypes());
        return requireAll(yield.getResultsMutable(), parent->getResultTypes());
      })
      .Default([](Operation *) { return success(); });
}

/// A call returns the types its callee declares: a host function's matrix
/// result keeps its unencoded type and a `simit.convert` after the call
/// gives it its storage.
static void convertCallResults(func::FuncOp function) {
  function.walk([](func::CallOp call) {
    auto callee = SymbolTable::lookupNearestSymbolFrom<func::FuncOp>(
        call, call.getCalleeAttr());
    if (!callee)
      return;
    OpBuilder builder(call->getContext());
    builder.setInsertionPointAfter(call);
    for (auto [result, declared] :
         llvm::zip_equal(call.getResults(), callee.getResultTypes())) {
      if (result.getType() == declared)
        continue;
      Type encoded = result.getType();
      result.setType(declared);
      auto convert = ConvertOp::create(builder, call.getLoc(), encoded, result,
                                       /*restrict=*/false);
      result.replaceAllUsesExcept(convert, convert);
    }
  });
}

LogicalResult mlir::simit::assignStorage(func::FuncOp function) {
  DataFlowSolver solver(DataFlowConfig().setInterprocedural(false));
  solver.load<dataflow::DeadCodeAnalysis>();
  solver.load<dataflow::SparseConstantPropagation>();
  solver.load<StorageAnalysis>();
  if (failed(solver.initializeAndRun(function)) ||
      failed(reportUnsupported(function, solver)))
    return failure();
  retype(function, solver);
  convertCallResults(function);
  SmallVector<Operation *> ops;
  function.walk([&](Operation *op) { ops.push_back(op); });
  for (Operation *op : ops)
    if (failed(convertOperands(op)))
      return failure();
  return success();
}

bool mlir::simit::needsStorageAssignment(func::FuncOp function) {
  auto unassigned = [](Value value) {
    Type type = value.getType();
    if (auto ref = dyn_cast<RefType>(type))
      type = ref.getValueType();
    return holdsSetMatrix(type) && !getStorage(type);
  };
  WalkResult walk = function.walk([&](Operation *op) {
    // A conversion to a type without storage feeds a runtime function; a
    // host function's matrix result gets its storage by a conversion.
    bool found = !isa<ConvertOp, func::CallOp>(op) &&
                 llvm::any_of(op->getResults(), unassigned);
    for (Region &region : op->getRegions())
      for (Block &block : region)
        found |= llvm::any_of(block.getArguments(), unassigned);
    return found ? WalkResult::interrupt() : WalkResult::advance();
  });
  return walk.wasInterrupted();
}

namespace {
struct AssignStorage
    : public simit::impl::SimitAssignStorageBase<AssignStorage> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    DenseSet<StringAttr> elementFunctions;
    module.walk([&](Operation *op) {
      if (isa<MapOp, AssembleOp>(op))
        elementFunctions.insert(
            op->getAttrOfType<FlatSymbolRefAttr>("callee").getAttr());
    });
    bool failed = false;
    for (auto function : module.getOps<func::FuncOp>())
      if (!function.isExternal() &&
          !elementFunctions.contains(function.getSymNameAttr()))
        failed |= mlir::failed(assignStorage(function));
    if (failed)
      signalPassFailure();
  }
};
} // namespace
