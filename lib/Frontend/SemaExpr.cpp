//===- SemaExpr.cpp - Expression checking ---------------------------------===//

#include "SemaImpl.h"

#include "simit/Frontend/Sema.h"

#include <climits>

using namespace simit::frontend;
using llvm::cast;
using llvm::dyn_cast;
using llvm::dyn_cast_or_null;
using llvm::isa;

const char *simit::frontend::binaryOpSpelling(BinaryExpr::Op op) {
  switch (op) {
  case BinaryExpr::Op::Add: return "+";
  case BinaryExpr::Op::Sub: return "-";
  case BinaryExpr::Op::Mul: return "*";
  case BinaryExpr::Op::Div: return "/";
  case BinaryExpr::Op::LeftDiv: return "\\";
  case BinaryExpr::Op::ElemMul: return ".*";
  case BinaryExpr::Op::ElemDiv: return "./";
  case BinaryExpr::Op::Pow: return "^";
  case BinaryExpr::Op::And: return "and";
  case BinaryExpr::Op::Or: return "or";
  case BinaryExpr::Op::Xor: return "xor";
  }
  return "?";
}

const char *simit::frontend::compareOpSpelling(CompareExpr::Op op) {
  switch (op) {
  case CompareExpr::Op::Eq: return "==";
  case CompareExpr::Op::Ne: return "!=";
  case CompareExpr::Op::Lt: return "<";
  case CompareExpr::Op::Gt: return ">";
  case CompareExpr::Op::Le: return "<=";
  case CompareExpr::Op::Ge: return ">=";
  }
  return "?";
}

bool simit::frontend::isLiteral(const Expr &e) {
  switch (e.getKind()) {
  case Expr::Kind::IntLit:
  case Expr::Kind::FloatLit:
  case Expr::Kind::BoolLit:
  case Expr::Kind::StringLit:
  case Expr::Kind::ComplexLit:
  case Expr::Kind::DenseLit:
    return true;
  default:
    return false;
  }
}

void simit::frontend::foldLiteral(ExprPtr &expr) {
  if (auto *unary = dyn_cast<UnaryExpr>(expr.get())) {
    if (unary->op == UnaryExpr::Op::Not)
      return;
    foldLiteral(unary->operand);
    Expr *operand = unary->operand.get();
    bool negate = unary->op == UnaryExpr::Op::Neg;
    SMLoc loc = unary->loc;
    bool paren = unary->parenthesized;
    ExprPtr folded;
    if (auto *i = dyn_cast<IntLiteral>(operand)) {
      folded = std::make_unique<IntLiteral>(loc, negate ? -i->value : i->value);
    } else if (auto *f = dyn_cast<FloatLiteral>(operand)) {
      folded =
          std::make_unique<FloatLiteral>(loc, negate ? -f->value : f->value);
    } else if (auto *c = dyn_cast<ComplexLiteral>(operand)) {
      folded = std::make_unique<ComplexLiteral>(loc, negate ? -c->re : c->re,
                                                negate ? -c->im : c->im);
    } else if (isa<DenseLiteral>(operand)) {
      auto *d = cast<DenseLiteral>(operand);
      if (negate) {
        for (int64_t &v : d->intValues)
          v = -v;
        for (double &v : d->floatValues)
          v = -v;
        for (double &v : d->complexValues)
          v = -v;
      }
      d->loc = loc;
      folded = std::move(unary->operand);
    } else {
      return;
    }
    folded->parenthesized = paren;
    expr = std::move(folded);
    return;
  }
  if (auto *transpose = dyn_cast<TransposeExpr>(expr.get())) {
    foldLiteral(transpose->operand);
    Expr *operand = transpose->operand.get();
    if (auto *d = dyn_cast<DenseLiteral>(operand)) {
      if (d->shape.size() == 1) {
        d->column = !d->column;
      } else if (d->shape.size() == 2) {
        int64_t rows = d->shape[0], cols = d->shape[1];
        auto flip = [&](auto &values, int64_t width) {
          auto copy = values;
          for (int64_t r = 0; r < rows; ++r)
            for (int64_t c = 0; c < cols; ++c)
              for (int64_t k = 0; k < width; ++k)
                values[(c * rows + r) * width + k] =
                    copy[(r * cols + c) * width + k];
        };
        if (!d->intValues.empty())
          flip(d->intValues, 1);
        if (!d->floatValues.empty())
          flip(d->floatValues, 1);
        if (!d->complexValues.empty())
          flip(d->complexValues, 2);
        d->shape = {cols, rows};
      } else {
        return; // order >= 3: a type error reported by the checker
      }
      expr = std::move(transpose->operand);
      return;
    }
    if (isa<IntLiteral, FloatLiteral, BoolLiteral, ComplexLiteral,
            StringLiteral>(operand))
      expr = std::move(transpose->operand);
  }
}

