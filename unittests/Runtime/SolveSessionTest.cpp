//===--- SolveSessionTest.cpp - x = A \ b against dense Eigen solves ------===//

#include "simit/Runtime/SolveSession.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include <array>
#include <Eigen/Dense>

#include <random>
#include <vector>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// A matrix of n x n blocks of b x b in BCSR arrays on a band pattern
/// (blocks (r, c) with |r - c| <= 1), or on the pattern of its nonzero
/// blocks, with its dense copy.
template <typename T> struct BandSystem {
  std::vector<int32_t> rowptr{0}, colidx;
  std::vector<T> values;
  Eigen::MatrixXd dense;
  SquareBCSRView<T> view;

  BandSystem(int n, int b, const Eigen::MatrixXd &full,
             bool nonzeroBlocks = false)
      : dense(full) {
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) {
        bool stored = nonzeroBlocks
                          ? !full.block(r * b, c * b, b, b).isZero(0)
                          : std::abs(r - c) <= 1;
        if (!stored)
          continue;
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
  BandSystem(const BandSystem &) = delete;
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

constexpr int kBlocks = 12;

/// Symmetric, diagonally dominant: positive definite, on the band.
Eigen::MatrixXd spd(int b, unsigned seed) {
  Eigen::MatrixXd m = randomBand(kBlocks, b, seed);
  return m + m.transpose() +
         8 * Eigen::MatrixXd::Identity(kBlocks * b, kBlocks * b);
}

Eigen::MatrixXd nonSymmetric(int b, unsigned seed) {
  return randomBand(kBlocks, b, seed) +
         4 * Eigen::MatrixXd::Identity(kBlocks * b, kBlocks * b);
}

/// Symmetric with eigenvalues of both signs.
Eigen::MatrixXd indefinite(int b, unsigned seed) {
  Eigen::MatrixXd m = randomBand(kBlocks, b, seed);
  Eigen::MatrixXd a = m + m.transpose();
  a.diagonal() += Eigen::VectorXd::LinSpaced(kBlocks * b, -6, 6);
  return a;
}

SolveSettings settingsOf(SolveMethod method) {
  SolveSettings settings;
  settings.method = method;
  return settings;
}

/// Solves A x = b (b random) in `session` and compares x with a dense LU
/// of A to `tolerance` relative to ||x||; returns the report.
template <typename T>
SolveReport expectSolves(SolveSession &session, const Eigen::MatrixXd &a,
                         int b, double tolerance) {
  BandSystem<T> system(kBlocks, b, a);
  Eigen::VectorXd rhs = randomVector(kBlocks * b, 17);
  std::vector<T> bv(rhs.data(), rhs.data() + rhs.size()), x(rhs.size(), 7);
  llvm::Expected<SolveReport> report =
      session.solve(system.view, bv.data(), x.data(), "test");
  if (!report) {
    ADD_FAILURE() << llvm::toString(report.takeError());
    return {};
  }
  Eigen::VectorXd exact = a.fullPivLu().solve(rhs);
  for (int i = 0; i < kBlocks * b; ++i)
    EXPECT_NEAR(x[i], exact[i], tolerance * exact.norm()) << i;
  EXPECT_LE(report->relativeResidual, tolerance);
  EXPECT_TRUE(report->converged);
  return *report;
}

template <typename T>
std::string solveError(SolveSettings settings, const Eigen::MatrixXd &a,
                       int b) {
  SolveSession session(settings);
  BandSystem<T> system(kBlocks, b, a);
  Eigen::VectorXd rhs = randomVector(kBlocks * b, 5);
  std::vector<T> bv(rhs.data(), rhs.data() + rhs.size()), x(rhs.size());
  return errorOf(session.solve(system.view, bv.data(), x.data(), "test"));
}

/// Every method on SPD matrices of scalars and of 3x3 blocks, in f64 and
/// f32.
class EveryMethod : public ::testing::TestWithParam<SolveMethod> {};

TEST_P(EveryMethod, SolvesSymmetricPositiveDefiniteMatrices) {
  for (int b : {1, 3}) {
    SolveSession session(settingsOf(GetParam()));
    SolveReport report = expectSolves<double>(session, spd(b, 1), b, 1e-9);
    if (GetParam() != SolveMethod::Auto)
      EXPECT_EQ(report.method, GetParam());
    SolveReport single = expectSolves<float>(session, spd(b, 1), b, 1e-4);
    if (GetParam() != SolveMethod::Auto)
      EXPECT_EQ(single.method, GetParam());
  }
}

INSTANTIATE_TEST_SUITE_P(
    SolveSession, EveryMethod,
    ::testing::Values(SolveMethod::Auto, SolveMethod::ConjugateGradient,
                      SolveMethod::JacobiCG, SolveMethod::BlockJacobiCG,
                      SolveMethod::CholeskyCG, SolveMethod::Cholesky,
                      SolveMethod::LDLT, SolveMethod::LU),
    [](const ::testing::TestParamInfo<SolveMethod> &info) {
      std::string name = solveMethodName(info.param).str();
      std::replace(name.begin(), name.end(), '-', '_');
      return name;
    });

TEST(SolveSession, AutoTakesConjugateGradientsForSPD) {
  SolveSession session;
  EXPECT_EQ(expectSolves<double>(session, spd(3, 1), 3, 1e-10).method,
            SolveMethod::ConjugateGradient);
}

TEST(SolveSession, NonSymmetricMatricesTakeLU) {
  for (int b : {1, 3}) {
    SolveSession automatic;
    EXPECT_EQ(
        expectSolves<double>(automatic, nonSymmetric(b, 2), b, 1e-10).method,
        SolveMethod::LU);
    EXPECT_EQ(
        expectSolves<float>(automatic, nonSymmetric(b, 2), b, 1e-4).method,
        SolveMethod::LU);
    SolveSession lu(settingsOf(SolveMethod::LU));
    expectSolves<double>(lu, nonSymmetric(b, 2), b, 1e-10);
  }
}

// A float32 assembly rounds a block and its mirror differently: an SPD
// matrix whose upper triangle is off by 3e-7 relative (a few float32
// roundings) is symmetric for float32 programs, so auto takes CG and cg
// and cholesky solve it; in float64 the same matrix is not symmetric, and
// in float32 a difference of 1e-3 is not either.
TEST(SolveSession, Float32SymmetryAllowsRounding) {
  auto skewed = [](double by) {
    Eigen::MatrixXd a = spd(3, 21);
    Eigen::MatrixXd upper = a.triangularView<Eigen::StrictlyUpper>();
    return Eigen::MatrixXd(a + by * upper);
  };
  SolveSession automatic;
  EXPECT_EQ(expectSolves<float>(automatic, skewed(3e-7), 3, 1e-4).method,
            SolveMethod::ConjugateGradient);
  for (SolveMethod method : {SolveMethod::ConjugateGradient,
                             SolveMethod::Cholesky}) {
    SolveSession session(settingsOf(method));
    expectSolves<float>(session, skewed(3e-7), 3, 1e-4);
    EXPECT_THAT(solveError<double>(settingsOf(method), skewed(3e-7), 3),
                HasSubstr("not symmetric"));
    EXPECT_THAT(solveError<float>(settingsOf(method), skewed(1e-3), 3),
                HasSubstr("not symmetric"));
  }
}

TEST(SolveSession, SymmetricMethodsRefuseNonSymmetricMatrices) {
  for (SolveMethod method :
       {SolveMethod::ConjugateGradient, SolveMethod::JacobiCG,
        SolveMethod::BlockJacobiCG, SolveMethod::CholeskyCG,
        SolveMethod::Cholesky, SolveMethod::LDLT})
    EXPECT_THAT(solveError<double>(settingsOf(method), nonSymmetric(3, 2), 3),
                HasSubstr("not symmetric"))
        << solveMethodName(method).str();
}

// Cholesky's symmetry check: one entry out of place in a diagonal block,
// in a block below or above the diagonal, or a block stored on one side
// only (its mirror counts as zero) is found, through `\` and through chol;
// tiny differences pass.
TEST(SolveSession, CholeskyFindsEveryKindOfAsymmetry) {
  constexpr int b = 3;
  Eigen::MatrixXd symmetric = spd(b, 4);
  auto withEntry = [&](int row, int column, double value) {
    Eigen::MatrixXd a = symmetric;
    a(row, column) = value;
    return a;
  };
  struct Case {
    const char *what;
    Eigen::MatrixXd a;
    bool isSymmetric;
  };
  Case cases[] = {
      {"symmetric", symmetric, true},
      {"rounding", withEntry(7, 5, symmetric(7, 5) * (1 + 1e-14)), true},
      {"diagonal block", withEntry(4, 3, symmetric(4, 3) + 0.5), false},
      {"below", withEntry(4, 1, symmetric(4, 1) + 0.5), false},
      {"above", withEntry(1, 4, symmetric(1, 4) + 0.5), false},
      // Band blocks (5, 1) or (1, 5) stored alone (BandSystem stores the
      // blocks that are not zero).
      {"alone below", withEntry(5 * b, 1 * b, 0.5), false},
      {"alone above", withEntry(1 * b, 5 * b, 0.5), false},
  };
  for (const Case &c : cases) {
    BandSystem<double> system(kBlocks, b, c.a, /*nonzeroBlocks=*/true);
    SolveSession session(settingsOf(SolveMethod::Cholesky));
    Eigen::VectorXd rhs = randomVector(kBlocks * b, 5);
    std::vector<double> x(kBlocks * b);
    auto report = session.solve(system.view, rhs.data(), x.data(), "t");
    auto factor = session.factorise(FactorKind::Cholesky, system.view, "chol");
    if (c.isSymmetric) {
      EXPECT_TRUE(bool(report)) << c.what << ": " << errorOf(std::move(report));
      EXPECT_TRUE(bool(factor)) << c.what << ": " << errorOf(std::move(factor));
    } else {
      EXPECT_THAT(errorOf(std::move(report)), HasSubstr("not symmetric"))
          << c.what;
      EXPECT_THAT(errorOf(std::move(factor)), HasSubstr("not symmetric"))
          << c.what;
    }
  }
}

TEST(SolveSession, IndefiniteMatrices) {
  SolveSession automatic;
  EXPECT_EQ(
      expectSolves<double>(automatic, indefinite(3, 3), 3, 1e-10).method,
      SolveMethod::LU);
  SolveSession ldlt(settingsOf(SolveMethod::LDLT));
  expectSolves<double>(ldlt, indefinite(3, 3), 3, 1e-9);
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::Cholesky),
                                 indefinite(3, 3), 3),
              HasSubstr("not positive definite"));
}

