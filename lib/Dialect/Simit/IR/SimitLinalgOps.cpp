//===- SimitLinalgOps.cpp - Verifiers of the linear algebra operations ----===//
//
// Operands are builtin tensors or !simit.tensor; dimensions compare as
// hierarchies (outer dimension, then block dimensions), so blocked and
// unblocked operands combine as in the language (`K * x` with K blocked 3x3
// over points and x blocked 3 over points).
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

using namespace mlir;
using namespace mlir::simit;

/// Numeric scalars: floats, complex and integers other than i1.
static bool isNumeric(Type component) {
  if (auto integer = dyn_cast<IntegerType>(component))
    return integer.getWidth() > 1;
  return isa<FloatType, ComplexType>(component);
}

static LogicalResult verifyNumeric(Operation *op, Type type) {
  if (isNumeric(getComponentType(type)))
    return success();
  return op->emitOpError() << "operand must have a numeric component type, got "
                           << type;
}

static LogicalResult verifyOrder(Operation *op, Type type, unsigned order,
                                 StringRef what) {
  if (getTensorOrder(type) == order)
    return success();
  return op->emitOpError() << what << " must have order " << order << ", got "
                           << type;
}

static LogicalResult verifySameComponent(Operation *op, Type a, Type b) {
  if (getComponentType(a) == getComponentType(b))
    return success();
  return op->emitOpError() << "component types of " << a << " and " << b
                           << " differ";
}

static ArrayAttr hierarchy(Type type, unsigned dim) {
  return ArrayAttr::get(type.getContext(), getDimensionHierarchy(type, dim));
}

/// Checks that dimension `dimA` of `a` and `dimB` of `b` are one hierarchy.
static LogicalResult verifySameDimension(Operation *op, StringRef what, Type a,
                                         unsigned dimA, Type b, unsigned dimB) {
  ArrayAttr levelsA = hierarchy(a, dimA), levelsB = hierarchy(b, dimB);
  if (levelsA == levelsB)
    return success();
  return op->emitOpError() << what << ": dimension " << levelsA << " of " << a
                           << " differs from dimension " << levelsB << " of "
                           << b;
}

static LogicalResult verifyElementwise(Operation *op) {
  return verifyNumeric(op, op->getResult(0).getType());
}

LogicalResult AddOp::verify() { return verifyElementwise(*this); }
LogicalResult SubOp::verify() { return verifyElementwise(*this); }
LogicalResult MulOp::verify() { return verifyElementwise(*this); }
LogicalResult DivOp::verify() { return verifyElementwise(*this); }
LogicalResult NegOp::verify() { return verifyElementwise(*this); }

LogicalResult ScaleOp::verify() {
  Type component = getComponentType(getType());
  if (getScalar().getType() != component)
    return emitOpError() << "scalar type " << getScalar().getType()
                         << " differs from the component type " << component;
  return verifyNumeric(*this, getType());
}

LogicalResult MatVecOp::verify() {
  Type a = getMatrix().getType(), x = getVector().getType(), y = getType();
  if (failed(verifyOrder(*this, a, 2, "matrix")) ||
      failed(verifyOrder(*this, x, 1, "vector")) ||
      failed(verifyOrder(*this, y, 1, "result")) ||
      failed(verifySameComponent(*this, a, x)) ||
      failed(verifySameComponent(*this, a, y)) ||
      failed(verifyNumeric(*this, a)))
    return failure();
  if (failed(verifySameDimension(*this, "matrix columns and vector", a, 1, x,
                                 0)) ||
      failed(verifySameDimension(*this, "matrix rows and result", a, 0, y, 0)))
    return failure();
  return success();
}