//===----------------------------------------------------------------------===//
// Dispatch
//===----------------------------------------------------------------------===//

TypePtr Sema::checkExpr(ExprPtr &expr) {
  TypePtr type;
  switch (expr->getKind()) {
  case Expr::Kind::IntLit: {
    int64_t v = cast<IntLiteral>(*expr).value;
    if (v > INT32_MAX || v < INT32_MIN)
      diags.error(expr->loc, "integer literal does not fit in 32 bits");
    type = Type::scalar(ScalarKind::Int);
    break;
  }
  case Expr::Kind::FloatLit:
    type = Type::scalar(ScalarKind::Float);
    break;
  case Expr::Kind::BoolLit:
    type = Type::scalar(ScalarKind::Bool);
    break;
  case Expr::Kind::StringLit:
    type = Type::scalar(ScalarKind::String);
    break;
  case Expr::Kind::ComplexLit:
    type = Type::scalar(ScalarKind::Complex);
    break;
  case Expr::Kind::DenseLit: {
    auto &d = cast<DenseLiteral>(*expr);
    for (int64_t v : d.intValues)
      if (v > INT32_MAX || v < INT32_MIN) {
        diags.error(d.loc, "integer literal does not fit in 32 bits");
        break;
      }
    std::vector<Dim> dims;
    for (int64_t n : d.shape)
      dims.push_back(Dim::range(n));
    type = Type::tensor(d.component, dims, nullptr,
                        d.shape.size() == 1 && !d.column);
    break;
  }
  case Expr::Kind::Name:
    type = checkName(cast<NameExpr>(*expr));
    break;
  case Expr::Kind::Call:
    type = checkCall(cast<CallExpr>(*expr));
    break;
  case Expr::Kind::Read:
    type = checkRead(expr);
    break;
  case Expr::Kind::TupleRead:
    type = checkTupleRead(cast<TupleReadExpr>(*expr));
    break;
  case Expr::Kind::Field:
    type = checkField(expr);
    break;
  case Expr::Kind::SetRead:
    type = checkSetRead(cast<SetReadExpr>(*expr));
    break;
  case Expr::Kind::Unary:
    type = checkUnary(expr);
    break;
  case Expr::Kind::Binary:
    type = checkBinary(cast<BinaryExpr>(*expr));
    break;
  case Expr::Kind::Compare:
    type = checkCompare(cast<CompareExpr>(*expr));
    break;
  case Expr::Kind::Transpose:
    type = checkTranspose(expr);
    break;
  case Expr::Kind::Map:
    type = checkMap(cast<MapExpr>(*expr), /*isApply=*/false);
    break;
  }
  expr->type = type;
  return type;
}

//===----------------------------------------------------------------------===//
// Names
//===----------------------------------------------------------------------===//

TypePtr Sema::checkName(NameExpr &name) {
  const Decl *decl = lookupVariable(name.name);
  if (!decl) {
    if (lookupFunction(name.name))
      diags.error(name.loc, "function '" + name.name +
                                "' cannot be used as a value");
    else
      diags.error(name.loc, "undeclared variable '" + name.name + "'");
    return Type::error();
  }
  name.decl = decl;
  if (auto *generic = dyn_cast<GenericParamDecl>(decl)) {
    if (generic->isRange)
      return Type::scalar(ScalarKind::Int);
    diags.error(name.loc, "generic parameter '" + name.name +
                              "' is not a value (only '0:' parameters can be "
                              "used as an int)");
    return Type::error();
  }
  auto *var = cast<VarDecl>(decl);
  if (var->role == VarDecl::Role::IndexVar) {
    if (!ctx.inAssignment)
      diags.error(name.loc, "index variable '" + name.name +
                                "' is not allowed outside an assignment");
    else
      diags.error(name.loc, "index variable '" + name.name +
                                "' is not a value; it can only index a "
                                "tensor");
    return Type::error();
  }
  return var->type ? var->type : Type::error();
}

