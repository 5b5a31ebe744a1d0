//===- IRGenStmt.cpp - Statements and assignment targets ------------------===//
//
// `var`s and results live in zero-initialised simit.alloc slots, so control
// flow needs no region results: `if` is scf.if (elif in the else region),
// `while` scf.while with the condition in the before-region, `do … end
// while` scf.while with the body and the condition in the before-region,
// `for i in a:b` scf.for over index casts, `for p in S` scf.for up to
// simit.set_size with simit.set_element.
//
// A range loop with constant bounds whose variable picks an endpoint
// (`v(i)`) is unrolled, so every endpoint is a constant simit.tuple_get:
// element functions may write results only at their element and endpoints,
// and the map verifier recognises endpoints by their simit.tuple_get.
//
//===----------------------------------------------------------------------===//

#include "IRGenImpl.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/SCF/IR/SCF.h"

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

//===----------------------------------------------------------------------===//
// AST walk
//===----------------------------------------------------------------------===//

static void walkExprs(const std::vector<ExprPtr> &exprs,
                      const ExprVisitor &visit) {
  for (const ExprPtr &e : exprs)
    walkExpr(e.get(), visit);
}

void frontend::walkExpr(const Expr *e, const ExprVisitor &visit) {
  if (!e)
    return;
  visit(*e);
  switch (e->getKind()) {
  case Expr::Kind::Call:
    walkExprs(cast<CallExpr>(e)->args, visit);
    break;
  case Expr::Kind::Read:
    walkExpr(cast<ReadExpr>(e)->base.get(), visit);
    walkExprs(cast<ReadExpr>(e)->indices, visit);
    break;
  case Expr::Kind::TupleRead:
    walkExpr(cast<TupleReadExpr>(e)->base.get(), visit);
    walkExpr(cast<TupleReadExpr>(e)->index.get(), visit);
    break;
  case Expr::Kind::Field:
    walkExpr(cast<FieldExpr>(e)->base.get(), visit);
    break;
  case Expr::Kind::SetRead:
    walkExpr(cast<SetReadExpr>(e)->base.get(), visit);
    walkExprs(cast<SetReadExpr>(e)->offsets, visit);
    walkExprs(cast<SetReadExpr>(e)->directions, visit);
    break;
  case Expr::Kind::Unary:
    walkExpr(cast<UnaryExpr>(e)->operand.get(), visit);
    break;
  case Expr::Kind::Binary:
    walkExpr(cast<BinaryExpr>(e)->lhs.get(), visit);
    walkExpr(cast<BinaryExpr>(e)->rhs.get(), visit);
    break;
  case Expr::Kind::Compare:
    walkExprs(cast<CompareExpr>(e)->operands, visit);
    break;
  case Expr::Kind::Transpose:
    walkExpr(cast<TransposeExpr>(e)->operand.get(), visit);
    break;
  case Expr::Kind::Map:
    walkExprs(cast<MapExpr>(e)->args, visit);
    break;
  default:
    break;
  }
}

static void walkBlock(const frontend::Block *block, const ExprVisitor &visit) {
  if (!block)
    return;
  for (const StmtPtr &stmt : block->stmts) {
    switch (stmt->getKind()) {
    case Stmt::Kind::VarDecl:
      walkExpr(cast<VarDeclStmt>(*stmt).var->init.get(), visit);
      break;
    case Stmt::Kind::Assign:
      walkExprs(cast<AssignStmt>(*stmt).targets, visit);
      walkExpr(cast<AssignStmt>(*stmt).value.get(), visit);
      break;
    case Stmt::Kind::Expr:
      walkExpr(cast<ExprStmt>(*stmt).expr.get(), visit);
      break;
    case Stmt::Kind::If: {
      auto &s = cast<IfStmt>(*stmt);
      walkExprs(s.conditions, visit);
      for (const auto &b : s.blocks)
        walkBlock(b.get(), visit);
      walkBlock(s.elseBlock.get(), visit);
      break;
    }
    case Stmt::Kind::While:
      walkExpr(cast<WhileStmt>(*stmt).condition.get(), visit);
      walkBlock(cast<WhileStmt>(*stmt).body.get(), visit);
      break;
    case Stmt::Kind::DoWhile:
      walkBlock(cast<DoWhileStmt>(*stmt).body.get(), visit);
      walkExpr(cast<DoWhileStmt>(*stmt).condition.get(), visit);
      break;
    case Stmt::Kind::For: {
      auto &s = cast<ForStmt>(*stmt);
      walkExpr(s.lower.get(), visit);
      walkExpr(s.upper.get(), visit);
      walkBlock(s.body.get(), visit);
      break;
    }
    case Stmt::Kind::Print:
      walkExprs(cast<PrintStmt>(*stmt).args, visit);
      break;
    case Stmt::Kind::Apply:
      walkExpr(cast<ApplyStmt>(*stmt).map.get(), visit);
      break;
    case Stmt::Kind::IVarDecl:
      break;
    }
  }
}

