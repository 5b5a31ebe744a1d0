//===--- SupernodalCholesky.cpp - Numeric LL^T on a supernodal layout -----===//

#include "SupernodalCholesky.h"

#include "llvm/Support/ErrorHandling.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

extern "C" {
void dgemm_(const char *transa, const char *transb, const int *m, const int *n,
            const int *k, const double *alpha, const double *a, const int *lda,
            const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc);
void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k,
            const double *alpha, const double *a, const int *lda,
            const double *beta, double *c, const int *ldc);
}

using namespace simit;
using namespace simit::direct;

namespace {

// The dense loops below are compiled twice, for the host's AVX2 and FMA
// when it has them (chosen when the library loads) and for any x86-64.
#if defined(__x86_64__) && defined(__GNUC__)
#define SIMIT_HOST_VECTOR_CLONES                                               \
  __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define SIMIT_HOST_VECTOR_CLONES
#endif

/// Multiply-adds from which an update goes to BLAS: below it the call's own
/// cost (packing, dispatch) outweighs its faster kernel.
constexpr int64_t kBlasProductWork = 128 * 1024;

/// Which supernode each group of `width` consecutive columns belongs to
/// (each column for width 1, each block column for a block's width).
std::vector<int32_t> supernodeOfColumns(const SupernodeLayout &layout,
                                        int64_t width = 1) {
  std::vector<int32_t> supernodeOf(static_cast<size_t>(layout.size() / width));
  for (int64_t s = 0; s < layout.supernodes; ++s) {
    if (layout.first[s] % width != 0)
      llvm::report_fatal_error("simit: a Cholesky supernode splits a block");
    std::fill(supernodeOf.begin() + layout.first[s] / width,
              supernodeOf.begin() + layout.first[s + 1] / width,
              static_cast<int32_t>(s));
  }
  return supernodeOf;
}

/// Rows and columns of the tiles of c that the small products keep in
/// registers across the whole k loop (two AVX2 or one AVX-512 register of
/// doubles per column).
constexpr int64_t kTileRows = 8, kTileColumns = 4;

/// c's rows [i0, i0 + kTileRows) x columns [j0, j0 + Columns) of a * b^T.
template <int64_t Columns>
inline void productTile(const double *__restrict a, int64_t lda, int64_t k,
                        int64_t i0, int64_t j0, double *__restrict c,
                        int64_t m) {
  double sum[Columns][kTileRows] = {};
  for (int64_t p = 0; p < k; ++p) {
    const double *__restrict column = a + p * lda;
    for (int64_t j = 0; j < Columns; ++j)
      for (int64_t i = 0; i < kTileRows; ++i)
        sum[j][i] += column[i0 + i] * column[j0 + j];
  }
  for (int64_t j = 0; j < Columns; ++j)
    for (int64_t i = 0; i < kTileRows; ++i)
      c[(j0 + j) * m + i0 + i] = sum[j][i];
}

/// The tiles of c's columns [j0, j0 + Columns) from row j0 down. The last
/// tile is moved up to end at row m rather than cut short: its rows are
/// computed twice, to the same values.
template <int64_t Columns>
inline void productColumns(const double *a, int64_t lda, int64_t m, int64_t k,
                           int64_t j0, double *c) {
  for (int64_t i0 = j0;; i0 += kTileRows) {
    int64_t top = std::min(i0, m - kTileRows);
    productTile<Columns>(a, lda, k, top, j0, c, m);
    if (top + kTileRows >= m)
      return;
  }
}

/// c (m x m1, column-major) = the lower trapezoid of a * b^T, where a is
/// the m x k panel at `a` (leading dimension lda) and b its first m1 rows.
/// Entries above the diagonal of c may be written too.
SIMIT_HOST_VECTOR_CLONES void lowerProduct(const double *a, int64_t lda,
                                           int64_t m, int64_t m1, int64_t k,
                                           double *__restrict c) {
  if (m * m1 * k >= kBlasProductWork) {
    // The top m1 x m1 block's lower triangle, then the rows below it.
    int im = static_cast<int>(m), im1 = static_cast<int>(m1),
        rest = static_cast<int>(m - m1), ik = static_cast<int>(k),
        ilda = static_cast<int>(lda);
    double one = 1, zero = 0;
    dsyrk_("L", "N", &im1, &ik, &one, a, &ilda, &zero, c, &im);
    if (rest > 0)
      dgemm_("N", "T", &rest, &im1, &ik, &one, a + m1, &ilda, a, &ilda, &zero,
             c + m1, &im);
    return;
  }
  if (m < kTileRows) {
    for (int64_t j = 0; j < m1; ++j)
      for (int64_t i = j; i < m; ++i) {
        double sum = 0;
        for (int64_t p = 0; p < k; ++p)
          sum += a[p * lda + i] * a[p * lda + j];
        c[j * m + i] = sum;
      }
    return;
  }
  // Tiles of kTileColumns columns; as with rows, the last is moved left
  // rather than cut short, and fewer columns than a tile get their own.
  switch (m1) {
  case 1:
    return productColumns<1>(a, lda, m, k, 0, c);
  case 2:
    return productColumns<2>(a, lda, m, k, 0, c);
  case 3:
    return productColumns<3>(a, lda, m, k, 0, c);
  }
  for (int64_t j0 = 0;; j0 += kTileColumns) {
    int64_t left = std::min(j0, m1 - kTileColumns);
    productColumns<kTileColumns>(a, lda, m, k, left, c);
    if (left + kTileColumns >= m1)
      return;
  }
}

/// Cholesky of the leading `columns` x `columns` block of the rows x
/// columns matrix at `a` (leading dimension ld), the rows below solved
/// against it, one column at a time. Returns the first column with a pivot
/// that is not positive, or `columns`.
SIMIT_HOST_VECTOR_CLONES int64_t factoriseColumns(double *a, int64_t ld,
                                                  int64_t rows,
                                                  int64_t columns) {
  for (int64_t j = 0; j < columns; ++j) {
    double *__restrict column = a + j * ld;
    for (int64_t p = 0; p < j; ++p) {
      const double *__restrict earlier = a + p * ld;
      double scale = earlier[j];
      for (int64_t i = j; i < rows; ++i)
        column[i] -= earlier[i] * scale;
    }
    double pivot = column[j];
    if (!(pivot > 0) || !std::isfinite(pivot))
      return j;
    double diagonal = std::sqrt(pivot), inverse = 1 / diagonal;
    column[j] = diagonal;
    for (int64_t i = j + 1; i < rows; ++i)
      column[i] *= inverse;
  }
  return columns;
}

/// Columns of a panel factorised together: the update from the columns
/// before them is one product of register tiles (lowerProduct), not a
/// column at a time. Faster than LAPACK's dpotrf and dtrsm at every panel
/// size of the chamber and of fem-dragon (whose numeric factorisation
/// took 43 ms with them, 39 ms without); 8 was the best width on both.
constexpr int64_t kPanelBlock = 8;

/// The panel of one supernode (height x columns, leading dimension height)
/// with all updates from earlier supernodes applied becomes L's: Cholesky
/// of its diagonal block, then the rows below solved against it, by
/// blocks of kPanelBlock columns (`scratch` holds height x kPanelBlock).
/// Returns the panel's first column with a pivot that is not positive, or
/// `columns`.
int64_t factorisePanel(double *panel, int64_t height, int64_t columns,
                       double *scratch) {
  for (int64_t j0 = 0; j0 < columns; j0 += kPanelBlock) {
    int64_t width = std::min(kPanelBlock, columns - j0), rows = height - j0;
    double *block = panel + j0 * height + j0;
    if (j0 > 0) {
      lowerProduct(panel + j0, height, rows, width, j0, scratch);
      for (int64_t j = 0; j < width; ++j) {
        double *__restrict target = block + j * height;
        const double *__restrict update = scratch + j * rows;
        for (int64_t i = j; i < rows; ++i)
          target[i] -= update[i];
      }
    }
    int64_t factorised = factoriseColumns(block, height, rows, width);
    if (factorised < width)
      return j0 + factorised;
  }
  return columns;
}

/// Columns of a panel taken together in the forward solve, so that the
/// rows below the diagonal block are loaded and stored once per group.
constexpr int64_t kColumnGroup = 4;
/// sums[g] -= columns[g] . dense over `m` rows, for the kColumnGroup
/// columns of a group at once: each entry of `dense` is loaded once for
/// all of them, and each column's sum runs in four lanes.
template <typename T>
inline __attribute__((always_inline)) void
subtractGroupDots(const T *const *columns, const double *__restrict dense,
                  int64_t m, double *sums) {
  constexpr int64_t kLanes = 4;
  double lane[kColumnGroup][kLanes] = {};
  int64_t i = 0;
  for (; i + kLanes <= m; i += kLanes)
    for (int64_t g = 0; g < kColumnGroup; ++g)
      for (int64_t l = 0; l < kLanes; ++l)
        lane[g][l] += columns[g][i + l] * dense[i + l];
  for (int64_t g = 0; g < kColumnGroup; ++g) {
    double sum = 0;
    for (int64_t j = i; j < m; ++j)
      sum += columns[g][j] * dense[j];
    for (int64_t l = 0; l < kLanes; ++l)
      sum += lane[g][l];
    sums[g] -= sum;
  }
}

} // namespace

