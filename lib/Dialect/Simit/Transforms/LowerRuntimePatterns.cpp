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
FunctionLowering::runtimePatternOf(Location loc, RuntimeFunction function,
                                   ValueRange args, StringAttr rows) {
  MLIRContext *ctx = b.getContext();
  Type i64 = b.getI64Type();
  func::FuncOp build =
      declareRuntime(loc, runtimeName(function),
                     FunctionType::get(ctx, args.getTypes(),
                                       {LLVM::LLVMPointerType::get(ctx)}));
  Value handle = func::CallOp::create(b, loc, build, args).getResult(0);
  Value blocks = callRuntime(loc, runtimeName(RuntimeFunction::PatternBlocks),
                             {i64}, {handle});
  auto indexArray = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  Value rowptr =
      memref::AllocOp::create(b, loc, indexArray,
                              ValueRange{arith::AddIOp::create(
                                  b, loc, getSetSize(rows), indexConstant(1))});
  Value colidx = memref::AllocOp::create(
      b, loc, indexArray,
      ValueRange{arith::IndexCastOp::create(b, loc, b.getIndexType(), blocks)});
  func::FuncOp take = declareRuntime(
      loc, runtimeName(RuntimeFunction::PatternTake),
      FunctionType::get(ctx, {handle.getType(), indexArray, indexArray}, {}));
  func::CallOp::create(b, loc, take, ValueRange{handle, rowptr, colidx});
  return {rowptr, colidx};
}

bool mlir::simit::loops::isBindingPattern(StorageAttr runtimeEncoding) {
  return runtimeEncoding &&
         (runtimeEncoding.getKind() == StorageKind::Union ||
          runtimeEncoding.getKind() == StorageKind::Transpose) &&
         !storage::findHost(runtimeEncoding);
}

/// The number of blocks of `set` as the runtime's pattern functions take
/// it (i64).
static Value blockCount(FunctionLowering &l, Location loc, StringAttr set) {
  return arith::IndexCastOp::create(l.b, loc, l.b.getI64Type(),
                                    l.getSetSize(set));
}

void FunctionLowering::buildProductPattern(Location loc, const Storage &storage,
                                           const Storage &lhs,
                                           const Storage &rhs) {
  std::pair<Value, Value> lhsPattern = bcsrIndexArrays(loc, lhs);
  std::pair<Value, Value> rhsPattern = bcsrIndexArrays(loc, rhs);
  runtimePatterns[storage.runtimeEncoding] = runtimePatternOf(
      loc, RuntimeFunction::ProductPattern,
      {lhsPattern.first, lhsPattern.second, rhsPattern.first, rhsPattern.second,
       blockCount(*this, loc, storage.cols)},
      storage.rows);
}

void FunctionLowering::buildRuntimePattern(Location loc,
                                           const Storage &storage) {
  // Products are built where they are computed (lowerMatMul), host
  // functions' matrices where they are returned: what is left is a
  // transpose of a BCSR matrix or a union of members that are all BCSR or
  // block diagonal (storageOfEncoding).
  StorageAttr encoding = storage.runtimeEncoding;
  Value cols = blockCount(*this, loc, storage.cols);
  if (encoding.getKind() == StorageKind::Transpose) {
    Storage stored = *storageOfEncoding(encoding.getOperand(), storage.cols,
                                        storage.rows, setTypes);
    runtimePatterns[encoding] =
        runtimePatternOf(loc, RuntimeFunction::TransposePattern,
                         {rowPointers(stored), columnIndices(stored),
                          blockCount(*this, loc, storage.rows)},
                         storage.rows);
    return;
  }
  assert(encoding.getKind() == StorageKind::Union &&
         "a runtime pattern neither returned nor computed");
  // The union of the first two members, then of that and each next one; a
  // block diagonal member as the BCSR pattern of its layout.
  auto member = [&](unsigned i) {
    return bcsrIndexArrays(loc, *storageOfEncoding(encoding.getMember(i),
                                                   storage.rows, storage.cols,
                                                   setTypes));
  };
  std::pair<Value, Value> united = member(0);
  for (unsigned i = 1, n = encoding.getMembers().size(); i < n; ++i) {
    std::pair<Value, Value> next = member(i);
    united = runtimePatternOf(
        loc, RuntimeFunction::UnionPattern,
        {united.first, united.second, next.first, next.second, cols},
        storage.rows);
  }
  runtimePatterns[encoding] = united;
}