/// Whether `var` occurs in the position of a tuple read inside `body`.
/// Whether `var` picks an endpoint of a tuple (`v(i)`) or a grid offset
/// (`P[i]`) in `body`: these must be constants, so a loop over `var` with
/// constant bounds is unrolled.
static bool picksStatically(const frontend::Block &body, const VarDecl *var) {
  bool found = false;
  auto uses = [&](const Expr *expr) {
    if (expr)
      walkExpr(expr, [&](const Expr &inner) {
        if (auto *name = dyn_cast<NameExpr>(&inner))
          found |= name->decl == var;
      });
  };
  walkBlock(&body, [&](const Expr &e) {
    if (auto *read = dyn_cast<TupleReadExpr>(&e))
      uses(read->index.get());
    if (auto *read = dyn_cast<SetReadExpr>(&e)) {
      for (const ExprPtr &offset : read->offsets)
        uses(offset.get());
      for (const ExprPtr &direction : read->directions)
        uses(direction.get());
    }
  });
  return found;
}

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

void IRGenerator::genBlock(const frontend::Block &block) {
  for (const StmtPtr &stmt : block.stmts)
    genStmt(*stmt);
}

void IRGenerator::genStmt(const Stmt &stmt) {
  switch (stmt.getKind()) {
  case Stmt::Kind::VarDecl:
    genVarDecl(*cast<VarDeclStmt>(stmt).var);
    return;
  case Stmt::Kind::IVarDecl:
    return; // index variables only name loops of index expressions
  case Stmt::Kind::Assign: {
    auto &assign = cast<AssignStmt>(stmt);
    if (assign.isIndexExpr)
      genIndexAssign(assign);
    else
      genAssign(assign);
    return;
  }
  case Stmt::Kind::Expr:
    (void)genValues(*cast<ExprStmt>(stmt).expr);
    return;
  case Stmt::Kind::If:
    genIf(cast<IfStmt>(stmt), 0);
    return;
  case Stmt::Kind::While:
    genWhile(cast<WhileStmt>(stmt));
    return;
  case Stmt::Kind::DoWhile:
    genDoWhile(cast<DoWhileStmt>(stmt));
    return;
  case Stmt::Kind::For:
    genFor(cast<ForStmt>(stmt));
    return;
  case Stmt::Kind::Print:
    genPrint(cast<PrintStmt>(stmt));
    return;
  case Stmt::Kind::Apply:
    (void)genMap(*cast<ApplyStmt>(stmt).map);
    return;
  }
}

Value IRGenerator::allocSlot(const VarDecl &var) {
  mlir::Type type = convertType(var.type, var.loc);
  Value slot = dialect::AllocOp::create(builder, loc(var.loc),
                                      dialect::RefType::get(&context, type));
  bindings[&var] = {slot, /*isSlot=*/true};
  return slot;
}

Value IRGenerator::slotOf(const VarDecl &var, SMLoc where) {
  if (var.role == VarDecl::Role::Extern) {
    mlir::Type type = convertType(var.type, where);
    return dialect::ExternRefOp::create(builder, loc(where),
                                      dialect::RefType::get(&context, type),
                                      var.name);
  }
  auto it = bindings.find(&var);
  if (it != bindings.end() && it->second.isSlot)
    return it->second.value;
  return unsupported(where, "writing '" + var.name + "'",
                     dialect::RefType::get(&context,
                                         convertType(var.type, where)));
}

void IRGenerator::genVarDecl(const VarDecl &var) {
  mlir::Type type = convertType(var.type, var.loc);
  if (var.role == VarDecl::Role::Const) {
    // Constant literals take the declared shape (leading 1s may differ).
    std::optional<FoldedLiteral> literal = foldLiteral(*var.init);
    Value value = literal && !literal->shape.empty()
                      ? genConstant(*literal, type, var.init->loc)
                      : coerce(genExpr(*var.init), type, var.init->loc);
    bindings[&var] = {value, /*isSlot=*/false};
    return;
  }
  Value init = var.init ? genExpr(*var.init) : Value();
  Value slot = allocSlot(var);
  if (init)
    dialect::StoreOp::create(builder, loc(var.init->loc),
                           coerce(init, type, var.init->loc), slot);
}

