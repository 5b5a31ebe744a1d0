//===- IRGenExpr.cpp - Expressions ----------------------------------------===//
//
// Scalars use arith, math and complex; tensors the simit linear-algebra ops,
// a scalar operand of `+ - .* ./ /` broadcast with simit.broadcast. `*`
// follows sema's product kind: scale, dot (row * column), outer (column *
// row), matvec, matmul, and row * matrix as matvec with the transposed matrix.
// Vectors carry no orientation in the IR, so `'` on a vector is a no-op.
// Chained comparisons evaluate each operand once and and the results; the
// ordered comparisons of complex values compare real parts.
//
//===----------------------------------------------------------------------===//

#include "IRGenImpl.h"

#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/Dialect/ControlFlow/IR/ControlFlowOps.h"
#include "mlir/Dialect/UB/IR/UBOps.h"
#include "mlir/IR/Matchers.h"

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

static bool isTensor(Value value) {
  return dialect::isTensorType(value.getType());
}

Value IRGenerator::genExpr(const Expr &e) {
  switch (e.getKind()) {
  case Expr::Kind::IntLit:
  case Expr::Kind::FloatLit:
  case Expr::Kind::BoolLit:
  case Expr::Kind::StringLit:
  case Expr::Kind::ComplexLit:
  case Expr::Kind::DenseLit:
    return genConstant(*foldLiteral(e), convertType(e.type, e.loc), e.loc);
  case Expr::Kind::Name:
    return genName(cast<NameExpr>(e));
  case Expr::Kind::Read:
    return genRead(cast<ReadExpr>(e));
  case Expr::Kind::TupleRead:
    return genTupleRead(cast<TupleReadExpr>(e));
  case Expr::Kind::Field:
    return genField(cast<FieldExpr>(e));
  case Expr::Kind::SetRead:
    return genSetRead(cast<SetReadExpr>(e));
  case Expr::Kind::Unary:
    return genUnary(cast<UnaryExpr>(e));
  case Expr::Kind::Binary:
    return genBinary(cast<BinaryExpr>(e));
  case Expr::Kind::Compare:
    return genCompare(cast<CompareExpr>(e));
  case Expr::Kind::Transpose:
    return genTranspose(cast<TransposeExpr>(e));
  case Expr::Kind::Call:
  case Expr::Kind::Map: {
    SmallVector<Value> values = genValues(e);
    if (values.size() == 1)
      return values.front();
    return unsupported(e.loc, "a call without exactly one value used as a "
                              "value");
  }
  }
  llvm_unreachable("unknown expression kind");
}

//===----------------------------------------------------------------------===//
// Names
//===----------------------------------------------------------------------===//

Value IRGenerator::genName(const NameExpr &e) {
  if (auto *generic = dyn_cast<GenericParamDecl>(e.decl)) {
    // A `0:N` parameter used as an int: the size of its bound range.
    if (currentFunc && generic->index < currentFunc->binding.size() &&
        currentFunc->binding[generic->index].kind == Dim::Kind::Range)
      return intConstant(currentFunc->binding[generic->index].size, e.loc);
    return unsupported(e.loc, "the value of generic parameter '" + e.name +
                                  "' outside an instance");
  }
  return genVarValue(*cast<VarDecl>(e.decl), e.loc);
}

Value IRGenerator::genVarValue(const VarDecl &var, SMLoc where) {
  if (var.type->isSet())
    return genSet(&var, where);
  if (var.role == VarDecl::Role::GlobalConst) {
    mlir::Type type = convertType(var.type, where);
    if (std::optional<FoldedLiteral> literal = foldLiteral(*var.init))
      return genConstant(*literal, type, where);
    return unsupported(where, "global constant '" + var.name +
                                  "' with a non-literal value",
                       type);
  }
  if (var.role == VarDecl::Role::Extern)
    return dialect::LoadOp::create(builder, loc(where), slotOf(var, where));
  auto it = bindings.find(&var);
  if (it == bindings.end())
    return unsupported(where, "a use of '" + var.name +
                                  "' where it has no value",
                       convertType(var.type, where));
  if (it->second.isSlot)
    return dialect::LoadOp::create(builder, loc(where), it->second.value);
  return it->second.value;
}

