//===--- SpringModel.h - Spring force and stiffness ------------*- C++ -*-===//
//
// The spring of bench/scenes.md (springs-bunny): energy k (l - l0)^2 / 2 with
// d = x1 - x0, l = |d|, U = d / l and tension f = k (l - l0). Endpoint 0
// feels f U and endpoint 1 feels -f U; the energy's Hessian block with
// respect to x0 is (k - f/l) U U^T + (f/l) I.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_SPRINGMODEL_H
#define SIMIT_BENCH_SPRINGMODEL_H

#include <Eigen/Core>

namespace simit::bench {

template <typename Scalar> struct SpringResponse {
  Eigen::Matrix<Scalar, 3, 1> forceOnFirst;  // f U; the second gets -f U
  Eigen::Matrix<Scalar, 3, 3> hessianBlock;  // d^2 E / dx0^2
};

template <typename Scalar>
SpringResponse<Scalar> springResponse(const Eigen::Matrix<Scalar, 3, 1> &x0,
                                      const Eigen::Matrix<Scalar, 3, 1> &x1,
                                      Scalar stiffness, Scalar restLength) {
  Eigen::Matrix<Scalar, 3, 1> d = x1 - x0;
  Scalar l = d.norm();
  Eigen::Matrix<Scalar, 3, 1> u = d / l;
  Scalar tension = stiffness * (l - restLength);
  Scalar tensionPerLength = tension / l;
  SpringResponse<Scalar> out;
  out.forceOnFirst = tension * u;
  out.hessianBlock = (stiffness - tensionPerLength) * u * u.transpose();
  out.hessianBlock.diagonal().array() += tensionPerLength;
  return out;
}

} // namespace simit::bench

#endif // SIMIT_BENCH_SPRINGMODEL_H