// Cholesky's numeric factorisation (SupernodalCholesky.h) on random
// matrices of scalars and of blocks, on patterns that give it supernodes of
// every kind: random sparse ones (a few columns wide, updated by the dense
// loops), a wide band (wide supernodes updating one another through BLAS)
// and a full matrix (one supernode, factorised by blocks of columns whose
// updates go through BLAS); against Eigen's dense LL^T.
TEST(SolveSession, CholeskyMatchesEigenOnRandomPatterns) {
  constexpr int n = 60;
  enum Pattern { TwoPerRow, EightPerRow, Band, Full };
  for (int b : {1, 2, 3})
    for (Pattern pattern : {TwoPerRow, EightPerRow, Band, Full}) {
      std::mt19937 rng(100 * b + pattern);
      std::uniform_real_distribution<double> value(-1, 1);
      std::uniform_int_distribution<int> column(0, n - 1);
      Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n * b, n * b);
      auto fill = [&](int r, int c) {
        for (int i = 0; i < b; ++i)
          for (int j = 0; j < b; ++j)
            m(r * b + i, c * b + j) = value(rng);
      };
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
          if (pattern == Full || (pattern == Band && std::abs(r - c) <= 10))
            fill(r, c);
      if (pattern == TwoPerRow || pattern == EightPerRow)
        for (int r = 0; r < n; ++r)
          for (int k = 0; k < (pattern == TwoPerRow ? 2 : 8); ++k)
            fill(r, column(rng));
      Eigen::MatrixXd a =
          m * m.transpose() + Eigen::MatrixXd::Identity(n * b, n * b);
      BandSystem<double> system(n, b, a, /*nonzeroBlocks=*/true);
      SolveSession session(settingsOf(SolveMethod::Cholesky));
      Eigen::VectorXd rhs = randomVector(n * b, 7);
      std::vector<double> x(n * b);
      auto report = session.solve(system.view, rhs.data(), x.data(), "t");
      ASSERT_TRUE(bool(report)) << "block size " << b << ", pattern " << pattern
                                << ": " << llvm::toString(report.takeError());
      Eigen::VectorXd exact = a.llt().solve(rhs);
      for (int i = 0; i < n * b; ++i)
        EXPECT_NEAR(x[i], exact[i], 1e-11 * exact.norm())
            << "block size " << b << ", pattern " << pattern << ", unknown "
            << i;
    }
}