Value IRGenerator::genSet(const VarDecl *set, SMLoc where) {
  if (set->role == VarDecl::Role::Extern)
    return dialect::GetSetOp::create(builder, loc(where), setType(set),
                                   set->name);
  auto it = bindings.find(set);
  if (it == bindings.end())
    return unsupported(where, "set '" + set->name + "' here", setType(set));
  return it->second.value;
}

//===----------------------------------------------------------------------===//
// Arithmetic
//===----------------------------------------------------------------------===//

Value IRGenerator::coerce(Value value, mlir::Type type, SMLoc where) {
  if (value.getType() == type)
    return value;
  if (dialect::isScalarType(value.getType()) && dialect::isTensorType(type))
    return dialect::BroadcastOp::create(builder, loc(where), type, value);
  auto from = dyn_cast<RankedTensorType>(value.getType());
  auto to = dyn_cast<RankedTensorType>(type);
  if (from && to && from.getElementType() == to.getElementType() &&
      from.getNumElements() == to.getNumElements()) {
    // A constant of another shape with as many components (language.md 5:
    // shapes may differ in leading 1s), copied component by component.
    Location l = loc(where);
    Value result = dialect::ZerosOp::create(builder, l, to);
    auto indicesOf = [&](int64_t linear, ArrayRef<int64_t> shape) {
      SmallVector<Value> indices(shape.size());
      for (int64_t d = shape.size() - 1; d >= 0; --d) {
        indices[d] = indexConstant(linear % shape[d], where);
        linear /= shape[d];
      }
      return indices;
    };
    for (int64_t i = 0; i < to.getNumElements(); ++i) {
      Value component = dialect::ExtractOp::create(
          builder, l, to.getElementType(), value,
          indicesOf(i, from.getShape()));
      result = dialect::InsertOp::create(builder, l, component, result,
                                         indicesOf(i, to.getShape()));
    }
    return result;
  }
  return unsupported(where, "converting a value of type " +
                                typeString(value.getType()) + " to " +
                                typeString(type),
                     type);
}

Value IRGenerator::genUnary(const UnaryExpr &e) {
  Value operand = genExpr(*e.operand);
  Location l = loc(e.loc);
  switch (e.op) {
  case UnaryExpr::Op::Plus:
    return operand;
  case UnaryExpr::Op::Not: {
    Value trueValue =
        arith::ConstantOp::create(builder, l, builder.getBoolAttr(true));
    return arith::XOrIOp::create(builder, l, operand, trueValue);
  }
  case UnaryExpr::Op::Neg:
    break;
  }
  if (isTensor(operand))
    return dialect::NegOp::create(builder, l, operand);
  switch (e.type->component) {
  case ScalarKind::Int:
    return arith::SubIOp::create(builder, l, intConstant(0, e.loc), operand);
  case ScalarKind::Float:
    return arith::NegFOp::create(builder, l, operand);
  case ScalarKind::Complex:
    return complex::NegOp::create(builder, l, operand);
  default:
    return unsupported(e.loc, "negation of this type", operand.getType());
  }
}

