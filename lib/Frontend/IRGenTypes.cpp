//===- IRGenTypes.cpp - Types, locations and literals ---------------------===//
//
// float -> f64 (f32 in single precision), int -> i32, bool -> i1,
// complex -> complex<float>, string -> !simit.string, opaque ->
// !simit.opaque. A tensor of integer ranges with a scalar component is a
// builtin tensor (vector orientation is not part of the IR type); one with
// a set dimension or a tensor block is a !simit.tensor. Order-0 tensors are
// scalars.
//
//===----------------------------------------------------------------------===//

#include "IRGenImpl.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"

#include <cmath>

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

Location IRGenerator::loc(SMLoc where) {
  if (!where.isValid())
    return FileLineColLoc::get(fileName, 0, 0);
  auto [line, column] = diags.lineAndColumn(where);
  return FileLineColLoc::get(fileName, line, column);
}

mlir::Type IRGenerator::floatType() {
  return options.singlePrecision ? mlir::Type(builder.getF32Type())
                                 : mlir::Type(builder.getF64Type());
}

mlir::Type IRGenerator::scalarType(ScalarKind kind) {
  switch (kind) {
  case ScalarKind::Int:
    return builder.getI32Type();
  case ScalarKind::Float:
    return floatType();
  case ScalarKind::Bool:
    return builder.getI1Type();
  case ScalarKind::Complex:
    return ComplexType::get(floatType());
  case ScalarKind::String:
    return dialect::StringType::get(&context);
  }
  llvm_unreachable("unknown scalar kind");
}

Attribute IRGenerator::dimAttr(const Dim &dim, SMLoc where) {
  switch (dim.kind) {
  case Dim::Kind::Range:
    return builder.getI64IntegerAttr(dim.size);
  case Dim::Kind::Set:
    return builder.getStringAttr(setName(dim.set));
  case Dim::Kind::Generic:
    if (currentFunc && dim.generic->index < currentFunc->binding.size())
      return dimAttr(currentFunc->binding[dim.generic->index], where);
    break;
  }
  unsupported(where, "a tensor dimension given by an unbound generic "
                     "parameter '" + dim.generic->name + "'");
  return builder.getI64IntegerAttr(1);
}

mlir::Type IRGenerator::convertType(const TypePtr &type, SMLoc where) {
  switch (type->kind) {
  case frontend::Type::Kind::Tensor: {
    mlir::Type component = scalarType(type->component);
    if (type->dims.empty())
      return component;
    bool builtin = !type->block;
    for (const Dim &dim : type->dims)
      builtin &= dim.kind == Dim::Kind::Range;
    if (builtin) {
      SmallVector<int64_t> shape;
      for (const Dim &dim : type->dims)
        shape.push_back(dim.size);
      return RankedTensorType::get(shape, component);
    }
    SmallVector<Attribute> dims;
    for (const Dim &dim : type->dims)
      dims.push_back(dimAttr(dim, where));
    mlir::Type block = type->block ? convertType(type->block, where) : component;
    return dialect::SystemTensorType::get(&context, builder.getArrayAttr(dims),
                                        block);
  }
  case frontend::Type::Kind::Element:
    return elementType(type->element);
  case frontend::Type::Kind::Tuple: {
    SmallVector<mlir::Type> members;
    for (const ElementDecl *member : type->members)
      members.push_back(elementType(member));
    SmallVector<StringAttr> names;
    for (const std::string &name : type->memberNames)
      names.push_back(builder.getStringAttr(name));
    return dialect::TupleType::get(&context, members, names);
  }
  case frontend::Type::Kind::Opaque:
    return dialect::OpaqueType::get(&context);
  default:
    break;
  }
  unsupported(where, "a value of type '" + type->str() + "'");
  return builder.getI32Type();
}

dialect::ElementType IRGenerator::elementType(const ElementDecl *element) {
  auto it = elementTypes.find(element);
  if (it != elementTypes.end())
    return it->second;
  SmallVector<StringAttr> names;
  SmallVector<mlir::Type> types;
  for (const ElementDecl::Field &field : element->fields) {
    names.push_back(builder.getStringAttr(field.name));
    types.push_back(convertType(field.type, field.loc));
  }
  auto type = dialect::ElementType::get(
      &context, builder.getStringAttr(element->name), names, types);
  elementTypes[element] = type;
  return type;
}

