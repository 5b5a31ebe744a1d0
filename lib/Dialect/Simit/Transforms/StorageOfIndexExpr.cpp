//===- StorageOfIndexExpr.cpp - Storage of index expression results -------===//
//
// The body of an index expression with a matrix result C(i, j), read as a
// path expression: each matrix input is its storage, transposed when read
// as (j, i); a sum joins, a product of matrices read at the same (i, j)
// keeps the smaller storage, and a product of A(i, k) and B(k, j) over the
// one summed variable k composes them. Scalars, vectors and local tensors
// scale; added to a matrix they would fill every block, so the body must
// map zero to zero.
//
//===----------------------------------------------------------------------===//

#include "StorageAnalysis.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "llvm/ADT/TypeSwitch.h"

using namespace mlir;
using namespace mlir::simit;

namespace {
/// What a body value is, as far as the blocks it can be nonzero at go.
struct PathValue {
  enum class Kind {
    /// Zero everywhere.
    Zero,
    /// Not known to be zero anywhere (scalars, vectors, constants).
    Full,
    /// Zero outside the blocks of `encoding` at (i, j).
    AtResult,
    /// Zero outside `encoding` at (i, k), k the summed variable.
    Left,
    /// Zero outside `encoding` at (k, j).
    Right,
    /// No storage: `reason` says why.
    Unsupported
  };
  Kind kind;
  StorageAttr encoding;
  std::string reason;

  static PathValue of(Kind kind, StorageAttr encoding = {}) {
    return {kind, encoding, {}};
  }
  static PathValue error(const Twine &why) {
    return {Kind::Unsupported, {}, why.str()};
  }
};
using Kind = PathValue::Kind;
} // namespace

/// The storage of an element-wise product: the smaller of two storages
/// when one contains the other; otherwise their join, which holds every
/// nonzero of the product (their intersection has no encoding).
static PathValue meet(Kind kind, StorageAttr a, StorageAttr b) {
  if (storage::contains(a, b))
    return PathValue::of(kind, b);
  if (storage::contains(b, a))
    return PathValue::of(kind, a);
  return PathValue::of(kind, storage::join(a, b));
}

static PathValue sum(const PathValue &a, const PathValue &b) {
  if (a.kind == Kind::Unsupported || b.kind == Kind::Zero)
    return a;
  if (b.kind == Kind::Unsupported || a.kind == Kind::Zero)
    return b;
  if (a.kind == Kind::Full || b.kind == Kind::Full)
    return PathValue::of(Kind::Full);
  if (a.kind != b.kind)
    return PathValue::error("cannot add terms of a summed product and terms "
                            "without it");
  return PathValue::of(a.kind, storage::join(a.encoding, b.encoding));
}

static PathValue product(const PathValue &a, const PathValue &b) {
  if (a.kind == Kind::Unsupported)
    return a;
  if (b.kind == Kind::Unsupported)
    return b;
  if (a.kind == Kind::Zero || b.kind == Kind::Zero)
    return PathValue::of(Kind::Zero);
  if (a.kind == Kind::Full)
    return b;
  if (b.kind == Kind::Full)
    return a;
  if (a.kind == b.kind)
    return meet(a.kind, a.encoding, b.encoding);
  if (a.kind == Kind::Left && b.kind == Kind::Right)
    return PathValue::of(Kind::AtResult,
                         storage::product({a.encoding, b.encoding}));
  if (a.kind == Kind::Right && b.kind == Kind::Left)
    return PathValue::of(Kind::AtResult,
                         storage::product({b.encoding, a.encoding}));
  return PathValue::error("cannot multiply a matrix read at (i, j) with one "
                          "read along the summed variable");
}

/// The storage of a quotient: the dividend's, where the divisor stores
/// every block of it (elsewhere the quotient is no number).
static PathValue quotient(const PathValue &a, const PathValue &b) {
  if (a.kind == Kind::Unsupported || b.kind == Kind::Full ||
      a.kind == Kind::Zero)
    return a;
  if (b.kind == Kind::Unsupported)
    return b;
  if (a.kind == Kind::AtResult && b.kind == Kind::AtResult &&
      storage::contains(b.encoding, a.encoding))
    return a;
  return PathValue::error("a division by a matrix component that does not "
                          "store every block of the dividend has no "
                          "storage");
}