void IRGenerator::genAssign(const AssignStmt &stmt) {
  SmallVector<Value> values = stmt.targets.size() == 1
                                  ? SmallVector<Value>{genExpr(*stmt.value)}
                                  : genValues(*stmt.value);
  if (values.size() != stmt.targets.size()) {
    unsupported(stmt.loc, "an assignment of " + Twine(values.size()) +
                              " values to " + Twine(stmt.targets.size()) +
                              " targets");
    return;
  }
  for (auto [target, value] : llvm::zip(stmt.targets, values)) {
    // In a function mapped with `reduce +` and `inout` extra arguments
    // (run as a map that stores), a write to a result adds.
    if (accumulatedResultOf(*target))
      value = genElementwise(BinaryExpr::Op::Add, genExpr(*target), value,
                             convertType(target->type, target->loc),
                             stmt.value->loc);
    writeTarget(*target, value, stmt.value->loc);
  }
}

void IRGenerator::writeTarget(const Expr &target, Value value, SMLoc where) {
  Location l = loc(target.loc);
  if (auto *name = dyn_cast<NameExpr>(&target)) {
    auto *var = cast<VarDecl>(name->decl);
    mlir::Type type = convertType(var->type, target.loc);
    if (var->role == VarDecl::Role::Implicit) {
      bindings[var] = {coerce(value, type, where), /*isSlot=*/false};
      return;
    }
    dialect::StoreOp::create(builder, l, coerce(value, type, where),
                           slotOf(*var, target.loc));
    return;
  }
  if (auto *field = dyn_cast<FieldExpr>(&target)) {
    Value base = genExpr(*field->base);
    if (field->isSetField)
      dialect::FieldWriteOp::create(builder, l, value, base, field->field);
    else
      dialect::ElemWriteOp::create(builder, l, value, base, field->field);
    return;
  }
  if (auto *read = dyn_cast<ReadExpr>(&target); read && !read->isSlice()) {
    // An endpoint picked by a computed position: one write per position.
    for (const ExprPtr &index : read->indices) {
      auto *pick = dyn_cast<TupleReadExpr>(index.get());
      if (!pick || !pick->index || endpointPositions.count(pick))
        continue;
      Value position = genExpr(*pick->index);
      if (constantInt(position))
        continue;
      writeAtEachEndpoint(*pick, position,
                          [&] { writeTarget(target, value, where); });
      return;
    }
    // Read the whole, replace the part, write the whole back.
    Value whole = genExpr(*read->base);
    SmallVector<Value> indices;
    for (const ExprPtr &index : read->indices)
      indices.push_back(genIndex(*index));
    Value part = coerce(value, convertType(target.type, target.loc), where);
    Value updated =
        dialect::InsertOp::create(builder, l, part, whole, indices);
    writeTarget(*read->base, updated, where);
    return;
  }
  unsupported(target.loc, "this assignment target");
}

void IRGenerator::writeAtEachEndpoint(const TupleReadExpr &pick,
                                      Value position,
                                      llvm::function_ref<void()> write) {
  // if position == 0 { write v(0) } else if ... else { write v(n-1) }: the
  // map verifier accepts writes at constant endpoints only.
  unsigned size = cast<dialect::TupleType>(
                      convertType(pick.base->type, pick.loc))
                      .size();
  // The last branch takes every other position: check it names one.
  checkEndpointPosition(position, size, pick.loc);
  OpBuilder::InsertionGuard guard(builder);
  Location l = loc(pick.loc);
  for (unsigned k = 0; k < size; ++k) {
    endpointPositions[&pick] = k;
    if (k + 1 == size) {
      write();
      break;
    }
    Value isK = arith::CmpIOp::create(builder, l, arith::CmpIPredicate::eq,
                                      position, intConstant(k, pick.loc));
    auto ifOp = scf::IfOp::create(builder, l, isK, /*withElseRegion=*/true);
    builder.setInsertionPoint(ifOp.thenBlock()->getTerminator());
    write();
    builder.setInsertionPoint(ifOp.elseBlock()->getTerminator());
  }
  endpointPositions.erase(&pick);
}

void IRGenerator::genIf(const IfStmt &stmt, size_t branch) {
  const Expr &condition = *stmt.conditions[branch];
  bool hasElse = branch + 1 < stmt.conditions.size() || stmt.elseBlock;
  Value c = genExpr(condition);
  auto ifOp = scf::IfOp::create(builder, loc(condition.loc), c, hasElse);
  OpBuilder::InsertionGuard guard(builder);
  builder.setInsertionPoint(ifOp.thenBlock()->getTerminator());
  genBlock(*stmt.blocks[branch]);
  if (!hasElse)
    return;
  builder.setInsertionPoint(ifOp.elseBlock()->getTerminator());
  if (branch + 1 < stmt.conditions.size())
    genIf(stmt, branch + 1);
  else
    genBlock(*stmt.elseBlock);
}