//===----------------------------------------------------------------------===//
// Reads
//===----------------------------------------------------------------------===//

TypePtr Sema::checkRead(ExprPtr &expr) {
  auto &read = cast<ReadExpr>(*expr);
  auto *name = dyn_cast<NameExpr>(read.base.get());
  if (name && !name->parenthesized) {
    const Decl *decl = lookupVariable(name->name);
    if (!decl) {
      if (lookupFunction(name->name)) {
        auto call = std::make_unique<CallExpr>(read.loc, name->name);
        call->args = std::move(read.indices);
        expr = std::move(call);
        return checkCall(cast<CallExpr>(*expr));
      }
      if (allFunctionNames.count(name->name))
        diags.error(name->loc, "undeclared function '" + name->name +
                                   "' (a function can only call functions "
                                   "declared before it, not itself)");
      else
        diags.error(name->loc, "undeclared function or variable '" +
                                   name->name + "'");
      return Type::error();
    }
    auto *var = dyn_cast<VarDecl>(decl);
    if (var && var->type && var->type->isTuple()) {
      auto tuple = std::make_unique<TupleReadExpr>(read.loc,
                                                   std::move(read.base));
      if (read.indices.size() != 1 || !read.indices[0]) {
        diags.error(read.loc, "a tuple read takes exactly one index");
        expr = std::move(tuple);
        return Type::error();
      }
      tuple->index = std::move(read.indices[0]);
      expr = std::move(tuple);
      return checkTupleRead(cast<TupleReadExpr>(*expr));
    }
  }
  return checkTensorRead(read);
}

bool Sema::checkIndex(ExprPtr &index, const Dim &dim, SMLoc loc) {
  TypePtr t = checkExpr(index);
  if (t->isError())
    return false;
  switch (dim.kind) {
  case Dim::Kind::Range:
    if (!t->isScalar(ScalarKind::Int)) {
      diags.error(loc, "index must be an integral value, found '" +
                           t->str() + "'");
      return false;
    }
    if (auto *lit = dyn_cast<IntLiteral>(index.get());
        lit && (lit->value < 0 || lit->value >= dim.size)) {
      diags.error(loc, "index " + std::to_string(lit->value) +
                           " is out of range for a dimension of size " +
                           std::to_string(dim.size));
      return false;
    }
    return true;
  case Dim::Kind::Set: {
    const Type &setType = *dim.set->type;
    if (!t->isElement()) {
      diags.error(loc, "expected an element of set '" + dim.set->name +
                           "' as index, found '" + t->str() + "'");
      return false;
    }
    if (t->element != setType.element) {
      diags.error(loc, "expected an element of set '" + dim.set->name +
                           "' (of type '" + setType.element->name +
                           "'), found '" + t->str() + "'");
      return false;
    }
    checkElementOrigin(*index, dim.set, loc);
    return true;
  }
  case Dim::Kind::Generic:
    if (dim.generic->isRange && !t->isScalar(ScalarKind::Int)) {
      diags.error(loc, "index must be an integral value, found '" +
                           t->str() + "'");
      return false;
    }
    if (!t->isScalar(ScalarKind::Int) && !t->isElement()) {
      diags.error(loc, "expected an element or an int as index, found '" +
                           t->str() + "'");
      return false;
    }
    if (t->isElement() && ctx.func) {
      std::optional<OriginKey> key;
      const VarDecl *origin = originOf(*index, &key);
      if (!origin && key && !ctx.func->genericFromOrigin.count(dim.generic))
        ctx.func->genericFromOrigin[dim.generic] = *key;
    }
    return true;
  }
  return false;
}

void Sema::checkElementOrigin(const Expr &element, const VarDecl *set,
                              SMLoc loc) {
  std::optional<OriginKey> key;
  const VarDecl *origin = originOf(element, &key);
  if (origin) {
    if (origin != set)
      diags.error(loc, "expected an element of set '" + set->name +
                           "', but it is inferred to be of set '" +
                           origin->name + "'");
    return;
  }
  if (key && ctx.func)
    ctx.func->inferredOrigins[*key] = set;
}