/// How input `i` is read: its storage oriented to the result's (i, j), or
/// to (i, k) / (k, j) for the summed variable k.
static PathValue readInput(IndexExprOp op, unsigned i, StorageAttr encoding,
                           std::optional<int64_t> summed) {
  if (!encoding)
    return PathValue::of(Kind::Full);
  ArrayRef<int64_t> result = op.getResultIndices();
  ArrayRef<int64_t> list = op.getInputIndexList(i);
  int64_t r = result[0], c = result[1], a = list[0], b = list[1];
  if (a == r && b == c)
    return PathValue::of(Kind::AtResult, encoding);
  if (a == c && b == r)
    return PathValue::of(Kind::AtResult, storage::transpose(encoding));
  if (summed && a == r && b == *summed)
    return PathValue::of(Kind::Left, encoding);
  if (summed && a == *summed && b == r)
    return PathValue::of(Kind::Left, storage::transpose(encoding));
  if (summed && a == *summed && b == c)
    return PathValue::of(Kind::Right, encoding);
  if (summed && a == c && b == *summed)
    return PathValue::of(Kind::Right, storage::transpose(encoding));
  return PathValue::error("input #" + Twine(i) +
                          " is read along indices no storage rule knows");
}

/// Whether `op` is a constant zero.
static bool isZeroConstant(Operation *op) {
  auto constant = dyn_cast<arith::ConstantOp>(op);
  if (!constant)
    return false;
  if (auto f = dyn_cast<FloatAttr>(constant.getValue()))
    return f.getValue().isZero();
  if (auto n = dyn_cast<IntegerAttr>(constant.getValue()))
    return n.getValue().isZero();
  return false;
}

StorageRule mlir::simit::getIndexExprStorage(IndexExprOp op,
                                             ArrayRef<StorageAttr> inputs) {
  ArrayRef<int64_t> result = op.getResultIndices();
  SmallVector<int64_t> summed;
  for (int64_t v = 0, e = op.getIndexVars().size(); v < e; ++v)
    if (!llvm::is_contained(result, v))
      summed.push_back(v);
  if (summed.size() > 1)
    return StorageRule::error("an index expression with a matrix result and "
                              "more than one summed variable has no storage");
  std::optional<int64_t> k;
  if (!summed.empty())
    k = summed.front();

  Block &body = op.getBody().front();
  DenseMap<Value, PathValue> values;
  for (auto [i, arg] : llvm::enumerate(body.getArguments()))
    values[arg] = readInput(op, i, inputs[i], k);
  auto valueOf = [&](Value v) {
    auto it = values.find(v);
    // Values from outside the body are scalars.
    return it == values.end() ? PathValue::of(Kind::Full) : it->second;
  };
  for (Operation &inner : body.without_terminator()) {
    if (inner.getNumResults() != 1)
      return StorageRule::error("'" + inner.getName().getStringRef() +
                                "' in the body has no storage rule");
    SmallVector<PathValue> operands =
        llvm::map_to_vector(inner.getOperands(), valueOf);
    PathValue value =
        TypeSwitch<Operation *, PathValue>(&inner)
            .Case<arith::AddFOp, arith::SubFOp, arith::AddIOp, arith::SubIOp,
                  complex::AddOp, complex::SubOp>(
                [&](auto) { return sum(operands[0], operands[1]); })
            .Case<arith::MulFOp, arith::MulIOp, complex::MulOp>(
                [&](auto) { return product(operands[0], operands[1]); })
            .Case<arith::DivFOp, arith::DivSIOp, complex::DivOp>(
                [&](auto) { return quotient(operands[0], operands[1]); })
            // A comparison only chooses (select): its result is no
            // component, and the choice is nonzero where a choice is.
            .Case<arith::CmpFOp, arith::CmpIOp>(
                [&](auto) { return PathValue::of(Kind::Full); })
            .Case([&](arith::SelectOp) {
              return sum(operands[1], operands[2]);
            })
            .Case<arith::NegFOp, complex::NegOp>(
                [&](auto) { return operands[0]; })
            .Default([&](Operation *other) {
              if (isZeroConstant(other))
                return PathValue::of(Kind::Zero);
              if (llvm::all_of(operands, [](const PathValue &v) {
                    return v.kind == Kind::Full;
                  }))
                return PathValue::of(Kind::Full);
              return PathValue::error(
                  "'" + other->getName().getStringRef() +
                  "' of a matrix component does not keep zero blocks zero");
            });
    values[inner.getResult(0)] = value;
  }
  PathValue yielded = valueOf(body.getTerminator()->getOperand(0));
  switch (yielded.kind) {
  case Kind::Zero:
    return StorageRule::of(storage::empty(op.getContext()));
  case Kind::AtResult:
    return StorageRule::of(yielded.encoding);
  case Kind::Unsupported:
    return StorageRule::error(yielded.reason);
  case Kind::Full:
    // Nonzero outside the sparsity of its matrix operands (a scalar or an
    // outer product of vectors added to a sparse matrix): every block.
    return StorageRule::of(storage::dense(op.getContext()));
  case Kind::Left:
  case Kind::Right:
    return StorageRule::error("the summed variable of this index expression "
                              "does not join two matrices");
  }
  llvm_unreachable("path value kind");
}
