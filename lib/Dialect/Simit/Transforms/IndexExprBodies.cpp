//===- IndexExprBodies.cpp - What an index expression's body computes -----===//
//
// Analyses of the scalar body of a simit.index_expr that decide how its loop
// nest runs: whether it multiplies matrix entries, and which variables'
// terms can be nonzero outside the sparse inputs' blocks.
//
//===----------------------------------------------------------------------===//

#include "IndexExprLowering.h"

#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/IR/Matchers.h"

using namespace mlir;
using namespace mlir::simit;

bool mlir::simit::loops::multipliesMatrices(IndexExprOp op) {
  Block &body = op.getBody().front();
  auto fromMatrix = [&](Value v) {
    // The values a body computes from its arguments, seen through one
    // level of arithmetic.
    auto isMatrixArg = [&](Value x) {
      auto arg = dyn_cast<BlockArgument>(x);
      return arg && arg.getOwner() == &body &&
             op.getInputIndexList(arg.getArgNumber()).size() == 2;
    };
    if (isMatrixArg(v))
      return true;
    Operation *def = v.getDefiningOp();
    return def && llvm::any_of(def->getOperands(), isMatrixArg);
  };
  WalkResult walk = body.walk([&](Operation *inner) {
    if (isa<arith::MulFOp, arith::DivFOp, arith::MulIOp, arith::DivSIOp>(
            inner) &&
        fromMatrix(inner->getOperand(0)) && fromMatrix(inner->getOperand(1)))
      return WalkResult::interrupt();
    return WalkResult::advance();
  });
  return walk.wasInterrupted();
}

// `A(i,j) + s`, `A(i,j) + u(i) * v(j)` and `s / A(i,j)` are nonzero where A
// is zero.
llvm::SmallDenseSet<unsigned> mlir::simit::loops::varsNonzeroOutsideMatrices(
    IndexExprOp op, function_ref<bool(unsigned)> isSparseInput) {
  Block &body = op.getBody().front();
  // Per value: whether it is zero wherever the sparse matrices are.
  DenseMap<Value, bool> bounded;
  auto boundedValue = [&](Value v) {
    if (auto arg = dyn_cast<BlockArgument>(v); arg && arg.getOwner() == &body)
      return isSparseInput(arg.getArgNumber());
    auto it = bounded.find(v);
    return it != bounded.end() && it->second;
  };
  llvm::SmallDenseSet<unsigned> vars;
  llvm::SmallDenseSet<int64_t> nested;
  // Post-order: a sum's body comes before the sum.
  body.walk([&](Operation *inner) {
    auto operand = [&](unsigned i) {
      return boundedValue(inner->getOperand(i));
    };
    bool value = false;
    if (isa<arith::MulFOp, arith::MulIOp, complex::MulOp>(inner)) {
      value = operand(0) || operand(1);
    } else if (isa<arith::DivFOp, arith::DivSIOp, complex::DivOp>(inner)) {
      value = operand(0);
    } else if (isa<arith::AddFOp, arith::SubFOp, arith::AddIOp, arith::SubIOp,
                   complex::AddOp, complex::SubOp>(inner)) {
      value = operand(0) && operand(1);
    } else if (isa<arith::SelectOp>(inner)) {
      value = operand(1) && operand(2);
    } else if (isa<arith::NegFOp, complex::NegOp>(inner)) {
      value = operand(0);
    } else if (auto sum = dyn_cast<IndexSumOp>(inner)) {
      value =
          boundedValue(sum.getBody().front().getTerminator()->getOperand(0));
      for (int64_t v : sum.getVars()) {
        nested.insert(v);
        if (!value)
          vars.insert(v);
      }
    } else if (auto constant = dyn_cast<arith::ConstantOp>(inner)) {
      value = matchPattern(constant.getResult(), m_AnyZeroFloat()) ||
              matchPattern(constant.getResult(), m_Zero());
    }
    for (Value result : inner->getResults())
      bounded[result] = value;
  });
  if (!boundedValue(body.getTerminator()->getOperand(0)))
    for (unsigned v = 0, e = op.getIndexVars().size(); v < e; ++v)
      if (!nested.contains(v))
        vars.insert(v);
  return vars;
}