TypePtr Sema::checkTensorRead(ReadExpr &read) {
  TypePtr base = checkExpr(read.base);
  if (base->isError())
    return base;
  if (!base->isTensor()) {
    diags.error(read.loc, "cannot index a value of type '" + base->str() +
                              "': not a tensor");
    return Type::error();
  }
  if (base->order() == 0) {
    diags.error(read.loc, "cannot index a scalar");
    return Type::error();
  }
  if (read.indices.size() != base->order()) {
    diags.error(read.loc, "expected " + std::to_string(base->order()) +
                              (base->order() == 1 ? " index" : " indices") +
                              " but found " +
                              std::to_string(read.indices.size()));
    return Type::error();
  }
  bool slice = read.isSlice();
  bool ok = true;
  std::vector<Dim> kept;
  for (size_t i = 0; i < read.indices.size(); ++i) {
    ExprPtr &index = read.indices[i];
    SMLoc loc = i < read.indexLocs.size() ? read.indexLocs[i] : read.loc;
    if (!index) {
      kept.push_back(base->dims[i]);
      continue;
    }
    // Index variables: only directly as indices of a read in an assignment.
    if (auto *name = dyn_cast<NameExpr>(index.get())) {
      auto *var = dyn_cast_or_null<VarDecl>(lookupVariable(name->name));
      if (var && var->role == VarDecl::Role::IndexVar) {
        name->decl = var;
        name->type = var->type;
        if (!ctx.inAssignment) {
          diags.error(loc, "index variable '" + var->name +
                               "' is not allowed outside an assignment");
          ok = false;
        } else if (ctx.inIndexPosition) {
          diags.error(loc, "index variable '" + var->name +
                               "' cannot be used in a nested read");
          ok = false;
        } else if (slice) {
          diags.error(loc, "index variables cannot be mixed with slices");
          ok = false;
        } else {
          ctx.ivarsSeen.insert(var);
          std::vector<Dim> range = base->hierarchy(i);
          auto [it, inserted] = ctx.ivarRanges.emplace(var, range);
          if (!inserted && it->second.front() != range.front()) {
            diags.error(loc, "index variable '" + var->name +
                                 "' ranges over '" + range.front().str() +
                                 "' here but over '" +
                                 it->second.front().str() + "' elsewhere");
            ok = false;
          }
        }
        continue;
      }
    }
    bool saved = ctx.inIndexPosition;
    ctx.inIndexPosition = true;
    ok &= checkIndex(index, base->dims[i], loc);
    ctx.inIndexPosition = saved;
  }
  if (!ok)
    return Type::error();
  if (!slice)
    return base->block ? base->block : Type::scalar(base->component);
  bool row = base->row;
  if (kept.size() == 1 && read.indices.size() >= 2)
    row = read.indices[read.indices.size() - 2] != nullptr;
  return Type::tensor(base->component, kept, base->block, row);
}

TypePtr Sema::checkTupleRead(TupleReadExpr &read) {
  TypePtr base = checkExpr(read.base);
  if (base->isError())
    return base;
  if (!base->isTuple()) {
    diags.error(read.loc, "'" + base->str() + "' is not a tuple");
    return Type::error();
  }
  if (!read.member.empty()) {
    if (base->memberNames.empty()) {
      diags.error(read.loc, "an unnamed tuple is read by index, as t(0)");
      return Type::error();
    }
    for (size_t i = 0; i < base->memberNames.size(); ++i)
      if (base->memberNames[i] == read.member)
        read.memberIndex = i;
    if (read.memberIndex < 0) {
      diags.error(read.loc, "undefined tuple member '" + read.member + "'");
      return Type::error();
    }
  } else {
    if (!base->memberNames.empty()) {
      diags.error(read.loc, "a named tuple is read by member name, as t.a");
      return Type::error();
    }
    bool saved = ctx.inIndexPosition;
    ctx.inIndexPosition = true;
    TypePtr index = checkExpr(read.index);
    ctx.inIndexPosition = saved;
    if (index->isError())
      return index;
    if (!index->isScalar(ScalarKind::Int)) {
      diags.error(read.index->loc, "tuple index must be an int, found '" +
                                       index->str() + "'");
      return Type::error();
    }
    if (auto *lit = dyn_cast<IntLiteral>(read.index.get())) {
      if (lit->value < 0 || lit->value >= (int64_t)base->members.size()) {
        diags.error(read.index->loc,
                    "tuple index " + std::to_string(lit->value) +
                        " is out of range for a tuple of " +
                        std::to_string(base->members.size()));
        return Type::error();
      }
      read.memberIndex = lit->value;
    }
  }
  size_t member = read.memberIndex < 0 ? 0 : read.memberIndex;
  return Type::elementOf(base->members[member]);
}

