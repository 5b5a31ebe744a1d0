//===- LowerProducts.cpp - Products of system matrices --------------------===//
//
// C = A B of two system matrices (simit.matmul, which simit-linalg-to-index-
// expr keeps) is stored on the pattern of the product, built once per
// binding by the runtime (symbolic SpGEMM, the product_rowptr/colidx
// bindings); each call computes the values with the runtime's numeric
// product. A block diagonal factor keeps the other factor's pattern. The
// transpose of an incidence times the incidence is summed edge by edge on
// the edge set's pattern; a diagonal factor scales an incidence's blocks;
// other products with an incidence factor read its rows through a
// bind-time view (simit::IncidenceView).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include <array>

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// Whether the runtime's product takes a factor stored as `s`: block
/// diagonal, BCSR, dense, or an incidence read row by row.
static bool isProductOperand(const Storage &s) {
  return s.kind == Storage::Kind::Diagonal || s.isBCSR() ||
         s.kind == Storage::Kind::Incidence ||
         s.kind == Storage::Kind::DenseMatrix ||
         s.kind == Storage::Kind::Stencil;
}

/// Whether `h` (over (V, E)) times `g` (over (E, V)) is an incidence's
/// transpose times an incidence of one edge set, stored on its pattern
/// (simit-assign-storage composes them so).
static bool isIncidenceGram(const Storage &h, const Storage &g,
                            const Storage &result) {
  return h.kind == Storage::Kind::Incidence && h.transposed &&
         g.kind == Storage::Kind::Incidence && !g.transposed &&
         h.edges == g.edges && result.kind == Storage::Kind::Pattern &&
         result.edges == g.edges && result.rows == h.rows &&
         result.cols == g.cols;
}

/// The (rows, cols) of the blocks of a system matrix; scalars are 1x1.
static std::pair<int64_t, int64_t> blockShape(Value matrix) {
  SmallVector<int64_t> shape =
      cast<SystemTensorType>(matrix.getType()).getBlockShape();
  if (shape.empty())
    return {1, 1};
  return {shape[0], shape[1]};
}

/// out[at] = x[xAt] y[yAt] of one block each, or out[at] += it with
/// `accumulate`: a (rows x mid) block times a (mid x cols) one, unrolled
/// (arrays of scalars have no block dimensions).
static void emitBlockProduct(FunctionLowering &l, Location loc, bool blocked,
                             std::array<int64_t, 3> shape, Value out, Value at,
                             Value x, Value xAt, Value y, Value yAt,
                             bool accumulate) {
  OpBuilder &b = l.b;
  auto index = [&](Value block, int64_t r, int64_t c) {
    SmallVector<Value> indices{block};
    if (blocked)
      indices.append({l.indexConstant(r), l.indexConstant(c)});
    return indices;
  };
  auto [rows, mid, cols] = shape;
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t c = 0; c < cols; ++c) {
      Value sum =
          accumulate ? memref::LoadOp::create(b, loc, out, index(at, r, c))
                     : Value();
      for (int64_t m = 0; m < mid; ++m) {
        Value xrm = memref::LoadOp::create(b, loc, x, index(xAt, r, m));
        Value ymc = memref::LoadOp::create(b, loc, y, index(yAt, m, c));
        Value term = multiplyNumbers(b, loc, xrm, ymc);
        sum = sum ? addNumbers(b, loc, sum, term) : term;
      }
      memref::StoreOp::create(b, loc, sum, out, index(at, r, c));
    }
}

/// Whether a product's blocks are matrices (not scalars), and its (rows,
/// mid, cols) block shape.
static std::pair<bool, std::array<int64_t, 3>> productShape(MatMulOp op) {
  bool blocked =
      !cast<SystemTensorType>(op.getType()).getBlockShape().empty();
  return {blocked,
          {blockShape(op.getLhs()).first, blockShape(op.getLhs()).second,
           blockShape(op.getRhs()).second}};
}

