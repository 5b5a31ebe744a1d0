//===--- NumericsLayout.h - Layouts the numerics check scans ----*- C++ -*-===//
//
// simit-check-numerics passes one of these to the runtime's
// simit_rt_check_numerics_* with each array it scans. This header depends
// on nothing but the C++ standard library.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ABI_NUMERICSLAYOUT_H
#define SIMIT_ABI_NUMERICSLAYOUT_H

#include <cstdint>

/// How block k of an array that simit_rt_check_numerics_* scans sits in
/// its tensor (docs/lowering.md, storage of system tensors).
enum SimitNumericsLayout : int32_t {
  /// A vector: block k is element k of the row set.
  SIMIT_NUMERICS_VECTOR = 0,
  /// A diagonal matrix: block k is (k, k).
  SIMIT_NUMERICS_DIAGONAL = 1,
  /// BCSR: the row r with rowptr[r] <= k < rowptr[r + 1], column colidx[k].
  SIMIT_NUMERICS_PATTERN = 2,
  /// `perRow` blocks a row (an incidence matrix): row k / perRow, column
  /// colidx[k].
  SIMIT_NUMERICS_FIXED_ROWS = 3,
  /// A grid stencil matrix of `perRow` offsets: block k is row
  /// k % (blocks / perRow) at offset number k / (blocks / perRow).
  SIMIT_NUMERICS_STENCIL = 4,
  /// A dense matrix of `perRow` columns: block k is (k / perRow,
  /// k % perRow).
  SIMIT_NUMERICS_DENSE = 5,
};

#endif // SIMIT_ABI_NUMERICSLAYOUT_H
