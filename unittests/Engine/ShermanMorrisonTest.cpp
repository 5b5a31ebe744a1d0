//===--- ShermanMorrisonTest.cpp - (A + u*v') \ b against Eigen -----------===//
//
// A program that solves a sparse 3x3-block matrix plus an outer product of
// two system vectors (minus one, and minus a second: rank 2, the Woodbury
// form), run under several solvers; every answer is checked against a dense
// Eigen solve of the same matrix, and the statistics say what was done.
// Without simit-sherman-morrison the dense sum is solved as written.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "gtest/gtest.h"

#include <Eigen/Dense>

#include <random>

using namespace simit;
using namespace simit::test;

namespace {

constexpr const char *kSource = R"sim(
element Point
  m : float;
  u : tensor[3](float);
  v : tensor[3](float);
  b : tensor[3](float);
  x : tensor[3](float);
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);

const I = [1.0, 0.0, 0.0; 0.0, 1.0, 0.0; 0.0, 0.0, 1.0];

func stiffness(s : Spring, p : (Point*2))
    -> (K : matrix[points,points](matrix[3,3](float)))
  K(p(0),p(0)) = s.k * I;
  K(p(0),p(1)) = -s.k * I;
  K(p(1),p(0)) = -s.k * I;
  K(p(1),p(1)) = s.k * I;
end

func mass(p : Point) -> (M : matrix[points,points](matrix[3,3](float)))
  M(p,p) = p.m * I;
end

export func main()
  K = map stiffness to springs reduce +;
  M = map mass to points reduce +;
  A = K + M;
  points.x = (A + points.u * points.v') \ points.b;
end
)sim";

constexpr int kPoints = 8;

/// Which low-rank update of A the program solves with.
enum class Update { Sum, Difference, RankTwo };

/// The solve of kSource for `update`.
std::string sourceOf(Update update) {
  std::string source = kSource;
  llvm::StringRef sum = "(A + points.u * points.v')";
  const char *replacement =
      update == Update::Difference ? "(A - points.u * points.v')"
      : update == Update::RankTwo
          ? "(A + points.u * points.v' - points.v * points.b')"
          : "(A + points.u * points.v')";
  source.replace(source.find(sum.str()), sum.size(), replacement);
  return source;
}

/// A chain of springs with a mass per point and random u, v, b; `dense`
/// is the updated A.
struct Scene {
  Set points{"points"};
  Set springs{"springs", {&points, &points}};
  FieldRef<double> m = points.addField<double>("m");
  FieldRef<double, 3> u = points.addField<double, 3>("u");
  FieldRef<double, 3> v = points.addField<double, 3>("v");
  FieldRef<double, 3> b = points.addField<double, 3>("b");
  FieldRef<double, 3> x = points.addField<double, 3>("x");
  FieldRef<double> k = springs.addField<double>("k");
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3 * kPoints, 3 * kPoints);
  Eigen::VectorXd uv, vv, bv;

  explicit Scene(Update update) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> value(-1, 1);
    uv.resize(3 * kPoints);
    vv.resize(3 * kPoints);
    bv.resize(3 * kPoints);
    for (int p = 0; p < kPoints; ++p) {
      points.add();
      m.set(p, 1.0 + p);
      std::array<double, 3> ub, vb, bb;
      for (int i = 0; i < 3; ++i) {
        ub[i] = uv[3 * p + i] = value(rng);
        vb[i] = vv[3 * p + i] = value(rng);
        bb[i] = bv[3 * p + i] = value(rng);
        dense(3 * p + i, 3 * p + i) += 1.0 + p;
      }
      u.set(p, ub);
      v.set(p, vb);
      b.set(p, bb);
    }
    for (int p = 0; p + 1 < kPoints; ++p) {
      double stiffness = 10.0 + p;
      k.set(springs.add(p, p + 1), stiffness);
      for (int i = 0; i < 3; ++i) {
        dense(3 * p + i, 3 * p + i) += stiffness;
        dense(3 * (p + 1) + i, 3 * (p + 1) + i) += stiffness;
        dense(3 * p + i, 3 * (p + 1) + i) -= stiffness;
        dense(3 * (p + 1) + i, 3 * p + i) -= stiffness;
      }
    }
    dense += (update == Update::Difference ? -1.0 : 1.0) * uv * vv.transpose();
    if (update == Update::RankTwo)
      dense -= vv * bv.transpose();
  }
};