void IRGenerator::genWhile(const WhileStmt &stmt) {
  Location l = loc(stmt.loc);
  auto whileOp = scf::WhileOp::create(builder, l, TypeRange(), ValueRange());
  OpBuilder::InsertionGuard guard(builder);
  builder.createBlock(&whileOp.getBefore());
  Value c = genExpr(*stmt.condition);
  scf::ConditionOp::create(builder, loc(stmt.condition->loc), c,
                           ValueRange());
  builder.createBlock(&whileOp.getAfter());
  genBlock(*stmt.body);
  scf::YieldOp::create(builder, l);
}

void IRGenerator::genDoWhile(const DoWhileStmt &stmt) {
  Location l = loc(stmt.loc);
  auto whileOp = scf::WhileOp::create(builder, l, TypeRange(), ValueRange());
  OpBuilder::InsertionGuard guard(builder);
  builder.createBlock(&whileOp.getBefore());
  genBlock(*stmt.body);
  Value c = genExpr(*stmt.condition);
  scf::ConditionOp::create(builder, loc(stmt.condition->loc), c,
                           ValueRange());
  builder.createBlock(&whileOp.getAfter());
  scf::YieldOp::create(builder, l);
}

void IRGenerator::genFor(const ForStmt &stmt) {
  if (stmt.isRange()) {
    Value lower = genExpr(*stmt.lower);
    Value upper = genExpr(*stmt.upper);
    genRangeFor(stmt, lower, upper);
    return;
  }
  Dim domain = stmt.domainDim;
  if (domain.kind == Dim::Kind::Generic && currentFunc &&
      domain.generic->index < currentFunc->binding.size())
    domain = currentFunc->binding[domain.generic->index];
  if (domain.kind == Dim::Kind::Range) {
    Value lower = intConstant(0, stmt.domainLoc);
    Value upper = intConstant(domain.size, stmt.domainLoc);
    genRangeFor(stmt, lower, upper);
    return;
  }
  if (domain.kind != Dim::Kind::Set) {
    unsupported(stmt.domainLoc, "a loop over an unbound generic parameter");
    return;
  }
  Location l = loc(stmt.loc);
  Value set = genSet(domain.set, stmt.domainLoc);
  Value size = dialect::SetSizeOp::create(builder, loc(stmt.domainLoc), set);
  Value zero = indexConstant(0, stmt.loc);
  Value one = indexConstant(1, stmt.loc);
  auto forOp = scf::ForOp::create(builder, l, zero, size, one);
  OpBuilder::InsertionGuard guard(builder);
  builder.setInsertionPoint(forOp.getBody()->getTerminator());
  Value element = dialect::SetElementOp::create(builder, loc(stmt.var->loc), set,
                                              forOp.getInductionVar());
  bindings[stmt.var.get()] = {element, /*isSlot=*/false};
  genBlock(*stmt.body);
}

void IRGenerator::genRangeFor(const ForStmt &stmt, Value lower, Value upper) {
  std::optional<int64_t> lo = constantInt(lower), hi = constantInt(upper);
  if (lo && hi && picksStatically(*stmt.body, stmt.var.get())) {
    for (int64_t i = *lo; i < *hi; ++i) {
      bindings[stmt.var.get()] = {intConstant(i, stmt.var->loc), false};
      genBlock(*stmt.body);
    }
    return;
  }
  Location l = loc(stmt.loc);
  Value lowerIndex = toIndex(lower, stmt.loc);
  Value upperIndex = toIndex(upper, stmt.loc);
  Value one = indexConstant(1, stmt.loc);
  auto forOp = scf::ForOp::create(builder, l, lowerIndex, upperIndex, one);
  OpBuilder::InsertionGuard guard(builder);
  builder.setInsertionPoint(forOp.getBody()->getTerminator());
  Value i = arith::IndexCastOp::create(builder, loc(stmt.var->loc),
                                       builder.getI32Type(),
                                       forOp.getInductionVar());
  bindings[stmt.var.get()] = {i, /*isSlot=*/false};
  genBlock(*stmt.body);
}

void IRGenerator::genPrint(const PrintStmt &stmt) {
  SmallVector<Value> values;
  for (const ExprPtr &arg : stmt.args)
    values.push_back(genExpr(*arg));
  dialect::PrintOp::create(builder, loc(stmt.loc), values, stmt.newline);
}
