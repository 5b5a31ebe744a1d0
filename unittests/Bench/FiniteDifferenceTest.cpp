//===--- FiniteDifferenceTest.cpp - Forces and stiffness against FD -------===//
//
// The bench/fd-check of scenes.md: elastic forces are minus the gradient of
// the elastic energy and stiffness blocks are the derivative of the forces,
// both compared with central finite differences on random deformed elements.
// The paper's dPdF typo, (mu - log J), must fail the same stiffness check.
//
//===----------------------------------------------------------------------===//

#include "NeoHookean.h"
#include "SpringModel.h"

#include <gtest/gtest.h>

#include <random>

using namespace simit::bench;
using Vec3d = Vec3<double>;
using Tet = std::array<Vec3d, 4>;

namespace {

const NeoHookeanMaterial kDragonMaterial =
    NeoHookeanMaterial::fromYoungPoisson(1e6, 0.45);

/// A random rest tet (either orientation) and a random deformation of it
/// that keeps J > 0.
struct DeformedTet {
  Tet rest, deformed;
};

DeformedTet randomDeformedTet(std::mt19937 &rng) {
  std::uniform_real_distribution<double> unit(-1, 1);
  DeformedTet t;
  do {
    for (Vec3d &x : t.rest)
      x = Vec3d(unit(rng), unit(rng), unit(rng));
  } while (std::abs(edgeMatrix(t.rest).determinant()) < 0.1);
  Mat3<double> f;
  do {
    f = Mat3<double>::Identity() + 0.3 * Mat3<double>::NullaryExpr([&] {
          return unit(rng);
        });
  } while (f.determinant() < 0.3);
  Vec3d shift(unit(rng), unit(rng), unit(rng));
  for (int i = 0; i < 4; ++i)
    t.deformed[i] = f * t.rest[i] + shift;
  return t;
}

/// Neo-Hookean energy W (mu/2 (tr F^T F - 3) - mu log J + lambda/2 log^2 J),
/// whose derivative with respect to F is the P of scenes.md.
double tetEnergy(const Tet &x, const TetRestShape<double> &rest,
                 const NeoHookeanMaterial &m) {
  Mat3<double> f = edgeMatrix(x) * rest.inverseDm;
  double logJ = std::log(f.determinant());
  return rest.volume * (m.mu / 2 * (f.squaredNorm() - 3) - m.mu * logJ +
                        m.lambda / 2 * logJ * logJ);
}

/// |K - K_fd| / |K| over the full 12x12 stiffness of a tet, K_fd from
/// central differences of the forces.
double stiffnessError(const DeformedTet &t, StiffnessCoefficient coefficient) {
  TetRestShape<double> rest = tetRestShape(t.rest);
  TetElasticity<double> analytic;
  tetElasticity(t.deformed, rest, kDragonMaterial, true, analytic, coefficient);
  const double step = 1e-6;
  double diffSq = 0, normSq = 0;
  for (int j = 0; j < 4; ++j)
    for (int c = 0; c < 3; ++c) {
      Tet plus = t.deformed, minus = t.deformed;
      plus[j][c] += step;
      minus[j][c] -= step;
      TetElasticity<double> fPlus, fMinus;
      tetElasticity(plus, rest, kDragonMaterial, false, fPlus);
      tetElasticity(minus, rest, kDragonMaterial, false, fMinus);
      for (int i = 0; i < 4; ++i) {
        Vec3d numeric = (fPlus.force[i] - fMinus.force[i]) / (2 * step);
        diffSq += (analytic.stiffness[i][j].col(c) - numeric).squaredNorm();
        normSq += analytic.stiffness[i][j].col(c).squaredNorm();
      }
    }
  return std::sqrt(diffSq / normSq);
}

TEST(NeoHookeanFD, ForceIsMinusEnergyGradient) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    DeformedTet t = randomDeformedTet(rng);
    TetRestShape<double> rest = tetRestShape(t.rest);
    TetElasticity<double> analytic;
    tetElasticity(t.deformed, rest, kDragonMaterial, false, analytic);
    const double step = 1e-6;
    double diffSq = 0, normSq = 0;
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 3; ++c) {
        Tet plus = t.deformed, minus = t.deformed;
        plus[i][c] += step;
        minus[i][c] -= step;
        double numeric = -(tetEnergy(plus, rest, kDragonMaterial) -
                           tetEnergy(minus, rest, kDragonMaterial)) /
                         (2 * step);
        diffSq += std::pow(analytic.force[i][c] - numeric, 2);
        normSq += std::pow(analytic.force[i][c], 2);
      }
    EXPECT_LT(std::sqrt(diffSq / normSq), 1e-6) << "trial " << trial;
  }
}

