//===- LowerProducts.cpp - Products of system matrices --------------------===//
//
// C = A B of two system matrices (simit.matmul, which simit-linalg-to-index-
// expr keeps) is stored on the pattern of the product, built once per
// binding by the runtime (symbolic SpGEMM, the product_rowptr/colidx
// bindings); each call computes the values with the runtime's numeric
// product. A block diagonal factor keeps the other factor's pattern. The
// transpose of an incidence times the incidence is summed edge by edge on
// the edge set's pattern.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "SourcePosition.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// Whether the runtime's product takes a matrix stored as `s`: block
/// diagonal or BCSR.
static bool isProductOperand(const Storage &s) {
  return s.kind == Storage::Kind::Diagonal || s.isBCSR();
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

LogicalResult FunctionLowering::lowerIncidenceGram(MatMulOp op,
                                                   const Storage &g,
                                                   const Storage &result) {
  // Row e of g holds a block per endpoint position k (block e * c + k), and
  // h = the transposed incidence holds (endpoint_k(e), e) there too; an
  // edge adds h_i g_j at (endpoint_i(e), endpoint_j(e)) for every pair of
  // positions, which is where an assembly over the edge set writes (the
  // bind-time pattern_locations). Products of blocks are bilinear, so an
  // edge naming a vertex twice adds each of its blocks there.
  Location loc = op.getLoc();
  auto type = cast<SystemTensorType>(op.getType());
  auto blockShape = [](Value v) {
    SmallVector<int64_t> shape =
        cast<SystemTensorType>(v.getType()).getBlockShape();
    return shape.empty() ? SmallVector<int64_t>{1, 1} : shape;
  };
  bool blocked = !type.getBlockShape().empty();
  SmallVector<int64_t> hBlock = blockShape(op.getLhs()),
                       gBlock = blockShape(op.getRhs());
  int64_t rows = hBlock[0], mid = hBlock[1], cols = gBlock[1];
  int64_t c = g.cardinality;
  Value h = lookup(op.getLhs()), gArray = lookup(op.getRhs());
  Value out = allocSystem(loc, type, result, /*zeroFill=*/true);
  Value locations = getPatternArray(BindingKind::PatternLocations,
                                    result.edges, result.rows, result.cols, c);
  // Edges write shared blocks: the loop stays sequential.
  scf::ForOp::create(
      b, loc, indexConstant(0), getSetSize(g.edges), indexConstant(1),
      ValueRange{}, [&](OpBuilder &nb, Location, Value e, ValueRange) {
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
        Value first = arith::MulIOp::create(b, loc, e, indexConstant(c));
        auto at = [&](Value block, int64_t r, int64_t s) {
          SmallVector<Value> indices{block};
          if (blocked)
            indices.append({indexConstant(r), indexConstant(s)});
          return indices;
        };
        for (int64_t i = 0; i < c; ++i) {
          Value hPos = arith::AddIOp::create(b, loc, first, indexConstant(i));
          for (int64_t j = 0; j < c; ++j) {
            Value gPos =
                arith::AddIOp::create(b, loc, first, indexConstant(j));
            Value pos = arith::IndexCastOp::create(
                b, loc, b.getIndexType(),
                memref::LoadOp::create(
                    b, loc, locations,
                    ValueRange{e, indexConstant(i * c + j)}));
            for (int64_t r = 0; r < rows; ++r)
              for (int64_t s = 0; s < cols; ++s) {
                Value sum = memref::LoadOp::create(b, loc, out, at(pos, r, s));
                for (int64_t m = 0; m < mid; ++m) {
                  Value x = memref::LoadOp::create(b, loc, h, at(hPos, r, m));
                  Value y =
                      memref::LoadOp::create(b, loc, gArray, at(gPos, m, s));
                  sum = arith::AddFOp::create(
                      b, loc, sum, arith::MulFOp::create(b, loc, x, y));
                }
                memref::StoreOp::create(b, loc, sum, out, at(pos, r, s));
              }
          }
        }
        scf::YieldOp::create(b, loc);
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
  if (isIncidenceGram(a, b2, storage) && isa<FloatType>(component))
    return lowerIncidenceGram(op, b2, storage);
  if (!isProductOperand(a) || !isProductOperand(b2) ||
      !isProductOperand(storage))
    return op.emitError("products are supported of matrices assembled from "
                        "sets and their sums; these are stored as ")
           << a.describe() << " and " << b2.describe();
  if (!component.isF64() && !component.isF32())
    return op.emitError("products of system matrices take f64 or f32 "
                        "components");

  MLIRContext *ctx = b.getContext();
  int64_t dyn = ShapedType::kDynamic;
  Type i32 = b.getI32Type();
  Type indexArray = MemRefType::get({dyn}, i32);
  auto values = MemRefType::get({dyn, dyn, dyn}, component);
  auto calleeType = FunctionType::get(
      ctx,
      {i32, indexArray, indexArray, values, i32, indexArray, indexArray,
       values, i32, indexArray, indexArray, values, b.getI64Type(),
       LLVM::LLVMPointerType::get(ctx)},
      {});
  std::string name = "simit_rt_matmul_bcsr";
  if (component.isF32())
    name += "_f32";
  func::FuncOp callee = declareRuntime(loc, name, calleeType);
  if (!callee)
    return op.emitError("@") << name << " is declared with another type";

  // Each matrix: its layout (0 BCSR, 1 block diagonal), index arrays and
  // values.
  SmallVector<Value> args;
  auto addMatrix = [&](const Storage &s, Value array) {
    bool diagonal = s.kind == Storage::Kind::Diagonal;
    args.push_back(arith::ConstantIntOp::create(b, loc, i32, diagonal));
    args.push_back(diagonal ? emptyIndexArray() : rowPointers(s));
    args.push_back(diagonal ? emptyIndexArray() : columnIndices(s));
    args.push_back(asRuntimeBlocks(loc, array, values));
  };
  addMatrix(a, lookup(op.getLhs()));
  addMatrix(b2, lookup(op.getRhs()));
  Value result = allocSystem(loc, type, storage, /*zeroFill=*/false);
  addMatrix(storage, result);
  args.push_back(arith::IndexCastOp::create(b, loc, b.getI64Type(),
                                            getSetSize(storage.cols)));
  args.push_back(stringConstant(loc, "product" + sourcePositionSuffix(op)));
  func::CallOp::create(b, loc, callee, args);
  map(op, result);
  return success();
}
