//===--- SparseProduct.h - Products of block sparse matrices ----*- C++ -*-===//
//
// C = A B for block sparse matrices in arrays owned elsewhere (lowered
// code's BCSR or block diagonal arrays), on a pattern of C built once per
// binding (productPattern), so each call is only the numeric phase.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SPARSEPRODUCT_H
#define SIMIT_RUNTIME_SPARSEPRODUCT_H

#include "llvm/Support/Error.h"

#include <cstdint>

namespace simit {

/// A matrix of rows x cols blocks of blockRows x blockCols row-major
/// components: BCSR (row r's blocks rowptr[r] .. rowptr[r + 1] at columns
/// colidx[...], sorted), or block diagonal when rowptr is null (block r at
/// (r, r)), or dense when `dense` is set (every block, row by row: block
/// r * cols + c). With `positions` (an incidence's rows, IncidenceView),
/// block k of the rows is at value position positions[k], and a row may
/// name a column twice; such a matrix is only read.
template <typename T> struct BlockMatrixView {
  int64_t rows = 0, cols = 0;
  int64_t blockRows = 1, blockCols = 1;
  const int32_t *rowptr = nullptr;
  const int32_t *colidx = nullptr;
  const int32_t *positions = nullptr;
  bool dense = false;
  T *values = nullptr;

  int64_t begin(int64_t r) const {
    return rowptr ? rowptr[r] : dense ? r * cols : r;
  }
  int64_t end(int64_t r) const {
    return rowptr ? rowptr[r + 1] : dense ? (r + 1) * cols : r + 1;
  }
  int64_t column(int64_t k) const {
    return colidx ? colidx[k] : dense ? k % cols : k;
  }
  T *block(int64_t k) const {
    return values + (positions ? positions[k] : k) * blockRows * blockCols;
  }
};

/// Overwrites C's values with A B. C's pattern must hold every block of the
/// product; shapes must agree. Errors name the mismatch or the first block
/// of the product missing from C's pattern.
template <typename T>
llvm::Error multiplyInto(const BlockMatrixView<T> &a,
                         const BlockMatrixView<T> &b,
                         const BlockMatrixView<T> &c);

} // namespace simit

#endif // SIMIT_RUNTIME_SPARSEPRODUCT_H
