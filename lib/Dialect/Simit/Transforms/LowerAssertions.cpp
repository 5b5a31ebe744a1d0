//===- LowerAssertions.cpp - Failed assertions end the run ----------------===//

#include "StringConstant.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITLOWERASSERTIONS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
constexpr llvm::StringLiteral kFail = "simit_rt_fail";

struct LowerAssertions
    : public simit::impl::SimitLowerAssertionsBase<LowerAssertions> {
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
    auto failType =
        FunctionType::get(ctx, {LLVM::LLVMPointerType::get(ctx)}, {});
    auto fail = module.lookupSymbol<func::FuncOp>(kFail);
    if (!fail) {
      OpBuilder b = OpBuilder::atBlockEnd(module.getBody());
      fail = func::FuncOp::create(b, module.getLoc(), kFail, failType);
      fail.setPrivate();
    } else if (fail.getFunctionType() != failType) {
      fail.emitError("@") << kFail << " is declared with another type";
      return signalPassFailure();
    }

    for (cf::AssertOp op : assertions) {
      OpBuilder b(op);
      Location loc = op.getLoc();
      Value failed = arith::XOrIOp::create(
          b, loc, op.getArg(),
          arith::ConstantIntOp::create(b, loc, b.getI1Type(), 1));
      auto ifFailed = scf::IfOp::create(b, loc, failed);
      b.setInsertionPointToStart(ifFailed.thenBlock());
      func::CallOp::create(
          b, loc, fail,
          ValueRange{createStringConstant(b, module, loc, op.getMsg())});
      op.erase();
    }
  }
};
} // namespace
