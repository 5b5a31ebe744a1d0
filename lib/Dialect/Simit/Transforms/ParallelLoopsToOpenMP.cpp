//===- ParallelLoopsToOpenMP.cpp - Marked set loops on all cores ----------===//
//
// simit-parallel-loops marks the loops whose iterations may run concurrently
// (`simit.parallel`); each becomes an OpenMP worksharing loop in a parallel
// region of its own, and every other scf.parallel stays sequential. The
// iterations' stack slots move to the start of the parallel region: one set
// per thread, reused by its iterations, as the sequential lowering reuses
// one set for all (HoistParallelAllocas.cpp), so that LLVM keeps them in
// registers.
//
//===----------------------------------------------------------------------===//

#include "RuntimeFunction.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/OpenMP/OpenMPDialect.h"

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

LogicalResult convertLoop(scf::ParallelOp loop) {
  if (loop.getNumResults() != 0)
    return loop.emitError("a loop marked ")
           << kParallelLoopAttr << " must not have results";
  Location loc = loop.getLoc();
  OpBuilder b(loop);
  auto region = omp::ParallelOp::create(b, loc, omp::ParallelOperands());
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
  void runOnOperation() override {
    SmallVector<scf::ParallelOp> marked;
    getOperation().walk([&](scf::ParallelOp loop) {
      if (loop->hasAttr(kParallelLoopAttr))
        marked.push_back(loop);
    });
    for (scf::ParallelOp loop : marked)
      if (failed(convertLoop(loop)))
        return signalPassFailure();
  }
};
} // namespace
