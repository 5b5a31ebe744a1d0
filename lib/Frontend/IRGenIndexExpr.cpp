//===- IRGenIndexExpr.cpp - Index expressions (ivar assignments) ----------===//
//
// `C(i,j) = A(i,k) * B(k,j) + D(j,i);` becomes one simit.index_expr over the
// variables (free ones first, each with the dimension hierarchy it indexes
// as its domain) whose inputs are the reads with index variables (a read
// with fixed indices, `A(i,0)`, is sliced first) and the scalar
// subexpressions without them, evaluated before it.
//
// A summed variable is summed over the smallest subexpression holding all
// its uses: over `A(i,k) * B(k,j)` above, so D is added once. Where that is
// the whole right side the variable is simply left out of the result (the
// index expression sums it); elsewhere the subexpression is wrapped in
// simit.index_sum.
//
// A target that repeats a variable or mixes in fixed indices (`B(i,i)`,
// `B(i,0)`) gets the value over its distinct variables, written component
// by component in a loop nest (integer-range variables only).
//
//===----------------------------------------------------------------------===//

#include "IRGenImpl.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/Dialect/SCF/IR/SCF.h"

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

namespace simit::frontend {
struct IndexExprState {
  SmallVector<const VarDecl *> vars;   // free, then summed
  SmallVector<ArrayAttr> domains;      // per variable, null until known
  SmallVector<Value> inputs;
  SmallVector<SmallVector<int64_t>> inputIndices;
  llvm::DenseMap<const Expr *, unsigned> inputOf;
  /// Subexpressions (not the whole right side) that sum variables.
  llvm::DenseMap<const Expr *, SmallVector<int64_t>> sumsAt;
  mlir::Type component;
  mlir::Block *body = nullptr;
  bool ok = true;

  int64_t indexOf(const VarDecl *var) const {
    return llvm::find(vars, var) - vars.begin();
  }
};
} // namespace simit::frontend

static const VarDecl *indexVarOf(const Expr *e) {
  auto *name = dyn_cast_or_null<NameExpr>(e);
  auto *var = name ? dyn_cast<VarDecl>(name->decl) : nullptr;
  return var && var->role == VarDecl::Role::IndexVar ? var : nullptr;
}

static bool hasIndexVar(const Expr &e) {
  bool found = false;
  walkExpr(&e, [&](const Expr &inner) { found |= indexVarOf(&inner) != nullptr; });
  return found;
}

static unsigned countUses(const Expr &e, const VarDecl *var) {
  unsigned count = 0;
  walkExpr(&e, [&](const Expr &inner) { count += indexVarOf(&inner) == var; });
  return count;
}

/// The operands an index expression body combines.
static SmallVector<const Expr *> operandsOf(const Expr &e) {
  if (auto *unary = dyn_cast<UnaryExpr>(&e))
    return {unary->operand.get()};
  if (auto *binary = dyn_cast<BinaryExpr>(&e))
    return {binary->lhs.get(), binary->rhs.get()};
  return {};
}

/// The type of `type` keeping only the dimensions marked in `kept`
/// (unblocked tensors).
static mlir::Type slicedType(mlir::Type type, ArrayRef<bool> kept) {
  if (auto tensor = dyn_cast<RankedTensorType>(type)) {
    SmallVector<int64_t> shape;
    for (auto [size, keep] : llvm::zip(tensor.getShape(), kept))
      if (keep)
        shape.push_back(size);
    return RankedTensorType::get(shape, tensor.getElementType());
  }
  auto system = dyn_cast<dialect::SystemTensorType>(type);
  if (!system || dialect::isTensorType(system.getBlockType()))
    return {};
  SmallVector<Attribute> dims;
  SmallVector<int64_t> shape;
  bool allRanges = true;
  for (auto [dim, keep] : llvm::zip(system.getDims(), kept)) {
    if (!keep)
      continue;
    dims.push_back(dim);
    if (auto size = dyn_cast<IntegerAttr>(dim))
      shape.push_back(size.getInt());
    else
      allRanges = false;
  }
  if (allRanges)
    return RankedTensorType::get(shape, system.getBlockType());
  return dialect::SystemTensorType::get(
      type.getContext(), ArrayAttr::get(type.getContext(), dims),
      system.getBlockType());
}

