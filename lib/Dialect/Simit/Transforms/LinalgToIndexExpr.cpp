//===- LinalgToIndexExpr.cpp - Linear algebra as index expressions --------===//
//
// Each linear algebra operation on system tensors is one index expression:
// one index variable per distinct dimension, whose domain is that
// dimension's whole hierarchy (set, then block ranges), and a scalar body.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/IR/PatternMatch.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITLINALGTOINDEXEXPR
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// The scalar operation of a body.
/// SquaredModulus: |x|^2 of one input (x * x, or re^2 + im^2 for complex).
enum class BodyKind { Add, Sub, Mul, Div, Neg, SquaredModulus };

/// Whether `type` is a matrix over two sets.
bool isSystemMatrix(Type type) {
  auto tensor = dyn_cast<SystemTensorType>(type);
  return tensor && tensor.getOrder() == 2 &&
         isa<StringAttr>(tensor.getDims()[0]) &&
         isa<StringAttr>(tensor.getDims()[1]);
}

/// The body of an element-wise operation; `ofMatrix` when its result is a
/// system matrix.
Value emitScalar(OpBuilder &b, Location loc, BodyKind kind, ValueRange args,
                 bool ofMatrix);

/// The body on complex components. Complex division follows the rule of
/// the float one: outside a matrix's sparsity 0/0 reads as zero.
Value emitComplex(OpBuilder &b, Location loc, BodyKind kind, ValueRange args,
                  bool ofMatrix) {
  switch (kind) {
  case BodyKind::Add:
    return complex::AddOp::create(b, loc, args[0], args[1]);
  case BodyKind::Sub:
    return complex::SubOp::create(b, loc, args[0], args[1]);
  case BodyKind::Mul:
    return complex::MulOp::create(b, loc, args[0], args[1]);
  case BodyKind::Neg:
    return complex::NegOp::create(b, loc, args[0]);
  case BodyKind::SquaredModulus: {
    Value re = complex::ReOp::create(b, loc, args[0]);
    Value im = complex::ImOp::create(b, loc, args[0]);
    return emitScalar(b, loc, BodyKind::Add,
                      {emitScalar(b, loc, BodyKind::Mul, {re, re}, false),
                       emitScalar(b, loc, BodyKind::Mul, {im, im}, false)},
                      false);
  }
  case BodyKind::Div: {
    Value quotient = complex::DivOp::create(b, loc, args[0], args[1]);
    if (!ofMatrix)
      return quotient;
    Type part = cast<ComplexType>(args[0].getType()).getElementType();
    Attribute zeroPart = b.getZeroAttr(part);
    Value zero = complex::ConstantOp::create(
        b, loc, args[0].getType(), b.getArrayAttr({zeroPart, zeroPart}));
    Value isZero = complex::EqualOp::create(b, loc, args[0], zero);
    return arith::SelectOp::create(b, loc, isZero, zero, quotient);
  }
  }
  llvm_unreachable("body kind");
}

Value emitScalar(OpBuilder &b, Location loc, BodyKind kind, ValueRange args,
                 bool ofMatrix) {
  if (isa<ComplexType>(args[0].getType()))
    return emitComplex(b, loc, kind, args, ofMatrix);
  bool isFloat = isa<FloatType>(args[0].getType());
  switch (kind) {
  case BodyKind::SquaredModulus:
    return emitScalar(b, loc, BodyKind::Mul, {args[0], args[0]}, ofMatrix);
  case BodyKind::Add:
    return isFloat ? arith::AddFOp::create(b, loc, args[0], args[1]).getResult()
                   : arith::AddIOp::create(b, loc, args[0], args[1]).getResult();
  case BodyKind::Sub:
    return isFloat ? arith::SubFOp::create(b, loc, args[0], args[1]).getResult()
                   : arith::SubIOp::create(b, loc, args[0], args[1]).getResult();
  case BodyKind::Mul:
    return isFloat ? arith::MulFOp::create(b, loc, args[0], args[1]).getResult()
                   : arith::MulIOp::create(b, loc, args[0], args[1]).getResult();
  case BodyKind::Div: {
    Value quotient =
        isFloat ? arith::DivFOp::create(b, loc, args[0], args[1]).getResult()
                : arith::DivSIOp::create(b, loc, args[0], args[1]).getResult();
    // Vectors divide as IEEE numbers (0/0 is NaN, which the numerics
    // checks report). Components outside a matrix's sparsity read as zero
    // (language.md 7.5), also where its storage holds a zero block (the
    // diagonal of a vertex no edge touches): there a zero dividend gives
    // zero, not 0/0.
    if (!ofMatrix)
      return quotient;
    Value zero =
        arith::ConstantOp::create(b, loc, b.getZeroAttr(args[0].getType()));
    Value isZero =
        isFloat ? arith::CmpFOp::create(b, loc, arith::CmpFPredicate::OEQ,
                                        args[0], zero)
                      .getResult()
                : arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                                        args[0], zero)
                      .getResult();
    return arith::SelectOp::create(b, loc, isZero, zero, quotient);
  }
  case BodyKind::Neg: {
    if (isFloat)
      return arith::NegFOp::create(b, loc, args[0]);
    Value zero = arith::ConstantOp::create(b, loc,
                                           b.getZeroAttr(args[0].getType()));
    return arith::SubIOp::create(b, loc, zero, args[0]);
  }
  }
  llvm_unreachable("body kind");
}