/// Runs main with the given options and checks x against Eigen; returns
/// the program's statistics.
std::vector<SolveStatementStats>
expectDenseAnswer(ProgramOptions options, Update update = Update::Sum) {
  Program program(options);
  std::string source = sourceOf(update);
  if (llvm::Error err = program.loadString(source, "rank-one.sim")) {
    ADD_FAILURE() << message(std::move(err));
    return {};
  }
  llvm::Expected<Function> main = program.compile("main");
  if (!main) {
    ADD_FAILURE() << message(main.takeError());
    return {};
  }
  Scene scene(update);
  EXPECT_EQ(message(main->bind("points", scene.points)), "success");
  EXPECT_EQ(message(main->bind("springs", scene.springs)), "success");
  EXPECT_EQ(message(main->run()), "success");
  Eigen::VectorXd exact = scene.dense.fullPivLu().solve(scene.bv);
  for (int p = 0; p < kPoints; ++p)
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(scene.x.get(p)[i], exact[3 * p + i], 1e-10 * exact.norm())
          << p << " " << i;
  return program.solver().statistics();
}

TEST(ShermanMorrison, RewriteMatchesADenseSolve) {
  ProgramOptions options;
  options.solver.method = SolveMethod::Cholesky;
  std::vector<SolveStatementStats> stats = expectDenseAnswer(options);
  // Two solves with A (one factorisation, reused) and the last step.
  ASSERT_EQ(stats.size(), 3u);
  EXPECT_EQ(stats[0].statement,
            "solve [Sherman-Morrison A^-1 u] (rank-one.sim:33:41)");
  EXPECT_EQ(stats[0].factorisations, 1);
  EXPECT_EQ(stats[1].statement,
            "solve [Sherman-Morrison A^-1 b] (rank-one.sim:33:41)");
  EXPECT_EQ(stats[1].reuses, 1);
  EXPECT_EQ(stats[1].factorisations, 0);
  EXPECT_EQ(stats[2].statement, "Sherman-Morrison (rank-one.sim:33:41)");
  EXPECT_EQ(stats[2].methods,
            std::vector<SolveMethod>{SolveMethod::ShermanMorrison});
  EXPECT_LE(stats[2].maxRelativeResidual, 1e-12);
}

TEST(ShermanMorrison, DifferenceMatchesADenseSolve) {
  ProgramOptions options;
  options.solver.method = SolveMethod::Cholesky;
  std::vector<SolveStatementStats> stats =
      expectDenseAnswer(options, Update::Difference);
  ASSERT_EQ(stats.size(), 3u);
  EXPECT_EQ(stats[2].methods,
            std::vector<SolveMethod>{SolveMethod::ShermanMorrison});
}

// Rank 2: three solves with A's one factorisation, then the 2 x 2 system.
TEST(ShermanMorrison, RankTwoMatchesADenseSolve) {
  ProgramOptions options;
  options.solver.method = SolveMethod::Cholesky;
  std::vector<SolveStatementStats> stats =
      expectDenseAnswer(options, Update::RankTwo);
  ASSERT_EQ(stats.size(), 4u);
  EXPECT_EQ(stats[0].statement, "solve [Woodbury A^-1 u1] (rank-one.sim:33:64)");
  EXPECT_EQ(stats[0].factorisations, 1);
  EXPECT_EQ(stats[1].statement, "solve [Woodbury A^-1 u2] (rank-one.sim:33:64)");
  EXPECT_EQ(stats[1].reuses, 1);
  EXPECT_EQ(stats[2].reuses, 1);
  EXPECT_EQ(stats[3].statement, "Woodbury (rank-one.sim:33:64)");
  EXPECT_EQ(stats[3].methods,
            std::vector<SolveMethod>{SolveMethod::ShermanMorrison});
  EXPECT_LE(stats[3].maxRelativeResidual, 1e-12);
}

TEST(ShermanMorrison, AutoSolvesWithConjugateGradients) {
  std::vector<SolveStatementStats> stats = expectDenseAnswer({});
  ASSERT_EQ(stats.size(), 3u);
  EXPECT_EQ(stats[0].methods,
            std::vector<SolveMethod>{SolveMethod::ConjugateGradient});
}

// Without the rewrite A + u v^T is stored dense (the outer product has a
// block everywhere) and solved as written, by one LU of every block: the
// same answer, the slow path of the seed.
TEST(ShermanMorrison, WithoutTheRewriteTheDenseSumIsSolved) {
  ProgramOptions options;
  options.shermanMorrison = false;
  std::vector<SolveStatementStats> stats = expectDenseAnswer(options);
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_EQ(stats[0].statement, "solve (rank-one.sim:33:41)");
  EXPECT_EQ(stats[0].methods, std::vector<SolveMethod>{SolveMethod::LU});
}

} // namespace