void IRGenerator::collectIndexInputs(const Expr &e, IndexExprState &state) {
  if (!hasIndexVar(e)) {
    // Computed once, before the index expression.
    Value value = genExpr(e);
    if (!dialect::isScalarType(value.getType())) {
      unsupported(e.loc, "a tensor without index variables inside an index "
                         "expression");
      state.ok = false;
      return;
    }
    state.inputOf[&e] = state.inputs.size();
    state.inputs.push_back(value);
    state.inputIndices.push_back({});
    return;
  }
  if (auto *read = dyn_cast<ReadExpr>(&e)) {
    if (hasIndexVar(*read->base) || read->isSlice()) {
      unsupported(e.loc, "this read inside an index expression");
      state.ok = false;
      return;
    }
    Value base = genExpr(*read->base);
    SmallVector<int64_t> indexList;
    SmallVector<Value> fixed;
    SmallVector<bool> kept;
    for (auto [pos, index] : llvm::enumerate(read->indices)) {
      const VarDecl *var = indexVarOf(index.get());
      kept.push_back(var != nullptr);
      if (!var) {
        fixed.push_back(genIndex(*index));
        continue;
      }
      int64_t v = state.indexOf(var);
      indexList.push_back(v);
      if (!state.domains[v])
        state.domains[v] = builder.getArrayAttr(
            dialect::getDimensionHierarchy(base.getType(), pos));
    }
    if (!fixed.empty()) {
      mlir::Type type = slicedType(base.getType(), kept);
      if (!type) {
        unsupported(e.loc, "fixed indices into a blocked tensor inside an "
                           "index expression");
        state.ok = false;
        return;
      }
      base = dialect::SliceOp::create(builder, loc(e.loc), type, base, fixed,
                                      kept);
    }
    state.inputOf[&e] = state.inputs.size();
    state.inputs.push_back(base);
    state.inputIndices.push_back(indexList);
    return;
  }
  SmallVector<const Expr *> operands = operandsOf(e);
  if (operands.empty()) {
    unsupported(e.loc, "this operation inside an index expression");
    state.ok = false;
    return;
  }
  for (const Expr *operand : operands)
    collectIndexInputs(*operand, state);
}

Value IRGenerator::genIndexBody(const Expr &e, IndexExprState &state) {
  auto sums = state.sumsAt.find(&e);
  if (sums == state.sumsAt.end())
    return genIndexBodyOp(e, state);
  auto sum = dialect::IndexSumOp::create(
      builder, loc(e.loc), state.component,
      builder.getDenseI64ArrayAttr(sums->second));
  OpBuilder::InsertionGuard guard(builder);
  builder.createBlock(&sum.getBody());
  Value summand = genIndexBodyOp(e, state);
  dialect::IndexSumYieldOp::create(builder, loc(e.loc), summand);
  return sum;
}

Value IRGenerator::genIndexBodyOp(const Expr &e, IndexExprState &state) {
  auto input = state.inputOf.find(&e);
  if (input != state.inputOf.end())
    return state.body->getArgument(input->second);
  if (auto *unary = dyn_cast<UnaryExpr>(&e)) {
    Value operand = genIndexBody(*unary->operand, state);
    if (unary->op != UnaryExpr::Op::Neg)
      return operand;
    if (isa<IntegerType>(operand.getType()))
      return arith::SubIOp::create(builder, loc(e.loc), intConstant(0, e.loc),
                                   operand);
    if (isa<ComplexType>(operand.getType()))
      return complex::NegOp::create(builder, loc(e.loc), operand);
    return arith::NegFOp::create(builder, loc(e.loc), operand);
  }
  auto &binary = cast<BinaryExpr>(e);
  Value a = genIndexBody(*binary.lhs, state);
  Value b = genIndexBody(*binary.rhs, state);
  return genElementwise(binary.op, a, b, state.component, e.loc);
}