TypePtr Sema::checkField(ExprPtr &expr) {
  auto &field = cast<FieldExpr>(*expr);
  if (auto *name = dyn_cast<NameExpr>(field.base.get());
      name && !name->parenthesized) {
    auto *var = dyn_cast_or_null<VarDecl>(lookupVariable(name->name));
    if (var && var->type && var->type->isTuple()) {
      auto tuple = std::make_unique<TupleReadExpr>(field.loc,
                                                   std::move(field.base));
      tuple->member = field.field;
      expr = std::move(tuple);
      return checkTupleRead(cast<TupleReadExpr>(*expr));
    }
  }
  TypePtr base = checkExpr(field.base);
  if (base->isError())
    return base;
  if (isa<ReadExpr, FieldExpr>(field.base.get())) {
    diags.error(field.fieldLoc, "a field access cannot follow an index or "
                                "another field unless reading a tuple");
    return Type::error();
  }
  const ElementDecl *element = nullptr;
  if (base->isSet() || base->isElement())
    element = base->element;
  if (!element) {
    diags.error(field.fieldLoc, "cannot read field '" + field.field +
                                    "' of a value of type '" + base->str() +
                                    "': not a set or element");
    return Type::error();
  }
  field.element = element;
  field.fieldIndex = element->fieldIndex(field.field);
  if (field.fieldIndex < 0) {
    diags.error(field.fieldLoc, "undefined field '" + field.field +
                                    "' of element type '" + element->name +
                                    "'");
    return Type::error();
  }
  TypePtr fieldType = element->fields[field.fieldIndex].type;
  if (!fieldType || fieldType->isError())
    return Type::error();
  if (base->isElement())
    return fieldType;
  field.isSetField = true;
  if (fieldType->order() > 1) {
    diags.error(field.fieldLoc, "only scalar and vector set fields can be "
                                "read as global vectors; '" + field.field +
                                    "' has type '" + fieldType->str() + "'");
    return Type::error();
  }
  const VarDecl *set = varOf(*field.base);
  if (!set)
    return Type::error();
  return Type::tensor(fieldType->component, {Dim::ofSet(set)},
                      fieldType->isScalar() ? nullptr : fieldType, false);
}

TypePtr Sema::checkSetRead(SetReadExpr &read) {
  const VarDecl *set = nullptr;
  if (auto *name = dyn_cast<NameExpr>(read.base.get())) {
    TypePtr t = checkExpr(read.base);
    if (t->isError())
      return t;
    if (t->isSet())
      set = cast<VarDecl>(name->decl);
  }
  auto checkInts = [&](std::vector<ExprPtr> &list) {
    bool ok = true;
    for (ExprPtr &e : list) {
      TypePtr t = checkExpr(e);
      if (!t->isError() && !t->isScalar(ScalarKind::Int)) {
        diags.error(e->loc, "grid offsets must be integral, found '" +
                                t->str() + "'");
        ok = false;
      }
    }
    return ok;
  };
  if (set && set->type->isGrid()) {
    unsigned rank = set->type->gridRank;
    if (!read.hasDirections || read.offsets.size() != rank ||
        read.directions.size() != rank) {
      diags.error(read.loc, "a read of grid '" + set->name + "' takes " +
                                std::to_string(2 * rank) +
                                " indices (offsets; direction)");
      return Type::error();
    }
    if (!checkInts(read.offsets) || !checkInts(read.directions))
      return Type::error();
    read.grid = set;
    return Type::elementOf(set->type->element, set);
  }
  if (set && ctx.func) {
    for (auto &p : ctx.func->params) {
      if (!p->type || !p->type->isGrid() || p->type->endpoints.front() != set)
        continue;
      unsigned rank = p->type->gridRank;
      if (read.hasDirections || read.offsets.size() != rank) {
        diags.error(read.loc, "a read of grid point set '" + set->name +
                                  "' takes " + std::to_string(rank) +
                                  " offsets");
        return Type::error();
      }
      if (!checkInts(read.offsets))
        return Type::error();
      read.grid = p.get();
      return Type::elementOf(set->type->element, set);
    }
  }
  diags.error(read.loc, "set reads '[...]' are only allowed on grids and on "
                        "the point set of a grid parameter");
  return Type::error();
}

