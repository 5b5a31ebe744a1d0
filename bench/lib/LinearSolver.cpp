//===--- LinearSolver.cpp - CG, Jacobi CG and sparse direct solves --------===//

#include "LinearSolver.h"

namespace simit::bench {

template <typename Scalar>
LinearSolver<Scalar>::LinearSolver(SolverOptions options)
    : options_(options) {}

template <typename Scalar> LinearSolver<Scalar>::~LinearSolver() = default;

template <typename Scalar>
void LinearSolver<Scalar>::analyzePattern(const Matrix &a) {
  if (options_.kind != SolverKind::Direct)
    return;
  colMajor_ = a;
  factorization_ = std::make_unique<Factorization>();
  factorization_->analyzePattern(colMajor_);
}

template <typename Scalar>
SolveResult LinearSolver<Scalar>::solve(const Matrix &a, const Vector &b,
                                        Vector &x) {
  if (options_.kind == SolverKind::Direct)
    return solveDirect(a, b, x);
  return solveCG(a, b, x);
}

template <typename Scalar>
SolveResult LinearSolver<Scalar>::solveCG(const Matrix &a, const Vector &b,
                                          Vector &x) {
  const bool jacobi = options_.kind == SolverKind::JacobiCG;
  const Scalar tolerance = static_cast<Scalar>(options_.tolerance);
  if (jacobi)
    inverseDiagonal_ = a.diagonal().cwiseInverse();

  r_ = b;
  r_.noalias() -= a * x;
  Scalar rr = r_.squaredNorm();
  SolveResult result;
  if (rr <= tolerance) {
    result.residualNormSq = rr;
    return result;
  }
  if (jacobi)
    z_ = inverseDiagonal_.cwiseProduct(r_);
  const Vector &z = jacobi ? z_ : r_;
  p_ = z;
  Scalar rz = jacobi ? r_.dot(z_) : rr;
  int iteration = 0;
  while (iteration < options_.maxIterations) {
    ap_.noalias() = a * p_;
    Scalar alpha = rz / p_.dot(ap_);
    x += alpha * p_;
    r_ -= alpha * ap_;
    ++iteration;
    rr = r_.squaredNorm();
    if (rr <= tolerance)
      break;
    Scalar rzNext = rr;
    if (jacobi) {
      z_ = inverseDiagonal_.cwiseProduct(r_);
      rzNext = r_.dot(z_);
    }
    p_ = z + (rzNext / rz) * p_;
    rz = rzNext;
  }
  result.iterations = iteration;
  result.residualNormSq = rr;
  return result;
}

template <typename Scalar>
SolveResult LinearSolver<Scalar>::solveDirect(const Matrix &a,
                                              const Vector &b, Vector &x) {
  // The pattern never changes, so the symbolic factorisation made by
  // analyzePattern stays valid for every frame's values.
  colMajor_ = a;
  factorization_->factorize(colMajor_);
  SolveResult result;
  if (factorization_->info() != Eigen::Success) {
    result.succeeded = false;
    return result;
  }
  x = factorization_->solve(b);
  r_ = b;
  r_.noalias() -= a * x;
  result.residualNormSq = r_.squaredNorm();
  return result;
}

template class LinearSolver<float>;
template class LinearSolver<double>;

} // namespace simit::bench