// A stored zero block whose mirror is not stored (the pattern is not
// symmetric, the matrix is) must still be in Cholesky's analysis, above the
// diagonal or below it: a path of 12 blocks of 3x3 plus a zero block
// (0, 11) or (11, 0) alone, which closes it into a cycle.
TEST(SolveSession, CholeskyOnAPatternWithOneSidedZeroBlocks) {
  constexpr int n = 12, b = 3;
  Eigen::MatrixXd a = 4 * Eigen::MatrixXd::Identity(n * b, n * b);
  for (int r = 0; r + 1 < n; ++r)
    for (int i = 0; i < b; ++i)
      a(b * r + i, b * (r + 1) + i) = a(b * (r + 1) + i, b * r + i) = -1;
  Eigen::VectorXd rhs = randomVector(n * b, 3), exact = a.llt().solve(rhs);
  for (bool above : {true, false}) {
    std::vector<int32_t> rowptr{0}, colidx;
    std::vector<double> values;
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) {
        bool lone = above ? (r == 0 && c == n - 1) : (r == n - 1 && c == 0);
        if (std::abs(r - c) > 1 && !lone)
          continue;
        colidx.push_back(c);
        for (int i = 0; i < b; ++i)
          for (int j = 0; j < b; ++j)
            values.push_back(a(b * r + i, b * c + j));
      }
      rowptr.push_back(static_cast<int32_t>(colidx.size()));
    }
    SquareBCSRView<double> view;
    view.rows = n;
    view.blockSize = b;
    view.rowptr = rowptr.data();
    view.colidx = colidx.data();
    view.values = values.data();
    SolveSession session(settingsOf(SolveMethod::Cholesky));
    std::vector<double> x(n * b);
    auto report = session.solve(view, rhs.data(), x.data(), "t");
    ASSERT_TRUE(bool(report)) << llvm::toString(report.takeError());
    for (int i = 0; i < n * b; ++i)
      EXPECT_NEAR(x[i], exact[i], 1e-13) << (above ? "above " : "below ") << i;
  }
}

// The column whose pivot fails is named in the matrix's own numbering, not
// in the factorisation's fill-reducing order: with one negative diagonal
// entry in an otherwise positive definite matrix, it is that entry's.
TEST(SolveSession, CholeskyNamesTheFailingColumnOfTheMatrix) {
  Eigen::MatrixXd a = spd(3, 2);
  a(16, 16) = -100;
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::Cholesky), a, 3),
              HasSubstr("fails at scalar column 16"));
}

// A full matrix is one supernode, factorised by column blocks: a pivot
// that fails in a later block is named by its own column.
TEST(SolveSession, CholeskyNamesTheFailingColumnInsideAWidePanel) {
  constexpr int n = 40, b = 3;
  Eigen::MatrixXd m = Eigen::MatrixXd::Random(n * b, n * b);
  Eigen::MatrixXd a =
      m * m.transpose() + Eigen::MatrixXd::Identity(n * b, n * b);
  a(100, 100) = -1e3;
  BandSystem<double> system(n, b, a, /*nonzeroBlocks=*/true);
  SolveSession session(settingsOf(SolveMethod::Cholesky));
  Eigen::VectorXd rhs = randomVector(n * b, 3);
  std::vector<double> x(n * b);
  EXPECT_THAT(errorOf(session.solve(system.view, rhs.data(), x.data(), "t")),
              HasSubstr("fails at scalar column 100"));
}

TEST(SolveSession, SingularMatrixIsAnError) {
  Eigen::MatrixXd a = spd(3, 4);
  a.row(5).setZero();
  a.col(5).setZero();
  for (SolveMethod method : {SolveMethod::Auto, SolveMethod::LU})
    EXPECT_THAT(solveError<double>(settingsOf(method), a, 3),
                HasSubstr("singular"));
  EXPECT_THAT(solveError<float>(settingsOf(SolveMethod::LU), a, 3),
              HasSubstr("singular"));
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::Cholesky), a, 3),
              HasSubstr("not positive definite"));
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::LDLT), a, 3),
              HasSubstr("zero pivot"));
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::JacobiCG), a, 3),
              HasSubstr("diagonal entry of row 5 is zero"));
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::BlockJacobiCG), a, 3),
              HasSubstr("diagonal block of block row 1 is singular"));
}

