//===- IndexProductsToMatMul.cpp - Matrix products written with ivars -----===//
//
// `C(i,j) = A(i,k) * B(k,j) + D(j,i)` (language.md 7.8) on system matrices
// sums, for each (i, j), over every k: the loops of an index expression
// cannot enumerate that sparsely, while simit.matmul composes the two
// patterns (a runtime-built product pattern). Each sum over one variable of
// the product of two system matrices, each indexed by it once, becomes an
// input `P(i,j)` with P = matmul(A, B) (operands transposed as their index
// lists say); the variable leaves the expression. On matrices of blocks a
// variable runs over the set and then the block's rows or columns, so the
// sum is the product of the matrices of scalars the blocks make up: that
// of the blocked matrices.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include <algorithm>

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITINDEXPRODUCTSTOMATMUL
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// A sum over `var` of the product of inputs `lhs` and `rhs`: the index
/// list of `lhs` is (row, var) or (var, row), that of `rhs` (var, col) or
/// (col, var).
struct IndexProduct {
  Operation *sum; // the simit.index_sum, or null: the whole body
  Operation *product;
  unsigned lhs, rhs;
  int64_t var, row, col;
};

/// Whether `type` is a matrix over two sets of scalars or of matrix
/// blocks (whose variables run over the set, then the block's rows or
/// columns).
bool isSystemMatrix(Type type) {
  auto tensor = dyn_cast<SystemTensorType>(type);
  return tensor && tensor.isSetMatrix() &&
         (tensor.getBlockShape().empty() || tensor.getBlockShape().size() == 2);
}

/// A matrix over (rows, cols) with `like`'s components, in blocks of
/// `block` (empty: scalars).
SystemTensorType matrixOf(SystemTensorType like, Attribute rows, Attribute cols,
                          ArrayRef<int64_t> block) {
  Type component = like.getComponentType();
  return SystemTensorType::get(
      like.getContext(), ArrayAttr::get(like.getContext(), {rows, cols}),
      block.empty() ? component : RankedTensorType::get(block, component));
}

/// The other variable of a two-variable index list containing `var` once.
std::optional<int64_t> otherVariable(ArrayRef<int64_t> list, int64_t var) {
  if (list.size() != 2 || llvm::count(list, var) != 1)
    return std::nullopt;
  return list[0] == var ? list[1] : list[0];
}

/// Whether `value` is the product of two inputs summed over `var` as
/// `IndexProduct` says; fills it.
bool matchProduct(IndexExprOp op, Value value, int64_t var,
                  IndexProduct &match) {
  Operation *product = value.getDefiningOp();
  if (!product || !isa<arith::MulFOp, arith::MulIOp>(product))
    return false;
  auto lhs = dyn_cast<BlockArgument>(product->getOperand(0));
  auto rhs = dyn_cast<BlockArgument>(product->getOperand(1));
  Block &body = op.getBody().front();
  if (!lhs || !rhs || lhs.getOwner() != &body || rhs.getOwner() != &body ||
      lhs == rhs || !lhs.hasOneUse() || !rhs.hasOneUse())
    return false;
  unsigned l = lhs.getArgNumber(), r = rhs.getArgNumber();
  std::optional<int64_t> row = otherVariable(op.getInputIndexList(l), var);
  std::optional<int64_t> col = otherVariable(op.getInputIndexList(r), var);
  if (!row || !col || *row == var || *col == var ||
      !isSystemMatrix(op.getInputs()[l].getType()) ||
      !isSystemMatrix(op.getInputs()[r].getType()))
    return false;
  // No other input may be indexed by the summed variable.
  for (unsigned i = 0, e = op.getInputs().size(); i < e; ++i)
    if (i != l && i != r && llvm::is_contained(op.getInputIndexList(i), var))
      return false;
  match = {nullptr, product, l, r, var, *row, *col};
  return true;
}

/// The first product of two system matrices summed over a variable in
/// `op`: in a simit.index_sum over that variable alone, or making up the
/// whole body with the one summed variable of the expression.
std::optional<IndexProduct> findProduct(IndexExprOp op) {
  std::optional<IndexProduct> found;
  op.getBody().walk([&](IndexSumOp sum) {
    if (found || sum.getVars().size() != 1)
      return;
    Value summand = sum.getBody().front().getTerminator()->getOperand(0);
    IndexProduct match;
    if (matchProduct(op, summand, sum.getVars()[0], match)) {
      match.sum = sum;
      found = match;
    }
  });
  if (found)
    return found;
  SmallVector<int64_t> summed;
  for (int64_t v = 0, e = op.getIndexVars().size(); v < e; ++v)
    if (!llvm::is_contained(op.getResultIndices(), v))
      summed.push_back(v);
  bool nested = !op.getBody().getOps<IndexSumOp>().empty();
  IndexProduct match;
  if (summed.size() == 1 && !nested &&
      matchProduct(op, op.getBody().front().getTerminator()->getOperand(0),
                   summed.front(), match))
    return match;
  return std::nullopt;
}

