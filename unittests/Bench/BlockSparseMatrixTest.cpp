//===--- BlockSparseMatrixTest.cpp - Pattern and block offsets ------------===//

#include "BlockSparseMatrix.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>
#include <set>

using namespace simit::bench;

namespace {

TEST(BlockSparseMatrix, PatternHoldsRequestedAndDiagonalBlocks) {
  std::vector<std::pair<int, int>> blocks = {{0, 2}, {2, 0}, {0, 2}, {3, 1}};
  BlockSparseMatrix<double> m(4, blocks);
  std::set<std::pair<int, int>> expected = {{0, 0}, {1, 1}, {2, 2}, {3, 3},
                                            {0, 2}, {2, 0}, {3, 1}};
  EXPECT_EQ(m.numBlocks(), static_cast<int>(expected.size()));
  EXPECT_EQ(m.matrix().nonZeros(), 9 * static_cast<long>(expected.size()));
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col)
      EXPECT_EQ(m.blockOffset(row, col) >= 0, expected.count({row, col}) == 1)
          << row << "," << col;
}

// Blocks scattered through offsets and strides land where a dense matrix
// built entry by entry puts them.
TEST(BlockSparseMatrix, AddBlockMatchesDenseAssembly) {
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> vertex(0, 19);
  std::uniform_real_distribution<double> value(-1, 1);
  std::vector<std::pair<int, int>> blocks;
  for (int i = 0; i < 60; ++i)
    blocks.emplace_back(vertex(rng), vertex(rng));
  std::vector<std::pair<int, int>> symmetric = blocks;
  for (const auto &[row, col] : blocks)
    symmetric.emplace_back(col, row);
  BlockSparseMatrix<double> sparse(20, symmetric);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(60, 60);
  for (int repeat = 0; repeat < 2; ++repeat)
    for (const auto &[row, col] : blocks) {
      Eigen::Matrix3d block = Eigen::Matrix3d::NullaryExpr(
          [&](Eigen::Index, Eigen::Index) { return value(rng); });
      dense.block<3, 3>(3 * row, 3 * col) += block;
      sparse.addBlock(sparse.blockOffset(row, col), sparse.rowStride(row),
                      block);
      dense.block<3, 3>(3 * col, 3 * row) -= block;
      sparse.subtractBlock(sparse.blockOffset(col, row), sparse.rowStride(col),
                           block);
    }
  EXPECT_EQ((Eigen::MatrixXd(sparse.matrix()) - dense).norm(), 0);
}

TEST(BlockSparseMatrix, MissingBlockHasNoOffset) {
  BlockSparseMatrix<float> m(3, {{0, 1}});
  EXPECT_EQ(m.blockOffset(1, 0), -1);
  EXPECT_EQ(m.blockOffset(2, 0), -1);
  EXPECT_EQ(m.blockOffset(0, 1), 3); // row 0: blocks (0,0), (0,1)
  EXPECT_EQ(m.rowStride(0), 6);
  EXPECT_EQ(m.rowStride(1), 3);
}

} // namespace