TEST(SolveSession, CappedIterativeSolveIsReported) {
  SolveSettings settings = settingsOf(SolveMethod::ConjugateGradient);
  settings.maxIterations = 2;
  SolveSession session(settings);
  BandSystem<double> system(kBlocks, 3, spd(3, 8));
  Eigen::VectorXd rhs = randomVector(kBlocks * 3, 9);
  std::vector<double> x(rhs.size());
  for (int solve = 0; solve < 2; ++solve) {
    auto report = session.solve(system.view, rhs.data(), x.data(), "capped");
    ASSERT_TRUE(bool(report)) << llvm::toString(report.takeError());
    EXPECT_FALSE(report->converged);
    EXPECT_EQ(report->iterations, 2);
    // The reported residual is the true one.
    Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), x.size());
    EXPECT_NEAR(report->relativeResidual,
                (rhs - system.dense * xv).norm() / rhs.norm(), 1e-12);
    EXPECT_GT(report->relativeResidual, 1e-6);
  }
  std::vector<SolveStatementStats> stats = session.statistics();
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].statement, "capped");
  EXPECT_EQ(stats[0].solves, 2);
  EXPECT_EQ(stats[0].notConverged, 2);
  EXPECT_EQ(stats[0].iterations, 4);

  settings.strict = true;
  EXPECT_THAT(solveError<double>(settings, spd(3, 8), 3),
              HasSubstr("stopped at the iteration cap of 2"));
}

TEST(SolveSession, ToleranceIsTheTrueRelativeResidual) {
  SolveSettings settings = settingsOf(SolveMethod::JacobiCG);
  settings.tolerance = 1e-4;
  SolveSession session(settings);
  BandSystem<double> system(kBlocks, 3, spd(3, 10));
  Eigen::VectorXd rhs = randomVector(kBlocks * 3, 11);
  std::vector<double> x(rhs.size());
  auto report = session.solve(system.view, rhs.data(), x.data(), "tol");
  ASSERT_TRUE(bool(report));
  EXPECT_TRUE(report->converged);
  Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), x.size());
  double residual = (rhs - system.dense * xv).norm() / rhs.norm();
  EXPECT_LE(residual, 1e-4);
  // Stopped early: looser than a converged solve.
  EXPECT_GT(residual, 1e-14);
}

/// Iterations of one solve of `system` x = rhs in `session` as `statement`;
/// x starts as NaN (never read) and must match a dense LU to 1e-8.
int iterationsOf(SolveSession &session, const BandSystem<double> &system,
                 const Eigen::VectorXd &rhs, llvm::StringRef statement) {
  std::vector<double> x(rhs.size(), std::nan(""));
  auto report = session.solve(system.view, rhs.data(), x.data(), statement);
  if (!report) {
    ADD_FAILURE() << llvm::toString(report.takeError());
    return -1;
  }
  Eigen::VectorXd exact = system.dense.fullPivLu().solve(rhs);
  for (int i = 0; i < rhs.size(); ++i)
    EXPECT_NEAR(x[i], exact[i], 1e-8 * exact.norm()) << i;
  EXPECT_TRUE(report->converged);
  return report->iterations;
}

TEST(SolveSession, WarmStartBeginsAtTheStatementsPreviousAnswer) {
  SolveSettings settings = settingsOf(SolveMethod::ConjugateGradient);
  settings.tolerance = 1e-10;
  SolveSession warm(settings);
  settings.warmStart = false;
  SolveSession cold(settings);
  BandSystem<double> system(kBlocks, 3, spd(3, 12));
  Eigen::VectorXd first = randomVector(kBlocks * 3, 13);
  Eigen::VectorXd nearby = first + 1e-4 * randomVector(kBlocks * 3, 14);

  int fromZero = iterationsOf(cold, system, first, "s");
  EXPECT_GT(fromZero, 3);
  EXPECT_EQ(iterationsOf(warm, system, first, "s"), fromZero);
  // A nearby right-hand side: fewer iterations from the previous answer.
  int coldNearby = iterationsOf(cold, system, nearby, "s");
  EXPECT_LT(iterationsOf(warm, system, nearby, "s"), coldNearby);
  // The same system again: the previous answer already meets the tolerance.
  EXPECT_EQ(iterationsOf(warm, system, nearby, "s"), 0);
  EXPECT_EQ(iterationsOf(cold, system, nearby, "s"), coldNearby);
  // Another statement starts from zero.
  EXPECT_EQ(iterationsOf(warm, system, nearby, "t"), coldNearby);
  // So does a statement whose unknowns changed size.
  BandSystem<double> smaller(kBlocks, 1, spd(1, 15));
  Eigen::VectorXd small = randomVector(kBlocks, 16);
  SolveSession coldSmall(settings);
  EXPECT_EQ(iterationsOf(warm, smaller, small, "s"),
            iterationsOf(coldSmall, smaller, small, "s"));
}

