//===- VectorizeElementLoops.cpp - Element kernels across vector lanes ----===//
//
// An element function's arithmetic is the same for every element of its set:
// the loop over a chunk of the set runs it on `lanes` elements at a time, one
// element per lane of a machine vector, instead of relying on LLVM to find
// parallelism inside one element (a 3x3 block is a poor fit for a vector of
// eight). What the elements write (scatters into system tensors, stores,
// calls, anything not understood) then runs element by element in the loop's
// order, reading the kernel's results from small stack buffers. The
// arithmetic of each lane is the scalar arithmetic (no reassociation, no
// contraction), so results are bit-identical to the scalar loop's.
//
//===----------------------------------------------------------------------===//

#include "ElementLoopVectorizer.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Utils/IndexingUtils.h"
#include "mlir/Dialect/Utils/StaticValueUtils.h"
#include "mlir/IR/IRMapping.h"
#include "mlir/Interfaces/SideEffectInterfaces.h"
#include "mlir/Interfaces/ViewLikeInterface.h"
#include "mlir/Transforms/RegionUtils.h"
#include "llvm/ADT/MapVector.h"

#include <map>

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITVECTORIZEELEMENTLOOPS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::element_vectorize;

namespace mlir::simit::element_vectorize {

Type componentType(Type type) {
  if (auto vector = dyn_cast<VectorType>(type)) {
    if (vector.isScalable())
      return {};
    type = vector.getElementType();
  }
  if (type.isIntOrIndexOrFloat())
    return type;
  return {};
}

int64_t componentCount(Type type) {
  if (auto vector = dyn_cast<VectorType>(type))
    return vector.getNumElements();
  return 1;
}

bool allConstantIndices(ValueRange indices) {
  return llvm::all_of(indices, [](Value index) {
    return getConstantIntValue(index).has_value();
  });
}

int64_t linearPosition(ArrayRef<int64_t> shape, ValueRange indices) {
  int64_t position = 0;
  for (auto [size, index] : llvm::zip(shape, indices))
    position = position * size + *getConstantIntValue(index);
  return position;
}

int64_t firstComponent(VectorType type, ArrayRef<int64_t> position) {
  int64_t first = 0;
  for (auto [index, stride] :
       llvm::zip(position, computeStrides(type.getShape())))
    first += index * stride;
  return first;
}

Value viewRoot(Value memref) {
  while (auto view = memref.getDefiningOp<ViewLikeOpInterface>())
    memref = view.getViewSource();
  return memref;
}

} // namespace mlir::simit::element_vectorize

//===----------------------------------------------------------------------===//
// Planning
//===----------------------------------------------------------------------===//

/// The alloca a fill loop `scf.parallel (%i) = (0) to (n) { store %c, %a[%i] }`
/// fills, or null.
static Value filledAlloca(Operation *op) {
  auto fill = dyn_cast<scf::ParallelOp>(op);
  if (!fill || fill.getNumLoops() != 1 || fill.getNumResults() != 0 ||
      fill.getBody()->getOperations().size() != 2)
    return {};
  auto store = dyn_cast<memref::StoreOp>(fill.getBody()->front());
  if (!store || store.getIndices().size() != 1 ||
      store.getIndices()[0] != fill.getInductionVars()[0] ||
      fill->isAncestor(store.getValueToStore().getParentBlock()->getParentOp()))
    return {};
  auto alloca = store.getMemRef().getDefiningOp<memref::AllocaOp>();
  if (!alloca || alloca.getType().getRank() != 1)
    return {};
  std::optional<int64_t> lb = getConstantIntValue(fill.getLowerBound()[0]),
                         ub = getConstantIntValue(fill.getUpperBound()[0]),
                         step = getConstantIntValue(fill.getStep()[0]);
  if (lb != 0 || step != 1 || ub != alloca.getType().getDimSize(0))
    return {};
  return alloca;
}

bool ElementLoopVectorizer::isPromotedAccess(Operation *op,
                                             Value &alloca) const {
  Value memref;
  if (auto load = dyn_cast<vector::LoadOp>(op))
    memref = load.getBase();
  else if (auto store = dyn_cast<vector::StoreOp>(op))
    memref = store.getBase();
  else if (auto load = dyn_cast<memref::LoadOp>(op))
    memref = load.getMemRef();
  else if (auto store = dyn_cast<memref::StoreOp>(op))
    memref = store.getMemRef();
  else
    memref = filledAlloca(op);
  if (!memref || !promoted.contains(memref))
    return false;
  alloca = memref;
  return true;
}