LogicalResult MatMulOp::verify() {
  Type a = getLhs().getType(), b = getRhs().getType(), c = getType();
  if (failed(verifyOrder(*this, a, 2, "left operand")) ||
      failed(verifyOrder(*this, b, 2, "right operand")) ||
      failed(verifyOrder(*this, c, 2, "result")) ||
      failed(verifySameComponent(*this, a, b)) ||
      failed(verifySameComponent(*this, a, c)) ||
      failed(verifyNumeric(*this, a)))
    return failure();
  if (failed(verifySameDimension(*this, "inner dimensions", a, 1, b, 0)) ||
      failed(verifySameDimension(*this, "result rows", a, 0, c, 0)) ||
      failed(verifySameDimension(*this, "result columns", b, 1, c, 1)))
    return failure();
  return success();
}

LogicalResult TransposeOp::verify() {
  Type a = getOperand().getType(), t = getType();
  if (failed(verifyOrder(*this, a, 2, "operand")) ||
      failed(verifyOrder(*this, t, 2, "result")) ||
      failed(verifySameComponent(*this, a, t)))
    return failure();
  if (failed(verifySameDimension(*this, "result rows", a, 1, t, 0)) ||
      failed(verifySameDimension(*this, "result columns", a, 0, t, 1)))
    return failure();
  return success();
}

LogicalResult DotOp::verify() {
  Type a = getLhs().getType(), b = getRhs().getType();
  if (failed(verifyOrder(*this, a, 1, "left operand")) ||
      failed(verifyOrder(*this, b, 1, "right operand")) ||
      failed(verifySameComponent(*this, a, b)) ||
      failed(verifyNumeric(*this, a)) ||
      failed(verifySameDimension(*this, "operands", a, 0, b, 0)))
    return failure();
  if (getType() != getComponentType(a))
    return emitOpError() << "result type " << getType()
                         << " differs from the component type "
                         << getComponentType(a);
  return success();
}

LogicalResult OuterOp::verify() {
  Type a = getLhs().getType(), b = getRhs().getType(), c = getType();
  if (failed(verifyOrder(*this, a, 1, "left operand")) ||
      failed(verifyOrder(*this, b, 1, "right operand")) ||
      failed(verifyOrder(*this, c, 2, "result")) ||
      failed(verifySameComponent(*this, a, b)) ||
      failed(verifySameComponent(*this, a, c)) ||
      failed(verifyNumeric(*this, a)))
    return failure();
  if (failed(verifySameDimension(*this, "result rows", a, 0, c, 0)) ||
      failed(verifySameDimension(*this, "result columns", b, 0, c, 1)))
    return failure();
  return success();
}

LogicalResult NormOp::verify() {
  Type a = getOperand().getType();
  if (failed(verifyOrder(*this, a, 1, "operand")) ||
      failed(verifyNumeric(*this, a)))
    return failure();
  Type component = getComponentType(a);
  Type expected = component;
  if (auto complex = dyn_cast<ComplexType>(component))
    expected = complex.getElementType();
  if (!isa<FloatType>(expected))
    return emitOpError() << "operand must have float or complex components, "
                            "got "
                         << a;
  if (getType() != expected)
    return emitOpError() << "result type " << getType() << " should be "
                         << expected;
  return success();
}

/// Checks `a x = b`: a matrix, and vectors over its rows (`b`) and columns
/// (`x`), of one float or numeric component.
static LogicalResult verifyLinearSystem(Operation *op, Type a, Type b, Type x) {
  if (failed(verifyOrder(op, a, 2, "matrix")) ||
      failed(verifyOrder(op, b, 1, "right-hand side")) ||
      failed(verifyOrder(op, x, 1, "result")) ||
      failed(verifySameComponent(op, a, b)) ||
      failed(verifySameComponent(op, a, x)) || failed(verifyNumeric(op, a)))
    return failure();
  return failure(
      failed(verifySameDimension(op, "matrix rows and right-hand side", a, 0,
                                 b, 0)) ||
      failed(verifySameDimension(op, "matrix columns and result", a, 1, x, 0)));
}

LogicalResult SolveOp::verify() {
  return verifyLinearSystem(*this, getMatrix().getType(), getRhs().getType(),
                            getType());
}