LogicalResult FunctionLowering::lowerIncidenceGram(MatMulOp op,
                                                   const Storage &h,
                                                   const Storage &g,
                                                   const Storage &result) {
  // Row e of g holds a block per endpoint position k in its columns' set
  // (block e * m + j for the j-th such k), and h = a transposed incidence
  // holds (endpoint_k(e), e) the same way for its rows' set; an edge adds
  // h_i g_j at (endpoint_i(e), endpoint_j(e)) for every pair of positions,
  // which is where an assembly over the edge set writes (the bind-time
  // pattern_locations, indexed by the edge set's own positions). Products
  // of blocks are bilinear, so an edge naming a vertex twice adds each of
  // its blocks there.
  Location loc = op.getLoc();
  auto type = cast<SystemTensorType>(op.getType());
  auto [blocked, shape] = productShape(op);
  int64_t c = setTypes.lookup(g.edges).getCardinality();
  auto positionsOf = [&](const Storage &s) {
    if (!s.positions.empty())
      return SmallVector<int64_t, 4>(s.positions);
    return llvm::to_vector<4>(llvm::seq<int64_t>(0, c));
  };
  SmallVector<int64_t, 4> hPositions = positionsOf(h),
                          gPositions = positionsOf(g);
  Value hArray = lookup(op.getLhs()), gArray = lookup(op.getRhs());
  Value out = allocSystem(loc, type, result, /*zeroFill=*/true);
  Value locations = getPatternArray(BindingKind::PatternLocations,
                                    result.edges, result.rows, result.cols, c);
  // Edges write shared blocks: the loop stays sequential.
  forLoop(loc, getSetSize(g.edges), [&](Value e) {
    Value hFirst =
        arith::MulIOp::create(b, loc, e, indexConstant(h.cardinality));
    Value gFirst =
        g.cardinality == h.cardinality
            ? hFirst
            : arith::MulIOp::create(b, loc, e, indexConstant(g.cardinality));
    for (auto [i, hk] : llvm::enumerate(hPositions)) {
      Value hAt = arith::AddIOp::create(b, loc, hFirst, indexConstant(i));
      for (auto [j, gk] : llvm::enumerate(gPositions)) {
        Value gAt = arith::AddIOp::create(b, loc, gFirst, indexConstant(j));
        Value at = arith::IndexCastOp::create(
            b, loc, b.getIndexType(),
            memref::LoadOp::create(b, loc, locations,
                                   ValueRange{e, indexConstant(hk * c + gk)}));
        emitBlockProduct(*this, loc, blocked, shape, out, at, hArray, hAt,
                         gArray, gAt, /*accumulate=*/true);
      }
    }
  });
  map(op, out);
  return success();
}

LogicalResult FunctionLowering::lowerScaledIncidence(MatMulOp op,
                                                     const Storage &incidence,
                                                     bool diagonalOnRight) {
  // Block e * c + k of the incidence is (e, endpoint_k(e)), or
  // (endpoint_k(e), e) transposed; the diagonal factor scales it by its
  // block at the column (on the right) or the row (on the left).
  Location loc = op.getLoc();
  auto type = cast<SystemTensorType>(op.getType());
  auto [blocked, shape] = productShape(op);
  Value x = lookup(op.getLhs()), y = lookup(op.getRhs());
  Value out = allocSystem(loc, type, incidence, /*zeroFill=*/false);
  // Each block is written once, by its edge.
  forLoop(loc, getSetSize(incidence.edges), [&](Value e) {
    forEachEdgeBlock(loc, incidence, e, [&](Value endpoint, Value at) {
      Value row = incidence.transposed ? endpoint : e;
      Value col = incidence.transposed ? e : endpoint;
      Value xAt = diagonalOnRight ? at : row;
      Value yAt = diagonalOnRight ? col : at;
      emitBlockProduct(*this, loc, blocked, shape, out, at, x, xAt, y, yAt,
                       /*accumulate=*/false);
    });
  });
  map(op, out);
  return success();
}

