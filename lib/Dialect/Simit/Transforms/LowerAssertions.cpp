//===- LowerAssertions.cpp - Failed assertions end the run ----------------===//

#include "RuntimeFunction.h"
#include "StringConstant.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/UB/IR/UBOps.h"
#include "llvm/ADT/SetVector.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITLOWERASSERTIONS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {

/// A value of `type` for the branch that failed: its results are only read
/// when simit_rt_fail returns (in a parallel region), and zeros keep later
/// iterations free of poison where the type has one.
Value valueAfterFailure(OpBuilder &b, Location loc, Type type) {
  if (auto zero = dyn_cast_or_null<TypedAttr>(b.getZeroAttr(type)))
    if (arith::ConstantOp::isBuildableWith(zero, type))
      return arith::ConstantOp::create(b, loc, zero);
  return ub::PoisonOp::create(b, loc, type);
}

/// `cf.assert %ok` becomes `scf.if %ok` around the rest of its block, whose
/// other branch calls `fail`.
void lowerAssertion(cf::AssertOp op, func::FuncOp fail, ModuleOp module) {
  Block *block = op->getBlock();
  Operation *end = block->mightHaveTerminator() ? block->getTerminator()
                                                : nullptr;
  llvm::SetVector<Operation *> rest;
  for (Operation *it = op->getNextNode(); it && it != end;
       it = it->getNextNode())
    rest.insert(it);
  SmallVector<Value> escaping;
  for (Operation *moved : rest)
    for (Value result : moved->getResults())
      if (llvm::any_of(result.getUsers(), [&](Operation *user) {
            return !rest.contains(block->findAncestorOpInBlock(*user));
          }))
        escaping.push_back(result);

  OpBuilder b(op);
  Location loc = op.getLoc();
  auto ifOk = scf::IfOp::create(b, loc, ValueRange(escaping).getTypes(),
                                op.getArg(), /*withElseRegion=*/true);
  for (Block *branch : {ifOk.thenBlock(), ifOk.elseBlock()})
    if (branch->mightHaveTerminator())
      branch->getTerminator()->erase();
  for (Operation *moved : rest)
    moved->moveBefore(ifOk.thenBlock(), ifOk.thenBlock()->end());
  b.setInsertionPointToEnd(ifOk.thenBlock());
  scf::YieldOp::create(b, loc, escaping);

  b.setInsertionPointToEnd(ifOk.elseBlock());
  func::CallOp::create(
      b, loc, fail,
      ValueRange{createStringConstant(b, module, loc, op.getMsg())});
  SmallVector<Value> afterFailure;
  for (Value value : escaping)
    afterFailure.push_back(valueAfterFailure(b, loc, value.getType()));
  scf::YieldOp::create(b, loc, afterFailure);

  for (auto [value, result] : llvm::zip(escaping, ifOk.getResults()))
    value.replaceUsesWithIf(result, [&](OpOperand &use) {
      return !ifOk->isAncestor(use.getOwner());
    });
  op.erase();
}

struct LowerAssertions
    : public mlir::simit::impl::SimitLowerAssertionsBase<LowerAssertions> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    SmallVector<cf::AssertOp> assertions;
    // Kernels keep theirs: the GPU lowering turns them into device
    // assertions, and device code cannot call the host.
    module.walk([&](cf::AssertOp op) {
      for (Operation *parent = op->getParentOp(); parent;
           parent = parent->getParentOp())
        if (parent->getName().getDialectNamespace() == "gpu")
          return;
      assertions.push_back(op);
    });
    if (assertions.empty())
      return;

    MLIRContext *ctx = module.getContext();
    func::FuncOp fail = declareRuntimeFunction(
        module, kRuntimeFail,
        FunctionType::get(ctx, {LLVM::LLVMPointerType::get(ctx)}, {}));
    if (!fail)
      return signalPassFailure();

    for (cf::AssertOp op : assertions)
      lowerAssertion(op, fail, module);
  }
};
} // namespace