//===----------------------------------------------------------------------===//
// Operators
//===----------------------------------------------------------------------===//

TypePtr Sema::checkUnary(ExprPtr &expr) {
  foldLiteral(expr);
  if (!isa<UnaryExpr>(expr.get()))
    return checkExpr(expr);
  auto &unary = cast<UnaryExpr>(*expr);
  TypePtr t = checkExpr(unary.operand);
  if (t->isError())
    return t;
  if (unary.op == UnaryExpr::Op::Not) {
    if (!t->isScalar(ScalarKind::Bool)) {
      diags.error(unary.loc, "'not' expects a boolean operand, found '" +
                                 t->str() + "'");
      return Type::error();
    }
    return t;
  }
  if (!t->isNumericTensor()) {
    diags.error(unary.loc, "numeric negation expects a numeric operand, "
                           "found '" + t->str() + "'");
    return Type::error();
  }
  return t;
}

static TypePtr vectorOver(ScalarKind component, const std::vector<Dim> &dims,
                          bool row, size_t level = 0) {
  TypePtr block = level + 1 < dims.size()
                      ? vectorOver(component, dims, row, level + 1)
                      : nullptr;
  return Type::tensor(component, {dims[level]}, block, row);
}

static TypePtr matrixOver(ScalarKind component, const std::vector<Dim> &rows,
                          const std::vector<Dim> &cols, size_t level = 0) {
  TypePtr block = level + 1 < rows.size() && level + 1 < cols.size()
                      ? matrixOver(component, rows, cols, level + 1)
                      : nullptr;
  return Type::tensor(component, {rows[level], cols[level]}, block, false);
}

TypePtr Sema::checkBinary(BinaryExpr &binary) {
  TypePtr a = checkExpr(binary.lhs);
  TypePtr b = checkExpr(binary.rhs);
  if (a->isError() || b->isError())
    return Type::error();
  const char *op = binaryOpSpelling(binary.op);
  if (binary.op == BinaryExpr::Op::Pow) {
    diags.error(binary.loc, "operator '^' is not supported yet");
    return Type::error();
  }
  if (binary.op == BinaryExpr::Op::And || binary.op == BinaryExpr::Op::Or ||
      binary.op == BinaryExpr::Op::Xor) {
    for (const TypePtr &t : {a, b})
      if (!t->isScalar(ScalarKind::Bool)) {
        diags.error(binary.loc, std::string("boolean operands expected for '") +
                                    op + "', found '" + t->str() + "'");
        return Type::error();
      }
    return a;
  }
  if (binary.op == BinaryExpr::Op::Add && a->isScalar(ScalarKind::String) &&
      b->isScalar(ScalarKind::String))
    return a;
  for (const TypePtr &t : {a, b})
    if (!t->isNumericTensor()) {
      diags.error(binary.loc, std::string("operand of '") + op +
                                  "' must be numeric, found '" + t->str() +
                                  "'");
      return Type::error();
    }
  if (a->component != b->component) {
    diags.error(binary.loc, std::string("incompatible tensor types '") +
                                a->str() + "' and '" + b->str() + "' for '" +
                                op + "'");
    return Type::error();
  }
  switch (binary.op) {
  case BinaryExpr::Op::Mul:
    return checkProduct(binary, a, b);
  case BinaryExpr::Op::Div:
    if (b->isScalar())
      return a;
    if (a->isScalar())
      return b;
    diags.error(binary.loc, "division requires a scalar operand; found '" +
                                a->str() + "' and '" + b->str() + "'");
    return Type::error();
  case BinaryExpr::Op::LeftDiv:
    if (!a->isMatrix() || !b->isColumnVector()) {
      diags.error(binary.loc, "'\\' solves a matrix and a column vector; "
                              "found '" + a->str() + "' and '" + b->str() +
                                  "'");
      return Type::error();
    }
    if (a->component == ScalarKind::Int) {
      diags.error(binary.loc, "'\\' solves systems of float or complex "
                              "components; found '" +
                                  a->str() + "'");
      return Type::error();
    }
    if (a->hierarchy(0) != b->hierarchy(0)) {
      diags.error(binary.loc, "dimension mismatch in '\\': '" + a->str() +
                                  "' and '" + b->str() + "'");
      return Type::error();
    }
    return vectorOver(a->component, a->hierarchy(1), false);
  default:
    break;
  }
  if (typesEqual(a, b))
    return a;
  if (a->isScalar())
    return b;
  if (b->isScalar())
    return a;
  diags.error(binary.loc, std::string("incompatible tensor types '") +
                              a->str() + "' and '" + b->str() + "' for '" +
                              op + "'");
  return Type::error();
}