// pcg-cholesky keeps the first matrix's factorisation as the preconditioner
// of the statement's later solves: exact for the same matrix but for the
// factor's rounding to float (two iterations to 1e-10), a few iterations
// for a nearby one, and a solve that needs more than refactorIterations
// factorises its own matrix.
TEST(SolveSession, CholeskyCGPreconditionsWithAnEarlierFactorisation) {
  SolveSettings settings = settingsOf(SolveMethod::CholeskyCG);
  settings.tolerance = 1e-10;
  settings.warmStart = false;
  SolveSession session(settings);
  Eigen::MatrixXd a = spd(3, 12);
  BandSystem<double> first(kBlocks, 3, a);
  Eigen::VectorXd rhs = randomVector(kBlocks * 3, 13);
  EXPECT_EQ(iterationsOf(session, first, rhs, "s"), 2);
  EXPECT_EQ(session.factorisationCounts().factorisations, 1);

  // A 1% change of every entry (symmetric, still SPD): the old factor is
  // a good preconditioner, not an exact one.
  Eigen::MatrixXd change = randomBand(kBlocks, 3, 31);
  auto changedBy = [&](double by) {
    return Eigen::MatrixXd(a + by * (change + change.transpose()));
  };
  BandSystem<double> nearby(kBlocks, 3, changedBy(0.01));
  int lagged = iterationsOf(session, nearby, rhs, "s");
  EXPECT_GT(lagged, 1);
  EXPECT_LE(lagged, 8);
  EXPECT_EQ(session.factorisationCounts().factorisations, 1);

  // A threshold below that: the solve factorises `farther` and converges
  // with it in two or three steps more.
  settings.refactorIterations = 1;
  session.setSettings(settings);
  BandSystem<double> farther(kBlocks, 3, changedBy(0.05));
  int refactorised = iterationsOf(session, farther, rhs, "s");
  EXPECT_GE(refactorised, 2);
  EXPECT_LE(refactorised, 4);
  EXPECT_EQ(session.factorisationCounts().factorisations, 2);

  // Another statement has a preconditioner of its own.
  EXPECT_EQ(iterationsOf(session, first, rhs, "t"), 2);
  EXPECT_EQ(session.factorisationCounts().factorisations, 3);
  auto stats = session.statistics();
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_EQ(stats[0].factorisations, 2);
}

// The float factor's triangular solves on supernodes of many shapes: a
// random sparse SPD matrix of 80 blocks (fill, wide and narrow
// supernodes), solved twice with the same matrix; the second solve is
// preconditioned by the first one's factor and needs two iterations.
TEST(SolveSession, CholeskyCGOnARandomPattern) {
  constexpr int n = 80, b = 3;
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> value(-1, 1);
  std::uniform_int_distribution<int> column(0, n - 1);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n * b, n * b);
  for (int r = 0; r < n; ++r)
    for (int k = 0; k < 3; ++k) {
      int c = column(rng);
      for (int i = 0; i < b; ++i)
        for (int j = 0; j < b; ++j)
          m(r * b + i, c * b + j) = value(rng);
    }
  Eigen::MatrixXd a = m * m.transpose() +
                      Eigen::MatrixXd::Identity(n * b, n * b);
  BandSystem<double> system(n, b, a, /*nonzeroBlocks=*/true);
  SolveSettings settings = settingsOf(SolveMethod::CholeskyCG);
  settings.tolerance = 1e-10;
  settings.warmStart = false;
  SolveSession session(settings);
  Eigen::VectorXd rhs = randomVector(n * b, 43);
  Eigen::VectorXd exact = a.llt().solve(rhs);
  for (int round = 0; round < 2; ++round) {
    std::vector<double> x(n * b);
    auto report = session.solve(system.view, rhs.data(), x.data(), "random");
    ASSERT_TRUE(bool(report)) << llvm::toString(report.takeError());
    EXPECT_EQ(report->iterations, 2);
    for (int i = 0; i < n * b; ++i)
      EXPECT_NEAR(x[i], exact[i], 1e-9 * exact.norm()) << i;
  }
  EXPECT_EQ(session.factorisationCounts().factorisations, 1);
}

// The preconditioner of a matrix that is not positive definite cannot be
// factorised: the error names it as cholesky's does.
TEST(SolveSession, CholeskyCGRefusesIndefiniteMatrices) {
  EXPECT_THAT(solveError<double>(settingsOf(SolveMethod::CholeskyCG),
                                 indefinite(3, 3), 3),
              HasSubstr("not positive definite"));
}

TEST(SolveSession, FactorisationIsReusedForTheSameValues) {
  for (SolveMethod method :
       {SolveMethod::Cholesky, SolveMethod::LDLT, SolveMethod::LU}) {
    SCOPED_TRACE(solveMethodName(method).str());
    SolveSession session(settingsOf(method));
    BandSystem<double> system(kBlocks, 3, spd(3, 12));
    Eigen::VectorXd b1 = randomVector(kBlocks * 3, 1),
                    b2 = randomVector(kBlocks * 3, 2);
    std::vector<double> x(b1.size());
    auto solve = [&](const SquareBCSRView<double> &a, const Eigen::VectorXd &b,
                     const Eigen::MatrixXd &dense) {
      auto report = session.solve(a, b.data(), x.data(), "reuse");
      ASSERT_TRUE(bool(report)) << llvm::toString(report.takeError());
      Eigen::VectorXd exact = dense.fullPivLu().solve(b);
      for (int i = 0; i < b.size(); ++i)
        EXPECT_NEAR(x[i], exact[i], 1e-10 * exact.norm());
    };
    auto expectCounts = [&](int64_t analyses, int64_t numeric,
                            int64_t reuses) {
      FactorisationCounts counts = session.factorisationCounts();
      EXPECT_EQ(counts.analyses, analyses);
      EXPECT_EQ(counts.factorisations, numeric);
      EXPECT_EQ(counts.reuses, reuses);
    };
    solve(system.view, b1, system.dense);
    solve(system.view, b2, system.dense);
    expectCounts(1, 1, 1);

    // The same values in other arrays: found by content, reused.
    BandSystem<double> copy(kBlocks, 3, system.dense);
    solve(copy.view, b1, copy.dense);
    expectCounts(1, 1, 2);

    // Values changed in place: a new numeric factorisation on the same
    // analysis, never the stale one.
    for (double &v : system.values)
      v *= 2;
    solve(system.view, b1, 2 * system.dense);
    expectCounts(1, 2, 2);

    // Another pattern: a new analysis.
    BandSystem<double> scalar(kBlocks, 1, spd(1, 13));
    solve(scalar.view, b1.head(kBlocks), scalar.dense);
    expectCounts(2, 3, 2);

    std::vector<SolveStatementStats> stats = session.statistics();
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0].solves, 5);
    EXPECT_EQ(stats[0].analyses, 2);
    EXPECT_EQ(stats[0].factorisations, 3);
    EXPECT_EQ(stats[0].reuses, 2);
  }
}