std::string IRGenerator::setName(const VarDecl *set) {
  if (set->role == VarDecl::Role::Extern)
    return set->name;
  const VarDecl *match = nullptr;
  for (const auto &global : program.globals) {
    const frontend::Type *type = global->type.get();
    if (global->role != VarDecl::Role::Extern || !type || !type->isSet() ||
        type->element != set->type->element ||
        type->endpoints != set->type->endpoints ||
        type->gridRank != set->type->gridRank)
      continue;
    if (match)
      return set->name; // ambiguous
    match = global.get();
  }
  return match ? match->name : set->name;
}

dialect::SetType IRGenerator::setType(const VarDecl *set) {
  const frontend::Type &type = *set->type;
  SmallVector<StringAttr> endpoints;
  for (const VarDecl *endpoint : type.endpoints)
    endpoints.push_back(builder.getStringAttr(endpoint->name));
  return dialect::SetType::get(&context, builder.getStringAttr(setName(set)),
                             elementType(type.element), endpoints,
                             type.gridRank);
}

bool IRGenerator::isSlotParam(const VarDecl &param) {
  return param.inout && (param.type->isTensor() || param.type->isOpaque());
}

mlir::Type IRGenerator::paramType(const VarDecl &param) {
  if (param.type->isSet())
    return setType(&param);
  mlir::Type type = convertType(param.type, param.loc);
  if (isSlotParam(param))
    return dialect::RefType::get(&context, type);
  return type;
}

//===----------------------------------------------------------------------===//
// Literals
//===----------------------------------------------------------------------===//

std::optional<FoldedLiteral> IRGenerator::foldLiteral(const Expr &e) {
  FoldedLiteral literal;
  switch (e.getKind()) {
  case Expr::Kind::IntLit:
    literal.ints = {cast<IntLiteral>(e).value};
    return literal;
  case Expr::Kind::BoolLit:
    literal.kind = ScalarKind::Bool;
    literal.ints = {cast<BoolLiteral>(e).value};
    return literal;
  case Expr::Kind::FloatLit:
    literal.kind = ScalarKind::Float;
    literal.floats = {cast<FloatLiteral>(e).value};
    return literal;
  case Expr::Kind::ComplexLit: {
    auto &c = cast<ComplexLiteral>(e);
    literal.kind = ScalarKind::Complex;
    literal.complexes = {{c.re, c.im}};
    return literal;
  }
  case Expr::Kind::StringLit:
    literal.kind = ScalarKind::String;
    literal.string = cast<StringLiteral>(e).value;
    return literal;
  case Expr::Kind::DenseLit: {
    auto &d = cast<DenseLiteral>(e);
    literal.kind = d.component;
    literal.shape = d.shape;
    literal.ints = d.intValues;
    literal.floats = d.floatValues;
    for (size_t i = 0; i + 1 < d.complexValues.size(); i += 2)
      literal.complexes.emplace_back(d.complexValues[i],
                                     d.complexValues[i + 1]);
    return literal;
  }
  case Expr::Kind::Unary: {
    auto &u = cast<UnaryExpr>(e);
    std::optional<FoldedLiteral> operand = foldLiteral(*u.operand);
    if (!operand || u.op == UnaryExpr::Op::Not)
      return std::nullopt;
    if (u.op == UnaryExpr::Op::Neg) {
      for (int64_t &v : operand->ints)
        v = -v;
      for (double &v : operand->floats)
        v = -v;
      for (std::complex<double> &v : operand->complexes)
        v = -v;
    }
    return operand;
  }
  case Expr::Kind::Transpose: {
    std::optional<FoldedLiteral> operand =
        foldLiteral(*cast<TransposeExpr>(e).operand);
    if (!operand || operand->shape.size() != 2)
      return operand;
    int64_t rows = operand->shape[0], columns = operand->shape[1];
    auto transpose = [&](auto &values) {
      if (values.empty())
        return;
      auto copy = values;
      for (int64_t r = 0; r < rows; ++r)
        for (int64_t c = 0; c < columns; ++c)
          values[c * rows + r] = copy[r * columns + c];
    };
    transpose(operand->ints);
    transpose(operand->floats);
    transpose(operand->complexes);
    operand->shape = {columns, rows};
    return operand;
  }
  default:
    return std::nullopt;
  }
}

