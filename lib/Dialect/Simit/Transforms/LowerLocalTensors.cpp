//===- LowerLocalTensors.cpp - Small dense tensors as flat vectors --------===//
//
// A local tensor (a builtin ranked tensor, or a `!simit.tensor` of integer
// dimensions) becomes a 1-D vector of its components in row-major order
// (blocks contiguous), so it stays an SSA value: loop-carried values, branches
// and value semantics need no buffers. Linear algebra on such tensors is
// unrolled over their (small, static) shapes; variables holding them are
// memref.alloca'd arrays of components. A complex component is stored as
// its (re, im) pair of floats (vectors cannot hold complex numbers), and
// arithmetic on complex components uses the complex dialect.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include "mlir/Dialect/ControlFlow/IR/ControlFlowOps.h"
#include "mlir/Dialect/Tensor/IR/Tensor.h"
#include "mlir/Dialect/Utils/StaticValueUtils.h"
#include "mlir/IR/Matchers.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

Value FunctionLowering::component(Type type, Value lowered, Value position) {
  if (!isa<VectorType>(lowered.getType()))
    return lowered;
  Location loc = lowered.getLoc();
  auto complex = dyn_cast<ComplexType>(getComponentType(type));
  if (!complex)
    return vector::ExtractOp::create(b, loc, lowered, OpFoldResult(position));
  Value rePosition = arith::MulIOp::create(b, loc, position, indexConstant(2));
  Value imPosition =
      arith::AddIOp::create(b, loc, rePosition, indexConstant(1));
  Value re =
      vector::ExtractOp::create(b, loc, lowered, OpFoldResult(rePosition));
  Value im =
      vector::ExtractOp::create(b, loc, lowered, OpFoldResult(imPosition));
  return complex::CreateOp::create(b, loc, complex, re, im);
}

Value FunctionLowering::component(Type type, Value lowered, int64_t position) {
  if (!isa<VectorType>(lowered.getType()))
    return lowered;
  Location loc = lowered.getLoc();
  auto complex = dyn_cast<ComplexType>(getComponentType(type));
  if (!complex)
    return vector::ExtractOp::create(b, loc, lowered,
                                     ArrayRef<int64_t>{position});
  Value re = vector::ExtractOp::create(b, loc, lowered,
                                       ArrayRef<int64_t>{2 * position});
  Value im = vector::ExtractOp::create(b, loc, lowered,
                                       ArrayRef<int64_t>{2 * position + 1});
  return complex::CreateOp::create(b, loc, complex, re, im);
}

Value FunctionLowering::insertComponent(Value lowered, Value scalar,
                                        Value position) {
  Location loc = lowered.getLoc();
  if (!isa<ComplexType>(scalar.getType()))
    return vector::InsertOp::create(b, loc, scalar, lowered,
                                    OpFoldResult(position));
  Value re = arith::MulIOp::create(b, loc, position, indexConstant(2));
  Value im = arith::AddIOp::create(b, loc, re, indexConstant(1));
  lowered = vector::InsertOp::create(
      b, loc, complex::ReOp::create(b, loc, scalar), lowered, OpFoldResult(re));
  return vector::InsertOp::create(b, loc, complex::ImOp::create(b, loc, scalar),
                                  lowered, OpFoldResult(im));
}

Value FunctionLowering::fromComponents(Type loweredType,
                                       ArrayRef<Value> components) {
  if (!isa<VectorType>(loweredType))
    return components.front();
  Location loc = function.getLoc();
  SmallVector<Value> numbers;
  for (Value c : components) {
    if (!isa<ComplexType>(c.getType())) {
      numbers.push_back(c);
      continue;
    }
    numbers.push_back(complex::ReOp::create(b, loc, c));
    numbers.push_back(complex::ImOp::create(b, loc, c));
  }
  return vector::FromElementsOp::create(b, loc, cast<VectorType>(loweredType),
                                        numbers);
}

namespace {
/// Scalar (or element-wise vector) arithmetic on floats and integers, and
/// scalar arithmetic on complex numbers.
struct Arith {
  OpBuilder &b;
  Location loc;