TypePtr Sema::checkProduct(BinaryExpr &binary, const TypePtr &a,
                           const TypePtr &b) {
  using MK = BinaryExpr::MulKind;
  if (a->isScalar() || b->isScalar()) {
    binary.mulKind = MK::Scale;
    return a->isScalar() ? b : a;
  }
  auto fail = [&](const std::string &why) {
    diags.error(binary.loc, why + ": '" + a->str() + "' * '" + b->str() + "'");
    return Type::error();
  };
  if (a->order() > 2 || b->order() > 2)
    return fail("'*' is not defined for tensors of order 3 or more");
  auto mismatch = [&] { return fail("dimension mismatch in '*'"); };
  // A row of matrix blocks (A(p,:) of a blocked matrix, or A(:,q)') times a
  // vector sums the products of its blocks with the vector's: a vector of
  // the blocks' rows. Vectors of matrix blocks come only from slices.
  auto hasMatrixBlocks = [](const TypePtr &t) {
    return t->isVector() && t->block && t->block->isMatrix();
  };
  if (hasMatrixBlocks(a) || hasMatrixBlocks(b)) {
    if (!a->isRowVector() || !b->isColumnVector() || hasMatrixBlocks(b))
      return fail("a slice of a blocked matrix is multiplied only as "
                  "A(p,:) * x or A(:,q)' * x");
    std::vector<Dim> cols = a->block->hierarchy(1);
    cols.insert(cols.begin(), a->dims[0]);
    if (cols != b->hierarchy(0))
      return mismatch();
    binary.mulKind = MK::BlockRowVec;
    return vectorOver(a->component, a->block->hierarchy(0), false);
  }
  if (a->isRowVector() && b->isColumnVector()) {
    if (a->hierarchy(0) != b->hierarchy(0))
      return mismatch();
    binary.mulKind = MK::Inner;
    return Type::scalar(a->component);
  }
  if (a->isColumnVector() && b->isRowVector()) {
    binary.mulKind = MK::Outer;
    return matrixOver(a->component, a->hierarchy(0), b->hierarchy(0));
  }
  if (a->isMatrix() && b->isColumnVector()) {
    if (a->hierarchy(1) != b->hierarchy(0))
      return mismatch();
    binary.mulKind = MK::MatVec;
    return vectorOver(a->component, a->hierarchy(0), false);
  }
  if (a->isRowVector() && b->isMatrix()) {
    if (a->hierarchy(0) != b->hierarchy(0))
      return mismatch();
    binary.mulKind = MK::VecMat;
    return vectorOver(a->component, b->hierarchy(1), true);
  }
  if (a->isMatrix() && b->isMatrix()) {
    if (a->hierarchy(1) != b->hierarchy(0))
      return mismatch();
    binary.mulKind = MK::MatMat;
    return matrixOver(a->component, a->hierarchy(0), b->hierarchy(1));
  }
  if (a->isRowVector() && b->isRowVector())
    return fail("cannot multiply two row vectors");
  if (a->isColumnVector() && b->isColumnVector())
    return fail("cannot multiply two column vectors");
  if (a->isMatrix())
    return fail("cannot multiply a matrix by a row vector");
  return fail("cannot multiply a column vector by a matrix");
}

