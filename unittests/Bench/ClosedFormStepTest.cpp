//===--- ClosedFormStepTest.cpp - One implicit step, computed by hand -----===//
//
// One free vertex falling under gravity for one linearly implicit step,
// with its 3x3 system solved in closed form.
//
//===----------------------------------------------------------------------===//

#include "FemScene.h"
#include "SpringsScene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace simit::bench;

namespace {

class ClosedFormStep : public ::testing::TestWithParam<SolverKind> {
protected:
  SolverOptions solver() const { return {GetParam(), 50, 1e-30}; }
};

// Two points, (0,0,0) fixed (z < 0.1) and (1,1,1) free, one spring at rest
// along U = (1,1,1)/sqrt(3). The free point's system is
// (a I + c U U^T) v = h m g with a = m + h viscous, c = h^2 k, whose solution
// is (h m / a) (g - c / (a + c) U (U . g)).
TEST_P(ClosedFormStep, SpringHoldsAFallingPoint) {
  simit::Mesh mesh;
  mesh.points = {{0, 0, 0}, {1, 1, 1}};
  mesh.edges = {{0, 1}};
  SpringsParams params;
  SpringsScene<double> scene(mesh, params, solver());
  ASSERT_TRUE(scene.isFixed(0));
  ASSERT_FALSE(scene.isFixed(1));

  const double h = 1e-2, k = 1e4, g = 9.81;
  const double m = 0.5 * 1e3 * M_PI * 1e-4 * std::sqrt(3.0);
  EXPECT_NEAR(scene.mass(1), m, 1e-15);
  const double a = m + h * 2.0, c = h * h * k;
  // U . g = -g / sqrt(3), and U (U . g) = -g/3 in every component.
  const double vx = h * m / a * (c / (a + c) * g / 3);
  const double vy = h * m / a * (-g + c / (a + c) * g / 3);

  FrameStats stats = scene.step();
  ASSERT_TRUE(stats.succeeded);
  const Eigen::VectorXd &v = scene.velocities();
  EXPECT_NEAR(v[3], vx, 1e-12);
  EXPECT_NEAR(v[4], vy, 1e-12);
  EXPECT_NEAR(v[5], vx, 1e-12);
  const Eigen::VectorXd &x = scene.positions();
  EXPECT_NEAR(x[3], 1 + h * vx, 1e-14);
  EXPECT_NEAR(x[4], 1 + h * vy, 1e-14);
  EXPECT_NEAR(x[5], 1 + h * vx, 1e-14);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(x[i], 0);
    EXPECT_EQ(v[i], 0);
  }
}

// The unit corner tet with only (0,1,0) free (y >= 0.05). At rest F = I,
// so there is no elastic force and K_11 = -W (mu I + (mu + lambda) e_y e_y^T)
// with W = 1/6: the free vertex solves
// (m I + h^2 W (mu I + (mu + lambda) e_y e_y^T)) v' = m v + h m g.
TEST_P(ClosedFormStep, TetCornerFalls) {
  simit::Mesh mesh;
  mesh.points = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, 0, 0}};
  mesh.tets = {{0, 1, 2, 3}};
  FemParams params;
  params.fixedBelowY = 0.05;
  params.initialVelocity = {0.1, 0.2, -0.3};
  FemScene<double> scene(mesh, params, solver());
  for (int vertex : {0, 2, 3})
    ASSERT_TRUE(scene.isFixed(vertex));

  const double e = 1e6, nu = 0.45, h = 0.01, w = 1.0 / 6;
  const double mu = e / (2 * (1 + nu));
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
  const double m = 1000 * w / 4;
  EXPECT_NEAR(scene.mass(1), m, 1e-12);
  const double soft = m + h * h * w * mu;
  const double stiff = m + h * h * w * (2 * mu + lambda);
  const double vx = m * 0.1 / soft;
  const double vy = m * (0.2 - h * 10) / stiff;
  const double vz = m * -0.3 / soft;

  ASSERT_TRUE(scene.step().succeeded);
  const Eigen::VectorXd &v = scene.velocities();
  EXPECT_NEAR(v[3], vx, 1e-12);
  EXPECT_NEAR(v[4], vy, 1e-12);
  EXPECT_NEAR(v[5], vz, 1e-12);
  EXPECT_NEAR(scene.positions()[4], 1 + h * vy, 1e-14);
  for (int vertex : {0, 2, 3})
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(v[3 * vertex + axis], 0);
      EXPECT_EQ(scene.positions()[3 * vertex + axis],
                scene.initialPositions()[3 * vertex + axis]);
    }
}

INSTANTIATE_TEST_SUITE_P(Solvers, ClosedFormStep,
                         ::testing::Values(SolverKind::CG,
                                           SolverKind::JacobiCG,
                                           SolverKind::Direct));

} // namespace
