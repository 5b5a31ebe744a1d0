//===--- SparseProducts.cpp - Products of system matrices -----------------===//
//
// C = A B of system matrices, each BCSR or block diagonal (A and B may be
// incidences read row by row), into C's pattern (simit::multiplyInto).
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
using IndexArray = MemRefDescriptor<int32_t, 1>;

/// The BlockMatrixView of lowered arrays: BCSR (layout 0), block diagonal
/// (layout 1, index arrays unused), an incidence's rows (layout 2) or dense
/// (layout 3, `cols` blocks a row, index arrays unused).
template <typename T>
simit::BlockMatrixView<T> blockMatrix(int32_t layout, IndexArray *rowptr,
                                      IndexArray *colidx, IndexArray *positions,
                                      MemRefDescriptor<T, 3> *values,
                                      int64_t cols) {
  simit::BlockMatrixView<T> view;
  view.blockRows = values->sizes[1];
  view.blockCols = values->sizes[2];
  view.values = values->data + values->offset;
  view.cols = cols;
  if (layout == 1) {
    view.rows = values->sizes[0];
    return view;
  }
  if (layout == 3) {
    view.dense = true;
    view.rows = cols ? values->sizes[0] / cols : 0;
    return view;
  }
  view.rows = rowptr->sizes[0] - 1;
  view.rowptr = rowptr->data + rowptr->offset;
  view.colidx = colidx->data + colidx->offset;
  if (layout == 2)
    view.positions = positions->data + positions->offset;
  return view;
}

template <typename T>
bool multiplyMatrices(int32_t layoutA, IndexArray *rowptrA, IndexArray *colidxA,
                      IndexArray *positionsA, MemRefDescriptor<T, 3> *a,
                      int32_t layoutB, IndexArray *rowptrB, IndexArray *colidxB,
                      IndexArray *positionsB, MemRefDescriptor<T, 3> *b,
                      int32_t layoutC, IndexArray *rowptrC, IndexArray *colidxC,
                      MemRefDescriptor<T, 3> *c, int64_t cols,
                      const char *where) {
  for (IndexArray *m : {rowptrA, colidxA, positionsA, rowptrB, colidxB,
                        positionsB, rowptrC, colidxC})
    if (!isContiguous(*m))
      return fail(where, "index arrays must be contiguous");
  if (!isContiguous(*a) || !isContiguous(*b) || !isContiguous(*c))
    return fail(where, "value arrays must be contiguous");
  if (layoutC == 2)
    return fail(where, "the product's result must be BCSR or block diagonal");
  // B's rows are A's columns; a dense B has `cols` blocks a row.
  simit::BlockMatrixView<T> right =
      blockMatrix(layoutB, rowptrB, colidxB, positionsB, b, cols);
  simit::BlockMatrixView<T> result =
      blockMatrix(layoutC, rowptrC, colidxC, nullptr, c, cols);
  simit::BlockMatrixView<T> left = blockMatrix(
      layoutA, rowptrA, colidxA, positionsA, a,
      layoutA == 3 ? right.rows : 0);
  left.cols = right.rows;
  if (llvm::Error err = simit::multiplyInto(left, right, result))
    return fail(where, llvm::toString(std::move(err)));
  return true;
}
} // namespace

/// The C entry point of the product of `T` matrices (RuntimeFunctions.h).
#define SIMIT_RT_MATMUL_BCSR(NAME, T)                                          \
  extern "C" void NAME(                                                        \
      int32_t layoutA, IndexArray *rowptrA, IndexArray *colidxA,               \
      IndexArray *positionsA, MemRefDescriptor<T, 3> *a, int32_t layoutB,      \
      IndexArray *rowptrB, IndexArray *colidxB, IndexArray *positionsB,        \
      MemRefDescriptor<T, 3> *b, int32_t layoutC, IndexArray *rowptrC,         \
      IndexArray *colidxC, MemRefDescriptor<T, 3> *c, int64_t cols,            \
      const char *where) {                                                     \
    if (!multiplyMatrices(layoutA, rowptrA, colidxA, positionsA, a, layoutB,   \
                          rowptrB, colidxB, positionsB, b, layoutC, rowptrC,   \
                          colidxC, c, cols, where))                            \
      abandonRun();                                                            \
  }

SIMIT_RT_MATMUL_BCSR(_mlir_ciface_simit_rt_matmul_bcsr, double)
SIMIT_RT_MATMUL_BCSR(_mlir_ciface_simit_rt_matmul_bcsr_f32, float)
SIMIT_RT_MATMUL_BCSR(_mlir_ciface_simit_rt_matmul_bcsr_i32, int32_t)
