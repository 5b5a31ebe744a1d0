//===- GPUParallelLoopsToLaunch.cpp - Set loops become GPU kernels --------===//
//
// A set loop has one iteration per element and millions of elements, so it
// maps to a one-dimensional grid with one thread per iteration; the block size
// is fixed (an option) and the grid covers the trip count, with threads past
// the end doing nothing. Scalar reductions are combined in two levels (a
// block-wide gpu.all_reduce, then one atomic per block into an accumulator)
// so that contention on the accumulator stays at one update per block.
//
//===----------------------------------------------------------------------===//

#include "LoopTrips.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/GPU/IR/GPUDialect.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITPARALLELLOOPSTOGPU
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;

namespace {
/// How one `scf.reduce` region combines: the atomic that folds a block's
/// partial into the accumulator and the block-wide reduction.
struct Combiner {
  arith::AtomicRMWKind atomicKind;
  gpu::AllReduceOperation blockReduction;
};

/// Recognises a reduction region that adds its two arguments, of a type
/// that memref.atomic_rmw accepts (not index).
FailureOr<Combiner> matchCombiner(Region &reduction) {
  Block &block = reduction.front();
  auto yield = dyn_cast<scf::ReduceReturnOp>(block.getTerminator());
  if (!yield || block.getOperations().size() != 2 ||
      !isa<FloatType, IntegerType>(yield.getResult().getType()))
    return failure();
  Operation *combine = yield.getResult().getDefiningOp();
  if (!combine || combine->getBlock() != &block ||
      !llvm::is_contained(combine->getOperands(), block.getArgument(0)) ||
      !llvm::is_contained(combine->getOperands(), block.getArgument(1)))
    return failure();
  if (isa<arith::AddFOp>(combine))
    return Combiner{arith::AtomicRMWKind::addf, gpu::AllReduceOperation::ADD};
  if (isa<arith::AddIOp>(combine))
    return Combiner{arith::AtomicRMWKind::addi, gpu::AllReduceOperation::ADD};
  return failure();
}

/// Adds the `contract` fast-math flag to every floating-point operation in
/// the kernel.
void allowContraction(gpu::LaunchOp launch) {
  launch.walk([](arith::ArithFastMathInterface op) {
    arith::FastMathFlagsAttr attr = op.getFastMathFlagsAttr();
    arith::FastMathFlags flags =
        attr ? attr.getValue() : arith::FastMathFlags::none;
    op->setAttr(op.getFastMathAttrName(),
                arith::FastMathFlagsAttr::get(
                    op->getContext(), flags | arith::FastMathFlags::contract));
  });
}

class LoopToLaunch {
public:
  LoopToLaunch(scf::ParallelOp loop, int64_t blockSize, bool fpContract)
      : loop(loop), blockSize(blockSize), fpContract(fpContract) {}

  LogicalResult run();

private:
  /// The loop's induction variables for the linear iteration index `linear`
  /// (the last dimension varies fastest).
  SmallVector<Value> delinearize(OpBuilder &b, Value linear);