Value IRGenerator::genElementwise(BinaryExpr::Op op, Value a, Value b,
                                  mlir::Type resultType, SMLoc where) {
  Location l = loc(where);
  using Op = BinaryExpr::Op;
  if (!isTensor(a) && !isTensor(b)) {
    mlir::Type type = a.getType();
    if (isa<IntegerType>(type)) {
      switch (op) {
      case Op::Add: return arith::AddIOp::create(builder, l, a, b);
      case Op::Sub: return arith::SubIOp::create(builder, l, a, b);
      case Op::Mul:
      case Op::ElemMul: return arith::MulIOp::create(builder, l, a, b);
      case Op::Div:
      case Op::ElemDiv: return arith::DivSIOp::create(builder, l, a, b);
      default: break;
      }
    } else if (isa<FloatType>(type)) {
      switch (op) {
      case Op::Add: return arith::AddFOp::create(builder, l, a, b);
      case Op::Sub: return arith::SubFOp::create(builder, l, a, b);
      case Op::Mul:
      case Op::ElemMul: return arith::MulFOp::create(builder, l, a, b);
      case Op::Div:
      case Op::ElemDiv: return arith::DivFOp::create(builder, l, a, b);
      default: break;
      }
    } else if (isa<ComplexType>(type)) {
      switch (op) {
      case Op::Add: return complex::AddOp::create(builder, l, a, b);
      case Op::Sub: return complex::SubOp::create(builder, l, a, b);
      case Op::Mul:
      case Op::ElemMul: return complex::MulOp::create(builder, l, a, b);
      case Op::Div:
      case Op::ElemDiv: return complex::DivOp::create(builder, l, a, b);
      default: break;
      }
    } else if (isa<dialect::StringType>(type) && op == Op::Add) {
      return dialect::StringConcatOp::create(builder, l, a, b);
    }
    return unsupported(where, std::string("operator '") +
                                  binaryOpSpelling(op) + "' on " +
                                  typeString(type),
                       resultType);
  }
  a = coerce(a, resultType, where);
  b = coerce(b, resultType, where);
  switch (op) {
  case Op::Add: return dialect::AddOp::create(builder, l, a, b);
  case Op::Sub: return dialect::SubOp::create(builder, l, a, b);
  case Op::ElemMul: return dialect::MulOp::create(builder, l, a, b);
  case Op::Div:
  case Op::ElemDiv: return dialect::DivOp::create(builder, l, a, b);
  default: break;
  }
  return unsupported(where, std::string("operator '") + binaryOpSpelling(op) +
                                "' on tensors",
                     resultType);
}

Value IRGenerator::genProduct(const BinaryExpr &e, Value a, Value b) {
  Location l = loc(e.loc);
  mlir::Type resultType = convertType(e.type, e.loc);
  if (!isTensor(a) && !isTensor(b))
    return genElementwise(BinaryExpr::Op::Mul, a, b, resultType, e.loc);
  using MK = BinaryExpr::MulKind;
  switch (e.mulKind) {
  case MK::Scale:
    return isTensor(a) ? dialect::ScaleOp::create(builder, l, b, a)
                       : dialect::ScaleOp::create(builder, l, a, b);
  case MK::Inner:
    return dialect::DotOp::create(builder, l, resultType, a, b);
  case MK::Outer:
    return dialect::OuterOp::create(builder, l, resultType, a, b);
  case MK::MatVec:
    return dialect::MatVecOp::create(builder, l, resultType, a, b);
  case MK::VecMat: {
    // v' M = (M' v)'; vectors have no orientation in the IR.
    mlir::Type transposedType = convertType(transposed(e.rhs->type), e.loc);
    Value mt = dialect::TransposeOp::create(builder, l, transposedType, b);
    return dialect::MatVecOp::create(builder, l, resultType, mt, a);
  }
  case MK::MatMat:
    return dialect::MatMulOp::create(builder, l, resultType, a, b);
  case MK::None:
    break;
  }
  return unsupported(e.loc, "this product", resultType);
}

/// `A(p,:) * x` of a blocked matrix A is block p of `A * x`, and
/// `A(:,q)' * x` block q of `A' * x`: the slice, a vector of matrix blocks,
/// has no IR type of its own, so it is never generated.
Value IRGenerator::genBlockRowProduct(const BinaryExpr &e) {
  mlir::Type resultType = convertType(e.type, e.loc);
  auto *transpose = dyn_cast<TransposeExpr>(e.lhs.get());
  auto *slice =
      dyn_cast<ReadExpr>(transpose ? transpose->operand.get() : e.lhs.get());
  // The row's position among the matrix's indices: 0 for A(p,:), 1 for
  // A(:,q)'.
  unsigned fixed = transpose ? 1 : 0;
  if (!slice || !slice->base->type->isMatrix() || !slice->indices[fixed] ||
      slice->indices[1 - fixed])
    return unsupported(e.loc,
                       "a product of a row of matrix blocks other than "
                       "A(p,:) * x and A(:,q)' * x",
                       resultType);
  Value matrix = genExpr(*slice->base);
  Value index = genIndex(*slice->indices[fixed]);
  Value x = genExpr(*e.rhs);
  Location l = loc(e.loc);
  TypePtr matrixType = slice->base->type;
  if (transpose) {
    matrixType = transposed(matrixType);
    matrix = dialect::TransposeOp::create(
        builder, l, convertType(matrixType, e.loc), matrix);
  }
  // A * x: a vector over A's rows of blocks like the result.
  TypePtr productType = frontend::Type::tensor(
      e.type->component, {matrixType->dims[0]}, e.type, /*row=*/false);
  Value product = dialect::MatVecOp::create(
      builder, l, convertType(productType, e.loc), matrix, x);
  return dialect::ExtractOp::create(builder, l, resultType, product,
                                    ValueRange{index});
}

