//===- UnrollLocalTensorLoops.cpp - Constant positions in local tensors ---===//
//
// A local tensor is an SSA vector (LowerLocalTensors.cpp): a component read
// or written at a position that depends on a loop's induction variable is a
// vector.extract or vector.insert with a dynamic position, which LLVM can
// only lower by storing the whole vector to the stack and reloading it. It
// unrolls small loops itself, but not the loops of element functions whose
// bodies are large (the Neo-Hookean stiffness: three dPdF calls per vertex),
// so their tensors stayed in memory. Unrolling such loops here makes every
// position a constant, and the tensors registers.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Analysis/SliceAnalysis.h"
#include "mlir/Dialect/SCF/Utils/Utils.h"
#include "mlir/Dialect/Utils/StaticValueUtils.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITUNROLLLOCALTENSORLOOPS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

/// The dynamic positions of a vector.extract or vector.insert (none for
/// other ops).
static SmallVector<Value> dynamicVectorPositions(Operation *op) {
  if (auto extract = dyn_cast<vector::ExtractOp>(op))
    return llvm::to_vector(extract.getDynamicPosition());
  if (auto insert = dyn_cast<vector::InsertOp>(op))
    return llvm::to_vector(insert.getDynamicPosition());
  return {};
}

/// Whether a position of a local tensor in `loop`'s body depends on its
/// induction variable.
static bool indexesLocalTensor(scf::ForOp loop) {
  SetVector<Operation *> dependents;
  ForwardSliceOptions options;
  getForwardSlice(loop.getInductionVar(), &dependents, options);
  auto dependsOnLoop = [&](Value value) {
    return value == loop.getInductionVar() ||
           (value.getDefiningOp() &&
            dependents.contains(value.getDefiningOp()));
  };
  return llvm::any_of(dependents, [&](Operation *op) {
    return llvm::any_of(dynamicVectorPositions(op), dependsOnLoop);
  });
}

/// The number of ops in `loop`'s body, nested ones included.
static int64_t bodySize(scf::ForOp loop) {
  int64_t size = 0;
  loop.getBody()->walk([&](Operation *) { ++size; });
  return size;
}

namespace {
struct UnrollLocalTensorLoops
    : public simit::impl::SimitUnrollLocalTensorLoopsBase<
          UnrollLocalTensorLoops> {
  using Base::Base;

  void runOnOperation() override {
    // Post-order: inner loops first, so that an outer loop is judged on
    // the positions and size its body has once they are unrolled.
    SmallVector<scf::ForOp> loops;
    getOperation()->walk([&](scf::ForOp loop) { loops.push_back(loop); });
    for (scf::ForOp loop : loops) {
      std::optional<int64_t> lower = getConstantIntValue(loop.getLowerBound());
      std::optional<int64_t> upper = getConstantIntValue(loop.getUpperBound());
      std::optional<int64_t> step = getConstantIntValue(loop.getStep());
      if (!lower || !upper || !step || *step <= 0)
        continue;
      int64_t trips = *upper > *lower ? (*upper - *lower + *step - 1) / *step
                                      : 0;
      if (trips == 0 || trips * bodySize(loop) > maxUnrolledOps ||
          !indexesLocalTensor(loop))
        continue;
      if (failed(loopUnrollFull(loop)))
        return signalPassFailure();
    }
  }
};
} // namespace