  scf::ParallelOp loop;
  int64_t blockSize;
  bool fpContract;
  SmallVector<Value> trips;
};

LogicalResult LoopToLaunch::run() {
  auto reduce = cast<scf::ReduceOp>(loop.getBody()->getTerminator());
  SmallVector<Combiner> combiners;
  for (Region &reduction : reduce.getReductions()) {
    FailureOr<Combiner> combiner = matchCombiner(reduction);
    if (failed(combiner))
      return loop.emitOpError(
          "has a reduction that the GPU path cannot combine: only "
          "arith.addf and arith.addi of the two region arguments, on float "
          "or integer (not index) values, are supported");
    combiners.push_back(*combiner);
  }

  Location loc = loop.getLoc();
  OpBuilder b(loop);
  for (auto [lb, ub, step] : llvm::zip(loop.getLowerBound(),
                                       loop.getUpperBound(), loop.getStep()))
    trips.push_back(simit::tripCount(b, loc, lb, ub, step));
  Value total = trips.front();
  for (Value trip : llvm::drop_begin(trips))
    total = arith::MulIOp::create(b, loc, total, trip);

  // Scalar accumulators live at the start of the function, so that a set
  // loop inside a host loop (a solver's iterations) reuses one accumulator,
  // and one device copy of it, across the iterations.
  SmallVector<Value> accumulators;
  if (!combiners.empty()) {
    auto function = loop->getParentOfType<func::FuncOp>();
    OpBuilder entry = OpBuilder::atBlockBegin(&function.getBody().front());
    for (Value init : loop.getInitVals()) {
      accumulators.push_back(memref::AllocaOp::create(
          entry, loc, MemRefType::get({}, init.getType())));
      memref::StoreOp::create(b, loc, init, accumulators.back());
    }
  }

  Value one = arith::ConstantIndexOp::create(b, loc, 1);
  Value threads = arith::ConstantIndexOp::create(b, loc, blockSize);
  // A grid of zero blocks is a launch error; one idle block is not.
  Value blocks = arith::MaxUIOp::create(
      b, loc, arith::CeilDivUIOp::create(b, loc, total, threads), one);
  auto launch =
      gpu::LaunchOp::create(b, loc, blocks, one, one, threads, one, one);

  OpBuilder body = OpBuilder::atBlockBegin(&launch.getBody().front());
  Value blockId = launch.getBlockIds().x;
  Value threadId = launch.getThreadIds().x;
  Value linear = arith::AddIOp::create(
      body, loc, arith::MulIOp::create(body, loc, blockId, threads), threadId);
  Value inRange = arith::CmpIOp::create(body, loc, arith::CmpIPredicate::ult,
                                        linear, total);
  // Without reductions the guard is a plain `scf.if` (with its yield); with
  // them, both branches are filled below.
  auto guard =
      combiners.empty()
          ? scf::IfOp::create(body, loc, inRange, /*withElseRegion=*/false)
          : scf::IfOp::create(body, loc, loop.getResultTypes(), inRange,
                              /*addThenBlock=*/true, /*addElseBlock=*/true);

  // The loop body moves into the guarded branch, which yields the values
  // the loop reduces.
  Block *thenBlock = guard.thenBlock();
  OpBuilder thenBuilder = OpBuilder::atBlockBegin(thenBlock);
  SmallVector<Value> ivs = delinearize(thenBuilder, linear);
  for (auto [iv, value] : llvm::zip(loop.getInductionVars(), ivs))
    iv.replaceAllUsesWith(value);
  Block *loopBody = loop.getBody();
  SmallVector<Value> partials(reduce.getOperands());
  if (combiners.empty())
    thenBlock->getOperations().splice(std::prev(thenBlock->end()),
                                      loopBody->getOperations(),
                                      loopBody->begin(), reduce->getIterator());
  else {
    thenBlock->getOperations().splice(thenBlock->end(),
                                      loopBody->getOperations(),
                                      loopBody->begin(), reduce->getIterator());
    OpBuilder yieldBuilder = OpBuilder::atBlockEnd(thenBlock);
    scf::YieldOp::create(yieldBuilder, loc, partials);
    OpBuilder elseBuilder = OpBuilder::atBlockBegin(guard.elseBlock());
    SmallVector<Value> identities;
    for (Value partial : partials)
      identities.push_back(arith::ConstantOp::create(
          elseBuilder, loc, elseBuilder.getZeroAttr(partial.getType())));
    scf::YieldOp::create(elseBuilder, loc, identities);
  }

  // Every thread of the block takes part in the block reduction; thread 0
  // then folds the block's sum into the accumulator.
  SmallVector<Value> blockSums;
  for (auto [partial, combiner] : llvm::zip(guard.getResults(), combiners))
    blockSums.push_back(gpu::AllReduceOp::create(
        body, loc, partial,
        gpu::AllReduceOperationAttr::get(b.getContext(),
                                         combiner.blockReduction),
        /*uniform=*/true));
  if (!combiners.empty()) {
    Value zero = arith::ConstantIndexOp::create(body, loc, 0);
    Value first = arith::CmpIOp::create(body, loc, arith::CmpIPredicate::eq,
                                        threadId, zero);
    auto leader = scf::IfOp::create(body, loc, first, /*withElseRegion=*/false);
    OpBuilder leaderBuilder = leader.getThenBodyBuilder();
    for (auto [sum, acc, combiner] :
         llvm::zip(blockSums, accumulators, combiners))
      memref::AtomicRMWOp::create(leaderBuilder, loc, combiner.atomicKind, sum,
                                  acc, ValueRange());
  }
  gpu::TerminatorOp::create(body, loc);
  if (fpContract)
    allowContraction(launch);

  b.setInsertionPointAfter(launch);
  for (auto [result, acc] : llvm::zip(loop.getResults(), accumulators))
    result.replaceAllUsesWith(memref::LoadOp::create(b, loc, acc));
  loop.erase();
  return success();
}

SmallVector<Value> LoopToLaunch::delinearize(OpBuilder &b, Value linear) {
  Location loc = loop.getLoc();
  SmallVector<Value> ivs(trips.size());
  Value rest = linear;
  for (int64_t dim = trips.size() - 1; dim >= 0; --dim) {
    Value index = rest;
    if (dim > 0) {
      index = b.createOrFold<arith::RemUIOp>(loc, rest, trips[dim]);
      rest = b.createOrFold<arith::DivUIOp>(loc, rest, trips[dim]);
    }
    Value offset =
        b.createOrFold<arith::MulIOp>(loc, index, loop.getStep()[dim]);
    ivs[dim] =
        b.createOrFold<arith::AddIOp>(loc, loop.getLowerBound()[dim], offset);
  }
  return ivs;
}

struct ParallelLoopsToGpu
    : public simit::impl::SimitParallelLoopsToGpuBase<ParallelLoopsToGpu> {
  using Base::Base;

  void runOnOperation() override {
    if (blockSize <= 0 || blockSize > 1024) {
      getOperation().emitError("simit-parallel-loops-to-gpu: block-size must "
                               "be in [1, 1024], got ")
          << static_cast<int64_t>(blockSize);
      return signalPassFailure();
    }
    SmallVector<scf::ParallelOp> loops;
    getOperation().walk([&](scf::ParallelOp loop) {
      if (!loop->getParentOfType<scf::ParallelOp>() &&
          !loop->getParentOfType<gpu::LaunchOp>() &&
          !loop->getParentOfType<gpu::GPUModuleOp>() &&
          loop->getParentOfType<func::FuncOp>())
        loops.push_back(loop);
    });
    for (scf::ParallelOp loop : loops)
      if (failed(LoopToLaunch(loop, blockSize, fpContract).run()))
        signalPassFailure();
  }
};
} // namespace