LogicalResult TriangularSolveOp::verify() {
  return verifyLinearSystem(*this, getMatrix().getType(), getRhs().getType(),
                            getType());
}

static LogicalResult verifyFloat(Operation *op, Type type) {
  if (isa<FloatType>(getComponentType(type)))
    return success();
  return op->emitOpError() << "operand must have float components, got "
                           << type;
}

LogicalResult FactorizeOp::verify() {
  Type a = getMatrix().getType();
  if (failed(verifyOrder(*this, a, 2, "matrix")) ||
      failed(verifyFloat(*this, a)))
    return failure();
  return verifySameDimension(*this, "a factorised matrix is square: rows and "
                                    "columns",
                             a, 0, a, 1);
}

StringRef FactorSolveOp::getIntrinsicName() {
  bool matrix = getTensorOrder(getRhs().getType()) == 2;
  if (getKind() == FactorizationKind::LU)
    return matrix ? "lumatsolve" : "lusolve";
  return matrix ? "lltmatsolve" : "lltsolve";
}

LogicalResult FactorSolveOp::verify() {
  Type b = getRhs().getType(), x = getType();
  unsigned order = getTensorOrder(b);
  if (order != 1 && order != 2)
    return emitOpError() << "right-hand side must be a vector or a matrix, got "
                         << b;
  if (failed(verifyOrder(*this, x, order, "result")) ||
      failed(verifyFloat(*this, b)) || failed(verifySameComponent(*this, b, x)))
    return failure();
  // A matrix right-hand side is solved column by column.
  if (order == 2)
    return verifySameDimension(*this, "right-hand side and result columns", b,
                               1, x, 1);
  return success();
}

LogicalResult WoodburyOp::verify() {
  Type b = getRhs().getType(), x = getType();
  if (failed(verifyLinearSystem(*this, getMatrix().getType(), b, x)) ||
      failed(verifyFloat(*this, b)))
    return failure();
  if (getUs().empty() || getVs().size() != getUs().size() ||
      getWs().size() != getUs().size())
    return emitOpError() << "needs k >= 1 vectors each of u, v and w, got "
                         << getUs().size() << ", " << getVs().size() << " and "
                         << getWs().size();
  auto isNot = [](Type type) {
    return [type](Value v) { return v.getType() != type; };
  };
  if (llvm::any_of(getUs(), isNot(b)))
    return emitOpError() << "every u must have the right-hand side's type "
                         << b;
  if (getSolution().getType() != x || llvm::any_of(getVs(), isNot(x)) ||
      llvm::any_of(getWs(), isNot(x)))
    return emitOpError() << "c and every v and w must have the result's type "
                         << x;
  return success();
}

/// Checks a dense square float matrix of size 2, 3 or 4.
static LogicalResult verifySmallSquareMatrix(Operation *op,
                                             RankedTensorType type) {
  if (type.getRank() != 2 || type.getDimSize(0) != type.getDimSize(1) ||
      type.getDimSize(0) < 2 || type.getDimSize(0) > 4 ||
      !isa<FloatType>(type.getElementType()))
    return op->emitOpError()
           << "operand must be a 2x2, 3x3 or 4x4 float matrix, got " << type;
  return success();
}

LogicalResult DetOp::verify() {
  auto type = cast<RankedTensorType>(getOperand().getType());
  if (failed(verifySmallSquareMatrix(*this, type)))
    return failure();
  if (getType() != type.getElementType())
    return emitOpError() << "result type " << getType()
                         << " differs from the component type "
                         << type.getElementType();
  return success();
}

LogicalResult InvOp::verify() {
  return verifySmallSquareMatrix(*this,
                                 cast<RankedTensorType>(getType()));
}

LogicalResult CrossOp::verify() {
  auto type = cast<RankedTensorType>(getType());
  if (type.getRank() != 1 || type.getDimSize(0) != 3 ||
      !isa<FloatType>(type.getElementType()))
    return emitOpError() << "operands must be float 3-vectors, got " << type;
  return success();
}