void IRGenerator::genIndexAssign(const AssignStmt &stmt) {
  const Expr &target = *stmt.targets.front();
  const Expr &value = *stmt.value;
  if (accumulatedResultOf(target)) {
    unsupported(target.loc, "an index expression assigning a result in a "
                            "function mapped with reduce and inout extra "
                            "arguments");
    return;
  }
  IndexExprState state;
  for (const VarDecl *var : stmt.freeIndexVars)
    state.vars.push_back(var);
  for (const VarDecl *var : stmt.reductionIndexVars)
    state.vars.push_back(var);
  state.domains.resize(state.vars.size());

  // The result: its type and the variables of its dimensions.
  auto *targetRead = dyn_cast<ReadExpr>(&target);
  mlir::Type targetType = convertType(target.type, target.loc);
  SmallVector<int64_t> resultIndices;
  bool direct = true;
  if (targetRead) {
    targetType = convertType(targetRead->base->type, target.loc);
    for (auto [pos, index] : llvm::enumerate(targetRead->indices)) {
      const VarDecl *var = indexVarOf(index.get());
      if (!var) {
        direct = false;
        continue;
      }
      int64_t v = state.indexOf(var);
      if (llvm::is_contained(resultIndices, v)) {
        direct = false;
        continue;
      }
      resultIndices.push_back(v);
      state.domains[v] = builder.getArrayAttr(
          dialect::getDimensionHierarchy(targetType, pos));
    }
  }
  state.component = dialect::getComponentType(targetType);
  mlir::Type resultType = targetType;
  if (!direct) {
    // The value over the distinct variables: a dense tensor over ranges, a
    // system tensor over sets (`B(i,i) = 2.0 * A(i,i)` on a system matrix).
    SmallVector<int64_t> shape;
    SmallVector<Attribute> sets;
    for (int64_t v : resultIndices) {
      ArrayAttr domain = state.domains[v];
      Attribute dim = domain.size() == 1 ? domain[0] : Attribute();
      if (auto size = dyn_cast_or_null<IntegerAttr>(dim))
        shape.push_back(size.getInt());
      else if (isa_and_nonnull<StringAttr>(dim))
        sets.push_back(dim);
      else
        shape.push_back(ShapedType::kDynamic);
    }
    if (llvm::is_contained(shape, ShapedType::kDynamic) ||
        (!shape.empty() && !sets.empty())) {
      unsupported(target.loc, "a target with repeated index variables or "
                              "fixed indices over blocks, or over both sets "
                              "and ranges");
      return;
    }
    resultType =
        sets.empty()
            ? mlir::Type(RankedTensorType::get(shape, state.component))
            : mlir::Type(dialect::SystemTensorType::get(
                  &context, builder.getArrayAttr(sets), state.component));
  }

  collectIndexInputs(value, state);
  if (!state.ok)
    return;
  for (auto [v, domain] : llvm::enumerate(state.domains))
    if (!domain) {
      unsupported(stmt.loc, "index variable '" + state.vars[v]->name +
                                "' indexes no tensor dimension");
      return;
    }

  // Where each summed variable is summed.
  for (const VarDecl *var : stmt.reductionIndexVars) {
    unsigned total = countUses(value, var);
    const Expr *scope = &value;
    for (bool descended = true; descended;) {
      descended = false;
      for (const Expr *operand : operandsOf(*scope))
        if (countUses(*operand, var) == total) {
          scope = operand;
          descended = true;
          break;
        }
    }
    if (scope != &value)
      state.sumsAt[scope].push_back(state.indexOf(var));
  }

  // `s = K(i,i)` of a blocked K sums blocks: the value is a block whose
  // dimensions no variable names.
  if (dialect::getTensorOrder(resultType) != resultIndices.size()) {
    unsupported(target.loc, "an index expression whose value is a block of "
                            "a blocked tensor (its variables index the "
                            "blocks, not their components)");
    return;
  }
  SmallVector<Attribute> names, domains;
  for (auto [var, domain] : llvm::zip(state.vars, state.domains)) {
    names.push_back(builder.getStringAttr(var->name));
    domains.push_back(domain);
  }
  auto op = dialect::IndexExprOp::create(
      builder, loc(stmt.loc), resultType, state.inputs,
      builder.getArrayAttr(names), builder.getArrayAttr(domains),
      resultIndices, state.inputIndices);
  {
    OpBuilder::InsertionGuard guard(builder);
    state.body = &op.getBody().front();
    builder.setInsertionPointToEnd(state.body);
    Value result = genIndexBody(value, state);
    dialect::YieldOp::create(builder, loc(value.loc), result);
  }
  if (!direct) {
    writeIndexedTarget(*targetRead, op, state);
    return;
  }
  writeTarget(targetRead ? *targetRead->base : target, op, stmt.loc);
}

