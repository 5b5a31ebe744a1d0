//===--- NeoHookean.h - Neo-Hookean tet force and stiffness ---*- C++ -*-===//
//
// The linear-tetrahedron Neo-Hookean model of bench/scenes.md (the paper's
// appendix A, with its dPdF typo corrected): rest data B = Dm^-1 and
// W = |det Dm| / 6, P(F) = mu (F - F^-T) + lambda log(J) F^-T, and the
// vertex forces f_i = -W P(F) B^T e_i, vertex 3 taking minus the others' sum.
//
// Writing b_i for row i of B (b_3 = -(b_0 + b_1 + b_2)) and g_i = F^-T b_i,
// the differential
//   dP(F; dF) = mu dF + c F^-T dF^T F^-T + lambda tr(F^-1 dF) F^-T,
//   c = mu - lambda log J,
// gives the stiffness blocks K_ij = d f_i / d x_j in closed form:
//   K_ij = -W (mu (b_i . b_j) I + c g_j g_i^T + lambda g_i g_j^T).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_NEOHOOKEAN_H
#define SIMIT_BENCH_NEOHOOKEAN_H

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <array>
#include <cmath>

namespace simit::bench {

struct NeoHookeanMaterial {
  double mu;
  double lambda;

  static NeoHookeanMaterial fromYoungPoisson(double youngsModulus,
                                             double poissonRatio) {
    double e = youngsModulus, nu = poissonRatio;
    return {e / (2 * (1 + nu)), e * nu / ((1 + nu) * (1 - 2 * nu))};
  }
};

/// The coefficient of F^-T dF^T F^-T in dP. PaperTypo is the (mu - log J) of
/// the paper's appendix A, kept so a test can show the finite-difference
/// check rejects it.
enum class StiffnessCoefficient { Corrected, PaperTypo };

template <typename Scalar> using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
template <typename Scalar> using Mat3 = Eigen::Matrix<Scalar, 3, 3>;

template <typename Scalar> struct TetRestShape {
  Mat3<Scalar> inverseDm; // B
  Scalar volume;          // W = |det Dm| / 6
};

/// Dm has columns x_i - x_3 (i = 0, 1, 2).
template <typename Scalar>
Mat3<Scalar> edgeMatrix(const std::array<Vec3<Scalar>, 4> &x) {
  Mat3<Scalar> d;
  d << x[0] - x[3], x[1] - x[3], x[2] - x[3];
  return d;
}

template <typename Scalar>
TetRestShape<Scalar> tetRestShape(const std::array<Vec3<Scalar>, 4> &x) {
  Mat3<Scalar> dm = edgeMatrix(x);
  return {dm.inverse(), std::abs(dm.determinant()) / Scalar(6)};
}

/// The rows b_0..b_3 of B, b_3 = -(b_0 + b_1 + b_2).
template <typename Scalar>
std::array<Vec3<Scalar>, 4> shapeGradients(const Mat3<Scalar> &inverseDm) {
  std::array<Vec3<Scalar>, 4> b;
  for (int i = 0; i < 3; ++i)
    b[i] = inverseDm.row(i).transpose();
  b[3] = -(b[0] + b[1] + b[2]);
  return b;
}

/// Elastic forces and (optionally) stiffness blocks of one tetrahedron at
/// deformed positions x.
template <typename Scalar> struct TetElasticity {
  std::array<Vec3<Scalar>, 4> force;
  Mat3<Scalar> stiffness[4][4]; // K_ij = d force_i / d x_j
};

template <typename Scalar>
void tetElasticity(const std::array<Vec3<Scalar>, 4> &x,
                   const TetRestShape<Scalar> &rest,
                   const NeoHookeanMaterial &material, bool withStiffness,
                   TetElasticity<Scalar> &out,
                   StiffnessCoefficient coefficient =
                       StiffnessCoefficient::Corrected) {
  const Scalar mu = static_cast<Scalar>(material.mu);
  const Scalar lambda = static_cast<Scalar>(material.lambda);
  Mat3<Scalar> f = edgeMatrix(x) * rest.inverseDm;
  // F^-T is the cofactor matrix over J: one determinant, no pivoting.
  Mat3<Scalar> cofactor;
  cofactor.col(0) = f.col(1).cross(f.col(2));
  cofactor.col(1) = f.col(2).cross(f.col(0));
  cofactor.col(2) = f.col(0).cross(f.col(1));
  Scalar j = f.col(0).dot(cofactor.col(0));
  Scalar logJ = std::log(j);
  Mat3<Scalar> inverseTranspose = cofactor / j;
  Mat3<Scalar> p =
      mu * (f - inverseTranspose) + lambda * logJ * inverseTranspose;

  std::array<Vec3<Scalar>, 4> b = shapeGradients(rest.inverseDm);
  Mat3<Scalar> wp = rest.volume * p;
  for (int i = 0; i < 4; ++i)
    out.force[i] = -(wp * b[i]);
  if (!withStiffness)
    return;

  Scalar c = coefficient == StiffnessCoefficient::Corrected
                 ? mu - lambda * logJ
                 : mu - logJ;
  std::array<Vec3<Scalar>, 4> g;
  for (int i = 0; i < 4; ++i)
    g[i] = inverseTranspose * b[i];
  const Scalar w = rest.volume;
  for (int i = 0; i < 4; ++i) {
    for (int k = i; k < 4; ++k) {
      Mat3<Scalar> block = (-w * c) * g[k] * g[i].transpose() +
                           (-w * lambda) * g[i] * g[k].transpose();
      block.diagonal().array() -= w * mu * b[i].dot(b[k]);
      out.stiffness[i][k] = block;
      out.stiffness[k][i] = block.transpose();
    }
  }
}

} // namespace simit::bench

#endif // SIMIT_BENCH_NEOHOOKEAN_H
