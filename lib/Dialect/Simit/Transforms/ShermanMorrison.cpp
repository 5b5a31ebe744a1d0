//===- ShermanMorrison.cpp - (A + u v^T) \ b without the dense matrix -----===//
//
// A sparse system matrix plus the outer product of two system vectors is a
// dense matrix: assembling and factorising it costs O(n^2) memory and more.
// Sherman–Morrison solves it with two solves of the sparse A, which share
// one factorisation, and a few dot products (the seed
// shared/seeds/003_0af6eb45af1efb0d.txt; docs/solvers.md).
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/IR/PatternMatch.h"
#include "mlir/IR/SymbolTable.h"
#include "mlir/Transforms/GreedyPatternRewriteDriver.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITSHERMANMORRISON
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {

constexpr StringLiteral kRuntimeName = "simit_rt_sherman_morrison";

/// `matrix` as A + u v^T or A - u v^T: the outer product, A, and whether
/// the product is subtracted.
struct RankOneSum {
  OuterOp outer;
  Value a;
  bool subtracted = false;
};

std::optional<RankOneSum> splitOuter(Value matrix) {
  if (auto add = matrix.getDefiningOp<AddOp>()) {
    for (auto [outer, other] : {std::pair(add.getLhs(), add.getRhs()),
                                std::pair(add.getRhs(), add.getLhs())})
      if (auto op = outer.getDefiningOp<OuterOp>())
        return RankOneSum{op, other};
    return std::nullopt;
  }
  // u v^T - A would need -A's factorisation: left as written.
  if (auto sub = matrix.getDefiningOp<SubOp>())
    if (auto op = sub.getRhs().getDefiningOp<OuterOp>())
      return RankOneSum{op, sub.getLhs(), /*subtracted=*/true};
  return std::nullopt;
}

/// A sum with an outer product among its terms (through nested adds and
/// subs).
bool holdsOuterProduct(Value value) {
  Operation *op = value.getDefiningOp();
  if (isa_and_present<AddOp, SubOp>(op))
    return holdsOuterProduct(op->getOperand(0)) ||
           holdsOuterProduct(op->getOperand(1));
  return isa_and_present<OuterOp>(op);
}

bool isSystemVector(Type type) {
  auto tensor = dyn_cast<SystemTensorType>(type);
  return tensor && tensor.isSystem() && tensor.getOrder() == 1;
}

/// The declaration of the last step for these operand types: one per type,
/// @simit_rt_sherman_morrison, @simit_rt_sherman_morrison_1, ...
func::FuncOp declareLastStep(ModuleOp module, FunctionType type,
                             PatternRewriter &rewriter) {
  for (int i = 0;; ++i) {
    std::string name = kRuntimeName.str();
    if (i)
      name += "_" + std::to_string(i);
    auto existing = module.lookupSymbol<func::FuncOp>(name);
    if (existing && existing.getFunctionType() == type)
      return existing;
    if (existing)
      continue;
    OpBuilder::InsertionGuard guard(rewriter);
    rewriter.setInsertionPointToEnd(module.getBody());
    auto function =
        func::FuncOp::create(rewriter, module.getLoc(), name, type);
    function.setPrivate();
    function->setAttr("simit.runtime_function",
                      rewriter.getStringAttr("sherman_morrison"));
    return function;
  }
}

struct RewriteRankOneSolve : OpRewritePattern<SolveOp> {
  using OpRewritePattern::OpRewritePattern;

  LogicalResult matchAndRewrite(SolveOp solve,
                                PatternRewriter &rewriter) const override {
    std::optional<RankOneSum> split = splitOuter(solve.getMatrix());
    if (!split)
      return rewriter.notifyMatchFailure(
          solve, "the matrix is not A + u v^T or A - u v^T");
    auto [outer, a, subtracted] = *split;
    auto matrixType = dyn_cast<SystemTensorType>(a.getType());
    if (!matrixType || !matrixType.isSetMatrix() ||
        a.getType() != solve.getMatrix().getType())
      return rewriter.notifyMatchFailure(solve, "A is not a system matrix");
    if (holdsOuterProduct(a))
      return rewriter.notifyMatchFailure(
          solve, "A holds an outer product itself (rank k > 1)");
    Value u = outer.getLhs(), v = outer.getRhs(), b = solve.getRhs();
    if (!isSystemVector(b.getType()) || u.getType() != b.getType() ||
        v.getType() != b.getType() ||
        solve.getResult().getType() != b.getType())
      return rewriter.notifyMatchFailure(
          solve, "u, v and b are not system vectors of one type");
    Type component = matrixType.getComponentType();
    if (!component.isF64() && !component.isF32())
      return rewriter.notifyMatchFailure(solve, "not a float matrix");

    Location loc = solve.getLoc();
    // A - u v^T = A + (-u) v^T.
    if (subtracted)
      u = NegOp::create(rewriter, loc, u.getType(), u);
    auto solveWithA = [&](Value rhs, StringRef note) {
      auto op = SolveOp::create(rewriter, loc, b.getType(), a, rhs);
      op->setAttr("simit.solve_note", rewriter.getStringAttr(note));
      return op.getResult();
    };
    Value w = solveWithA(u, "Sherman-Morrison A^-1 u");
    Value c = solveWithA(b, "Sherman-Morrison A^-1 b");
    SmallVector<Value> operands{a, u, v, b, w, c};
    auto type = FunctionType::get(rewriter.getContext(),
                                  ValueRange(operands).getTypes(),
                                  {b.getType()});
    func::FuncOp lastStep = declareLastStep(
        solve->getParentOfType<ModuleOp>(), type, rewriter);
    rewriter.replaceOpWithNewOp<func::CallOp>(solve, lastStep, operands);
    return success();
  }
};

struct ShermanMorrison
    : public simit::impl::SimitShermanMorrisonBase<ShermanMorrison> {
  void runOnOperation() override {
    RewritePatternSet patterns(&getContext());
    patterns.add<RewriteRankOneSolve>(&getContext());
    if (failed(applyPatternsGreedily(getOperation(), std::move(patterns))))
      signalPassFailure();
  }
};

} // namespace
