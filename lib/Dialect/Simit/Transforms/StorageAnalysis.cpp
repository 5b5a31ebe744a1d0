//===- StorageAnalysis.cpp - Storage of system matrices, as data flow -----===//
//
// The lattice and the rules of the ops that combine matrices. Region
// control flow (scf.for, scf.while, scf.if) is the framework's: the storage
// of a loop-carried value or branch result is the join of what reaches it.
// A slot's storage is the join of everything stored into it, computed at
// the `simit.alloc`, so that its loads see it.
//
//===----------------------------------------------------------------------===//

#include "StorageAnalysis.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "llvm/ADT/TypeSwitch.h"

using namespace mlir;
using namespace mlir::simit;

/// A loop-carried value or a slot may widen this often; a storage still
/// widening after that does not settle (a product in a loop grows forever).
static constexpr unsigned kMaxGrowth = 3;

/// The most rank-one terms a `lowrank` keeps.
static constexpr int64_t kMaxRank = 4;

bool mlir::simit::holdsSetMatrix(Type type) {
  if (auto ref = dyn_cast<RefType>(type))
    type = ref.getValueType();
  auto tensor = dyn_cast<SystemTensorType>(type);
  return tensor && tensor.isSetMatrix();
}

/// The op a diagnostic about `value` points at: its definition, or the op
/// owning the block it is an argument of.
static Operation *ownerOf(Value value) {
  if (Operation *def = value.getDefiningOp())
    return def;
  return cast<BlockArgument>(value).getOwner()->getParentOp();
}

//===----------------------------------------------------------------------===//
// StorageLattice
//===----------------------------------------------------------------------===//

ChangeResult StorageLattice::join(const AbstractSparseLattice &rhs) {
  const auto &other = static_cast<const StorageLattice &>(rhs);
  if (other.isUnsupported())
    return markUnsupported(other.origin, other.reason);
  if (other.isUninitialized())
    return ChangeResult::NoChange;
  return join(other.encoding, other.producer);
}

ChangeResult StorageLattice::join(StorageAttr incoming, Operation *from) {
  if (isUnsupported())
    return ChangeResult::NoChange;
  if (!encoding) {
    encoding = incoming;
    producer = from;
    return ChangeResult::Change;
  }
  StorageAttr joined = storage::join(encoding, incoming);
  if (joined == encoding)
    return ChangeResult::NoChange;
  encoding = joined;
  producer = from;
  Value value = getAnchor();
  bool carried = isa<BlockArgument>(value) || value.getDefiningOp<AllocOp>();
  if (carried && ++growth > kMaxGrowth)
    return markUnsupported(ownerOf(value),
                           "the storage of this loop-carried value keeps "
                           "growing (now '" +
                               joined.str() + "')");
  return ChangeResult::Change;
}

ChangeResult StorageLattice::markUnsupported(Operation *at, StringRef why) {
  if (isUnsupported())
    return ChangeResult::NoChange;
  origin = at;
  reason = why.str();
  return ChangeResult::Change;
}

void StorageLattice::print(raw_ostream &os) const {
  if (isUnsupported())
    os << "unsupported: " << reason;
  else if (encoding)
    os << encoding.str();
  else
    os << "<uninitialized>";
}

//===----------------------------------------------------------------------===//
// Rules
//===----------------------------------------------------------------------===//

/// A sum keeps the rank-one terms of both operands.
static StorageRule sumStorage(StorageAttr a, StorageAttr b) {
  auto split = [](StorageAttr x) -> std::pair<StorageAttr, int64_t> {
    if (x.getKind() == StorageKind::LowRank)
      return {x.getOperand(), x.getRank()};
    return {x, 0};
  };
  auto [baseA, rankA] = split(a);
  auto [baseB, rankB] = split(b);
  if (rankA + rankB > kMaxRank)
    return StorageRule::error("a sum with more than " + Twine(kMaxRank) +
                              " rank-one terms has no storage");
  return StorageRule::of(
      storage::lowRank(storage::join(baseA, baseB), rankA + rankB));
}

/// `.*` keeps the smaller storage (the other operand is restricted to
/// it); of two storages neither of which contains the other, their join,
/// which holds every nonzero (their intersection has no encoding).
static StorageRule mulStorage(StorageAttr a, StorageAttr b) {
  if (storage::contains(a, b))
    return StorageRule::of(b);
  if (storage::contains(b, a))
    return StorageRule::of(a);
  return StorageRule::of(storage::join(a, b));
}