  Value add(Value x, Value y) {
    if (isa<ComplexType>(x.getType()))
      return complex::AddOp::create(b, loc, x, y);
    if (isa<FloatType>(getElementTypeOrSelf(x)))
      return arith::AddFOp::create(b, loc, x, y);
    return arith::AddIOp::create(b, loc, x, y);
  }
  Value sub(Value x, Value y) {
    if (isa<ComplexType>(x.getType()))
      return complex::SubOp::create(b, loc, x, y);
    if (isa<FloatType>(getElementTypeOrSelf(x)))
      return arith::SubFOp::create(b, loc, x, y);
    return arith::SubIOp::create(b, loc, x, y);
  }
  Value mul(Value x, Value y) {
    if (isa<ComplexType>(x.getType()))
      return complex::MulOp::create(b, loc, x, y);
    if (isa<FloatType>(getElementTypeOrSelf(x)))
      return arith::MulFOp::create(b, loc, x, y);
    return arith::MulIOp::create(b, loc, x, y);
  }
  Value div(Value x, Value y) {
    if (isa<ComplexType>(x.getType()))
      return complex::DivOp::create(b, loc, x, y);
    if (isa<FloatType>(getElementTypeOrSelf(x)))
      return arith::DivFOp::create(b, loc, x, y);
    return arith::DivSIOp::create(b, loc, x, y);
  }
  Value neg(Value x) {
    if (isa<ComplexType>(x.getType()))
      return complex::NegOp::create(b, loc, x);
    if (isa<FloatType>(getElementTypeOrSelf(x)))
      return arith::NegFOp::create(b, loc, x);
    Value zero = arith::ConstantOp::create(b, loc, b.getZeroAttr(x.getType()));
    return arith::SubIOp::create(b, loc, zero, x);
  }
  /// 1 of a float or complex type.
  Value one(Type type) {
    if (auto complex = dyn_cast<ComplexType>(type)) {
      Type part = complex.getElementType();
      return complex::ConstantOp::create(
          b, loc, complex,
          b.getArrayAttr(
              {b.getFloatAttr(part, 1.0), b.getFloatAttr(part, 0.0)}));
    }
    return arith::ConstantOp::create(b, loc, b.getFloatAttr(type, 1.0));
  }
};
} // namespace

/// The components of the lowered value of the local value `original`.
static SmallVector<Value> allComponents(FunctionLowering &l, Value original) {
  SmallVector<Value> components;
  Value lowered = l.lookup(original);
  int64_t n = numComponents(original.getType());
  for (int64_t i = 0; i < n; ++i)
    components.push_back(l.component(original.getType(), lowered, i));
  return components;
}

/// The lowered local tensor of type `type` whose components all equal the
/// scalar `scalar`.
static Value broadcast(FunctionLowering &l, Location loc, Type loweredType,
                       Type type, Value scalar) {
  if (!isa<ComplexType>(scalar.getType()))
    return vector::BroadcastOp::create(l.b, loc, loweredType, scalar);
  return l.fromComponents(loweredType,
                          SmallVector<Value>(numComponents(type), scalar));
}

/// The determinant of the n x n matrix of components `m` (row major), by
/// cofactor expansion along the first row (n <= 4).
static Value determinant(Arith &a, ArrayRef<Value> m, int64_t n) {
  if (n == 1)
    return m[0];
  if (n == 2)
    return a.sub(a.mul(m[0], m[3]), a.mul(m[1], m[2]));
  Value det;
  for (int64_t col = 0; col < n; ++col) {
    SmallVector<Value> minor;
    for (int64_t r = 1; r < n; ++r)
      for (int64_t c = 0; c < n; ++c)
        if (c != col)
          minor.push_back(m[r * n + c]);
    Value term = a.mul(m[col], determinant(a, minor, n - 1));
    det = !det ? term : (col % 2 ? a.sub(det, term) : a.add(det, term));
  }
  return det;
}

/// The inverse of the n x n matrix `m`: the adjugate over the determinant.
static SmallVector<Value> inverse(Arith &a, ArrayRef<Value> m, int64_t n) {
  Value inverseDet = a.div(a.one(m[0].getType()), determinant(a, m, n));
  SmallVector<Value> result(n * n);
  for (int64_t r = 0; r < n; ++r)
    for (int64_t c = 0; c < n; ++c) {
      // inv(c, r) = (-1)^(r+c) det(minor without row r, column c) / det.
      SmallVector<Value> minor;
      for (int64_t i = 0; i < n; ++i)
        for (int64_t j = 0; j < n; ++j)
          if (i != r && j != c)
            minor.push_back(m[i * n + j]);
      Value cofactor =
          n == 1 ? a.one(m[0].getType()) : determinant(a, minor, n - 1);
      if ((r + c) % 2)
        cofactor = a.neg(cofactor);
      result[c * n + r] = a.mul(cofactor, inverseDet);
    }
  return result;
}