Value IRGenerator::genConstant(const FoldedLiteral &literal, mlir::Type type,
                               SMLoc where) {
  Location l = loc(where);
  if (literal.kind == ScalarKind::String)
    return dialect::StringConstantOp::create(builder, l, literal.string);
  auto tensorType = dyn_cast<RankedTensorType>(type);
  mlir::Type component = tensorType ? tensorType.getElementType() : type;
  // Under --float32 a literal beyond the single range is an error, as one
  // beyond the double range always is (language.md 4.1: the precision
  // applies to literals too).
  mlir::Type part = component;
  if (auto complexType = dyn_cast<ComplexType>(component))
    part = complexType.getElementType();
  if (part.isF32()) {
    auto beyond = [](double v) {
      return std::isfinite(v) && std::isinf(static_cast<float>(v));
    };
    bool tooLarge =
        llvm::any_of(literal.floats, beyond) ||
        llvm::any_of(literal.complexes, [&](std::complex<double> v) {
          return beyond(v.real()) || beyond(v.imag());
        });
    if (tooLarge)
      diags.error(where, "float literal is too large for a 32-bit float "
                         "(the program is compiled with single precision)");
  }
  if (!tensorType) {
    switch (literal.kind) {
    case ScalarKind::Int:
    case ScalarKind::Bool:
      return arith::ConstantOp::create(
          builder, l, builder.getIntegerAttr(component, literal.ints.front()));
    case ScalarKind::Float:
      return arith::ConstantOp::create(
          builder, l, builder.getFloatAttr(component, literal.floats.front()));
    case ScalarKind::Complex: {
      mlir::Type part = cast<ComplexType>(component).getElementType();
      std::complex<double> v = literal.complexes.front();
      return complex::ConstantOp::create(
          builder, l, component,
          builder.getArrayAttr({builder.getFloatAttr(part, v.real()),
                                builder.getFloatAttr(part, v.imag())}));
    }
    default:
      break;
    }
  } else {
    DenseElementsAttr value;
    switch (literal.kind) {
    case ScalarKind::Int: {
      SmallVector<APInt> ints;
      for (int64_t v : literal.ints)
        ints.emplace_back(32, v, /*isSigned=*/true);
      if ((int64_t)ints.size() == tensorType.getNumElements())
        value = DenseElementsAttr::get(tensorType, ints);
      break;
    }
    case ScalarKind::Float: {
      auto floatTy = cast<FloatType>(component);
      SmallVector<APFloat> floats;
      for (double v : literal.floats) {
        APFloat f(v);
        bool lost;
        f.convert(floatTy.getFloatSemantics(), APFloat::rmNearestTiesToEven,
                  &lost);
        floats.push_back(f);
      }
      if ((int64_t)floats.size() == tensorType.getNumElements())
        value = DenseElementsAttr::get(tensorType, floats);
      break;
    }
    case ScalarKind::Complex: {
      if ((int64_t)literal.complexes.size() != tensorType.getNumElements())
        break;
      if (options.singlePrecision) {
        SmallVector<std::complex<float>> values;
        for (std::complex<double> v : literal.complexes)
          values.emplace_back(v.real(), v.imag());
        value = DenseElementsAttr::get(tensorType, ArrayRef(values));
      } else {
        value = DenseElementsAttr::get(tensorType, ArrayRef(literal.complexes));
      }
      break;
    }
    default:
      break;
    }
    if (value)
      return arith::ConstantOp::create(builder, l, value);
  }
  return unsupported(where, "a literal of this shape for a value of type " +
                                typeString(type),
                     type);
}

Value IRGenerator::intConstant(int64_t value, SMLoc where) {
  return arith::ConstantOp::create(builder, loc(where),
                                   builder.getI32IntegerAttr(value));
}

Value IRGenerator::indexConstant(int64_t value, SMLoc where) {
  return arith::ConstantIndexOp::create(builder, loc(where), value);
}
