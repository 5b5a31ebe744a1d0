//===--- LinearSolverTest.cpp - CG and direct solves against dense LU -----===//

#include "LinearSolver.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <random>

using namespace simit::bench;

namespace {

using Matrix = LinearSolver<double>::Matrix;

/// A random sparse symmetric positive definite n x n matrix: a random
/// sparse B, then B^T B + n I.
Matrix randomSpd(int n, std::mt19937 &rng) {
  std::uniform_int_distribution<int> index(0, n - 1);
  std::uniform_real_distribution<double> value(-1, 1);
  std::vector<Eigen::Triplet<double>> triplets;
  for (int i = 0; i < 4 * n; ++i)
    triplets.emplace_back(index(rng), index(rng), value(rng));
  Eigen::SparseMatrix<double> b(n, n);
  b.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  Matrix spd = Eigen::SparseMatrix<double>(b.transpose() * b) +
               double(n) / 10 * identity;
  return spd;
}

Eigen::VectorXd denseSolve(const Matrix &a, const Eigen::VectorXd &b) {
  return Eigen::MatrixXd(a).partialPivLu().solve(b);
}

class SolverKinds : public ::testing::TestWithParam<SolverKind> {};

TEST_P(SolverKinds, MatchesDenseSolve) {
  std::mt19937 rng(17);
  Matrix a = randomSpd(90, rng);
  Eigen::VectorXd b = Eigen::VectorXd::Random(90);
  LinearSolver<double> solver({GetParam(), 1000, 1e-26});
  solver.analyzePattern(a);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(90);
  SolveResult result = solver.solve(a, b, x);
  ASSERT_TRUE(result.succeeded);
  Eigen::VectorXd exact = denseSolve(a, b);
  EXPECT_LT((x - exact).norm(), 1e-10 * exact.norm());
  EXPECT_LE(result.residualNormSq, 1e-24);
  if (GetParam() == SolverKind::Direct)
    EXPECT_EQ(result.iterations, 0);
  else
    EXPECT_GT(result.iterations, 0);
}

INSTANTIATE_TEST_SUITE_P(All, SolverKinds,
                         ::testing::Values(SolverKind::CG,
                                           SolverKind::JacobiCG,
                                           SolverKind::Direct));

TEST(CG, StopsAtTheIterationCap) {
  std::mt19937 rng(19);
  Matrix a = randomSpd(200, rng);
  Eigen::VectorXd b = Eigen::VectorXd::Random(200);
  LinearSolver<double> solver({SolverKind::CG, 5, 1e-30});
  Eigen::VectorXd x = Eigen::VectorXd::Zero(200);
  SolveResult result = solver.solve(a, b, x);
  EXPECT_EQ(result.iterations, 5);
  Eigen::VectorXd r = b - a * x;
  EXPECT_NEAR(result.residualNormSq, r.squaredNorm(),
              1e-9 * r.squaredNorm());
  EXPECT_GT(result.residualNormSq, 1e-30);
}

TEST(CG, StartsFromTheGivenIterate) {
  std::mt19937 rng(23);
  Matrix a = randomSpd(50, rng);
  Eigen::VectorXd b = Eigen::VectorXd::Random(50);
  Eigen::VectorXd x = denseSolve(a, b);
  Eigen::VectorXd start = x;
  LinearSolver<double> solver({SolverKind::CG, 50, 1e-20});
  SolveResult result = solver.solve(a, b, x);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(x, start);
}

// One CG step on a system with a single distinct eigenvalue is exact.
TEST(CG, OneIterationOnScaledIdentity) {
  Matrix a(3, 3);
  a.setIdentity();
  a *= 4.0;
  Eigen::VectorXd b(3), x = Eigen::VectorXd::Zero(3);
  b << 1, 2, 3;
  LinearSolver<double> solver({SolverKind::CG, 50, 1e-28});
  SolveResult result = solver.solve(a, b, x);
  EXPECT_EQ(result.iterations, 1);
  EXPECT_DOUBLE_EQ(x[2], 0.75);
}

} // namespace
