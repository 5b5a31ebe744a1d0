//===- GuardIntegerDivision.cpp - Divisions that cannot trap --------------===//

#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/Matchers.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITGUARDINTEGERDIVISION
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// An i1 that is true when any lane of `mask` is (vectors of integers are
/// divided lane by lane).
Value anyLane(OpBuilder &b, Location loc, Value mask) {
  if (!isa<VectorType>(mask.getType()))
    return mask;
  return vector::ReductionOp::create(b, loc, vector::CombiningKind::OR, mask);
}

Value splatConstant(OpBuilder &b, Location loc, Type type, const APInt &v) {
  if (auto vector = dyn_cast<VectorType>(type))
    return arith::ConstantOp::create(
        b, loc, DenseElementsAttr::get(vector, v));
  return arith::ConstantOp::create(b, loc, IntegerAttr::get(type, v));
}

/// Whether every lane of the constant `divisor` is non-zero and, for a
/// signed division, not -1 (so that nothing needs checking).
bool isSafeConstant(Value divisor, bool isSigned) {
  Attribute value;
  if (!matchPattern(divisor, m_Constant(&value)))
    return false;
  auto safe = [&](const APInt &d) {
    return !d.isZero() && !(isSigned && d.isAllOnes());
  };
  if (auto integer = dyn_cast<IntegerAttr>(value))
    return safe(integer.getValue());
  if (auto elements = dyn_cast<DenseIntElementsAttr>(value))
    return llvm::all_of(elements.getValues<APInt>(), safe);
  return false;
}

void guard(Operation *op, bool isSigned, bool isRemainder) {
  Value dividend = op->getOperand(0), divisor = op->getOperand(1);
  Type type = divisor.getType();
  if (!isa<IntegerType>(getElementTypeOrSelf(type)) ||
      isSafeConstant(divisor, isSigned))
    return;
  unsigned width = getElementTypeOrSelf(type).getIntOrFloatBitWidth();
  OpBuilder b(op);
  Location loc = op->getLoc();
  std::string where = sourcePositionSuffix(op);
  auto equals = [&](Value x, const APInt &v) {
    return arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq, x,
                                 splatConstant(b, loc, type, v));
  };
  auto notAny = [&](Value mask) {
    Value any = anyLane(b, loc, mask);
    return arith::XOrIOp::create(
        b, loc, any, arith::ConstantIntOp::create(b, loc, b.getI1Type(), 1));
  };

  Value zero = equals(divisor, APInt::getZero(width));
  cf::AssertOp::create(b, loc, notAny(zero),
                       (isRemainder ? "mod by zero" : "integer division by zero") +
                           where);
  if (!isSigned)
    return;
  Value minusOne = equals(divisor, APInt::getAllOnes(width));
  if (isRemainder) {
    // x mod -1 = x mod 1 = 0, without the hardware's overflow trap.
    Value one = splatConstant(b, loc, type, APInt(width, 1));
    op->setOperand(1, arith::SelectOp::create(b, loc, minusOne, one, divisor));
    return;
  }
  Value minimum = equals(dividend, APInt::getSignedMinValue(width));
  Value overflow = arith::AndIOp::create(b, loc, minusOne, minimum);
  cf::AssertOp::create(b, loc, notAny(overflow),
                       "integer overflow: the minimum integer divided by -1" +
                           where);
}

struct GuardIntegerDivision
    : public simit::impl::SimitGuardIntegerDivisionBase<GuardIntegerDivision> {
  void runOnOperation() override {
    getOperation().walk([](Operation *op) {
      if (isa<arith::DivSIOp, arith::CeilDivSIOp, arith::FloorDivSIOp>(op))
        guard(op, /*isSigned=*/true, /*isRemainder=*/false);
      else if (isa<arith::DivUIOp, arith::CeilDivUIOp>(op))
        guard(op, /*isSigned=*/false, /*isRemainder=*/false);
      else if (isa<arith::RemSIOp>(op))
        guard(op, /*isSigned=*/true, /*isRemainder=*/true);
      else if (isa<arith::RemUIOp>(op))
        guard(op, /*isSigned=*/false, /*isRemainder=*/true);
    });
  }
};
} // namespace