/// `value` as the matrix indexed (first, second) when `list` indexes it
/// (first, second) or (second, first).
Value oriented(OpBuilder &b, Location loc, Value value, ArrayRef<int64_t> list,
               int64_t first) {
  if (list[0] == first)
    return value;
  auto type = cast<SystemTensorType>(value.getType());
  SmallVector<int64_t> block = type.getBlockShape();
  std::reverse(block.begin(), block.end());
  return TransposeOp::create(
      b, loc, matrixOf(type, type.getDims()[1], type.getDims()[0], block),
      value);
}

/// Replaces `match` in `op` by an input P(row, col), P the product; returns
/// the new expression.
IndexExprOp rewrite(IndexExprOp op, const IndexProduct &match) {
  OpBuilder b(op);
  Location loc = op.getLoc();
  Value lhs = oriented(b, loc, op.getInputs()[match.lhs],
                       op.getInputIndexList(match.lhs), match.row);
  Value rhs = oriented(b, loc, op.getInputs()[match.rhs],
                       op.getInputIndexList(match.rhs), match.var);
  auto lhsType = cast<SystemTensorType>(lhs.getType());
  auto rhsType = cast<SystemTensorType>(rhs.getType());
  // Blocks of a x k times blocks of k x b are a x b.
  SmallVector<int64_t> block = lhsType.getBlockShape();
  if (!block.empty())
    block.back() = rhsType.getBlockShape().back();
  SystemTensorType productType =
      matrixOf(lhsType, lhsType.getDims()[0], rhsType.getDims()[1], block);
  Value product = MatMulOp::create(b, loc, productType, lhs, rhs);

  // Variables after the summed one move down by one.
  auto renumber = [&](int64_t v) { return v > match.var ? v - 1 : v; };
  SmallVector<Value> inputs;
  SmallVector<SmallVector<int64_t>> lists;
  for (unsigned i = 0, e = op.getInputs().size(); i < e; ++i) {
    if (i == match.lhs || i == match.rhs)
      continue;
    inputs.push_back(op.getInputs()[i]);
    lists.push_back(llvm::map_to_vector(op.getInputIndexList(i), renumber));
  }
  inputs.push_back(product);
  lists.push_back({renumber(match.row), renumber(match.col)});
  SmallVector<Attribute> vars, domains;
  for (int64_t v = 0, e = op.getIndexVars().size(); v < e; ++v)
    if (v != match.var) {
      vars.push_back(op.getIndexVars()[v]);
      domains.push_back(op.getDomains()[v]);
    }
  SmallVector<int64_t> result =
      llvm::map_to_vector(op.getResultIndices(), renumber);
  auto replacement =
      IndexExprOp::create(b, loc, op.getType(), inputs, b.getArrayAttr(vars),
                          b.getArrayAttr(domains), result, lists);

  // The body moves over: the product's argument replaces the sum (or the
  // product itself), the two factors' arguments go.
  Block &body = op.getBody().front();
  Value summed =
      match.sum ? match.sum->getResult(0) : match.product->getResult(0);
  BlockArgument productArg =
      body.addArgument(getComponentType(productType), loc);
  summed.replaceAllUsesWith(productArg);
  if (match.sum)
    match.sum->erase();
  else
    match.product->erase();
  body.eraseArguments([&](BlockArgument arg) {
    return arg.getArgNumber() == match.lhs || arg.getArgNumber() == match.rhs;
  });
  body.walk([&](IndexSumOp sum) {
    sum.setVars(llvm::map_to_vector(sum.getVars(), renumber));
  });
  replacement.getBody().getBlocks().clear();
  replacement.getBody().push_back(body.getParent()->getBlocks().remove(&body));
  op.replaceAllUsesWith(replacement.getResult());
  op.erase();
  return replacement;
}

struct IndexProductsToMatMul
    : public simit::impl::SimitIndexProductsToMatMulBase<
          IndexProductsToMatMul> {
  void runOnOperation() override {
    SmallVector<IndexExprOp> ops;
    getOperation().walk([&](IndexExprOp op) { ops.push_back(op); });
    // Each rewrite builds a new expression, which may hold another product.
    for (IndexExprOp op : ops)
      while (std::optional<IndexProduct> match = findProduct(op))
        op = rewrite(op, *match);
  }
};
} // namespace