// A solve skips the symmetry check only for the very values of a held
// factorisation: new values on the same pattern are checked again.
TEST(SolveSession, NewValuesOnAFactorisedPatternAreCheckedForSymmetry) {
  for (SolveMethod method : {SolveMethod::Cholesky, SolveMethod::LDLT}) {
    SCOPED_TRACE(solveMethodName(method).str());
    SolveSession session(settingsOf(method));
    BandSystem<double> system(kBlocks, 3, spd(3, 16));
    Eigen::VectorXd b = randomVector(kBlocks * 3, 17);
    std::vector<double> x(b.size());
    ASSERT_TRUE(bool(session.solve(system.view, b.data(), x.data(), "s")));
    ASSERT_TRUE(bool(session.solve(system.view, b.data(), x.data(), "s")));
    EXPECT_EQ(session.factorisationCounts().reuses, 1);
    // Entry (0, 1) of the first diagonal block, not its mirror (1, 0).
    system.values[1] += 1e-3;
    EXPECT_THAT(errorOf(session.solve(system.view, b.data(), x.data(), "s")),
                HasSubstr("not symmetric"));
  }
}

TEST(SolveSession, HeldFactorisationOutlivesNewValues) {
  SolveSession session;
  BandSystem<double> system(kBlocks, 3, spd(3, 14));
  auto held = session.factorise(FactorKind::Cholesky, system.view, "chol");
  ASSERT_TRUE(bool(held)) << llvm::toString(held.takeError());
  Eigen::MatrixXd first = system.dense;
  for (double &v : system.values)
    v *= 3;
  auto second = session.factorise(FactorKind::Cholesky, system.view, "chol");
  ASSERT_TRUE(bool(second));
  EXPECT_EQ(session.factorisationCounts().factorisations, 2);
  Eigen::VectorXd b = randomVector(kBlocks * 3, 15);
  std::vector<double> x(b.size());
  for (auto [factor, dense] : {std::pair(*held, first),
                               std::pair(*second, Eigen::MatrixXd(3 * first))}) {
    auto report = session.solveWith(*factor, b.data(), x.data(), "lltsolve");
    ASSERT_TRUE(bool(report)) << llvm::toString(report.takeError());
    Eigen::VectorXd exact = dense.llt().solve(b);
    for (int i = 0; i < b.size(); ++i)
      EXPECT_NEAR(x[i], exact[i], 1e-10 * exact.norm());
  }
  EXPECT_THAT(errorOf(session.factorise(FactorKind::Cholesky,
                                        BandSystem<double>(kBlocks, 3,
                                                           nonSymmetric(3, 2))
                                            .view,
                                        "chol")),
              HasSubstr("not symmetric"));
}

/// (A + u v^T) x = b through shermanMorrison, against `exact` to
/// `tolerance` relative to its norm; returns the method of the last step.
SolveMethod expectShermanMorrison(SolveSession &session,
                                  const BandSystem<double> &system,
                                  const Eigen::VectorXd &u,
                                  const Eigen::VectorXd &v,
                                  const Eigen::VectorXd &b,
                                  const Eigen::VectorXd &exact,
                                  double tolerance) {
  int64_t n = system.view.size();
  std::vector<double> w(n), c(n), x(n);
  auto solveA = [&](const Eigen::VectorXd &rhs, std::vector<double> &out) {
    auto report = session.solve(system.view, rhs.data(), out.data(), "A");
    ASSERT_TRUE(bool(report)) << llvm::toString(report.takeError());
  };
  solveA(u, w);
  solveA(b, c);
  auto report = session.shermanMorrison(system.view, u.data(), v.data(),
                                        b.data(), w.data(), c.data(),
                                        x.data(), "rank one");
  if (!report) {
    ADD_FAILURE() << llvm::toString(report.takeError());
    return SolveMethod::Auto;
  }
  for (int64_t i = 0; i < n; ++i)
    EXPECT_NEAR(x[i], exact[i], tolerance * exact.norm()) << i;
  Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), n);
  double residual = (b - system.dense * xv - u * v.dot(xv)).norm() / b.norm();
  EXPECT_NEAR(report->relativeResidual, residual, 1e-14);
  EXPECT_LE(residual, 1e-12);
  return report->method;
}

TEST(SolveSession, ShermanMorrisonMatchesADenseSolve) {
  for (SolveMethod method : {SolveMethod::Cholesky, SolveMethod::Auto}) {
    SolveSession session(settingsOf(method));
    BandSystem<double> system(kBlocks, 3, spd(3, 20));
    Eigen::VectorXd u = randomVector(kBlocks * 3, 21),
                    v = randomVector(kBlocks * 3, 22),
                    b = randomVector(kBlocks * 3, 23);
    Eigen::MatrixXd full = system.dense + u * v.transpose();
    EXPECT_EQ(expectShermanMorrison(session, system, u, v, b,
                                    full.fullPivLu().solve(b), 1e-9),
              SolveMethod::ShermanMorrison);
    if (method == SolveMethod::Cholesky) {
      // Both solves with A share one factorisation.
      EXPECT_EQ(session.factorisationCounts().factorisations, 1);
      EXPECT_EQ(session.factorisationCounts().reuses, 1);
    }
  }
}

