//===--- LinearSolver.h - CG, Jacobi CG and direct solves -----*- C++ -*-===//
//
// The solvers of bench/scenes.md: conjugate gradients from the current
// iterate, stopping when r.r <= tolerance or after an iteration cap, with or
// without a Jacobi preconditioner; and a sparse LDL^T factorisation, the
// exact solve that accuracy is judged against.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_LINEARSOLVER_H
#define SIMIT_BENCH_LINEARSOLVER_H

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <memory>

namespace simit::bench {

enum class SolverKind { CG, JacobiCG, Direct };

struct SolverOptions {
  SolverKind kind = SolverKind::CG;
  int maxIterations = 50;
  double tolerance = 1e-12; // on r.r, the squared residual norm
};

struct SolveResult {
  bool succeeded = true; // false only when a direct factorisation fails
  int iterations = 0;    // CG iterations; 0 for the direct solver
  double residualNormSq = 0; // r.r of the returned solution
};

template <typename Scalar> class LinearSolver {
public:
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::RowMajor, int>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  explicit LinearSolver(SolverOptions options);
  ~LinearSolver();

  /// One-off work that depends only on the pattern of `a` (the symbolic
  /// factorisation of the direct solver).
  void analyzePattern(const Matrix &a);

  /// Solves a x = b for symmetric positive definite a; x holds the initial
  /// iterate on entry.
  SolveResult solve(const Matrix &a, const Vector &b, Vector &x);


private:
  using ColMajorMatrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  using Factorization = Eigen::SimplicialLDLT<ColMajorMatrix>;

  SolveResult solveCG(const Matrix &a, const Vector &b, Vector &x);
  SolveResult solveDirect(const Matrix &a, const Vector &b, Vector &x);

  SolverOptions options_;
  // CG work vectors, kept between solves so a frame allocates nothing.
  Vector r_, z_, p_, ap_, inverseDiagonal_;
  ColMajorMatrix colMajor_;
  std::unique_ptr<Factorization> factorization_;
};

} // namespace simit::bench

#endif // SIMIT_BENCH_LINEARSOLVER_H