void ElementLoopVectorizer::findPromotableAllocas() {
  for (Operation &op : body->without_terminator()) {
    auto alloca = dyn_cast<memref::AllocaOp>(op);
    if (!alloca || !alloca.getType().hasStaticShape() ||
        !alloca.getType().getLayout().isIdentity() ||
        !componentType(alloca.getType().getElementType()) ||
        alloca->getNumOperands() != 0)
      continue;
    MemRefType type = alloca.getType();
    auto isWhole = [&](VectorType vector, ValueRange indices) {
      return vector.getShape() == type.getShape() &&
             llvm::all_of(indices, [](Value index) {
               return getConstantIntValue(index) == 0;
             });
    };
    bool promotable = llvm::all_of(alloca->getUses(), [&](OpOperand &use) {
      Operation *user = use.getOwner();
      if (user->getBlock() != body)
        return user->getBlock()->getParentOp()->getBlock() == body &&
               filledAlloca(user->getBlock()->getParentOp()) ==
                   alloca.getResult();
      if (auto load = dyn_cast<vector::LoadOp>(user))
        return isWhole(load.getVectorType(), load.getIndices());
      if (auto store = dyn_cast<vector::StoreOp>(user))
        return use.getOperandNumber() ==
                   store.getBaseMutable().getOperandNumber() &&
               isWhole(store.getVectorType(), store.getIndices());
      if (auto load = dyn_cast<memref::LoadOp>(user))
        return allConstantIndices(load.getIndices());
      if (auto store = dyn_cast<memref::StoreOp>(user))
        return use.getOperandNumber() ==
                   store.getMemrefMutable().getOperandNumber() &&
               allConstantIndices(store.getIndices());
      return false;
    });
    if (promotable)
      promoted.insert(alloca);
  }
}

void ElementLoopVectorizer::findWrittenMemrefs() {
  writtenRoots.clear();
  body->walk([&](Operation *op) {
    if (op->hasTrait<OpTrait::HasRecursiveMemoryEffects>())
      return;
    auto addAllMemrefOperands = [&] {
      for (Value operand : op->getOperands())
        if (isa<BaseMemRefType>(operand.getType()))
          writtenRoots.insert(viewRoot(operand));
    };
    auto effects = dyn_cast<MemoryEffectOpInterface>(op);
    if (!effects)
      return addAllMemrefOperands();
    SmallVector<MemoryEffects::EffectInstance> instances;
    effects.getEffects(instances);
    for (const MemoryEffects::EffectInstance &instance : instances) {
      if (!isa<MemoryEffects::Write, MemoryEffects::Free>(instance.getEffect()))
        continue;
      if (Value value = instance.getValue())
        writtenRoots.insert(viewRoot(value));
      else
        addAllMemrefOperands();
    }
  });
  for (Value alloca : promoted)
    writtenRoots.erase(alloca);
}

/// A memref.load from memory that nothing in the loop writes, through a
/// memref defined outside the loop: it may run before the lane ops.
bool ElementLoopVectorizer::isReadOnlyLoad(Operation *op) const {
  auto load = dyn_cast<memref::LoadOp>(op);
  if (!load || !componentType(load.getType()))
    return false;
  Value memref = load.getMemRef();
  return !loop->isAncestor(memref.getParentBlock()->getParentOp()) &&
         !writtenRoots.contains(viewRoot(memref));
}

/// Ops that act on each component alone (arith, math), and the vector ops
/// that only move components at constant positions.
bool ElementLoopVectorizer::canWiden(Operation *op) const {
  if (op->getNumRegions() != 0 || op->getNumResults() != 1 ||
      !componentType(op->getResult(0).getType()))
    return false;
  if (op->hasTrait<OpTrait::Elementwise>() && isPure(op))
    return llvm::all_of(op->getOperandTypes(), [](Type type) {
      return static_cast<bool>(componentType(type));
    });
  if (auto extract = dyn_cast<vector::ExtractOp>(op))
    return extract.getDynamicPosition().empty();
  if (auto insert = dyn_cast<vector::InsertOp>(op))
    return insert.getDynamicPosition().empty();
  if (auto broadcast = dyn_cast<vector::BroadcastOp>(op))
    return static_cast<bool>(componentType(broadcast.getSourceType()));
  return isa<vector::FromElementsOp, vector::ShapeCastOp, vector::TransposeOp>(
             op) ||
         isReadOnlyLoad(op);
}