TEST(SolveSession, RankOneObserverSeesEverySystem) {
  SolveSession session(settingsOf(SolveMethod::Cholesky));
  BandSystem<double> system(kBlocks, 3, spd(3, 28));
  Eigen::VectorXd u = randomVector(kBlocks * 3, 29),
                  v = randomVector(kBlocks * 3, 30),
                  b = randomVector(kBlocks * 3, 31);
  int calls = 0;
  session.observeRankOneSystems([&](const RankOneSystem &seen) {
    ++calls;
    EXPECT_EQ(seen.statement, "rank one");
    EXPECT_EQ(seen.a.values, system.view.values);
    EXPECT_EQ(seen.a.size(), system.view.size());
    EXPECT_EQ(seen.u, u.data());
    EXPECT_EQ(seen.v, v.data());
    EXPECT_EQ(seen.b, b.data());
  });
  Eigen::MatrixXd full = system.dense + u * v.transpose();
  expectShermanMorrison(session, system, u, v, b, full.fullPivLu().solve(b),
                        1e-9);
  EXPECT_EQ(calls, 1);
  session.observeRankOneSystems(nullptr);
  expectShermanMorrison(session, system, u, v, b, full.fullPivLu().solve(b),
                        1e-9);
  EXPECT_EQ(calls, 1);
}

TEST(SolveSession, ShermanMorrisonFallsBackToTheBorderedSystem) {
  // v = -(1 - 1e-10) w / |w|^2 for w = A^-1 u, plus a part orthogonal to
  // w: 1 + v.w = 1e-10 while |v||w| is about 1, so the formula would
  // divide by a number tiny next to the terms it came from. A + u v^T is
  // regular (det = 1e-10 det A) but ill-conditioned; with b = (A + u v^T) x
  // for a known x, LU on the bordered system (backward stable) keeps the
  // residual at rounding level and x to 1e-4.
  SolveSession session(settingsOf(SolveMethod::LU));
  BandSystem<double> system(kBlocks, 3, nonSymmetric(3, 24));
  Eigen::VectorXd u = randomVector(kBlocks * 3, 25),
                  x = randomVector(kBlocks * 3, 26);
  Eigen::VectorXd w = system.dense.fullPivLu().solve(u);
  Eigen::VectorXd other = randomVector(kBlocks * 3, 27);
  other -= other.dot(w) / w.squaredNorm() * w;
  Eigen::VectorXd v = -(1 - 1e-10) * w / w.squaredNorm() +
                      0.5 * other / (other.norm() * w.norm());
  Eigen::VectorXd b = system.dense * x + u * v.dot(x);
  EXPECT_EQ(expectShermanMorrison(session, system, u, v, b, x, 1e-4),
            SolveMethod::BorderedLU);
  std::vector<SolveStatementStats> stats = session.statistics();
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_EQ(stats[1].statement, "rank one");
  EXPECT_EQ(stats[1].methods,
            std::vector<SolveMethod>{SolveMethod::BorderedLU});
}

/// (A + u1 v1^T + u2 v2^T) x = b through woodbury against `exact`; returns
/// the method of the last step.
SolveMethod expectWoodbury(SolveSession &session,
                           const BandSystem<double> &system,
                           const std::array<Eigen::VectorXd, 2> &u,
                           const std::array<Eigen::VectorXd, 2> &v,
                           const Eigen::VectorXd &b,
                           const Eigen::VectorXd &exact, double tolerance) {
  int64_t n = system.view.size();
  std::array<std::vector<double>, 2> w{std::vector<double>(n),
                                       std::vector<double>(n)};
  std::vector<double> c(n), x(n);
  for (int t = 0; t < 2; ++t)
    EXPECT_TRUE(bool(session.solve(system.view, u[t].data(), w[t].data(),
                                   "A")));
  EXPECT_TRUE(bool(session.solve(system.view, b.data(), c.data(), "A")));
  const double *us[] = {u[0].data(), u[1].data()};
  const double *vs[] = {v[0].data(), v[1].data()};
  const double *ws[] = {w[0].data(), w[1].data()};
  auto report = session.woodbury<double>(system.view, us, vs, b.data(), ws,
                                         c.data(), x.data(), "rank two");
  if (!report) {
    ADD_FAILURE() << llvm::toString(report.takeError());
    return SolveMethod::Auto;
  }
  for (int64_t i = 0; i < n; ++i)
    EXPECT_NEAR(x[i], exact[i], tolerance * exact.norm()) << i;
  Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), n);
  Eigen::VectorXd r = b - system.dense * xv - u[0] * v[0].dot(xv) -
                      u[1] * v[1].dot(xv);
  EXPECT_NEAR(report->relativeResidual, r.norm() / b.norm(), 1e-14);
  EXPECT_LE(r.norm() / b.norm(), 1e-12);
  return report->method;
}

TEST(SolveSession, WoodburyMatchesADenseSolveAndFallsBack) {
  SolveSession session(settingsOf(SolveMethod::LU));
  BandSystem<double> system(kBlocks, 3, nonSymmetric(3, 32));
  int64_t n = kBlocks * 3;
  std::array<Eigen::VectorXd, 2> u{randomVector(n, 33), randomVector(n, 34)};
  std::array<Eigen::VectorXd, 2> v{randomVector(n, 35), randomVector(n, 36)};
  Eigen::VectorXd b = randomVector(n, 37);
  Eigen::MatrixXd full = system.dense + u[0] * v[0].transpose() +
                         u[1] * v[1].transpose();
  EXPECT_EQ(expectWoodbury(session, system, u, v, b,
                           full.fullPivLu().solve(b), 1e-9),
            SolveMethod::ShermanMorrison);

  // v1 with 1 + v1.w1 = 1e-10 and v1.w2 = 0 (w = A^-1 u): the 2 x 2
  // system's first pivot is tiny next to |v1||w1|, so the bordered
  // system [A U; V^T -I] is solved instead; with b from a known x, LU keeps
  // the residual at rounding level and x to 1e-4.
  Eigen::VectorXd w1 = system.dense.fullPivLu().solve(u[0]);
  Eigen::VectorXd w2 = system.dense.fullPivLu().solve(u[1]);
  // q: w1 without its part along w2, so q.w1 = |q|^2 and q.w2 = 0.
  Eigen::VectorXd q = w1 - w1.dot(w2) / w2.squaredNorm() * w2;
  Eigen::VectorXd other = randomVector(n, 38);
  other -= other.dot(q) / q.squaredNorm() * q;
  other -= other.dot(w2) / w2.squaredNorm() * w2;
  Eigen::VectorXd v1 = -(1 - 1e-10) / q.squaredNorm() * q +
                       0.5 * other / (other.norm() * w1.norm());
  std::array<Eigen::VectorXd, 2> nearlySingular{v1, v[1]};
  Eigen::VectorXd x = randomVector(n, 39);
  Eigen::VectorXd bx = system.dense * x + u[0] * v1.dot(x) +
                       u[1] * v[1].dot(x);
  EXPECT_EQ(expectWoodbury(session, system, u, nearlySingular, bx, x, 1e-4),
            SolveMethod::BorderedLU);
}