/// Builds `result = index_expr` with variables named i, j, k whose domains
/// are `domains`, and the given access lists.
Value buildIndexExpr(OpBuilder &b, Location loc, Type resultType,
                     ValueRange inputs, ArrayRef<ArrayAttr> domains,
                     ArrayRef<int64_t> resultIndices,
                     ArrayRef<SmallVector<int64_t>> inputIndices,
                     BodyKind kind) {
  static const char *const names[] = {"i", "j", "k"};
  SmallVector<Attribute> vars, domainAttrs;
  for (auto [v, domain] : llvm::enumerate(domains)) {
    vars.push_back(b.getStringAttr(names[v]));
    domainAttrs.push_back(domain);
  }
  OperationState state(loc, IndexExprOp::getOperationName());
  IndexExprOp::build(b, state, resultType, inputs, b.getArrayAttr(vars),
                     b.getArrayAttr(domainAttrs), resultIndices, inputIndices);
  auto op = cast<IndexExprOp>(b.create(state));
  Block &body = op.getBody().front();
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPointToStart(&body);
  Value value =
      emitScalar(b, loc, kind, body.getArguments(), isSystemMatrix(resultType));
  YieldOp::create(b, loc, value);
  return op.getResult();
}

ArrayAttr hierarchy(Type type, unsigned dim) {
  return ArrayAttr::get(type.getContext(), getDimensionHierarchy(type, dim));
}

