//===- EliminateDeadAssemblies.cpp - Drop unused map results --------------===//
//
// A map's element function computes every result for every element; a
// result nothing reads is work thrown away. The map is rebuilt with the used
// results and calls a copy of the element function that returns only those,
// so the loop lowering never writes (or sizes, or pattern-builds) the rest.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/Iterators.h"
#include "mlir/IR/SymbolTable.h"
#include "mlir/Interfaces/SideEffectInterfaces.h"

#include "llvm/ADT/STLExtras.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITELIMINATEDEADASSEMBLIES
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

/// Whether running `function` changes anything besides its results: a
/// write to memory it did not allocate itself (a field), a call, or an op
/// whose effects are unknown.
static bool hasEffects(func::FuncOp function) {
  auto isLocal = [&](Value value) {
    return value && value.getDefiningOp<AllocOp>() &&
           function->isAncestor(value.getDefiningOp());
  };
  WalkResult result = function.walk([&](Operation *op) {
    if (op == function || isa<func::ReturnOp>(op) ||
        op->hasTrait<OpTrait::HasRecursiveMemoryEffects>())
      return WalkResult::advance();
    if (isa<CallOpInterface>(op))
      return WalkResult::interrupt();
    auto effecting = dyn_cast<MemoryEffectOpInterface>(op);
    if (!effecting)
      return WalkResult::interrupt();
    SmallVector<MemoryEffects::EffectInstance> effects;
    effecting.getEffects(effects);
    for (const MemoryEffects::EffectInstance &effect : effects)
      if (isa<MemoryEffects::Write, MemoryEffects::Free>(effect.getEffect()) &&
          !isLocal(effect.getValue()))
        return WalkResult::interrupt();
    return WalkResult::advance();
  });
  return result.wasInterrupted();
}

/// Whether what is loaded from `slot` flows, through ops without effects
/// (not terminators: a returned or yielded value escapes), only into stores
/// back to `slot`: the variable no longer reaches a result.
static bool onlyFeedsItself(AllocOp slot) {
  SmallVector<Value> loaded;
  for (Operation *user : slot->getUsers()) {
    if (auto store = dyn_cast<StoreOp>(user);
        store && store.getRef() == slot.getResult())
      continue;
    if (!isa<LoadOp>(user))
      return false;
    loaded.push_back(user->getResult(0));
  }
  DenseSet<Operation *> seen;
  while (!loaded.empty()) {
    Value value = loaded.pop_back_val();
    for (Operation *user : value.getUsers()) {
      if (!seen.insert(user).second)
        continue;
      if (auto store = dyn_cast<StoreOp>(user)) {
        if (store.getRef() != slot.getResult())
          return false;
        continue;
      }
      if (user->hasTrait<OpTrait::IsTerminator>() ||
          user->getNumRegions() != 0 || !isMemoryEffectFree(user))
        return false;
      llvm::append_range(loaded, user->getResults());
    }
  }
  return true;
}

/// Erases what no longer reaches a result: unused values, and the
/// variables (`simit.alloc` slots) whose values only flow back into
/// themselves, with their loads and stores. The loop lowering takes a
/// variable holding a set tensor for a result of the element function, so
/// none may be left over.
static void eraseDeadWork(func::FuncOp function) {
  bool changed = true;
  while (changed) {
    changed = false;
    function.walk<WalkOrder::PostOrder, ReverseIterator>([&](Operation *op) {
      if (op != function && isOpTriviallyDead(op)) {
        op->erase();
        changed = true;
      }
    });
    SmallVector<AllocOp> dead;
    function.walk([&](AllocOp slot) {
      if (onlyFeedsItself(slot))
        dead.push_back(slot);
    });
    for (AllocOp slot : dead)
      for (Operation *user : llvm::make_early_inc_range(slot->getUsers()))
        if (isa<StoreOp>(user)) {
          user->erase();
          changed = true;
        }
  }
}

/// A copy of `callee` that returns only the results at `kept`, inserted
/// after it under a fresh name.
static func::FuncOp cloneWithResults(func::FuncOp callee,
                                     ArrayRef<unsigned> kept,
                                     SymbolTable &symbols) {
  std::string name = callee.getSymName().str() + "_live";
  for (unsigned index : kept)
    name += "_" + std::to_string(index);
  if (auto existing = symbols.lookup<func::FuncOp>(name))
    return existing;
  auto copy = cast<func::FuncOp>(callee->clone());
  copy.setSymName(name);
  SmallVector<Type> resultTypes;
  for (unsigned index : kept)
    resultTypes.push_back(callee.getFunctionType().getResult(index));
  copy.setType(FunctionType::get(callee.getContext(),
                                 callee.getFunctionType().getInputs(),
                                 resultTypes));
  copy.walk([&](func::ReturnOp ret) {
    SmallVector<Value> values;
    for (unsigned index : kept)
      values.push_back(ret.getOperand(index));
    ret->setOperands(values);
  });
  eraseDeadWork(copy);
  symbols.insert(copy, std::next(Block::iterator(callee)));
  return copy;
}

namespace {
struct EliminateDeadAssemblies
    : public simit::impl::SimitEliminateDeadAssembliesBase<
          EliminateDeadAssemblies> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    SymbolTable symbols(module);
    SmallVector<Operation *> maps;
    module.walk([&](Operation *op) {
      if (isa<MapOp, AssembleOp>(op) && op->getNumResults() > 0 &&
          llvm::any_of(op->getResults(),
                       [](Value result) { return result.use_empty(); }))
        maps.push_back(op);
    });
    DenseSet<Operation *> touchedCallees;
    for (Operation *op : maps) {
      auto calleeName = op->getAttrOfType<FlatSymbolRefAttr>("callee");
      auto callee = symbols.lookup<func::FuncOp>(calleeName.getValue());
      if (!callee || callee.isExternal())
        continue;
      SmallVector<unsigned> kept;
      for (OpResult result : op->getResults())
        if (!result.use_empty())
          kept.push_back(result.getResultNumber());
      touchedCallees.insert(callee);
      if (kept.empty() && !hasEffects(callee)) {
        op->erase();
        continue;
      }
      func::FuncOp copy = cloneWithResults(callee, kept, symbols);
      OpBuilder builder(op);
      // An assembly of nothing is a map run for its effects.
      bool asMap = kept.empty();
      OperationState state(op->getLoc(), asMap ? OperationName(
                                                     MapOp::getOperationName(),
                                                     op->getContext())
                                               : op->getName());
      state.addOperands(op->getOperands());
      state.addAttributes(op->getAttrs());
      if (asMap)
        state.attributes.erase(AssembleOp::getReductionAttrName(
            OperationName(AssembleOp::getOperationName(), op->getContext())));
      state.attributes.set("callee",
                           FlatSymbolRefAttr::get(copy.getSymNameAttr()));
      for (unsigned index : kept)
        state.addTypes(op->getResult(index).getType());
      Operation *rebuilt = builder.create(state);
      for (auto [newIndex, oldIndex] : llvm::enumerate(kept))
        op->getResult(oldIndex).replaceAllUsesWith(
            rebuilt->getResult(newIndex));
      op->erase();
    }
    // The original element functions, when no map calls them any more.
    for (Operation *callee : touchedCallees)
      if (SymbolTable::symbolKnownUseEmpty(callee, module))
        symbols.erase(callee);
  }
};
} // namespace