bool ElementLoopVectorizer::usesAny(Operation *op,
                                    const DenseSet<Value> &values) const {
  if (llvm::any_of(op->getOperands(),
                   [&](Value v) { return values.contains(v); }))
    return true;
  bool uses = false;
  for (Region &region : op->getRegions())
    visitUsedValuesDefinedAbove(region, [&](OpOperand *operand) {
      uses |= values.contains(operand->get());
    });
  return uses;
}

/// Sorts the body's ops into vector and lane ops. A promoted alloca that
/// would be written a value computed by a lane op is returned in `demote`.
bool ElementLoopVectorizer::classify(Value &demote) {
  laneOps.clear();
  prefetches.clear();
  varying.clear();
  varying.insert(iv);
  DenseSet<Value> laneValues;
  for (Operation &op : body->without_terminator()) {
    Value alloca;
    if (isa<memref::AllocaOp>(op) && promoted.contains(op.getResult(0)))
      continue;
    if (isPromotedAccess(&op, alloca)) {
      if (usesAny(&op, laneValues)) {
        demote = alloca;
        return false;
      }
      for (Value result : op.getResults())
        varying.insert(result);
      continue;
    }
    if (!usesAny(&op, laneValues) && isa<memref::PrefetchOp>(op) &&
        !loop->isAncestor(op.getOperand(0).getParentBlock()->getParentOp())) {
      // Prefetches for all lanes go first, so that their lines arrive while
      // the kernel computes.
      prefetches.insert(&op);
      continue;
    }
    if (!usesAny(&op, laneValues)) {
      // Uniform: computed once, as it was, for every lane.
      bool isUniform = !usesAny(&op, varying);
      if (isUniform &&
          (isReadOnlyLoad(&op) || (op.getNumRegions() == 0 && isPure(&op))))
        continue;
      if (!isUniform && canWiden(&op)) {
        varying.insert(op.getResult(0));
        continue;
      }
    }
    laneOps.insert(&op);
    for (Value result : op.getResults())
      laneValues.insert(result);
  }
  return true;
}

bool ElementLoopVectorizer::plan() {
  findPromotableAllocas();
  while (true) {
    findWrittenMemrefs();
    Value demote;
    if (classify(demote))
      break;
    promoted.erase(demote);
  }
  // Lanes: as many elements as the widest floating-point component of the
  // kernel fits in a machine vector.
  int64_t flops = 0;
  unsigned widest = 0;
  for (Operation &op : body->without_terminator()) {
    if (laneOps.contains(&op) || op.getNumResults() != 1 ||
        !varying.contains(op.getResult(0)) ||
        !op.hasTrait<OpTrait::Elementwise>())
      continue;
    Type type = componentType(op.getResult(0).getType());
    if (!isa<FloatType>(type))
      continue;
    flops += componentCount(op.getResult(0).getType());
    widest = std::max(widest, type.getIntOrFloatBitWidth());
  }
  // What the lane ops read of the vector ops, in the lane ops' order.
  for (Operation &op : body->without_terminator()) {
    if (!laneOps.contains(&op))
      continue;
    for (Value operand : op.getOperands())
      if (varying.contains(operand))
        needed.insert(operand);
    for (Region &region : op.getRegions())
      visitUsedValuesDefinedAbove(region, [&](OpOperand *operand) {
        if (varying.contains(operand->get()))
          needed.insert(operand->get());
      });
  }
  needed.remove(iv);
  if (flops < minVectorOps || widest == 0 || vectorBits < 2 * widest)
    return false;
  lanes = vectorBits / widest;
  return true;
}

//===----------------------------------------------------------------------===//
// The pass
//===----------------------------------------------------------------------===//

namespace {
struct VectorizeElementLoops
    : public simit::impl::SimitVectorizeElementLoopsBase<
          VectorizeElementLoops> {
  using Base::Base;

  void runOnOperation() override {
    SmallVector<scf::ParallelOp> candidates;
    getOperation().walk<WalkOrder::PreOrder>([&](scf::ParallelOp loop) {
      if (loop.getNumLoops() == 1 && loop.getNumResults() == 0 &&
          getConstantIntValue(loop.getStep()[0]) == 1 &&
          !loop->hasAttr(kParallelLoopAttr))
        candidates.push_back(loop);
    });
    // The rewrite replaces a loop, with the loops inside it.
    DenseSet<Operation *> replaced;
    for (scf::ParallelOp loop : candidates) {
      if (replaced.contains(loop))
        continue;
      ElementLoopVectorizer vectorizer(loop, vectorBits, minVectorOps);
      if (!vectorizer.plan())
        continue;
      loop.getBody()->walk(
          [&](scf::ParallelOp inner) { replaced.insert(inner); });
      vectorizer.rewrite();
    }
  }
};
} // namespace