void IRGenerator::writeIndexedTarget(const ReadExpr &target, Value value,
                                     IndexExprState &state) {
  auto *name = dyn_cast<NameExpr>(target.base.get());
  if (!name) {
    unsupported(target.loc, "a partial index expression target that is not a "
                            "variable");
    return;
  }
  Value slot = slotOf(*cast<VarDecl>(name->decl), target.loc);
  // One loop per distinct variable, in the order of the value's dimensions.
  SmallVector<int64_t> distinct;
  for (const ExprPtr &index : target.indices)
    if (const VarDecl *var = indexVarOf(index.get());
        var && !llvm::is_contained(distinct, state.indexOf(var)))
      distinct.push_back(state.indexOf(var));
  OpBuilder::InsertionGuard guard(builder);
  Location l = loc(target.loc);
  SmallVector<Value> ivs;
  for (int64_t v : distinct) {
    // A set domain: a loop over its elements, which index the value and
    // the target.
    const VarDecl *set = nullptr;
    for (auto [pos, index] : llvm::enumerate(target.indices))
      if (indexVarOf(index.get()) == state.vars[v] &&
          pos < target.base->type->dims.size() &&
          target.base->type->dims[pos].kind == Dim::Kind::Set)
        set = target.base->type->dims[pos].set;
    Value setValue = set ? genSet(set, target.loc) : Value();
    Value lower = indexConstant(0, target.loc);
    Value upper =
        set ? dialect::SetSizeOp::create(builder, l, setValue).getResult()
            : indexConstant(cast<IntegerAttr>(state.domains[v][0]).getInt(),
                            target.loc);
    Value one = indexConstant(1, target.loc);
    auto loop = scf::ForOp::create(builder, l, lower, upper, one);
    builder.setInsertionPoint(loop.getBody()->getTerminator());
    ivs.push_back(set ? dialect::SetElementOp::create(builder, l, setValue,
                                                      loop.getInductionVar())
                            .getResult()
                      : loop.getInductionVar());
  }
  SmallVector<Value> indices;
  for (const ExprPtr &index : target.indices) {
    if (const VarDecl *var = indexVarOf(index.get()))
      indices.push_back(ivs[llvm::find(distinct, state.indexOf(var)) -
                            distinct.begin()]);
    else
      indices.push_back(genIndex(*index));
  }
  Value component =
      dialect::ExtractOp::create(builder, l, state.component, value, ivs);
  Value whole = dialect::LoadOp::create(builder, l, slot);
  Value updated =
      dialect::InsertOp::create(builder, l, component, whole, indices);
  dialect::StoreOp::create(builder, l, updated, slot);
}
