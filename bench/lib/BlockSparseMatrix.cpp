//===--- BlockSparseMatrix.cpp - Fixed-pattern 3x3-block sparse matrix ----===//

#include "BlockSparseMatrix.h"

#include <algorithm>

namespace simit::bench {

template <typename Scalar>
BlockSparseMatrix<Scalar>::BlockSparseMatrix(
    int numBlockRows, const std::vector<std::pair<int, int>> &blocks)
    : rowStride_(numBlockRows) {
  std::vector<std::vector<int>> columns(numBlockRows);
  for (int row = 0; row < numBlockRows; ++row)
    columns[row].push_back(row);
  for (const auto &[row, col] : blocks)
    columns[row].push_back(col);
  long numBlocks = 0;
  for (auto &cols : columns) {
    std::sort(cols.begin(), cols.end());
    cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
    numBlocks += static_cast<long>(cols.size());
  }

  int n = 3 * numBlockRows;
  matrix_.resize(n, n);
  matrix_.resizeNonZeros(9 * numBlocks);
  int *rowStart = matrix_.outerIndexPtr();
  int *colIndex = matrix_.innerIndexPtr();
  int next = 0;
  for (int row = 0; row < numBlockRows; ++row) {
    rowStride_[row] = 3 * static_cast<int>(columns[row].size());
    for (int r = 0; r < 3; ++r) {
      rowStart[3 * row + r] = next;
      for (int col : columns[row])
        for (int c = 0; c < 3; ++c)
          colIndex[next++] = 3 * col + c;
    }
  }
  rowStart[n] = next;
  std::fill_n(matrix_.valuePtr(), next, Scalar(0));
}

template <typename Scalar>
int BlockSparseMatrix<Scalar>::blockOffset(int row, int col) const {
  const int *begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[3 * row];
  const int *end = begin + rowStride_[row];
  const int *found = std::lower_bound(begin, end, 3 * col);
  if (found == end || *found != 3 * col)
    return -1;
  return static_cast<int>(found - matrix_.innerIndexPtr());
}

template class BlockSparseMatrix<float>;
template class BlockSparseMatrix<double>;

} // namespace simit::bench
