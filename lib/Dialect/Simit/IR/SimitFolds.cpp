//===- SimitFolds.cpp - Folds and canonicalisations -----------------------===//
//
// Algebraic identities on the linear algebra operations. Scaling by zero
// assumes finite components (0 * inf is NaN), as the language's numerical
// code does.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/IR/Matchers.h"
#include "mlir/IR/PatternMatch.h"

using namespace mlir;
using namespace mlir::simit;

static bool isZeros(Value value) { return value.getDefiningOp<ZerosOp>(); }

/// Whether `attr` is the scalar constant `expected` (0 or 1), as a float,
/// integer or complex with zero imaginary part.
static bool isScalarConstant(Attribute attr, int64_t expected) {
  if (auto value = dyn_cast_or_null<FloatAttr>(attr))
    return value.getValueAsDouble() == static_cast<double>(expected);
  if (auto value = dyn_cast_or_null<IntegerAttr>(attr))
    return value.getValue() == expected;
  if (auto value = dyn_cast_or_null<ArrayAttr>(attr); value && value.size() == 2)
    return isScalarConstant(value[0], expected) &&
           isScalarConstant(value[1], 0);
  return false;
}

OpFoldResult AddOp::fold(FoldAdaptor) {
  if (isZeros(getRhs()))
    return getLhs();
  if (isZeros(getLhs()))
    return getRhs();
  return {};
}

OpFoldResult SubOp::fold(FoldAdaptor) {
  if (isZeros(getRhs()))
    return getLhs();
  return {};
}

OpFoldResult NegOp::fold(FoldAdaptor) {
  if (auto inner = getOperand().getDefiningOp<NegOp>())
    return inner.getOperand();
  return {};
}

OpFoldResult TransposeOp::fold(FoldAdaptor) {
  auto inner = getOperand().getDefiningOp<TransposeOp>();
  if (inner && inner.getOperand().getType() == getType())
    return inner.getOperand();
  return {};
}

OpFoldResult ScaleOp::fold(FoldAdaptor adaptor) {
  if (isScalarConstant(adaptor.getScalar(), 1))
    return getTensor();
  return {};
}

namespace {
/// scale(0, t) -> zeros.
struct ScaleByZero : public OpRewritePattern<ScaleOp> {
  using OpRewritePattern::OpRewritePattern;

  LogicalResult matchAndRewrite(ScaleOp op,
                                PatternRewriter &rewriter) const override {
    Attribute scalar;
    if (!matchPattern(op.getScalar(), m_Constant(&scalar)) ||
        !isScalarConstant(scalar, 0))
      return failure();
    rewriter.replaceOpWithNewOp<ZerosOp>(op, op.getType());
    return success();
  }
};
} // namespace

void ScaleOp::getCanonicalizationPatterns(RewritePatternSet &patterns,
                                          MLIRContext *context) {
  patterns.add<ScaleByZero>(context);
}