TypePtr Sema::checkCompare(CompareExpr &cmp) {
  std::vector<TypePtr> types;
  bool ok = true;
  for (ExprPtr &operand : cmp.operands) {
    types.push_back(checkExpr(operand));
    ok &= !types.back()->isError();
  }
  if (!ok)
    return Type::error();
  for (size_t i = 0; i < cmp.ops.size(); ++i) {
    const TypePtr &a = types[i], &b = types[i + 1];
    SMLoc loc = cmp.opLocs[i];
    for (const TypePtr &t : {a, b})
      if (!t->isScalar()) {
        diags.error(loc, std::string("operands of '") +
                             compareOpSpelling(cmp.ops[i]) +
                             "' must be scalars, found '" + t->str() + "'");
        return Type::error();
      }
    if (a->component != b->component) {
      diags.error(loc, std::string("cannot compare ") +
                           scalarKindName(a->component) + " and " +
                           scalarKindName(b->component));
      return Type::error();
    }
  }
  return Type::scalar(ScalarKind::Bool);
}

TypePtr Sema::checkTranspose(ExprPtr &expr) {
  foldLiteral(expr);
  if (!isa<TransposeExpr>(expr.get()))
    return checkExpr(expr);
  auto &transpose = cast<TransposeExpr>(*expr);
  TypePtr t = checkExpr(transpose.operand);
  if (t->isError())
    return t;
  if (!t->isTensor()) {
    diags.error(transpose.loc, "cannot transpose a value of type '" +
                                   t->str() + "'");
    return Type::error();
  }
  if (t->order() > 2) {
    diags.error(transpose.loc, "cannot transpose a tensor of order " +
                                   std::to_string(t->order()));
    return Type::error();
  }
  return transposed(t);
}

//===----------------------------------------------------------------------===//
// Element origins
//===----------------------------------------------------------------------===//

const VarDecl *Sema::originOf(const Expr &e,
                              std::optional<OriginKey> *key) const {
  auto inferred = [&](OriginKey k) -> const VarDecl * {
    if (key)
      *key = k;
    if (!ctx.func)
      return nullptr;
    auto it = ctx.func->inferredOrigins.find(k);
    return it == ctx.func->inferredOrigins.end() ? nullptr : it->second;
  };
  if (const VarDecl *var = varOf(e)) {
    if (var->type && var->type->isElement() && var->type->origin)
      return var->type->origin;
    if (var->role == VarDecl::Role::Param)
      return inferred({var, -1});
    return nullptr;
  }
  if (auto *tuple = dyn_cast<TupleReadExpr>(&e)) {
    const VarDecl *var = varOf(*tuple->base);
    if (!var || !var->type || !var->type->isTuple())
      return nullptr;
    if (var->role != VarDecl::Role::Param)
      return nullptr;
    if (var->type->memberNames.empty())
      return inferred({var, -1});
    if (tuple->memberIndex >= 0)
      return inferred({var, tuple->memberIndex});
    return nullptr;
  }
  if (auto *read = dyn_cast<SetReadExpr>(&e)) {
    if (read->type && read->type->isElement())
      return read->type->origin;
  }
  if (e.type && e.type->isElement())
    return e.type->origin;
  return nullptr;
}

std::vector<const VarDecl *> Sema::tupleOriginsOf(const Expr &e) const {
  std::vector<const VarDecl *> origins;
  const VarDecl *var = varOf(e);
  if (!var || !var->type || !var->type->isTuple())
    return origins;
  size_t n = var->type->members.size();
  bool named = !var->type->memberNames.empty();
  for (size_t i = 0; i < n; ++i) {
    const VarDecl *origin = nullptr;
    if (ctx.func) {
      auto it = ctx.func->inferredOrigins.find({var, named ? (int)i : -1});
      if (it != ctx.func->inferredOrigins.end())
        origin = it->second;
    }
    origins.push_back(origin);
  }
  return origins;
}