Value IRGenerator::genBinary(const BinaryExpr &e) {
  if (e.mulKind == BinaryExpr::MulKind::BlockRowVec)
    return genBlockRowProduct(e);
  Value a = genExpr(*e.lhs);
  Value b = genExpr(*e.rhs);
  Location l = loc(e.loc);
  using Op = BinaryExpr::Op;
  switch (e.op) {
  case Op::And:
    return arith::AndIOp::create(builder, l, a, b);
  case Op::Or:
    return arith::OrIOp::create(builder, l, a, b);
  case Op::Xor:
    return arith::XOrIOp::create(builder, l, a, b);
  case Op::Mul:
    return genProduct(e, a, b);
  case Op::LeftDiv:
    return dialect::SolveOp::create(builder, l, convertType(e.type, e.loc), a,
                                  b);
  case Op::Pow:
    return unsupported(e.loc, "'^'", convertType(e.type, e.loc));
  default:
    return genElementwise(e.op, a, b, convertType(e.type, e.loc), e.loc);
  }
}

Value IRGenerator::genTranspose(const TransposeExpr &e) {
  Value operand = genExpr(*e.operand);
  if (e.operand->type->order() != 2)
    return operand;
  return dialect::TransposeOp::create(builder, loc(e.loc),
                                    convertType(e.type, e.loc), operand);
}

//===----------------------------------------------------------------------===//
// Comparisons
//===----------------------------------------------------------------------===//

Value IRGenerator::genScalarCompare(CompareExpr::Op op, Value a, Value b,
                                    ScalarKind kind, SMLoc where) {
  Location l = loc(where);
  using Op = CompareExpr::Op;
  switch (kind) {
  case ScalarKind::Int:
  case ScalarKind::Bool: {
    // bool orders false before true: unsigned i1 comparisons.
    bool isSigned = kind == ScalarKind::Int;
    arith::CmpIPredicate predicate;
    switch (op) {
    case Op::Eq: predicate = arith::CmpIPredicate::eq; break;
    case Op::Ne: predicate = arith::CmpIPredicate::ne; break;
    case Op::Lt: predicate = isSigned ? arith::CmpIPredicate::slt : arith::CmpIPredicate::ult; break;
    case Op::Gt: predicate = isSigned ? arith::CmpIPredicate::sgt : arith::CmpIPredicate::ugt; break;
    case Op::Le: predicate = isSigned ? arith::CmpIPredicate::sle : arith::CmpIPredicate::ule; break;
    case Op::Ge: predicate = isSigned ? arith::CmpIPredicate::sge : arith::CmpIPredicate::uge; break;
    }
    return arith::CmpIOp::create(builder, l, predicate, a, b);
  }
  case ScalarKind::Complex:
    if (op == Op::Eq)
      return complex::EqualOp::create(builder, l, a, b);
    if (op == Op::Ne)
      return complex::NotEqualOp::create(builder, l, a, b);
    a = complex::ReOp::create(builder, l, a);
    b = complex::ReOp::create(builder, l, b);
    [[fallthrough]];
  case ScalarKind::Float: {
    // `!=` is true for NaN operands, the others false.
    arith::CmpFPredicate predicate;
    switch (op) {
    case Op::Eq: predicate = arith::CmpFPredicate::OEQ; break;
    case Op::Ne: predicate = arith::CmpFPredicate::UNE; break;
    case Op::Lt: predicate = arith::CmpFPredicate::OLT; break;
    case Op::Gt: predicate = arith::CmpFPredicate::OGT; break;
    case Op::Le: predicate = arith::CmpFPredicate::OLE; break;
    case Op::Ge: predicate = arith::CmpFPredicate::OGE; break;
    }
    return arith::CmpFOp::create(builder, l, predicate, a, b);
  }
  case ScalarKind::String: {
    dialect::StringPredicate predicate;
    switch (op) {
    case Op::Eq: predicate = dialect::StringPredicate::eq; break;
    case Op::Ne: predicate = dialect::StringPredicate::ne; break;
    case Op::Lt: predicate = dialect::StringPredicate::lt; break;
    case Op::Gt: predicate = dialect::StringPredicate::gt; break;
    case Op::Le: predicate = dialect::StringPredicate::le; break;
    case Op::Ge: predicate = dialect::StringPredicate::ge; break;
    }
    return dialect::StringCmpOp::create(builder, l, builder.getI1Type(),
                                      predicate, a, b);
  }
  }
  llvm_unreachable("unknown scalar kind");
}

