//===- ParallelLoopsToOpenMP.cpp - Marked set loops on all cores ----------===//
//
// simit-parallel-loops marks the loops whose iterations may run concurrently
// (`simit.parallel`); each becomes an OpenMP worksharing loop in a parallel
// region of its own, and every other scf.parallel stays sequential. The
// iterations' stack slots move to the start of the parallel region: one set
// per thread, reused by its iterations, as the sequential lowering reuses
// one set for all (HoistParallelAllocas.cpp), so that LLVM keeps them in
// registers. A region with little work runs on the calling thread alone.
//
//===----------------------------------------------------------------------===//

#include "LoopTrips.h"
#include "RuntimeFunction.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/OpenMP/OpenMPDialect.h"
#include "mlir/Dialect/SCF/IR/SCF.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITPARALLELLOOPSTOOPENMP
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
constexpr StringRef kRaise =
    runtimeName(::simit::abi::RuntimeFunction::RaiseParallelFailure);

/// Whether `loop` has enough work to share between threads: `owned` loops
/// at least `minIterations` iterations, loops over chunks (`reduction`,
/// `scatter`) at least two chunks.
Value sharesWork(OpBuilder &b, scf::ParallelOp loop, int64_t minIterations) {
  Location loc = loop.getLoc();
  Value trips = arith::ConstantIndexOp::create(b, loc, 1);
  for (auto [lb, ub, step] :
       llvm::zip(loop.getLowerBound(), loop.getUpperBound(), loop.getStep()))
    trips = b.createOrFold<arith::MulIOp>(loc, trips,
                                          tripCount(b, loc, lb, ub, step));
  auto kind = loop->getAttrOfType<StringAttr>(kParallelLoopAttr);
  int64_t least = kind && kind.getValue() == kOwnedLoop ? minIterations : 2;
  return arith::CmpIOp::create(b, loc, arith::CmpIPredicate::uge, trips,
                               arith::ConstantIndexOp::create(b, loc, least));
}

/// Whether the body of `loop` has at most `maxOps` operations.
bool isSmall(scf::ParallelOp loop, int64_t maxOps) {
  int64_t ops = 0;
  loop.getBody()->walk([&](Operation *) { ++ops; });
  return ops <= maxOps;
}

LogicalResult convertLoop(scf::ParallelOp loop, int64_t minIterations,
                          int64_t maxCopiedOps) {
  if (loop.getNumResults() != 0)
    return loop.emitError("a loop marked ")
           << kParallelLoopAttr << " must not have results";
  Location loc = loop.getLoc();
  OpBuilder b(loop);
  Value share = sharesWork(b, loop, minIterations);
  omp::ParallelOperands operands;
  if (isSmall(loop, maxCopiedOps)) {
    // Even a region on one thread costs the runtime's bookkeeping: a small
    // body is copied into a plain loop that runs instead.
    auto branch = scf::IfOp::create(b, loc, share, /*withElseRegion=*/true);
    b.setInsertionPointToStart(branch.elseBlock());
    b.clone(*loop)->removeAttr(kParallelLoopAttr);
    b.setInsertionPointToStart(branch.thenBlock());
  } else {
    operands.ifExpr = share;
  }
  auto region = omp::ParallelOp::create(b, loc, operands);
  b.createBlock(&region.getRegion());
  // The end of the region joins the threads: the loop needs no barrier of
  // its own.
  omp::WsloopOperands schedule;
  schedule.nowait = b.getUnitAttr();
  auto workshare = omp::WsloopOp::create(b, loc, schedule);
  omp::TerminatorOp::create(b, loc);
  b.createBlock(&workshare.getRegion());
  omp::LoopNestOperands bounds;
  bounds.loopLowerBounds = loop.getLowerBound();
  bounds.loopUpperBounds = loop.getUpperBound();
  bounds.loopSteps = loop.getStep();
  auto nest = omp::LoopNestOp::create(b, loc, bounds);

  // The loop's body becomes the nest's, its induction variables the nest's.
  Block *body = loop.getBody();
  body->getTerminator()->erase();
  nest.getRegion().push_back(body->getParent()->getBlocks().remove(body));
  b.setInsertionPointToEnd(body);
  omp::YieldOp::create(b, loc);

  SmallVector<memref::AllocaOp> slots;
  region.walk([&](memref::AllocaOp alloca) {
    if (alloca.getType().hasStaticShape() && alloca->getNumOperands() == 0)
      slots.push_back(alloca);
  });
  Block &entry = region.getRegion().front();
  for (memref::AllocaOp alloca : slots)
    alloca->moveBefore(&entry, entry.begin());
  loop.erase();

  // No thread may leave the region early: a failure inside it is recorded
  // and raised here, once every thread has finished.
  bool mayFail = region
                     .walk([](func::CallOp call) {
                       return call.getCallee() == kRuntimeFail
                                  ? WalkResult::interrupt()
                                  : WalkResult::advance();
                     })
                     .wasInterrupted();
  if (mayFail) {
    func::FuncOp raise = declareRuntimeFunction(
        region->getParentOfType<ModuleOp>(), kRaise,
        b.getFunctionType({}, {}));
    if (!raise)
      return failure();
    b.setInsertionPointAfter(region);
    func::CallOp::create(b, loc, raise, ValueRange{});
  }
  return success();
}

struct ParallelLoopsToOpenMP
    : public mlir::simit::impl::SimitParallelLoopsToOpenMPBase<
          ParallelLoopsToOpenMP> {
  using Base::Base;

  void runOnOperation() override {
    SmallVector<scf::ParallelOp> marked;
    getOperation().walk([&](scf::ParallelOp loop) {
      if (loop->hasAttr(kParallelLoopAttr))
        marked.push_back(loop);
    });
    for (scf::ParallelOp loop : marked)
      if (failed(convertLoop(loop, minIterations, maxCopiedOps)))
        return signalPassFailure();
  }
};
} // namespace
