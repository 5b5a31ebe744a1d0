//===--- SolversTest.cpp - Conjugate gradients against Eigen --------------===//

#include "simit/Runtime/Solvers.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include <Eigen/Dense>

#include <random>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// A random SPD block matrix over the pattern of a random edge set, built as
/// sum over edges of (G_e^T G_e) on the edge's blocks plus shift * I, with
/// its dense copy.
struct RandomSystem {
  Set verts{"verts"};
  Set edges{"edges", {&verts, &verts}};
  BCSRMatrix a;
  Eigen::MatrixXd dense;
  Eigen::VectorXd b;

  RandomSystem(int n, int blockSize, int numEdges, double shift,
               unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> value(-1, 1);
    std::uniform_int_distribution<int> pick(0, n - 1);
    for (int i = 0; i < n; ++i)
      verts.add();
    for (int e = 0; e < numEdges; ++e) {
      int u = pick(rng), v = pick(rng);
      edges.add(u, v == u ? (u + 1) % n : v);
    }
    auto pattern = SparsityPattern::get(edges, verts, verts);
    EXPECT_TRUE(bool(pattern));
    a = BCSRMatrix(*pattern, blockSize, blockSize);
    int m = 2 * blockSize;
    dense = Eigen::MatrixXd::Zero(n * blockSize, n * blockSize);
    for (int e = 0; e < edges.size(); ++e) {
      Eigen::MatrixXd g(m, m);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
          g(i, j) = value(rng);
      Eigen::MatrixXd local = g.transpose() * g;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          double *block = a.block((*pattern)->location(e, i, j));
          for (int r = 0; r < blockSize; ++r)
            for (int c = 0; c < blockSize; ++c) {
              double v = local(i * blockSize + r, j * blockSize + c);
              block[r * blockSize + c] += v;
              dense(edges.endpoint(e, i) * blockSize + r,
                    edges.endpoint(e, j) * blockSize + c) += v;
            }
        }
    }
    for (int r = 0; r < n; ++r) {
      double *block = a.block((*pattern)->findBlock(r, r));
      for (int i = 0; i < blockSize; ++i) {
        block[i * blockSize + i] += shift;
        dense(r * blockSize + i, r * blockSize + i) += shift;
      }
    }
    b = Eigen::VectorXd::NullaryExpr(n * blockSize,
                                     [&] { return value(rng); });
  }
};

void expectSolves(RandomSystem &system, Preconditioner preconditioner) {
  Eigen::VectorXd exact = system.dense.llt().solve(system.b);
  std::vector<double> x(system.b.size(), 0.0);
  SolverOptions options;
  options.maxIterations = 1000;
  options.tolerance = 1e-24;
  options.preconditioner = preconditioner;
  auto result = conjugateGradient(system.a, system.b.data(), x.data(),
                                  options);
  ASSERT_TRUE(bool(result)) << llvm::toString(result.takeError());
  EXPECT_TRUE(result->converged);
  EXPECT_LE(result->residualNormSquared, 1e-24);
  EXPECT_GT(result->iterations, 0);
  for (int i = 0; i < system.b.size(); ++i)
    EXPECT_NEAR(x[i], exact[i], 1e-9 * exact.lpNorm<Eigen::Infinity>()) << i;
  // The reported residual is the true one.
  Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), x.size());
  EXPECT_LE((system.b - system.dense * xv).squaredNorm(), 1e-20);
}

TEST(ConjugateGradient, ScalarSystemMatchesEigen) {
  RandomSystem system(40, 1, 80, 0.1, 1);
  expectSolves(system, Preconditioner::None);
}

TEST(ConjugateGradient, Block3SystemMatchesEigen) {
  RandomSystem system(30, 3, 70, 0.05, 2);
  expectSolves(system, Preconditioner::None);
}

TEST(ConjugateGradient, JacobiSystemMatchesEigen) {
  RandomSystem system(30, 3, 70, 0.05, 3);
  expectSolves(system, Preconditioner::Jacobi);
}

TEST(ConjugateGradient, BlockJacobiSystemMatchesEigen) {
  RandomSystem system(30, 3, 70, 0.05, 3);
  expectSolves(system, Preconditioner::BlockJacobi);
}

// The caller's preconditioner: with M = A exactly (a dense LLT of A), CG
// converges in one step; an error of the operator ends the solve.
TEST(ConjugateGradient, OperatorPreconditioner) {
  RandomSystem system(30, 3, 70, 0.05, 7);
  Eigen::LLT<Eigen::MatrixXd> llt(system.dense);
  std::vector<double> x(system.b.size(), 0.0);
  SolverOptions options;
  options.tolerance = 1e-20;
  options.preconditioner = Preconditioner::Operator;
  int applied = 0;
  options.apply = [&](const double *r, double *z) {
    ++applied;
    Eigen::Map<Eigen::VectorXd>(z, system.b.size()) =
        llt.solve(Eigen::Map<const Eigen::VectorXd>(r, system.b.size()));
    return llvm::Error::success();
  };
  auto result = conjugateGradient(system.a, system.b.data(), x.data(),
                                  options);
  ASSERT_TRUE(bool(result)) << llvm::toString(result.takeError());
  EXPECT_TRUE(result->converged);
  EXPECT_EQ(result->iterations, 1);
  EXPECT_EQ(applied, 2);
  Eigen::VectorXd exact = llt.solve(system.b);
  for (int i = 0; i < system.b.size(); ++i)
    EXPECT_NEAR(x[i], exact[i], 1e-10 * exact.norm()) << i;

  options.apply = [](const double *, double *) {
    return llvm::createStringError("the factor is gone");
  };
  std::fill(x.begin(), x.end(), 0.0);
  EXPECT_THAT(errorOf(conjugateGradient(system.a, system.b.data(), x.data(),
                                        options)),
              HasSubstr("the factor is gone"));
}