std::vector<BlockPlacement>
direct::blockPlacements(const SupernodeLayout &layout,
                        const int64_t *permutation, int64_t blockRows,
                        int64_t blockSize, const int32_t *rowptr,
                        const int32_t *colidx) {
  int64_t bs = blockSize;
  // Everything below is in blocks: blockPosition[b] is the block column
  // of L that holds the matrix's block row b. A block's unknowns must be
  // consecutive in L (and supernodes whole blocks) for its entries to lie
  // at fixed strides.
  std::vector<int32_t> blockPosition(static_cast<size_t>(blockRows));
  for (int64_t k = 0; k < blockRows; ++k) {
    int64_t first = permutation[k * bs];
    for (int64_t i = 0; i < bs; ++i)
      if (first % bs != 0 || permutation[k * bs + i] != first + i)
        llvm::report_fatal_error("simit: the Cholesky analysis split the "
                                 "unknowns of a block");
    blockPosition[first / bs] = static_cast<int32_t>(k);
  }
  std::vector<int32_t> supernodeOf = supernodeOfColumns(layout, bs);
  // Block (r, c), c <= r, in L's order: (max, min) of its row's and
  // column's positions. The blocks are sorted by the supernode of L's
  // column (counting sort), so that each panel's rows are indexed once
  // for all of its blocks.
  int64_t blocks = rowptr[blockRows];
  std::vector<int32_t> lower(static_cast<size_t>(blocks), -1),
      upper(static_cast<size_t>(blocks)),
      bucketStart(static_cast<size_t>(layout.supernodes) + 1, 0);
  // Whether the block's row comes first in L's order: then its columns are
  // L's rows (the block is read transposed).
  std::vector<bool> transposed(static_cast<size_t>(blocks));
  for (int64_t r = 0; r < blockRows; ++r)
    for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k) {
      if (colidx[k] > r)
        continue;
      int32_t row = blockPosition[r], column = blockPosition[colidx[k]];
      lower[k] = std::min(row, column);
      upper[k] = std::max(row, column);
      transposed[k] = row < column;
      ++bucketStart[supernodeOf[lower[k]] + 1];
    }
  std::partial_sum(bucketStart.begin(), bucketStart.end(), bucketStart.begin());
  std::vector<int32_t> sorted(static_cast<size_t>(bucketStart.back())),
      filled(bucketStart.begin(), bucketStart.end() - 1);
  for (int64_t k = 0; k < blocks; ++k)
    if (lower[k] >= 0)
      sorted[filled[supernodeOf[lower[k]]]++] = static_cast<int32_t>(k);

  std::vector<BlockPlacement> placements(static_cast<size_t>(blocks));
  std::vector<int32_t> indexInPanel(static_cast<size_t>(blockRows));
  for (int64_t s = 0; s < layout.supernodes; ++s) {
    int64_t height = layout.rowStart[s + 1] - layout.rowStart[s];
    const int64_t *rows = layout.rows + layout.rowStart[s];
    for (int64_t r = 0; r < height; r += bs)
      indexInPanel[rows[r] / bs] = static_cast<int32_t>(r);
    for (int32_t q = bucketStart[s]; q < bucketStart[s + 1]; ++q) {
      int32_t k = sorted[q];
      int64_t row = indexInPanel[upper[k]];
      // A symbolic analysis that missed an entry of A would have it land
      // on another entry of L: never a wrong factor, stop instead.
      for (int64_t i = 0; i < bs; ++i)
        if (row + i >= height || rows[row + i] != upper[k] * bs + i)
          llvm::report_fatal_error("simit: the Cholesky analysis lost an "
                                   "entry of the matrix's pattern");
      BlockPlacement &placement = placements[k];
      placement.position = layout.valueStart[s] +
                           (lower[k] * bs - layout.first[s]) * height + row;
      placement.rowStride = transposed[k] ? height : 1;
      placement.columnStride = transposed[k] ? 1 : height;
    }
  }
  return placements;
}

