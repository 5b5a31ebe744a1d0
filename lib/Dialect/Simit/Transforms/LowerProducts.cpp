//===- LowerProducts.cpp - Products of system matrices --------------------===//
//
// C = A B of two system matrices (simit.matmul, which simit-linalg-to-index-
// expr keeps) is stored on the pattern of the product, built once per
// binding by the runtime (symbolic SpGEMM, the product_rowptr/colidx
// bindings); each call computes the values with the runtime's numeric
// product. A block diagonal factor keeps the other factor's pattern.
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

LogicalResult FunctionLowering::lowerMatMul(MatMulOp op) {
  Location loc = op.getLoc();
  auto type = dyn_cast<SystemTensorType>(op.getType());
  if (!type || type.getOrder() != 2)
    return op.emitError("products of system tensors are supported for "
                        "matrices");
  Storage a = storageOf(op.getLhs()), b2 = storageOf(op.getRhs());
  Storage storage = storageOf(op);
  if (!isProductOperand(a) || !isProductOperand(b2) ||
      !isProductOperand(storage))
    return op.emitError("products are supported of matrices assembled from "
                        "sets and their sums; these are stored as ")
           << a.describe() << " and " << b2.describe();
  Type component = type.getComponentType();
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
  StringRef name = runtimeName(component.isF32()
                                   ? ::simit::abi::RuntimeFunction::MatmulBCSRF32
                                   : ::simit::abi::RuntimeFunction::MatmulBCSR);
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
