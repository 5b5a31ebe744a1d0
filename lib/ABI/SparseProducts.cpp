//===--- SparseProducts.cpp - Products of system matrices -----------------===//
//
// C = A B of system matrices, each BCSR or block diagonal, into C's
// pattern (simit::multiplyInto).
//
//===----------------------------------------------------------------------===//

#include "RunState.h"

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/SparseProduct.h"

using simit::abi::abandonRun;
using simit::abi::fail;
using simit::abi::isContiguous;
using simit::abi::MemRefDescriptor;

namespace {
/// The BlockMatrixView of lowered arrays: BCSR (layout 0) or block
/// diagonal (layout 1, index arrays unused).
template <typename T>
simit::BlockMatrixView<T> blockMatrix(int32_t layout,
                                      MemRefDescriptor<int32_t, 1> *rowptr,
                                      MemRefDescriptor<int32_t, 1> *colidx,
                                      MemRefDescriptor<T, 3> *values) {
  simit::BlockMatrixView<T> view;
  view.blockRows = values->sizes[1];
  view.blockCols = values->sizes[2];
  view.values = values->data + values->offset;
  if (layout == 1) {
    view.rows = view.cols = values->sizes[0];
    return view;
  }
  view.rows = rowptr->sizes[0] - 1;
  view.rowptr = rowptr->data + rowptr->offset;
  view.colidx = colidx->data + colidx->offset;
  return view;
}

template <typename T>
bool multiplyMatrices(int32_t layoutA, MemRefDescriptor<int32_t, 1> *rowptrA,
                      MemRefDescriptor<int32_t, 1> *colidxA,
                      MemRefDescriptor<T, 3> *a, int32_t layoutB,
                      MemRefDescriptor<int32_t, 1> *rowptrB,
                      MemRefDescriptor<int32_t, 1> *colidxB,
                      MemRefDescriptor<T, 3> *b, int32_t layoutC,
                      MemRefDescriptor<int32_t, 1> *rowptrC,
                      MemRefDescriptor<int32_t, 1> *colidxC,
                      MemRefDescriptor<T, 3> *c, int64_t cols,
                      const char *where) {
  for (auto *m : {rowptrA, colidxA, rowptrB, colidxB, rowptrC, colidxC})
    if (!isContiguous(*m))
      return fail(where, "index arrays must be contiguous");
  if (!isContiguous(*a) || !isContiguous(*b) || !isContiguous(*c))
    return fail(where, "value arrays must be contiguous");
  simit::BlockMatrixView<T> left = blockMatrix(layoutA, rowptrA, colidxA, a);
  simit::BlockMatrixView<T> right = blockMatrix(layoutB, rowptrB, colidxB, b);
  simit::BlockMatrixView<T> result = blockMatrix(layoutC, rowptrC, colidxC, c);
  left.cols = right.rows;
  right.cols = result.cols = cols;
  if (llvm::Error err = simit::multiplyInto(left, right, result))
    return fail(where, llvm::toString(std::move(err)));
  return true;
}
} // namespace

extern "C" void _mlir_ciface_simit_rt_matmul_bcsr(
    int32_t layoutA, MemRefDescriptor<int32_t, 1> *rowptrA,
    MemRefDescriptor<int32_t, 1> *colidxA, MemRefDescriptor<double, 3> *a,
    int32_t layoutB, MemRefDescriptor<int32_t, 1> *rowptrB,
    MemRefDescriptor<int32_t, 1> *colidxB, MemRefDescriptor<double, 3> *b,
    int32_t layoutC, MemRefDescriptor<int32_t, 1> *rowptrC,
    MemRefDescriptor<int32_t, 1> *colidxC, MemRefDescriptor<double, 3> *c,
    int64_t cols, const char *where) {
  if (!multiplyMatrices(layoutA, rowptrA, colidxA, a, layoutB, rowptrB, colidxB,
                        b, layoutC, rowptrC, colidxC, c, cols, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_matmul_bcsr_f32(
    int32_t layoutA, MemRefDescriptor<int32_t, 1> *rowptrA,
    MemRefDescriptor<int32_t, 1> *colidxA, MemRefDescriptor<float, 3> *a,
    int32_t layoutB, MemRefDescriptor<int32_t, 1> *rowptrB,
    MemRefDescriptor<int32_t, 1> *colidxB, MemRefDescriptor<float, 3> *b,
    int32_t layoutC, MemRefDescriptor<int32_t, 1> *rowptrC,
    MemRefDescriptor<int32_t, 1> *colidxC, MemRefDescriptor<float, 3> *c,
    int64_t cols, const char *where) {
  if (!multiplyMatrices(layoutA, rowptrA, colidxA, a, layoutB, rowptrB, colidxB,
                        b, layoutC, rowptrC, colidxC, c, cols, where))
    abandonRun();
}