/// The index expression equivalent to `op`, or null when `op` is not
/// linear algebra on system tensors.
Value rewrite(OpBuilder &b, Operation *op) {
  if (!llvm::any_of(op->getOperandTypes(), hasSetDimension) &&
      !llvm::any_of(op->getResultTypes(), hasSetDimension))
    return nullptr;
  Location loc = op->getLoc();
  Type resultType = op->getResult(0).getType();

  // Element-wise: one variable per dimension, read alike everywhere. A
  // scalar broadcast to the operand's type (`A / 2.0`) is read as the
  // scalar: a matrix of it would fill every block of the sets.
  auto elementwise = [&](BodyKind kind, ValueRange operands) {
    SmallVector<Value> inputs;
    for (Value operand : operands) {
      auto broadcast = operand.getDefiningOp<BroadcastOp>();
      inputs.push_back(broadcast ? broadcast.getOperand() : operand);
    }
    Type type = resultType;
    SmallVector<ArrayAttr> domains;
    SmallVector<int64_t> all;
    for (unsigned d = 0; d < getTensorOrder(type); ++d) {
      domains.push_back(hierarchy(type, d));
      all.push_back(d);
    }
    SmallVector<SmallVector<int64_t>> lists;
    for (Value input : inputs)
      lists.push_back(getTensorOrder(input.getType()) ? all
                                                      : SmallVector<int64_t>());
    return buildIndexExpr(b, loc, resultType, inputs, domains, all, lists,
                          kind);
  };
  if (isa<AddOp>(op))
    return elementwise(BodyKind::Add, op->getOperands());
  if (isa<SubOp>(op))
    return elementwise(BodyKind::Sub, op->getOperands());
  if (isa<MulOp>(op))
    return elementwise(BodyKind::Mul, op->getOperands());
  if (isa<DivOp>(op))
    return elementwise(BodyKind::Div, op->getOperands());
  if (isa<NegOp>(op))
    return elementwise(BodyKind::Neg, op->getOperands());
  if (isa<ScaleOp>(op))
    return elementwise(BodyKind::Mul, op->getOperands());

  if (auto matvec = dyn_cast<MatVecOp>(op)) {
    Type a = matvec.getMatrix().getType();
    return buildIndexExpr(b, loc, resultType, op->getOperands(),
                          {hierarchy(a, 0), hierarchy(a, 1)}, {0},
                          {{0, 1}, {1}}, BodyKind::Mul);
  }
  if (auto matmul = dyn_cast<MatMulOp>(op)) {
    Type a = matmul.getLhs().getType(), c = matmul.getRhs().getType();
    // Products of system matrices keep their op: the loop lowering stores
    // them on the product's pattern (LowerProducts.cpp).
    if (isSystemMatrix(a) && isSystemMatrix(c))
      return nullptr;
    return buildIndexExpr(b, loc, resultType, op->getOperands(),
                          {hierarchy(a, 0), hierarchy(c, 1), hierarchy(a, 1)},
                          {0, 1}, {{0, 2}, {2, 1}}, BodyKind::Mul);
  }
  if (auto transpose = dyn_cast<TransposeOp>(op)) {
    Type a = transpose.getOperand().getType();
    if (getTensorOrder(a) != 2)
      return nullptr;
    // Identity body: the product with nothing is the value itself.
    SmallVector<Attribute> vars{b.getStringAttr("i"), b.getStringAttr("j")};
    OperationState state(loc, IndexExprOp::getOperationName());
    IndexExprOp::build(b, state, resultType, op->getOperands(),
                       b.getArrayAttr(vars),
                       b.getArrayAttr({hierarchy(a, 0), hierarchy(a, 1)}),
                       {1, 0}, {{0, 1}});
    auto indexExpr = cast<IndexExprOp>(b.create(state));
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(&indexExpr.getBody().front());
    YieldOp::create(b, loc, indexExpr.getBody().getArgument(0));
    return indexExpr;
  }
  if (auto dot = dyn_cast<DotOp>(op)) {
    Type a = dot.getLhs().getType();
    return buildIndexExpr(b, loc, resultType, op->getOperands(),
                          {hierarchy(a, 0)}, {}, {{0}, {0}}, BodyKind::Mul);
  }
  if (auto outer = dyn_cast<OuterOp>(op)) {
    Type x = outer.getLhs().getType(), y = outer.getRhs().getType();
    return buildIndexExpr(b, loc, resultType, op->getOperands(),
                          {hierarchy(x, 0), hierarchy(y, 0)}, {0, 1},
                          {{0}, {1}}, BodyKind::Mul);
  }
  if (auto norm = dyn_cast<NormOp>(op)) {
    // norm(x) = sqrt(sum_i |x(i)|^2).
    Type x = norm.getOperand().getType();
    Value squares =
        buildIndexExpr(b, loc, resultType, {norm.getOperand()},
                       {hierarchy(x, 0)}, {}, {{0}}, BodyKind::SquaredModulus);
    return math::SqrtOp::create(b, loc, squares);
  }
  return nullptr;
}

struct LinalgToIndexExpr
    : public simit::impl::SimitLinalgToIndexExprBase<LinalgToIndexExpr> {
  void runOnOperation() override {
    SmallVector<Operation *> candidates;
    getOperation().walk([&](Operation *op) {
      if (isa<AddOp, SubOp, MulOp, DivOp, NegOp, ScaleOp, MatVecOp, MatMulOp,
              TransposeOp, DotOp, OuterOp, NormOp>(op))
        candidates.push_back(op);
    });
    for (Operation *op : candidates) {
      OpBuilder b(op);
      Value replacement = rewrite(b, op);
      if (!replacement)
        continue;
      SmallVector<Value> operands(op->getOperands());
      op->getResult(0).replaceAllUsesWith(replacement);
      op->erase();
      // A broadcast the index expression reads as its scalar has no storage
      // of its own.
      for (Value operand : operands)
        if (auto broadcast = operand.getDefiningOp<BroadcastOp>();
            broadcast && broadcast->use_empty())
          broadcast->erase();
    }
  }
};
} // namespace