/// Whether `index` is the variable of a loop `for i in a:b` with 0 <= a and
/// b <= size (the common case of element functions), so that it needs no
/// check.
static bool isLoopVariableBelow(Value index, int64_t size) {
  // Casts between int and index keep the loop's small values.
  while (auto cast = index.getDefiningOp<arith::IndexCastOp>())
    index = cast.getIn();
  auto loop = scf::getForInductionVarOwner(index);
  if (!loop)
    return false;
  std::optional<int64_t> lower = getConstantIntValue(loop.getLowerBound());
  std::optional<int64_t> upper = getConstantIntValue(loop.getUpperBound());
  std::optional<int64_t> step = getConstantIntValue(loop.getStep());
  return lower && upper && step && *lower >= 0 && *upper <= size && *step > 0;
}

/// The flat offset of the block at `indices` (one per outer dimension) of a
/// local tensor, in components. A dynamic index is asserted to lie in its
/// dimension: out of range, a flat vector would read a neighbouring
/// component or poison without a word. Loop variables within the dimension
/// need no check, nor constants within it; a constant outside it (a folded
/// `const` or scene constant: the frontend checks literals) fails the same
/// way when it runs, and addresses component 0 meanwhile.
static Value blockOffset(FunctionLowering &l, Location loc, Type type,
                         ValueRange indices) {
  SmallVector<int64_t> outer;
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    outer.assign(tensor.getShape().begin(), tensor.getShape().end());
  else
    for (Attribute dim : cast<SystemTensorType>(type).getDims())
      outer.push_back(cast<IntegerAttr>(dim).getInt());
  int64_t blockSize = numComponents(getBlockType(type));
  Value offset = l.indexConstant(0);
  for (auto [d, originalIndex] : llvm::enumerate(indices)) {
    Value index = originalIndex;
    std::optional<int64_t> constant = getConstantIntValue(index);
    bool outside = constant && (*constant < 0 || *constant >= outer[d]);
    if (outside || (!constant && !isLoopVariableBelow(index, outer[d]))) {
      // One unsigned compare also rejects negative indices.
      Value inRange = arith::CmpIOp::create(l.b, loc, arith::CmpIPredicate::ult,
                                            index, l.indexConstant(outer[d]));
      cf::AssertOp::create(l.b, loc, inRange,
                           "index out of range for a dimension of size " +
                               std::to_string(outer[d]) +
                               sourcePositionSuffix(loc));
    }
    if (outside)
      index = l.indexConstant(0);
    int64_t stride = blockSize;
    for (int64_t e = d + 1; e < static_cast<int64_t>(outer.size()); ++e)
      stride *= outer[e];
    Value scaled = arith::MulIOp::create(l.b, loc, index,
                                         l.indexConstant(stride));
    offset = arith::AddIOp::create(l.b, loc, offset, scaled);
  }
  return offset;
}

/// The shapes of the levels of a local tensor, outermost first: a builtin
/// ranked tensor has one level; a `!simit.tensor` of integer dimensions has
/// its dimensions followed by its block's levels. Scalars have none.
static SmallVector<SmallVector<int64_t>> levelShapes(Type type) {
  SmallVector<SmallVector<int64_t>> levels;
  while (true) {
    if (auto tensor = dyn_cast<RankedTensorType>(type)) {
      levels.emplace_back(tensor.getShape());
      return levels;
    }
    auto system = dyn_cast<SystemTensorType>(type);
    if (!system)
      return levels;
    SmallVector<int64_t> shape;
    for (Attribute dim : system.getDims())
      shape.push_back(cast<IntegerAttr>(dim).getInt());
    levels.push_back(shape);
    type = system.getBlockType();
  }
}