Value IRGenerator::genCompare(const CompareExpr &e) {
  SmallVector<Value> operands;
  for (const ExprPtr &operand : e.operands)
    operands.push_back(genExpr(*operand));
  Value result;
  for (size_t i = 0; i < e.ops.size(); ++i) {
    Value c = genScalarCompare(e.ops[i], operands[i], operands[i + 1],
                               e.operands[i]->type->component, e.opLocs[i]);
    result = result ? arith::AndIOp::create(builder, loc(e.opLocs[i]), result,
                                            c)
                          .getResult()
                    : c;
  }
  return result;
}

//===----------------------------------------------------------------------===//
// Reads
//===----------------------------------------------------------------------===//

std::optional<int64_t> IRGenerator::constantInt(Value value) {
  APInt constant;
  if (matchPattern(value, m_ConstantInt(&constant)))
    return constant.getSExtValue();
  return std::nullopt;
}

Value IRGenerator::toIndex(Value value, SMLoc where) {
  if (std::optional<int64_t> constant = constantInt(value))
    return indexConstant(*constant, where);
  return arith::IndexCastOp::create(builder, loc(where),
                                    builder.getIndexType(), value);
}

Value IRGenerator::genIndex(const Expr &index) {
  Value value = genExpr(index);
  if (isa<IntegerType>(value.getType()))
    return toIndex(value, index.loc);
  return value; // an element
}

Value IRGenerator::genRead(const ReadExpr &e) {
  Value base = genExpr(*e.base);
  SmallVector<Value> indices;
  SmallVector<bool> kept;
  for (const ExprPtr &index : e.indices) {
    kept.push_back(!index);
    if (index)
      indices.push_back(genIndex(*index));
  }
  // `v(:)`, `A(:,:)`: every dimension kept, the tensor itself.
  if (e.isSlice() && indices.empty() &&
      base.getType() == convertType(e.type, e.loc))
    return base;
  // Its blocks keep every dimension: no IR type has that shape.
  if (e.isSlice() && e.base->type->block)
    return unsupported(e.loc, "a slice of a blocked tensor outside the "
                              "products A(p,:) * x and A(:,q)' * x");
  mlir::Type resultType = convertType(e.type, e.loc);
  if (e.isSlice())
    return dialect::SliceOp::create(builder, loc(e.loc), resultType, base,
                                  indices, kept);
  return dialect::ExtractOp::create(builder, loc(e.loc), resultType, base,
                                  indices);
}

Value IRGenerator::genTupleRead(const TupleReadExpr &e) {
  Value tuple = genExpr(*e.base);
  mlir::Type elementType = convertType(e.type, e.loc);
  Location l = loc(e.loc);
  if (!e.index)
    return dialect::TupleGetOp::create(builder, l, elementType, tuple,
                                     e.memberIndex);
  auto fixed = endpointPositions.find(&e);
  if (fixed != endpointPositions.end())
    return dialect::TupleGetOp::create(builder, l, elementType, tuple,
                                     fixed->second);
  Value index = genExpr(*e.index);
  if (std::optional<int64_t> constant = constantInt(index))
    return dialect::TupleGetOp::create(builder, l, elementType, tuple,
                                     *constant);
  // A computed position selects among the components, once it is known to
  // name one.
  unsigned size = cast<dialect::TupleType>(tuple.getType()).size();
  checkEndpointPosition(index, size, e.loc);
  Value result = dialect::TupleGetOp::create(builder, l, elementType, tuple, 0);
  for (unsigned k = 1; k < size; ++k) {
    Value component =
        dialect::TupleGetOp::create(builder, l, elementType, tuple, k);
    Value isK = arith::CmpIOp::create(builder, l, arith::CmpIPredicate::eq,
                                      index, intConstant(k, e.loc));
    result = arith::SelectOp::create(builder, l, isK, component, result);
  }
  return result;
}

