//===- LowerRuntimePatterns.cpp - Patterns built when code runs -----------===//
//
// A host function's matrix has a pattern known only when the call returns
// (LowerHostCalls.cpp); a product with it, or a sum stored with other
// matrices, too. The runtime builds those patterns from the operands' index
// arrays each time the value is computed (simit_rt_product_pattern,
// simit_rt_union_pattern) and copies them into arrays of the lowered code,
// which then reads them as any BCSR matrix's (runtimePatterns).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;
using ::simit::abi::RuntimeFunction;

std::pair<Value, Value>
FunctionLowering::takeRuntimePattern(Location loc, Value handle, Value rows) {
  Value blocks = callRuntime(loc, runtimeName(RuntimeFunction::PatternBlocks),
                             {b.getI64Type()}, {handle});
  auto indexArray = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  Value rowptr = memref::AllocOp::create(
      b, loc, indexArray,
      ValueRange{arith::AddIOp::create(b, loc, rows, indexConstant(1))});
  Value colidx = memref::AllocOp::create(
      b, loc, indexArray,
      ValueRange{arith::IndexCastOp::create(b, loc, b.getIndexType(), blocks)});
  func::FuncOp take = declareRuntime(
      loc, runtimeName(RuntimeFunction::PatternTake),
      FunctionType::get(b.getContext(),
                        {handle.getType(), indexArray, indexArray}, {}));
  func::CallOp::create(b, loc, take, ValueRange{handle, rowptr, colidx});
  return {rowptr, colidx};
}

namespace {
/// The layout code of simit_rt_union_pattern: 0 BCSR, 1 block diagonal.
int32_t unionLayout(const Storage &s) {
  return s.kind == Storage::Kind::Diagonal ? 1 : 0;
}
} // namespace

void FunctionLowering::buildProductPattern(Location loc, const Storage &storage,
                                           const Storage &lhs,
                                           const Storage &rhs) {
  MLIRContext *ctx = b.getContext();
  auto indexArray = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  func::FuncOp product = declareRuntime(
      loc, runtimeName(RuntimeFunction::ProductPattern),
      FunctionType::get(
          ctx, {indexArray, indexArray, indexArray, indexArray, b.getI64Type()},
          {ptr}));
  Value cols = arith::IndexCastOp::create(b, loc, b.getI64Type(),
                                          getSetSize(storage.cols));
  Value handle = func::CallOp::create(
                     b, loc, product,
                     ValueRange{rowPointers(lhs), columnIndices(lhs),
                                rowPointers(rhs), columnIndices(rhs), cols})
                     .getResult(0);
  runtimePatterns[storage.runtimeEncoding] =
      takeRuntimePattern(loc, handle, getSetSize(storage.rows));
}

void FunctionLowering::buildRuntimePattern(Location loc,
                                           const Storage &storage) {
  // Products are built where they are computed (lowerMatMul), host
  // functions' matrices where they are returned: what is left is a
  // transpose of a BCSR matrix or a union of members that are all BCSR or
  // block diagonal (storageOfEncoding).
  StorageAttr encoding = storage.runtimeEncoding;
  MLIRContext *ctx = b.getContext();
  Type i32 = b.getI32Type(), i64 = b.getI64Type();
  auto indexArray = MemRefType::get({ShapedType::kDynamic}, i32);
  if (encoding.getKind() == StorageKind::Transpose) {
    Storage stored = *storageOfEncoding(encoding.getOperand(), storage.cols,
                                        storage.rows, setTypes);
    func::FuncOp transpose =
        declareRuntime(loc, runtimeName(RuntimeFunction::TransposePattern),
                       FunctionType::get(ctx, {indexArray, indexArray, i64},
                                         {LLVM::LLVMPointerType::get(ctx)}));
    Value handle = func::CallOp::create(
                       b, loc, transpose,
                       ValueRange{rowPointers(stored), columnIndices(stored),
                                  arith::IndexCastOp::create(
                                      b, loc, i64, getSetSize(storage.rows))})
                       .getResult(0);
    runtimePatterns[encoding] =
        takeRuntimePattern(loc, handle, getSetSize(storage.rows));
    return;
  }
  assert(encoding.getKind() == StorageKind::Union &&
         "a runtime pattern neither returned nor computed");
  func::FuncOp unite =
      declareRuntime(loc, runtimeName(RuntimeFunction::UnionPattern),
                     FunctionType::get(ctx,
                                       {i32, indexArray, indexArray, i32,
                                        indexArray, indexArray, i64, i64},
                                       {LLVM::LLVMPointerType::get(ctx)}));
  auto indexArraysOf = [&](const Storage &s) -> std::pair<Value, Value> {
    if (s.kind == Storage::Kind::Diagonal)
      return {emptyIndexArray(), emptyIndexArray()};
    return {rowPointers(s), columnIndices(s)};
  };
  Value rows = getSetSize(storage.rows);
  Value rows64 = arith::IndexCastOp::create(b, loc, i64, rows);
  Value cols64 =
      arith::IndexCastOp::create(b, loc, i64, getSetSize(storage.cols));
  // The union of the first two members, then of that and each next one.
  auto memberStorage = [&](unsigned i) {
    return *storageOfEncoding(encoding.getMember(i), storage.rows, storage.cols,
                              setTypes);
  };
  Storage first = memberStorage(0);
  std::pair<Value, Value> united = indexArraysOf(first);
  int32_t unitedLayout = unionLayout(first);
  for (unsigned i = 1, n = encoding.getMembers().size(); i < n; ++i) {
    Storage member = memberStorage(i);
    std::pair<Value, Value> arrays = indexArraysOf(member);
    Value handle =
        func::CallOp::create(
            b, loc, unite,
            ValueRange{
                arith::ConstantIntOp::create(b, loc, i32, unitedLayout),
                united.first, united.second,
                arith::ConstantIntOp::create(b, loc, i32, unionLayout(member)),
                arrays.first, arrays.second, rows64, cols64})
            .getResult(0);
    united = takeRuntimePattern(loc, handle, rows);
    unitedLayout = 0;
  }
  runtimePatterns[encoding] = united;
}