TEST(SolveSession, ZeroRightHandSideGivesZero) {
  SolveSession session(settingsOf(SolveMethod::Cholesky));
  BandSystem<double> system(kBlocks, 3, spd(3, 5));
  std::vector<double> b(kBlocks * 3, 0.0), x(kBlocks * 3, 3.0);
  auto report = session.solve(system.view, b.data(), x.data(), "zero");
  ASSERT_TRUE(bool(report));
  EXPECT_EQ(x, b);
}

TEST(SolveSession, NonFiniteRightHandSideIsAnError) {
  SolveSession session;
  BandSystem<double> system(kBlocks, 3, spd(3, 6));
  std::vector<double> b(kBlocks * 3, 1.0), x(kBlocks * 3);
  b[4] = std::nan("");
  EXPECT_THAT(errorOf(session.solve(system.view, b.data(), x.data(), "nan")),
              HasSubstr("NaN"));
}

TEST(SolveSession, MethodNamesRoundTrip) {
  for (SolveMethod method :
       {SolveMethod::Auto, SolveMethod::ConjugateGradient,
        SolveMethod::JacobiCG, SolveMethod::BlockJacobiCG,
        SolveMethod::CholeskyCG, SolveMethod::Cholesky, SolveMethod::LDLT,
        SolveMethod::LU})
    EXPECT_EQ(parseSolveMethod(solveMethodName(method)), method);
  EXPECT_EQ(parseSolveMethod("qr"), std::nullopt);
  SolveSettings bad;
  bad.tolerance = 2.0;
  EXPECT_THAT(errorOf(checkSolveSettings(bad, "--tol")),
              HasSubstr("--tol: the tolerance must lie between 0 and 1"));
  SolveSettings never;
  never.refactorIterations = 0;
  EXPECT_THAT(errorOf(checkSolveSettings(never, "--refactor-iters")),
              HasSubstr("the refactorisation threshold must be at least 1"));
}

TEST(IsSymmetric, MissingMirrorBlockCountsAsZero) {
  // Three 1x1 blocks, the middle one's mirror missing: symmetric only while
  // the middle one is zero.
  auto expectSymmetricWhileZero = [](std::vector<int32_t> rowptr,
                                     std::vector<int32_t> colidx) {
    std::vector<double> values{2.0, 0.0, 3.0};
    SquareBCSRView<double> view;
    view.rows = 2;
    view.rowptr = rowptr.data();
    view.colidx = colidx.data();
    view.values = values.data();
    EXPECT_TRUE(isSymmetric(view, 1e-12));
    values[1] = 1e-3;
    EXPECT_FALSE(isSymmetric(view, 1e-12));
  };
  // (0, 0), (0, 1), (1, 1): above the diagonal.
  expectSymmetricWhileZero({0, 2, 3}, {0, 1, 1});
  // (0, 0), (1, 0), (1, 1): below it.
  expectSymmetricWhileZero({0, 1, 3}, {0, 0, 1});
}

TEST(IsSymmetric, BlocksMustBeTransposes) {
  Eigen::MatrixXd a = spd(3, 7);
  EXPECT_TRUE(isSymmetric(BandSystem<double>(kBlocks, 3, a).view, 1e-12));
  // A symmetric block pattern whose off-diagonal blocks are not transposed.
  a(0, 4) += 1.0;
  EXPECT_FALSE(isSymmetric(BandSystem<double>(kBlocks, 3, a).view, 1e-12));
  // A diagonal block that is not symmetric itself, and one below the
  // diagonal that is not its mirror's transpose.
  Eigen::MatrixXd inBlock = spd(3, 7), below = spd(3, 7);
  inBlock(4, 5) += 1.0;
  below(7, 4) += 1.0;
  EXPECT_FALSE(
      isSymmetric(BandSystem<double>(kBlocks, 3, inBlock).view, 1e-12));
  EXPECT_FALSE(isSymmetric(BandSystem<double>(kBlocks, 3, below).view, 1e-12));
}

TEST(IsSymmetric, MirrorsFollowThePattern) {
  // One map for two patterns of two 1x1 block rows: first all four blocks
  // (symmetric), then (0, 0), (1, 0), (1, 1) without (0, 1). A map kept
  // from the first pattern would give (1, 0) a mirror and skip it.
  BlockMirrors mirrors;
  std::vector<int32_t> rowptr{0, 2, 4}, colidx{0, 1, 0, 1};
  std::vector<double> values{2.0, 1.0, 1.0, 3.0};
  SquareBCSRView<double> view;
  view.rows = 2;
  view.rowptr = rowptr.data();
  view.colidx = colidx.data();
  view.values = values.data();
  EXPECT_TRUE(isSymmetric(view, 1e-12, mirrors));
  rowptr = {0, 1, 3};
  colidx = {0, 0, 1};
  values = {2.0, 1.0, 3.0};
  view.rowptr = rowptr.data();
  view.colidx = colidx.data();
  view.values = values.data();
  EXPECT_FALSE(isSymmetric(view, 1e-12, mirrors));
  values[1] = 0.0;
  EXPECT_TRUE(isSymmetric(view, 1e-12, mirrors));
}

} // namespace