/// `./` keeps the dividend's storage; the divisor must store those blocks.
static StorageRule divStorage(StorageAttr dividend, StorageAttr divisor) {
  if (storage::contains(divisor, dividend))
    return StorageRule::of(dividend);
  return StorageRule::error("cannot divide '" + dividend.str() + "' by '" +
                            divisor.str() +
                            "': the divisor does not store every block of the "
                            "dividend");
}

/// The number of the first matrix result of host function call `call`
/// among those of its function, in program order.
static int64_t hostMatrixNumber(func::CallOp call) {
  auto function = call->getParentOfType<func::FuncOp>();
  int64_t number = 0;
  function.walk([&](func::CallOp other) {
    if (other == call)
      return WalkResult::interrupt();
    auto callee = SymbolTable::lookupNearestSymbolFrom<func::FuncOp>(
        other, other.getCalleeAttr());
    if (callee && callee->hasAttr("simit.extern_function"))
      number += llvm::count_if(other.getResultTypes(), holdsSetMatrix);
    return WalkResult::advance();
  });
  return number;
}

namespace {
/// The storage and producer of the operands of the op being visited.
struct Operands {
  ArrayRef<const StorageLattice *> lattices;
  StorageAttr operator[](unsigned i) const {
    return lattices[i]->getEncoding();
  }
  Operation *producer(unsigned i) const { return lattices[i]->getProducer(); }
};
} // namespace