TEST(NeoHookeanFD, StiffnessIsForceDerivative) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial)
    EXPECT_LT(stiffnessError(randomDeformedTet(rng),
                             StiffnessCoefficient::Corrected),
              1e-6)
        << "trial " << trial;
}

TEST(NeoHookeanFD, PaperTypoCoefficientFailsTheCheck) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial)
    EXPECT_GT(stiffnessError(randomDeformedTet(rng),
                             StiffnessCoefficient::PaperTypo),
              1e-3)
        << "trial " << trial;
}

TEST(NeoHookeanFD, StiffnessBlocksAreSymmetric) {
  std::mt19937 rng(3);
  DeformedTet t = randomDeformedTet(rng);
  TetElasticity<double> e;
  tetElasticity(t.deformed, tetRestShape(t.rest), kDragonMaterial, true, e);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_LT((e.stiffness[i][j] - e.stiffness[j][i].transpose()).norm(),
                1e-9 * e.stiffness[i][j].norm());
}

TEST(NeoHookean, RestStateHasNoForce) {
  std::mt19937 rng(5);
  DeformedTet t = randomDeformedTet(rng);
  TetElasticity<double> e;
  tetElasticity(t.rest, tetRestShape(t.rest), kDragonMaterial, false, e);
  for (const Vec3d &f : e.force)
    EXPECT_LT(f.norm(), 1e-8);
}

TEST(NeoHookean, NegativelyOrientedTetHasPositiveVolume) {
  Tet positive = {Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(0, 0, 1),
                  Vec3d(0, 0, 0)};
  Tet negative = {positive[1], positive[0], positive[2], positive[3]};
  EXPECT_GT(edgeMatrix(positive).determinant(), 0);
  EXPECT_LT(edgeMatrix(negative).determinant(), 0);
  EXPECT_DOUBLE_EQ(tetRestShape(positive).volume, 1.0 / 6);
  EXPECT_DOUBLE_EQ(tetRestShape(negative).volume, 1.0 / 6);
}

TEST(NeoHookean, LameParametersFromYoungPoisson) {
  NeoHookeanMaterial m = NeoHookeanMaterial::fromYoungPoisson(1e6, 0.45);
  EXPECT_NEAR(m.mu, 1e6 / 2.9, 1e-6);
  EXPECT_NEAR(m.lambda, 0.45e6 / (1.45 * 0.1), 1e-6);
}

double springEnergy(const Vec3d &x0, const Vec3d &x1, double k, double l0) {
  double stretch = (x1 - x0).norm() - l0;
  return k / 2 * stretch * stretch;
}

TEST(SpringFD, ForceIsMinusEnergyGradientAndHessianIsItsDerivative) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(-1, 1);
  const double k = 1e4, step = 1e-6;
  for (int trial = 0; trial < 20; ++trial) {
    Vec3d x0(unit(rng), unit(rng), unit(rng));
    Vec3d x1(unit(rng), unit(rng), unit(rng));
    // Stretched and compressed springs alike.
    double l0 = (x1 - x0).norm() * (1 + 0.5 * unit(rng));
    SpringResponse<double> s = springResponse(x0, x1, k, l0);
    Mat3<double> numericHessian;
    for (int c = 0; c < 3; ++c) {
      Vec3d plus = x0, minus = x0;
      plus[c] += step;
      minus[c] -= step;
      double numericForce =
          -(springEnergy(plus, x1, k, l0) - springEnergy(minus, x1, k, l0)) /
          (2 * step);
      EXPECT_NEAR(s.forceOnFirst[c], numericForce,
                  1e-6 * s.forceOnFirst.norm());
      numericHessian.col(c) = -(springResponse(plus, x1, k, l0).forceOnFirst -
                                springResponse(minus, x1, k, l0).forceOnFirst) /
                              (2 * step);
    }
    EXPECT_LT((s.hessianBlock - numericHessian).norm(),
              1e-6 * s.hessianBlock.norm())
        << "trial " << trial;
    // Endpoint 1 feels the opposite force: the energy's gradient in x1.
    Vec3d plus = x1;
    plus[0] += step;
    Vec3d minus = x1;
    minus[0] -= step;
    double numericOnSecond =
        -(springEnergy(x0, plus, k, l0) - springEnergy(x0, minus, k, l0)) /
        (2 * step);
    EXPECT_NEAR(-s.forceOnFirst[0], numericOnSecond,
                1e-6 * s.forceOnFirst.norm());
  }
}

} // namespace