LogicalResult FunctionLowering::lowerStencilProduct(MatMulOp op,
                                                    const Storage &result) {
  // Block (r, r + a) of A times block (r + a, r + a + b) of B adds to block
  // (r, r + (a + b)) of the product, whose stencil holds every sum a + b
  // (storage::product). A block diagonal factor is a stencil of the zero
  // offset alone: its block r is (r, r).
  Location loc = op.getLoc();
  auto type = cast<SystemTensorType>(op.getType());
  auto [blocked, shape] = productShape(op);
  auto offsetsOf = [&](Value factor) {
    Storage s = storageOf(factor);
    if (s.kind == Storage::Kind::Stencil)
      return s;
    Storage zero = result;
    unsigned rank =
        cast<DenseI64ArrayAttr>(result.offsets[0]).asArrayRef().size();
    zero.offsets = b.getArrayAttr(
        {DenseI64ArrayAttr::get(b.getContext(), SmallVector<int64_t>(rank))});
    return zero;
  };
  Storage sa = offsetsOf(op.getLhs()), sb = offsetsOf(op.getRhs());
  auto offset = [](const Storage &s, int64_t k) {
    return cast<DenseI64ArrayAttr>(s.offsets[k]).asArrayRef();
  };
  Value x = lookup(op.getLhs()), y = lookup(op.getRhs());
  Value out = allocSystem(loc, type, result, /*zeroFill=*/true);
  // Each row writes its own blocks only, in a fixed order.
  forLoop(loc, getSetSize(result.rows), [&](Value row) {
    for (int64_t i = 0, n = sa.offsets.size(); i < n; ++i) {
      Value ki = indexConstant(i);
      Value mid = stencilColumn(sa, row, ki);
      Value xAt = stencilBlock(sa, row, ki);
      for (int64_t j = 0, m = sb.offsets.size(); j < m; ++j) {
        SmallVector<int64_t> sum(offset(sa, i));
        for (auto [s, o] : llvm::zip_equal(sum, offset(sb, j)))
          s += o;
        auto at = llvm::find(result.offsets,
                             DenseI64ArrayAttr::get(b.getContext(), sum));
        assert(at != result.offsets.end() && "the stencil holds every sum");
        Value outAt = stencilBlock(
            result, row, indexConstant(at - result.offsets.begin()));
        Value yAt = stencilBlock(sb, mid, indexConstant(j));
        emitBlockProduct(*this, loc, blocked, shape, out, outAt, x, xAt, y,
                         yAt, /*accumulate=*/true);
      }
    }
  });
  map(op, out);
  return success();
}