void IRGenerator::checkEndpointPosition(Value position, unsigned size,
                                        SMLoc where) {
  Location l = loc(where);
  Value inRange = arith::CmpIOp::create(builder, l, arith::CmpIPredicate::ult,
                                        position, intConstant(size, where));
  cf::AssertOp::create(builder, l, inRange,
                       "endpoint index out of range for a tuple of " +
                           std::to_string(size) + " endpoints" +
                           dialect::sourcePositionSuffix(l));
}

Value IRGenerator::genField(const FieldExpr &e) {
  Value base = genExpr(*e.base);
  mlir::Type resultType = convertType(e.type, e.loc);
  if (e.isSetField)
    return dialect::FieldReadOp::create(builder, loc(e.loc), resultType, base,
                                      e.field);
  return dialect::ElemReadOp::create(builder, loc(e.loc), resultType, base,
                                   e.field);
}

Value IRGenerator::genSetRead(const SetReadExpr &e) {
  mlir::Type resultType = convertType(e.type, e.loc);
  if (!e.grid || !currentFunc)
    return unsupported(e.loc, "a set read outside a grid stencil",
                       resultType);
  // The point is the element parameter the grid parameter follows.
  const VarDecl *point = nullptr;
  for (const auto &param : currentFunc->params) {
    if (param.get() == e.grid)
      break;
    if (param->type->isElement())
      point = param.get();
  }
  if (!point)
    return unsupported(e.loc, "a grid read in a function without a point "
                              "parameter",
                       resultType);
  auto constants = [&](const std::vector<ExprPtr> &exprs) {
    SmallVector<int64_t> values;
    for (const ExprPtr &expr : exprs) {
      std::optional<FoldedLiteral> literal = foldLiteral(*expr);
      if (literal && literal->kind == ScalarKind::Int &&
          literal->shape.empty()) {
        values.push_back(literal->ints.front());
        continue;
      }
      // A variable of an unrolled loop (`for d in -1:2 ... P[d]`), or an
      // expression that folds to a constant.
      std::optional<int64_t> folded =
          isa<IntegerType>(convertType(expr->type, expr->loc))
              ? constantInt(genExpr(*expr))
              : std::nullopt;
      if (!folded)
        unsupported(expr->loc, "a grid offset that is not a constant (an int "
                               "literal, or the variable of a loop over "
                               "constant bounds)");
      values.push_back(folded.value_or(0));
    }
    return values;
  };
  Value grid = genVarValue(*e.grid, e.loc);
  Value pointValue = genVarValue(*point, e.loc);
  SmallVector<int64_t> offsets = constants(e.offsets);
  if (e.hasDirections) {
    SmallVector<int64_t> direction = constants(e.directions);
    // language.md 7.9: a direction has exactly one component, +1 or -1.
    if (llvm::count_if(direction, [](int64_t d) { return d != 0; }) != 1 ||
        llvm::any_of(direction, [](int64_t d) { return d < -1 || d > 1; })) {
      std::string text;
      for (int64_t d : direction)
        text += (text.empty() ? "" : ",") + std::to_string(d);
      diags.error(e.loc, "the direction of a grid edge read has exactly one "
                         "nonzero component, +1 or -1; found (" +
                             text + ")");
      failed = true;
      return mlir::ub::PoisonOp::create(builder, loc(e.loc), resultType);
    }
    return dialect::GridEdgeOp::create(builder, loc(e.loc), resultType, grid,
                                       pointValue, offsets, direction);
  }
  return dialect::GridPointOp::create(builder, loc(e.loc), resultType, grid,
                                    pointValue, offsets);
}
