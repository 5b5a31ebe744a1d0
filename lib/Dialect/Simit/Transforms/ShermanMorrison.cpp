//===- ShermanMorrison.cpp - (A + u v^T) \ b without the dense matrix -----===//
//
// A sparse system matrix plus the outer product of two system vectors is a
// dense matrix: assembling and factorising it costs O(n^2) memory and more.
// Sherman–Morrison solves it with two solves of the sparse A, which share
// one factorisation, and a few dot products (the seed
// shared/seeds/003_0af6eb45af1efb0d.txt; docs/solvers.md). A sum of k
// outer products (k <= 4) takes k + 1 solves and a k x k system (the
// Woodbury identity).
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/PatternMatch.h"
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

/// `matrix` as A plus or minus outer products, peeled from the outermost
/// add or sub: the products with their signs, and A.
struct LowRankSum {
  SmallVector<RankOneSum> terms;
  Value a;
};

std::optional<LowRankSum> splitOuters(Value matrix) {
  LowRankSum sum;
  sum.a = matrix;
  while (std::optional<RankOneSum> term = splitOuter(sum.a)) {
    sum.a = term->a;
    sum.terms.push_back(*term);
  }
  if (sum.terms.empty())
    return std::nullopt;
  return sum;
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

struct RewriteLowRankSolve : OpRewritePattern<SolveOp> {
  using OpRewritePattern::OpRewritePattern;

  LogicalResult matchAndRewrite(SolveOp solve,
                                PatternRewriter &rewriter) const override {
    std::optional<LowRankSum> split = splitOuters(solve.getMatrix());
    if (!split)
      return rewriter.notifyMatchFailure(
          solve, "the matrix is not A plus or minus outer products");
    Value a = split->a, b = solve.getRhs();
    auto matrixType = dyn_cast<SystemTensorType>(a.getType());
    if (!matrixType || !matrixType.isSetMatrix() ||
        a.getType() != solve.getMatrix().getType())
      return rewriter.notifyMatchFailure(solve, "A is not a system matrix");
    if (holdsOuterProduct(a))
      return rewriter.notifyMatchFailure(
          solve, "A holds an outer product that is not a term of the sum");
    unsigned rank = split->terms.size();
    if (rank > WoodburyOp::kMaxRank)
      return rewriter.notifyMatchFailure(solve, "more than 4 outer products");
    // u and b are over A's rows, v and x over its columns.
    Type rowVector = b.getType(), columnVector = solve.getType();
    if (!isSystemVector(rowVector) || !isSystemVector(columnVector) ||
        !llvm::all_of(split->terms, [&](RankOneSum t) {
          return t.outer.getLhs().getType() == rowVector &&
                 t.outer.getRhs().getType() == columnVector;
        }))
      return rewriter.notifyMatchFailure(
          solve, "the u and b, or the v and x, are not system vectors of "
                 "one type");
    Type component = matrixType.getComponentType();
    if (!component.isF64() && !component.isF32())
      return rewriter.notifyMatchFailure(solve, "not a float matrix");

    Location loc = solve.getLoc();
    std::string form = rank == 1 ? "Sherman-Morrison" : "Woodbury";
    auto solveWithA = [&](Value rhs, const Twine &what) {
      auto op = SolveOp::create(rewriter, loc, columnVector, a, rhs);
      op->setAttr("simit.solve_note",
                  rewriter.getStringAttr(form + " A^-1 " + what));
      return op.getResult();
    };
    SmallVector<Value> us, vs, ws;
    for (auto [i, term] : llvm::enumerate(split->terms)) {
      // A - u v^T = A + (-u) v^T.
      Value u = term.outer.getLhs();
      if (term.subtracted)
        u = NegOp::create(rewriter, loc, u.getType(), u);
      us.push_back(u);
      vs.push_back(term.outer.getRhs());
      ws.push_back(solveWithA(
          u, rank == 1 ? Twine("u") : "u" + Twine(i + 1)));
    }
    Value c = solveWithA(b, "b");
    rewriter.replaceOpWithNewOp<WoodburyOp>(solve, columnVector, a, b, c, us,
                                            vs, ws);
    return success();
  }
};

struct ShermanMorrison
    : public simit::impl::SimitShermanMorrisonBase<ShermanMorrison> {
  void runOnOperation() override {
    RewritePatternSet patterns(&getContext());
    patterns.add<RewriteLowRankSolve>(&getContext());
    if (failed(applyPatternsGreedily(getOperation(), std::move(patterns))))
      signalPassFailure();
  }
};

} // namespace
