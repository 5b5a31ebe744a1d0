//===- TimePhases.cpp - Timer calls around assemblies and solves ----------===//
//
// A time step is mostly assembly (maps) and linear solves; the driver wants
// both figures without the user splitting the step into functions. The
// runtime's phase timer accumulates the time between matching begin/end
// calls (lib/ABI/Timing.cpp).
//
//===----------------------------------------------------------------------===//

#include "RuntimeFunction.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITTIMEPHASES
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
enum Phase : int32_t { Assembly = 0, Solve = 1 };

constexpr StringRef kBegin = runtimeName(::simit::abi::RuntimeFunction::PhaseBegin);
constexpr StringRef kEnd = runtimeName(::simit::abi::RuntimeFunction::PhaseEnd);

bool isAssembly(Operation *op) { return isa<MapOp, AssembleOp>(op); }

/// Whether `op` runs at most once per call of the function whose body is
/// `body`: it is in the body, directly or inside `if`s only. Timer calls
/// around it then cost nothing per iteration of an enclosing loop.
bool runsAtMostOnce(Operation *op, Block *body) {
  for (Block *block = op->getBlock(); block != body;) {
    Operation *parent = block->getParentOp();
    if (!isa<scf::IfOp>(parent))
      return false;
    block = parent->getBlock();
  }
  return true;
}

/// The phase `op` of the exported function with body `body` is timed as, if
/// any.
std::optional<Phase> phaseOf(Operation *op, Block *body) {
  if (isAssembly(op))
    return Assembly;
  if (isa<SolveOp, FactorizeOp, FactorSolveOp, TriangularSolveOp, WoodburyOp>(
          op))
    return Solve;
  if (isa<scf::WhileOp>(op) && runsAtMostOnce(op, body)) {
    bool assembles = op->walk([](Operation *nested) {
                         return isAssembly(nested) ? WalkResult::interrupt()
                                                   : WalkResult::advance();
                       }).wasInterrupted();
    if (!assembles)
      return Solve;
  }
  return std::nullopt;
}

/// Declares `name(i32)` as a runtime function unless the module has it.
LogicalResult declareTimer(ModuleOp module, StringRef name) {
  Builder b(module.getContext());
  func::FuncOp timer = declareRuntimeFunction(
      module, name, b.getFunctionType({b.getI32Type()}, {}));
  if (!timer)
    return failure();
  timer->setAttr("simit.runtime_function", b.getUnitAttr());
  return success();
}

struct TimePhases : public mlir::simit::impl::SimitTimePhasesBase<TimePhases> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    SmallVector<std::pair<Operation *, Phase>> timed;
    for (auto function : module.getOps<func::FuncOp>()) {
      if (!isExportedFunction(function) || function.isExternal())
        continue;
      Block *body = &function.getBody().front();
      function.walk<WalkOrder::PreOrder>([&](Operation *op) {
        if (std::optional<Phase> phase = phaseOf(op, body)) {
          timed.emplace_back(op, *phase);
          return WalkResult::skip();
        }
        return WalkResult::advance();
      });
    }
    if (timed.empty())
      return;
    if (failed(declareTimer(module, kBegin)) ||
        failed(declareTimer(module, kEnd)))
      return signalPassFailure();
    for (auto [op, phase] : timed) {
      OpBuilder b(op);
      Value id = arith::ConstantIntOp::create(b, op->getLoc(), b.getI32Type(),
                                               phase);
      func::CallOp::create(b, op->getLoc(), kBegin, TypeRange(), id);
      b.setInsertionPointAfter(op);
      func::CallOp::create(b, op->getLoc(), kEnd, TypeRange(), id);
    }
  }
};
} // namespace