LogicalResult FunctionLowering::lowerMatMul(MatMulOp op) {
  Location loc = op.getLoc();
  auto type = dyn_cast<SystemTensorType>(op.getType());
  if (!type || type.getOrder() != 2)
    return op.emitError("products of system tensors are supported for "
                        "matrices");
  Storage a = storageOf(op.getLhs()), b2 = storageOf(op.getRhs());
  Storage storage = storageOf(op);
  Type component = type.getComponentType();
  if (isa<FloatType, IntegerType>(component)) {
    if (isIncidenceGram(a, b2, storage))
      return lowerIncidenceGram(op, a, b2, storage);
    // A diagonal factor keeps an incidence's storage.
    auto isIncidence = [](const Storage &s) {
      return s.kind == Storage::Kind::Incidence;
    };
    auto isDiagonal = [](const Storage &s) {
      return s.kind == Storage::Kind::Diagonal;
    };
    if (isIncidence(a) && isDiagonal(b2) && storage == a)
      return lowerScaledIncidence(op, a, /*diagonalOnRight=*/true);
    if (isDiagonal(a) && isIncidence(b2) && storage == b2)
      return lowerScaledIncidence(op, b2, /*diagonalOnRight=*/false);
    auto onGrid = [&](const Storage &s) {
      return (s.kind == Storage::Kind::Stencil &&
              s.edges == storage.edges) ||
             (isDiagonal(s) && s.rows == storage.rows);
    };
    if (storage.kind == Storage::Kind::Stencil && onGrid(a) && onGrid(b2))
      return lowerStencilProduct(op, storage);
  }
  // A stencil factor is copied onto its BCSR pattern for the runtime; the
  // result is written in place, so it cannot be one.
  if (!isProductOperand(a) || !isProductOperand(b2) ||
      storage.kind == Storage::Kind::Incidence ||
      storage.kind == Storage::Kind::Stencil || !isProductOperand(storage))
    return op.emitError("products are supported of matrices assembled from "
                        "sets and their sums; these are stored as ")
           << a.describe() << " and " << b2.describe();
  if (!component.isF64() && !component.isF32() &&
      !component.isSignlessInteger(32))
    return op.emitError("products of system matrices take f64, f32 or i32 "
                        "components");

  MLIRContext *ctx = b.getContext();
  int64_t dyn = ShapedType::kDynamic;
  Type i32 = b.getI32Type();
  Type indexArray = MemRefType::get({dyn}, i32);
  auto values = MemRefType::get({dyn, dyn, dyn}, component);
  auto calleeType = FunctionType::get(
      ctx,
      {i32, indexArray, indexArray, indexArray, values, i32, indexArray,
       indexArray, indexArray, values, i32, indexArray, indexArray, values,
       b.getI64Type(), LLVM::LLVMPointerType::get(ctx)},
      {});
  using ::simit::abi::RuntimeFunction;
  StringRef name =
      runtimeName(component.isF32()   ? RuntimeFunction::MatmulBCSRF32
                  : component.isF64() ? RuntimeFunction::MatmulBCSR
                                      : RuntimeFunction::MatmulBCSRI32);
  func::FuncOp callee = declareRuntime(loc, name, calleeType);
  if (!callee)
    return op.emitError("@") << name << " is declared with another type";

  // Each matrix: its layout (0 BCSR, 1 block diagonal, 2 an incidence's
  // rows, 3 dense), index arrays (the factors' with value positions) and
  // values.
  SmallVector<Value> args;
  auto addMatrix = [&](const Storage &s, Value array, bool isFactor) {
    int64_t layout = s.kind == Storage::Kind::Diagonal      ? 1
                     : s.kind == Storage::Kind::Incidence   ? 2
                     : s.kind == Storage::Kind::DenseMatrix ? 3
                                                            : 0;
    args.push_back(arith::ConstantIntOp::create(b, loc, i32, layout));
    if (s.kind == Storage::Kind::Stencil) {
      // Its blocks on its bind-time BCSR pattern.
      auto [rowPtr, colIdx, blocks] = stencilAsBCSR(loc, s, array);
      args.append({rowPtr, colIdx, emptyIndexArray(),
                   asRuntimeBlocks(loc, blocks, values)});
      return;
    }
    if (layout == 2) {
      llvm::append_range(args, incidenceRows(s));
    } else {
      bool indexed = layout == 0;
      args.push_back(indexed ? rowPointers(s) : emptyIndexArray());
      args.push_back(indexed ? columnIndices(s) : emptyIndexArray());
      if (isFactor)
        args.push_back(emptyIndexArray());
    }
    args.push_back(asRuntimeBlocks(loc, array, values));
  };
  // A product with a host function's matrix gets its pattern now.
  if (storage.kind == Storage::Kind::Host && !builtRuntimePattern(storage)) {
    auto hasPattern = [](const Storage &s) {
      return s.isBCSR() || s.kind == Storage::Kind::Stencil;
    };
    if (!hasPattern(a) || !hasPattern(b2))
      return op.emitError("a product whose pattern is built at run time "
                          "needs BCSR or stencil factors; these are stored "
                          "as ")
             << a.describe() << " and " << b2.describe();
    buildProductPattern(loc, storage, a, b2);
  }
  addMatrix(a, lookup(op.getLhs()), /*isFactor=*/true);
  addMatrix(b2, lookup(op.getRhs()), /*isFactor=*/true);
  Value result = allocSystem(loc, type, storage, /*zeroFill=*/false);
  addMatrix(storage, result, /*isFactor=*/false);
  args.push_back(arith::IndexCastOp::create(b, loc, b.getI64Type(),
                                            getSetSize(storage.cols)));
  args.push_back(stringConstant(loc, "product" + sourcePositionSuffix(op)));
  func::CallOp::create(b, loc, callee, args);
  map(op, result);
  return success();
}