/// The flat position of a component of a blocked tensor whose levels are
/// (rows_l x cols_l) (a vector level has cols_l = 1), given its row and
/// column digits per level (blocks contiguous, row-major within a level).
static int64_t hierarchicalOffset(ArrayRef<int64_t> rows,
                                  ArrayRef<int64_t> cols,
                                  ArrayRef<int64_t> row,
                                  ArrayRef<int64_t> col) {
  int64_t offset = 0;
  for (size_t l = 0; l < rows.size(); ++l)
    offset = offset * rows[l] * cols[l] + row[l] * cols[l] + col[l];
  return offset;
}

/// The digits of `flat` in the mixed radix `radices` (most significant
/// first).
static SmallVector<int64_t> digits(int64_t flat, ArrayRef<int64_t> radices) {
  SmallVector<int64_t> result(radices.size());
  for (int64_t l = radices.size() - 1; l >= 0; --l) {
    result[l] = flat % radices[l];
    flat /= radices[l];
  }
  return result;
}

// The storage positions of a local tensor's components in row-major
// order (LoopsLowering.h).
std::optional<SmallVector<int64_t>>
mlir::simit::loops::unblockedOrder(Type type, SmallVector<int64_t> &shape) {
  SmallVector<SmallVector<int64_t>> levels = levelShapes(type);
  shape.clear();
  if (levels.empty())
    return SmallVector<int64_t>{0};
  size_t rank = levels[0].size();
  SmallVector<int64_t> rows, cols;
  for (ArrayRef<int64_t> level : levels) {
    if (level.size() != rank || rank > 2)
      return std::nullopt;
    rows.push_back(level[0]);
    cols.push_back(rank == 2 ? level[1] : 1);
  }
  int64_t m = 1, n = 1;
  for (auto [r, c] : llvm::zip(rows, cols)) {
    m *= r;
    n *= c;
  }
  shape.push_back(m);
  if (rank == 2)
    shape.push_back(n);
  SmallVector<int64_t> order;
  for (int64_t i = 0; i < m; ++i)
    for (int64_t j = 0; j < n; ++j)
      order.push_back(
          hierarchicalOffset(rows, cols, digits(i, rows), digits(j, cols)));
  return order;
}

/// Unrolls matvec, matmul and transpose on blocked local tensors: their
/// dimensions are hierarchies (outer x block), so a row index of a blocked
/// matrix is one digit per level. Every level of every operand must have the
/// rank of the leaf level (all matrices, or all vectors).
static LogicalResult lowerBlockedLinalg(FunctionLowering &l, Arith &a,
                                        Operation *op,
                                        SmallVector<Value> &result) {
  auto fail = [&]() {
    return op->emitError("'")
           << op->getName()
           << "' on blocked local tensors of mixed block ranks is not "
              "supported";
  };
  auto levelsOf = [&](Value v, unsigned rank, SmallVector<int64_t> &rows,
                      SmallVector<int64_t> &cols) -> bool {
    for (ArrayRef<int64_t> shape : levelShapes(v.getType())) {
      if (shape.size() != rank)
        return false;
      rows.push_back(shape[0]);
      cols.push_back(rank == 2 ? shape[1] : 1);
    }
    return !rows.empty();
  };
  SmallVector<int64_t> ar, ac;
  if (!levelsOf(op->getOperand(0), 2, ar, ac))
    return fail();
  if (isa<TransposeOp>(op)) {
    SmallVector<Value> x = allComponents(l, op->getOperand(0));
    int64_t m = 1, n = 1;
    for (size_t k = 0; k < ar.size(); ++k) {
      m *= ar[k];
      n *= ac[k];
    }
    result.resize(m * n);
    for (int64_t i = 0; i < m; ++i)
      for (int64_t j = 0; j < n; ++j) {
        SmallVector<int64_t> id = digits(i, ar), jd = digits(j, ac);
        result[hierarchicalOffset(ac, ar, jd, id)] =
            x[hierarchicalOffset(ar, ac, id, jd)];
      }
    return success();
  }
  bool isMatVec = isa<MatVecOp>(op);
  SmallVector<int64_t> br, bc;
  if (!levelsOf(op->getOperand(1), isMatVec ? 1 : 2, br, bc) ||
      br.size() != ar.size() || br != ac)
    return fail();
  SmallVector<Value> x = allComponents(l, op->getOperand(0)),
                     y = allComponents(l, op->getOperand(1));
  int64_t m = 1, k = 1, n = 1;
  for (size_t d = 0; d < ar.size(); ++d) {
    m *= ar[d];
    k *= ac[d];
    n *= bc[d];
  }
  result.resize(m * n);
  for (int64_t i = 0; i < m; ++i)
    for (int64_t j = 0; j < n; ++j) {
      SmallVector<int64_t> id = digits(i, ar), jd = digits(j, bc);
      Value sum;
      for (int64_t p = 0; p < k; ++p) {
        SmallVector<int64_t> pd = digits(p, ac);
        Value t = a.mul(x[hierarchicalOffset(ar, ac, id, pd)],
                        y[hierarchicalOffset(br, bc, pd, jd)]);
        sum = sum ? a.add(sum, t) : t;
      }
      result[hierarchicalOffset(ar, bc, id, jd)] = sum;
    }
  return success();
}