int64_t direct::factorise(const SupernodeLayout &layout, double *values) {
  int64_t n = layout.size(), supernodes = layout.supernodes;
  std::vector<int32_t> supernodeOf = supernodeOfColumns(layout);
  // Left-looking: the supernodes whose panels still have rows to give are
  // kept in lists, one per supernode their next row falls in (head, next),
  // with the position of that row in their panel (nextRow).
  std::vector<int64_t> head(supernodes, -1), next(supernodes, -1),
      nextRow(supernodes, 0), indexInPanel(n, 0);
  // An update is at most (rows below a panel's columns) x (columns of the
  // panel it reaches), a panel's own at most its height x kPanelBlock; the
  // two take turns in one buffer, written before it is read.
  int64_t widest = 0, deepest = 0;
  for (int64_t s = 0; s < supernodes; ++s) {
    int64_t columns = layout.first[s + 1] - layout.first[s];
    widest = std::max(widest, columns);
    deepest = std::max(deepest,
                       layout.rowStart[s + 1] - layout.rowStart[s] - columns);
  }
  std::unique_ptr<double[]> update(new double[static_cast<size_t>(std::max(
      deepest * std::min(widest, deepest), (widest + deepest) * kPanelBlock))]);
  // Where the rows of an update lie in the panel it is subtracted from.
  std::vector<int64_t> rowInPanel(static_cast<size_t>(deepest));

  for (int64_t s = 0; s < supernodes; ++s) {
    int64_t k1 = layout.first[s], k2 = layout.first[s + 1];
    int64_t height = layout.rowStart[s + 1] - layout.rowStart[s];
    const int64_t *rows = layout.rows + layout.rowStart[s];
    double *panel = values + layout.valueStart[s];
    for (int64_t i = 0; i < height; ++i)
      indexInPanel[rows[i]] = i;

    for (int64_t d = head[s]; d != -1;) {
      int64_t following = next[d];
      int64_t dHeight = layout.rowStart[d + 1] - layout.rowStart[d];
      const int64_t *dRows = layout.rows + layout.rowStart[d];
      int64_t top = nextRow[d], end = top;
      while (end < dHeight && dRows[end] < k2)
        ++end;
      int64_t m = dHeight - top, m1 = end - top;
      lowerProduct(values + layout.valueStart[d] + top, dHeight, m, m1,
                   layout.first[d + 1] - layout.first[d], update.get());
      for (int64_t i = 0; i < m; ++i)
        rowInPanel[i] = indexInPanel[dRows[top + i]];
      for (int64_t j = 0; j < m1; ++j) {
        double *__restrict target = panel + (dRows[top + j] - k1) * height;
        const double *__restrict column = update.get() + j * m;
        for (int64_t i = j; i < m; ++i)
          target[rowInPanel[i]] -= column[i];
      }
      nextRow[d] = end;
      if (end < dHeight) {
        int64_t later = supernodeOf[dRows[end]];
        next[d] = head[later];
        head[later] = d;
      }
      d = following;
    }

    int64_t columns = k2 - k1;
    int64_t failed = factorisePanel(panel, height, columns, update.get());
    if (failed < columns)
      return k1 + failed;
    nextRow[s] = columns;
    if (columns < height) {
      int64_t later = supernodeOf[rows[columns]];
      next[s] = head[later];
      head[later] = s;
    }
  }
  return n;
}