LogicalResult
StorageAnalysis::visitOperation(Operation *op,
                                ArrayRef<const StorageLattice *> operands,
                                ArrayRef<StorageLattice *> results) {
  SmallVector<StorageLattice *> matrixResults;
  for (auto [result, lattice] : llvm::zip(op->getResults(), results))
    if (holdsSetMatrix(result.getType()))
      matrixResults.push_back(lattice);
  if (matrixResults.empty())
    return success();
  // An unsupported operand was reported where it arose; a matrix operand
  // not known yet is waited for.
  for (auto [value, lattice] : llvm::zip(op->getOperands(), operands)) {
    if (lattice->isUnsupported()) {
      for (StorageLattice *result : matrixResults)
        propagateIfChanged(result, result->join(*lattice));
      return success();
    }
    if (holdsSetMatrix(value.getType()) && lattice->isUninitialized())
      return success();
  }

  auto setResult = [&](unsigned i, const StorageRule &rule,
                       Operation *producer) {
    StorageLattice *lattice = results[i];
    if (!rule.unsupported.empty())
      propagateIfChanged(lattice, lattice->markUnsupported(op, rule.unsupported));
    else
      propagateIfChanged(lattice, lattice->join(rule.encoding, producer));
  };
  // An op that passes operand `i`'s storage through.
  auto passThrough = [&](unsigned i) {
    setResult(0, StorageRule::of(operands[i]->getEncoding()),
              operands[i]->getProducer());
  };
  Operands in{operands};
  MLIRContext *ctx = op->getContext();

  TypeSwitch<Operation *>(op)
      .Case([&](ZerosOp) {
        setResult(0, StorageRule::of(storage::empty(ctx)), op);
      })
      // Every block holds the scalar (simit-linalg-to-index-expr reads a
      // broadcast operand of element-wise ops as the scalar instead).
      .Case([&](BroadcastOp) {
        setResult(0, StorageRule::of(storage::dense(ctx)), op);
      })
      .Case<AddOp, SubOp>(
          [&](auto) { setResult(0, sumStorage(in[0], in[1]), op); })
      .Case([&](MulOp) { setResult(0, mulStorage(in[0], in[1]), op); })
      .Case([&](DivOp) { setResult(0, divStorage(in[0], in[1]), op); })
      .Case([&](NegOp) { passThrough(0); })
      .Case([&](ScaleOp scale) {
        passThrough(scale.getTensorMutable().getOperandNumber());
      })
      .Case([&](InsertOp insert) {
        passThrough(insert.getTensorMutable().getOperandNumber());
      })
      .Case([&](LoadOp) { passThrough(0); })
      .Case([&](TransposeOp) {
        setResult(0, StorageRule::of(storage::transpose(in[0])), op);
      })
      .Case([&](MatMulOp matmul) {
        if (!holdsSetMatrix(matmul.getLhs().getType()) ||
            !holdsSetMatrix(matmul.getRhs().getType()))
          setResult(0,
                    StorageRule::error("a product of a matrix over two sets "
                                       "and one over a range has no storage"),
                    op);
        else
          setResult(0, StorageRule::of(storage::product({in[0], in[1]})), op);
      })
      .Case([&](FactorSolveOp) {
        // lumatsolve / lltmatsolve: A^-1 B fills in every block.
        setResult(0, StorageRule::of(storage::dense(ctx)), op);
      })
      .Case([&](OuterOp) {
        setResult(0,
                  StorageRule::of(storage::lowRank(storage::empty(ctx), 1)),
                  op);
      })
      .Case([&](ConvertOp convert) {
        setResult(0, StorageRule::of(getStorage(convert.getType())), op);
      })
      .Case([&](AllocOp alloc) {
        // A slot starts as zeros and holds everything stored into it.
        StorageLattice *slot = results[0];
        ChangeResult changed = slot->join(storage::empty(ctx), op);
        for (Operation *user : alloc->getUsers()) {
          auto store = dyn_cast<StoreOp>(user);
          if (!store) {
            if (!isa<LoadOp>(user))
              changed |= slot->markUnsupported(
                  user, "a slot holding a system matrix can only be loaded "
                        "and stored");
            continue;
          }
          const StorageLattice *value =
              getLatticeElementFor(getProgramPointAfter(op), store.getValue());
          if (!value->isUninitialized())
            changed |= slot->join(*value);
        }
        propagateIfChanged(slot, changed);
      })
      .Case<MapOp, AssembleOp>([&](Operation *map) {
        for (auto [i, result] : llvm::enumerate(map->getResults()))
          if (holdsSetMatrix(result.getType()))
            setResult(i, getMapResultStorage(map, i), op);
      })
      .Case([&](IndexExprOp expr) {
        SmallVector<StorageAttr> inputs;
        for (unsigned i = 0, e = expr.getInputs().size(); i < e; ++i)
          inputs.push_back(in[i]);
        setResult(0, getIndexExprStorage(expr, inputs), op);
      })
      .Case([&](func::CallOp call) {
        // A host function's matrix results have whatever pattern it gives
        // them at run time: each its own, numbered within the function.
        auto callee = SymbolTable::lookupNearestSymbolFrom<func::FuncOp>(
            call, call.getCalleeAttr());
        StringAttr name =
            callee ? callee->getAttrOfType<StringAttr>("simit.extern_function")
                   : StringAttr();
        if (!name) {
          for (unsigned i = 0, e = call.getNumResults(); i < e; ++i)
            if (holdsSetMatrix(call.getResult(i).getType()))
              setResult(i,
                        StorageRule::error("the storage of this value is not "
                                           "known"),
                        op);
          return;
        }
        int64_t number = hostMatrixNumber(call);
        for (unsigned i = 0, e = call.getNumResults(); i < e; ++i)
          if (holdsSetMatrix(call.getResult(i).getType()))
            setResult(i, StorageRule::of(storage::host(name, number++)), op);
      })
      .Case([&](ExternRefOp) {
        setResult(0,
                  StorageRule::error("extern system matrices have no storage"),
                  op);
      })
      .Default([&](Operation *) {
        for (StorageLattice *lattice : matrixResults)
          propagateIfChanged(
              lattice, lattice->markUnsupported(
                           op, "no storage rule for the results of '" +
                                   op->getName().getStringRef().str() + "'"));
      });
  return success();
}

void StorageAnalysis::visitExternalCall(
    CallOpInterface call, ArrayRef<const StorageLattice *> arguments,
    ArrayRef<StorageLattice *> results) {
  (void)visitOperation(call, arguments, results);
}

void StorageAnalysis::setToEntryState(StorageLattice *lattice) {
  Value value = lattice->getAnchor();
  if (!holdsSetMatrix(value.getType()))
    return;
  Operation *owner = ownerOf(value);
  StringRef reason = isa<FunctionOpInterface>(owner)
                         ? "exported functions cannot take system matrices"
                         : "the storage of this value is not known";
  propagateIfChanged(lattice, lattice->markUnsupported(owner, reason));
}
