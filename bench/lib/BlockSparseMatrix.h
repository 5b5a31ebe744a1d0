//===--- BlockSparseMatrix.h - Fixed-pattern 3x3-block matrix -*- C++ -*-===//
//
// A sparse matrix of 3x3 blocks over the vertices of a mesh, stored as a
// scalar row-major Eigen::SparseMatrix whose pattern is built once at set-up.
// Each block is addressed by the value index of its (0,0) entry; the entry
// (r, c) of the block lies at offset + r * rowStride(blockRow) + c, so
// per-frame assembly writes straight into the value array without searching.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_BLOCKSPARSEMATRIX_H
#define SIMIT_BENCH_BLOCKSPARSEMATRIX_H

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <utility>
#include <vector>

namespace simit::bench {

template <typename Scalar> class BlockSparseMatrix {
public:
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::RowMajor, int>;
  using Block = Eigen::Matrix<Scalar, 3, 3>;

  /// A matrix with the given nonzero blocks (row vertex, column vertex),
  /// duplicates allowed, plus every diagonal block.
  BlockSparseMatrix(int numBlockRows,
                    const std::vector<std::pair<int, int>> &blocks);

  /// The value index of block (row, col)'s (0,0) entry, or -1 when the
  /// block is not in the pattern. A binary search: for set-up only.
  int blockOffset(int row, int col) const;

  /// The distance in the value array between consecutive scalar rows of
  /// block row `row`.
  int rowStride(int row) const { return rowStride_[row]; }

  /// values += block at the block whose (0,0) entry is at `offset`.
  void addBlock(int offset, int stride, const Block &block) {
    Scalar *values = matrix_.valuePtr() + offset;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        values[r * stride + c] += block(r, c);
  }

  /// values -= block at the block whose (0,0) entry is at `offset`.
  void subtractBlock(int offset, int stride, const Block &block) {
    Scalar *values = matrix_.valuePtr() + offset;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        values[r * stride + c] -= block(r, c);
  }

  Matrix &matrix() { return matrix_; }
  const Matrix &matrix() const { return matrix_; }
  int numBlocks() const { return static_cast<int>(matrix_.nonZeros() / 9); }

private:
  Matrix matrix_;
  std::vector<int> rowStride_;
};

} // namespace simit::bench

#endif // SIMIT_BENCH_BLOCKSPARSEMATRIX_H