LogicalResult FunctionLowering::lowerLocalOp(Operation *op, bool &handled) {
  handled = true;
  Location loc = op->getLoc();
  Arith a{b, loc};
  auto resultType = [&]() { return convertType(op->getResult(0).getType()); };
  auto operand = [&](unsigned i) { return lookup(op->getOperand(i)); };

  // The tensor dialect's element access, on flat vectors.
  if (auto from = dyn_cast<tensor::FromElementsOp>(op)) {
    SmallVector<Value> components;
    for (Value element : from.getElements())
      components.push_back(lookup(element));
    map(from, fromComponents(resultType(), components));
    return success();
  }
  if (auto extract = dyn_cast<tensor::ExtractOp>(op)) {
    Value offset = blockOffset(*this, loc, extract.getTensor().getType(),
                               llvm::to_vector(llvm::map_range(
                                   extract.getIndices(),
                                   [&](Value v) { return lookup(v); })));
    map(extract, component(extract.getTensor().getType(),
                           lookup(extract.getTensor()), offset));
    return success();
  }
  if (auto insert = dyn_cast<tensor::InsertOp>(op)) {
    Value offset = blockOffset(*this, loc, insert.getDest().getType(),
                               llvm::to_vector(llvm::map_range(
                                   insert.getIndices(),
                                   [&](Value v) { return lookup(v); })));
    map(insert, insertComponent(lookup(insert.getDest()),
                                lookup(insert.getScalar()), offset));
    return success();
  }
  if (auto splat = dyn_cast<tensor::SplatOp>(op)) {
    map(splat, broadcast(*this, loc, resultType(), splat.getType(),
                         lookup(splat.getInput())));
    return success();
  }
  if (op->getDialect() == op->getContext()->getLoadedDialect("tensor"))
    return op->emitError("'") << op->getName()
                              << "' is not supported by the loop lowering";
  if (op->getDialect() != op->getContext()->getLoadedDialect<SimitDialect>()) {
    handled = false;
    return success();
  }

  // Variables.
  if (auto alloc = dyn_cast<AllocOp>(op)) {
    auto type = dyn_cast_or_null<MemRefType>(convertType(alloc.getType()));
    if (!type)
      return op->emitError("variables of type ")
             << alloc.getType() << " are not supported by the loop lowering";
    Value slot = allocaSlot(loc, type);
    // Every execution of the declaration starts from zero.
    fill(loc, slot, zeroOf(type.getElementType()));
    map(alloc, slot);
    return success();
  }
  if (auto load = dyn_cast<LoadOp>(op)) {
    Value slot = lookup(load.getRef());
    auto type = cast<MemRefType>(slot.getType());
    if (type.getRank() == 0)
      map(load, memref::LoadOp::create(b, loc, slot, ValueRange{}));
    else
      map(load, loadWhole(loc, cast<VectorType>(resultType()), slot));
    return success();
  }
  if (auto store = dyn_cast<StoreOp>(op)) {
    Value slot = lookup(store.getRef());
    Value value = lookup(store.getValue());
    if (cast<MemRefType>(slot.getType()).getRank() == 0)
      memref::StoreOp::create(b, loc, value, slot, ValueRange{});
    else
      storeWhole(loc, value, slot);
    return success();
  }

  // Construction and access.
  if (isa<ZerosOp>(op)) {
    Type type = resultType();
    map(op->getResult(0),
        arith::ConstantOp::create(b, loc, b.getZeroAttr(type)));
    return success();
  }
  if (auto bcast = dyn_cast<BroadcastOp>(op)) {
    map(bcast,
        broadcast(*this, loc, resultType(), bcast.getType(), operand(0)));
    return success();
  }
  if (auto extract = dyn_cast<ExtractOp>(op)) {
    SmallVector<Value> indices;
    for (Value index : extract.getIndices())
      indices.push_back(lookup(index));
    Value offset =
        blockOffset(*this, loc, extract.getTensor().getType(), indices);
    Value tensor = lookup(extract.getTensor());
    int64_t n = numComponents(extract.getType());
    SmallVector<Value> components;
    for (int64_t c = 0; c < n; ++c)
      components.push_back(
          component(extract.getTensor().getType(), tensor,
                    arith::AddIOp::create(b, loc, offset, indexConstant(c))));
    map(extract, fromComponents(resultType(), components));
    return success();
  }
  if (auto insert = dyn_cast<InsertOp>(op)) {
    SmallVector<Value> indices;
    for (Value index : insert.getIndices())
      indices.push_back(lookup(index));
    Value offset =
        blockOffset(*this, loc, insert.getTensor().getType(), indices);
    Value tensor = lookup(insert.getTensor());
    Value value = lookup(insert.getValue());
    int64_t n = numComponents(insert.getValue().getType());
    for (int64_t c = 0; c < n; ++c) {
      Value position = arith::AddIOp::create(b, loc, offset, indexConstant(c));
      tensor = insertComponent(
          tensor, component(insert.getValue().getType(), value, c), position);
    }
    map(insert, tensor);
    return success();
  }
  if (auto slice = dyn_cast<SliceOp>(op)) {
    auto type = dyn_cast<RankedTensorType>(slice.getTensor().getType());
    if (!type)
      return op->emitError("slices of blocked tensors are not supported");
    ArrayRef<bool> kept = slice.getKept();
    Value tensor = lookup(slice.getTensor());
    // Walk the kept dimensions row-major; fixed ones take their index.
    SmallVector<int64_t> keptShape;
    for (auto [d, keep] : llvm::enumerate(kept))
      if (keep)
        keptShape.push_back(type.getDimSize(d));
    int64_t n = 1;
    for (int64_t s : keptShape)
      n *= s;
    SmallVector<Value> components;
    for (int64_t flat = 0; flat < n; ++flat) {
      SmallVector<int64_t> keptIndex(keptShape.size());
      int64_t rest = flat;
      for (int64_t k = keptShape.size() - 1; k >= 0; --k) {
        keptIndex[k] = rest % keptShape[k];
        rest /= keptShape[k];
      }
      SmallVector<Value> indices;
      unsigned nextKept = 0, nextFixed = 0;
      for (bool keep : kept)
        indices.push_back(keep ? indexConstant(keptIndex[nextKept++])
                               : lookup(slice.getIndices()[nextFixed++]));
      components.push_back(
          component(type, tensor, blockOffset(*this, loc, type, indices)));
    }
    map(slice, fromComponents(resultType(), components));
    return success();
  }

  // Arithmetic. Complex (re, im) pairs add, subtract and negate as floats;
  // products and quotients go component by component.
  bool complexResult =
      op->getNumResults() == 1 &&
      isa<ComplexType>(getComponentType(op->getResult(0).getType()));
  if (complexResult && isa<MulOp, DivOp, ScaleOp>(op)) {
    bool isScale = isa<ScaleOp>(op);
    Value tensor = isScale ? cast<ScaleOp>(op).getTensor() : op->getOperand(0);
    SmallVector<Value> x = allComponents(*this, tensor), r;
    SmallVector<Value> y =
        isScale ? SmallVector<Value>(x.size(),
                                     lookup(cast<ScaleOp>(op).getScalar()))
                : allComponents(*this, op->getOperand(1));
    for (auto [xi, yi] : llvm::zip_equal(x, y))
      r.push_back(isScale          ? a.mul(yi, xi)
                  : isa<MulOp>(op) ? a.mul(xi, yi)
                                   : a.div(xi, yi));
    map(op->getResult(0), fromComponents(resultType(), r));
    return success();
  }
  if (isa<AddOp, SubOp, MulOp, DivOp>(op)) {
    Value x = operand(0), y = operand(1);
    Value r = isa<AddOp>(op)   ? a.add(x, y)
              : isa<SubOp>(op) ? a.sub(x, y)
              : isa<MulOp>(op) ? a.mul(x, y)
                               : a.div(x, y);
    map(op->getResult(0), r);
    return success();
  }
  if (isa<NegOp>(op)) {
    map(op->getResult(0), a.neg(operand(0)));
    return success();
  }
  if (auto scale = dyn_cast<ScaleOp>(op)) {
    Value tensor = lookup(scale.getTensor());
    Value scalar = lookup(scale.getScalar());
    if (isa<VectorType>(tensor.getType()))
      scalar = vector::BroadcastOp::create(b, loc, tensor.getType(), scalar);
    map(scale, a.mul(scalar, tensor));
    return success();
  }

  // Linear algebra, unrolled over the static shapes.
  auto shapeOf = [](Value v) -> SmallVector<int64_t> {
    if (auto t = dyn_cast<RankedTensorType>(v.getType()))
      return SmallVector<int64_t>(t.getShape());
    return {};
  };
  // outer, det, inv, cross and solve read blocked operands unblocked (a
  // blocked matrix is the matrix of its components) and write the result
  // back into its blocked order.
  SmallVector<SmallVector<int64_t>> shapes(op->getNumOperands());
  SmallVector<SmallVector<Value>> unblocked(op->getNumOperands());
  auto readUnblocked = [&]() -> LogicalResult {
    for (auto [i, v] : llvm::enumerate(op->getOperands())) {
      std::optional<SmallVector<int64_t>> order =
          unblockedOrder(v.getType(), shapes[i]);
      if (!order)
        return op->emitError("'")
               << op->getName()
               << "' on blocked local tensors of mixed block ranks is not "
                  "supported";
      SmallVector<Value> x = allComponents(*this, v);
      for (int64_t position : *order)
        unblocked[i].push_back(x[position]);
    }
    return success();
  };
  auto mapUnblocked = [&](ArrayRef<Value> components) {
    Type type = op->getResult(0).getType();
    SmallVector<int64_t> shape;
    std::optional<SmallVector<int64_t>> order = unblockedOrder(type, shape);
    if (shape.empty()) {
      map(op->getResult(0), components[0]);
      return;
    }
    SmallVector<Value> r(components.size());
    for (auto [k, position] : llvm::enumerate(*order))
      r[position] = components[k];
    map(op->getResult(0), fromComponents(resultType(), r));
  };
  // Dot and norm only pair up components in storage order, which is the
  // same for equally blocked operands.
  if (isa<MatVecOp, MatMulOp, TransposeOp>(op) &&
      llvm::any_of(op->getOperandTypes(),
                   [](Type t) { return isa<SystemTensorType>(t); })) {
    SmallVector<Value> r;
    if (failed(lowerBlockedLinalg(*this, a, op, r)))
      return failure();
    map(op->getResult(0), fromComponents(resultType(), r));
    return success();
  }
  if (isa<OuterOp, DetOp, InvOp, CrossOp, SolveOp>(op) &&
      failed(readUnblocked()))
    return failure();

  if (isa<MatVecOp, MatMulOp>(op)) {
    SmallVector<int64_t> ls = shapeOf(op->getOperand(0)),
                         rs = shapeOf(op->getOperand(1));
    SmallVector<Value> x = allComponents(*this, op->getOperand(0)),
                       y = allComponents(*this, op->getOperand(1));
    int64_t m = ls[0], k = ls[1], n = rs.size() == 2 ? rs[1] : 1;
    SmallVector<Value> r;
    for (int64_t i = 0; i < m; ++i)
      for (int64_t j = 0; j < n; ++j) {
        Value sum;
        for (int64_t p = 0; p < k; ++p) {
          Value t = a.mul(x[i * k + p], y[p * n + j]);
          sum = sum ? a.add(sum, t) : t;
        }
        r.push_back(sum);
      }
    map(op->getResult(0), fromComponents(resultType(), r));
    return success();
  }
  if (isa<TransposeOp>(op)) {
    SmallVector<int64_t> s = shapeOf(op->getOperand(0));
    if (s.size() < 2) {
      map(op->getResult(0), operand(0));
      return success();
    }
    SmallVector<Value> x = allComponents(*this, op->getOperand(0)), r;
    for (int64_t j = 0; j < s[1]; ++j)
      for (int64_t i = 0; i < s[0]; ++i)
        r.push_back(x[i * s[1] + j]);
    map(op->getResult(0), fromComponents(resultType(), r));
    return success();
  }
  if (isa<DotOp, NormOp>(op)) {
    SmallVector<Value> x = allComponents(*this, op->getOperand(0));
    SmallVector<Value> y =
        isa<DotOp>(op) ? allComponents(*this, op->getOperand(1)) : x;
    Value sum;
    for (auto [xi, yi] : llvm::zip(x, y)) {
      Value t = a.mul(xi, yi);
      // The norm of complex components sums their squared moduli.
      if (isa<NormOp>(op) && isa<ComplexType>(xi.getType())) {
        Value re = complex::ReOp::create(b, loc, xi);
        Value im = complex::ImOp::create(b, loc, xi);
        Value reSquared = a.mul(re, re);
        t = a.add(reSquared, a.mul(im, im));
      }
      sum = sum ? a.add(sum, t) : t;
    }
    if (isa<NormOp>(op))
      sum = math::SqrtOp::create(b, loc, sum);
    map(op->getResult(0), sum);
    return success();
  }
  if (isa<OuterOp>(op)) {
    SmallVector<Value> r;
    for (Value xi : unblocked[0])
      for (Value yj : unblocked[1])
        r.push_back(a.mul(xi, yj));
    mapUnblocked(r);
    return success();
  }
  if (isa<DetOp, InvOp>(op)) {
    SmallVector<int64_t> s = shapes[0];
    if (s.size() != 2 || s[0] != s[1] || s[0] > 4)
      return op->emitError("'")
             << op->getName()
             << "' is supported for square matrices of at most 4 x 4";
    ArrayRef<Value> m = unblocked[0];
    if (isa<DetOp>(op))
      mapUnblocked(determinant(a, m, s[0]));
    else
      mapUnblocked(inverse(a, m, s[0]));
    return success();
  }
  if (isa<CrossOp>(op)) {
    if (shapes[0] != ArrayRef<int64_t>{3} || shapes[1] != shapes[0])
      return op->emitError("cross products need two vectors of 3 components");
    ArrayRef<Value> x = unblocked[0], y = unblocked[1];
    SmallVector<Value> r = {
        a.sub(a.mul(x[1], y[2]), a.mul(x[2], y[1])),
        a.sub(a.mul(x[2], y[0]), a.mul(x[0], y[2])),
        a.sub(a.mul(x[0], y[1]), a.mul(x[1], y[0]))};
    mapUnblocked(r);
    return success();
  }
  if (isa<SolveOp>(op)) {
    SmallVector<int64_t> s = shapes[0];
    if (s.size() != 2 || s[0] != s[1] || shapes[1] != ArrayRef<int64_t>{s[0]})
      return op->emitError("local solves are supported for square matrices "
                           "and a vector");
    int64_t n = s[0];
    // Larger systems: the runtime's LU with partial pivoting.
    if (n > 4) {
      Type number = getComponentType(op->getOperand(0).getType());
      if (!isa<FloatType>(number))
        return op->emitError("local solves of more than 4 x 4 take float "
                             "matrices");
      auto flat = [&](ArrayRef<Value> components) -> Value {
        return vector::FromElementsOp::create(
            b, loc,
            VectorType::get({static_cast<int64_t>(components.size())}, number),
            components);
      };
      Value x =
          solveByDenseLU(loc, op, flat(unblocked[0]), flat(unblocked[1]), n);
      SmallVector<Value> r;
      for (int64_t i = 0; i < n; ++i)
        r.push_back(vector::ExtractOp::create(b, loc, x, ArrayRef<int64_t>{i}));
      mapUnblocked(r);
      return success();
    }
    // Small dense systems: x = inv(A) b.
    SmallVector<Value> inv = inverse(a, unblocked[0], n);
    ArrayRef<Value> rhs = unblocked[1];
    SmallVector<Value> r;
    for (int64_t i = 0; i < n; ++i) {
      Value sum;
      for (int64_t j = 0; j < n; ++j) {
        Value t = a.mul(inv[i * n + j], rhs[j]);
        sum = sum ? a.add(sum, t) : t;
      }
      r.push_back(sum);
    }
    mapUnblocked(r);
    return success();
  }
  if (auto indexExpr = dyn_cast<IndexExprOp>(op))
    return lowerIndexExpr(indexExpr);
  handled = false;
  return success();
}
