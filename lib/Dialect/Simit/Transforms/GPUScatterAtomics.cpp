//===- GPUScatterAtomics.cpp - Shared accumulations become atomics --------===//
//
// Assembly scatters each element's contributions into blocks that other
// elements also write (through a location table or endpoint indices). When
// the set loop runs in parallel those read-modify-write sequences race, so
// they become single atomic read-modify-writes. An accumulation indexed by
// every induction variable of the loop is owned by its iteration and stays a
// plain load and store.
//
//===----------------------------------------------------------------------===//

#include "Accumulation.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITGPUSCATTERATOMICS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using mlir::simit::Accumulation;
using mlir::simit::matchAccumulation;

namespace {
/// The loop's iterations write disjoint locations through `store` when every
/// induction variable is one of its indices.
bool ownedByIteration(memref::StoreOp store, scf::ParallelOp loop) {
  return llvm::all_of(loop.getInductionVars(), [&](Value iv) {
    return llvm::is_contained(store.getIndices(), iv);
  });
}

void makeAtomic(memref::StoreOp store, const Accumulation &acc) {
  OpBuilder builder(store);
  Location loc = store.getLoc();
  bool isFloat = isa<FloatType>(acc.contribution.getType());
  Value value = acc.contribution;
  if (acc.negate)
    value = isFloat ? Value(arith::NegFOp::create(builder, loc, value))
                    : Value(arith::SubIOp::create(
                          builder, loc,
                          arith::ConstantOp::create(
                              builder, loc, builder.getZeroAttr(value.getType())),
                          value));
  auto kind = isFloat ? arith::AtomicRMWKind::addf : arith::AtomicRMWKind::addi;
  memref::AtomicRMWOp::create(builder, loc, kind, value, store.getMemRef(),
                              store.getIndices());
  store.erase();
  if (acc.combine->use_empty())
    acc.combine->erase();
  if (acc.load->use_empty())
    acc.load->erase();
}

struct GpuScatterAtomics
    : public simit::impl::SimitGpuScatterAtomicsBase<GpuScatterAtomics> {
  void runOnOperation() override {
    SmallVector<std::pair<memref::StoreOp, Accumulation>> racy;
    getOperation().walk([&](scf::ParallelOp loop) {
      // Only the outermost loop's iterations run concurrently on the GPU;
      // nested parallel loops run sequentially inside one thread.
      if (loop->getParentOfType<scf::ParallelOp>())
        return;
      loop.walk([&](memref::StoreOp store) {
        // A memref allocated inside the loop is private to an iteration.
        if (loop.getRegion().isAncestor(store.getMemRef().getParentRegion()))
          return;
        if (ownedByIteration(store, loop))
          return;
        if (std::optional<Accumulation> acc =
                matchAccumulation(store.getOperation()))
          racy.emplace_back(store, *acc);
      });
    });
    for (auto &[store, acc] : racy)
      makeAtomic(store, acc);
  }
};
} // namespace