template <typename T>
SIMIT_HOST_VECTOR_CLONES void
direct::solve(const SupernodeLayout &layout, const T *values,
              double *__restrict y, double *__restrict dense) {
  // L y' = y, supernode by supernode: the diagonal block's forward
  // substitution, then the rows below take the panel times its solution,
  // summed in `dense` (contiguous, so the products are dense loops) and
  // scattered into y once per row.
  for (int64_t s = 0; s < layout.supernodes; ++s) {
    int64_t k1 = layout.first[s], columns = layout.first[s + 1] - k1;
    int64_t height = layout.rowStart[s + 1] - layout.rowStart[s];
    int64_t m = height - columns;
    const int64_t *below = layout.rows + layout.rowStart[s] + columns;
    const T *panel = values + layout.valueStart[s];
    for (int64_t j = 0; j < columns; ++j) {
      const T *column = panel + j * height;
      double yj = y[k1 + j] / column[j];
      y[k1 + j] = yj;
      for (int64_t i = j + 1; i < columns; ++i)
        y[k1 + i] -= column[i] * yj;
    }
    std::fill(dense, dense + m, 0.0);
    for (int64_t j = 0; j < columns; j += kColumnGroup) {
      int64_t group = std::min(kColumnGroup, columns - j);
      double solved[kColumnGroup] = {};
      const T *column[kColumnGroup];
      for (int64_t g = 0; g < kColumnGroup; ++g) {
        // A short last group repeats its last column, times zero.
        column[g] = panel + (j + std::min(g, group - 1)) * height + columns;
        solved[g] = g < group ? y[k1 + j + g] : 0.0;
      }
      for (int64_t i = 0; i < m; ++i)
        dense[i] += column[0][i] * solved[0] + column[1][i] * solved[1] +
                    column[2][i] * solved[2] + column[3][i] * solved[3];
    }
    for (int64_t i = 0; i < m; ++i)
      y[below[i]] -= dense[i];
  }
  // L^T x' = y', in reverse, a group of columns at a time from the last:
  // each column's sum over its panel rows below the group (the supernode's
  // later columns, already solved in y, and the rows below it, gathered
  // into `dense` once), then the group's own triangle.
  for (int64_t s = layout.supernodes; s-- > 0;) {
    int64_t k1 = layout.first[s], columns = layout.first[s + 1] - k1;
    int64_t height = layout.rowStart[s + 1] - layout.rowStart[s];
    int64_t m = height - columns;
    const int64_t *below = layout.rows + layout.rowStart[s] + columns;
    const T *panel = values + layout.valueStart[s];
    for (int64_t i = 0; i < m; ++i)
      dense[i] = y[below[i]];
    for (int64_t end = columns; end > 0;) {
      int64_t group = std::min(kColumnGroup, end), j0 = end - group;
      double sums[kColumnGroup];
      const T *solvedRows[kColumnGroup], *belowRows[kColumnGroup];
      for (int64_t g = 0; g < kColumnGroup; ++g) {
        // A short group repeats its last column; its sums are not used.
        const T *column = panel + (j0 + std::min(g, group - 1)) * height;
        solvedRows[g] = column + end;
        belowRows[g] = column + columns;
        sums[g] = y[k1 + j0 + std::min(g, group - 1)];
      }
      subtractGroupDots(solvedRows, y + k1 + end, columns - end, sums);
      subtractGroupDots(belowRows, dense, m, sums);
      for (int64_t j = end; j-- > j0;) {
        const T *column = panel + j * height;
        double sum = sums[j - j0];
        for (int64_t i = j + 1; i < end; ++i)
          sum -= column[i] * y[k1 + i];
        y[k1 + j] = sum / column[j];
      }
      end = j0;
    }
  }
}

template void direct::solve(const SupernodeLayout &, const float *, double *,
                            double *);
template void direct::solve(const SupernodeLayout &, const double *, double *,
                            double *);