TEST(ConjugateGradient, JacobiHelpsABadlyScaledSystem) {
  // Scale rows and columns by very different factors: D A D stays SPD but
  // its condition number explodes; Jacobi undoes the scaling.
  RandomSystem system(30, 3, 70, 0.5, 4);
  std::vector<double> scale(system.b.size());
  for (size_t i = 0; i < scale.size(); ++i)
    scale[i] = std::pow(10.0, static_cast<double>(i % 5));
  const SparsityPattern &p = *system.a.pattern;
  for (int r = 0; r < p.numRows(); ++r)
    for (int k = p.rowPointers()[r]; k < p.rowPointers()[r + 1]; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          system.a.block(k)[i * 3 + j] *=
              scale[r * 3 + i] * scale[p.columnIndices()[k] * 3 + j];
  for (int i = 0; i < system.dense.rows(); ++i)
    for (int j = 0; j < system.dense.cols(); ++j)
      system.dense(i, j) *= scale[i] * scale[j];
  SolverOptions options;
  options.maxIterations = 5000;
  options.tolerance = 1e-16;
  std::vector<double> plainX(system.b.size(), 0.0), jacobiX = plainX;
  auto plain = conjugateGradient(system.a, system.b.data(), plainX.data(),
                                 options);
  options.preconditioner = Preconditioner::Jacobi;
  auto jacobi = conjugateGradient(system.a, system.b.data(), jacobiX.data(),
                                  options);
  ASSERT_TRUE(plain && jacobi);
  EXPECT_TRUE(jacobi->converged);
  EXPECT_LT(jacobi->iterations, plain->iterations);
}

TEST(ConjugateGradient, StopsAtTheIterationCap) {
  RandomSystem system(40, 3, 90, 0.01, 5);
  std::vector<double> x(system.b.size(), 0.0);
  SolverOptions options; // 50 iterations, r.r <= 1e-12
  options.maxIterations = 3;
  auto result = conjugateGradient(system.a, system.b.data(), x.data(),
                                  options);
  ASSERT_TRUE(bool(result));
  EXPECT_EQ(result->iterations, 3);
  EXPECT_FALSE(result->converged);
  // The recursively updated residual still equals b - A x.
  Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), x.size());
  EXPECT_NEAR((system.b - system.dense * xv).squaredNorm(),
              result->residualNormSquared, 1e-10);
}

TEST(ConjugateGradient, ExactStartNeedsNoIteration) {
  RandomSystem system(10, 1, 20, 1.0, 6);
  Eigen::VectorXd exact = system.dense.llt().solve(system.b);
  std::vector<double> x(exact.data(), exact.data() + exact.size());
  auto result = conjugateGradient(system.a, system.b.data(), x.data(),
                                  SolverOptions());
  ASSERT_TRUE(bool(result));
  EXPECT_EQ(result->iterations, 0);
  EXPECT_TRUE(result->converged);
}

TEST(ConjugateGradient, IndefiniteMatrixIsAnError) {
  auto pattern = SparsityPattern::fromArrays(2, 2, {0, 1, 2}, {0, 1});
  BCSRMatrix a(pattern, 1, 1);
  a.values = {1.0, -1.0};
  std::vector<double> b = {0.0, 1.0}, x = {0.0, 0.0};
  EXPECT_THAT(errorOf(conjugateGradient(a, b.data(), x.data(),
                                        SolverOptions())),
              HasSubstr("the matrix is not positive definite"));
}

TEST(ConjugateGradient, JacobiNeedsANonZeroDiagonal) {
  auto pattern = SparsityPattern::fromArrays(2, 2, {0, 1, 2}, {1, 0});
  BCSRMatrix a(pattern, 1, 1);
  a.values = {1.0, 1.0};
  std::vector<double> b = {1.0, 1.0}, x = {0.0, 0.0};
  SolverOptions options;
  options.preconditioner = Preconditioner::Jacobi;
  EXPECT_THAT(errorOf(conjugateGradient(a, b.data(), x.data(), options)),
              HasSubstr("the diagonal entry of row 0 is zero"));
}

TEST(ConjugateGradient, RectangularMatrixIsAnError) {
  auto pattern = SparsityPattern::fromArrays(1, 2, {0, 1}, {1});
  BCSRMatrix a(pattern, 1, 1);
  std::vector<double> b = {1.0}, x = {0.0, 0.0};
  EXPECT_THAT(errorOf(conjugateGradient(a, b.data(), x.data(),
                                        SolverOptions())),
              HasSubstr("expected a square matrix, found 1x2 blocks"));
}

} // namespace
