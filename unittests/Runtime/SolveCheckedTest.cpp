//===--- SolveCheckedTest.cpp - x = A \ b against dense Eigen solves ------===//

#include "simit/Runtime/Solvers.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include <Eigen/Dense>

#include <random>
#include <vector>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// A matrix of n x n blocks of b x b in BCSR arrays on a band pattern
/// (blocks (r, c) with |r - c| <= 1), with its dense copy.
template <typename T> struct BandSystem {
  std::vector<int32_t> rowptr{0}, colidx;
  std::vector<T> values;
  Eigen::MatrixXd dense;

  BandSystem(int n, int b, const Eigen::MatrixXd &full) : dense(full) {
    for (int r = 0; r < n; ++r) {
      for (int c = std::max(0, r - 1); c <= std::min(n - 1, r + 1); ++c) {
        colidx.push_back(c);
        for (int i = 0; i < b; ++i)
          for (int j = 0; j < b; ++j)
            values.push_back(static_cast<T>(full(r * b + i, c * b + j)));
      }
      rowptr.push_back(static_cast<int32_t>(colidx.size()));
    }
    view.rows = n;
    view.blockSize = b;
    view.rowptr = rowptr.data();
    view.colidx = colidx.data();
    view.values = values.data();
  }
  SquareBCSRView<T> view;
};

/// A random matrix with the band pattern of n x n blocks of b x b.
Eigen::MatrixXd randomBand(int n, int b, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n * b, n * b);
  for (int i = 0; i < n * b; ++i)
    for (int j = 0; j < n * b; ++j)
      if (std::abs(i / b - j / b) <= 1)
        m(i, j) = value(rng);
  return m;
}

Eigen::VectorXd randomVector(int size, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1, 1);
  return Eigen::VectorXd::NullaryExpr(size, [&] { return value(rng); });
}

/// Solves with solveChecked and compares with a dense LU; returns the
/// method used.
template <typename T>
SolveMethod expectSolves(const Eigen::MatrixXd &a, int n, int b,
                         double tolerance) {
  BandSystem<T> system(n, b, a);
  Eigen::VectorXd rhs = randomVector(n * b, 17);
  std::vector<T> bv(rhs.data(), rhs.data() + rhs.size()), x(rhs.size(), 7);
  llvm::Expected<SolveReport> report =
      solveChecked(system.view, bv.data(), x.data());
  if (!report) {
    ADD_FAILURE() << llvm::toString(report.takeError());
    return SolveMethod::SparseLU;
  }
  Eigen::VectorXd exact = a.fullPivLu().solve(rhs);
  for (int i = 0; i < n * b; ++i)
    EXPECT_NEAR(x[i], exact[i], tolerance * exact.norm()) << i;
  EXPECT_LE(report->relativeResidual, tolerance);
  return report->method;
}

constexpr int kBlocks = 12, kBlockSize = 3, kSize = kBlocks * kBlockSize;

Eigen::MatrixXd spd(unsigned seed) {
  Eigen::MatrixXd m = randomBand(kBlocks, kBlockSize, seed);
  // Symmetric, diagonally dominant: positive definite, on the band.
  return m + m.transpose() + 8 * Eigen::MatrixXd::Identity(kSize, kSize);
}

TEST(SolveChecked, SymmetricPositiveDefiniteTakesConjugateGradients) {
  EXPECT_EQ(expectSolves<double>(spd(1), kBlocks, kBlockSize, 1e-10),
            SolveMethod::ConjugateGradient);
  EXPECT_EQ(expectSolves<float>(spd(1), kBlocks, kBlockSize, 1e-4),
            SolveMethod::ConjugateGradient);
}

TEST(SolveChecked, NonSymmetricTakesSparseLU) {
  Eigen::MatrixXd a = randomBand(kBlocks, kBlockSize, 2) +
                      4 * Eigen::MatrixXd::Identity(kSize, kSize);
  EXPECT_EQ(expectSolves<double>(a, kBlocks, kBlockSize, 1e-10),
            SolveMethod::SparseLU);
  EXPECT_EQ(expectSolves<float>(a, kBlocks, kBlockSize, 1e-4),
            SolveMethod::SparseLU);
}

TEST(SolveChecked, SymmetricIndefiniteFallsBackToSparseLU) {
  Eigen::MatrixXd m = randomBand(kBlocks, kBlockSize, 3);
  Eigen::MatrixXd a = m + m.transpose();
  a.diagonal() += Eigen::VectorXd::LinSpaced(kSize, -6, 6);
  EXPECT_EQ(expectSolves<double>(a, kBlocks, kBlockSize, 1e-10),
            SolveMethod::SparseLU);
}

TEST(SolveChecked, SingularMatrixIsAnError) {
  Eigen::MatrixXd a = spd(4);
  a.row(5).setZero();
  a.col(5).setZero();
  BandSystem<double> system(kBlocks, kBlockSize, a);
  Eigen::VectorXd rhs = randomVector(kSize, 5);
  std::vector<double> x(kSize);
  EXPECT_THAT(errorOf(solveChecked(system.view, rhs.data(), x.data())),
              HasSubstr("singular"));
}

TEST(SolveChecked, ZeroRightHandSideGivesZero) {
  BandSystem<double> system(kBlocks, kBlockSize, spd(5));
  std::vector<double> b(kSize, 0.0), x(kSize, 3.0);
  auto report = solveChecked(system.view, b.data(), x.data());
  ASSERT_TRUE(bool(report));
  EXPECT_EQ(x, b);
}

TEST(SolveChecked, NonFiniteRightHandSideIsAnError) {
  BandSystem<double> system(kBlocks, kBlockSize, spd(6));
  std::vector<double> b(kSize, 1.0), x(kSize);
  b[4] = std::nan("");
  EXPECT_THAT(errorOf(solveChecked(system.view, b.data(), x.data())),
              HasSubstr("NaN"));
}

TEST(IsSymmetric, MissingMirrorBlockCountsAsZero) {
  // Blocks (0, 0), (0, 1), (1, 1): symmetric only while (0, 1) is zero.
  std::vector<int32_t> rowptr{0, 2, 3}, colidx{0, 1, 1};
  std::vector<double> values{2.0, 0.0, 3.0};
  SquareBCSRView<double> view;
  view.rows = 2;
  view.rowptr = rowptr.data();
  view.colidx = colidx.data();
  view.values = values.data();
  EXPECT_TRUE(isSymmetric(view, 1e-12));
  values[1] = 1e-3;
  EXPECT_FALSE(isSymmetric(view, 1e-12));
}

TEST(IsSymmetric, BlocksMustBeTransposes) {
  Eigen::MatrixXd a = spd(7);
  EXPECT_TRUE(isSymmetric(BandSystem<double>(kBlocks, kBlockSize, a).view,
                          1e-12));
  // A symmetric block pattern whose off-diagonal blocks are not transposed.
  a(0, 4) += 1.0;
  EXPECT_FALSE(isSymmetric(BandSystem<double>(kBlocks, kBlockSize, a).view,
                           1e-12));
}

} // namespace
