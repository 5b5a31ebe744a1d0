//===--- Solvers.h - Iterative solvers on BCSR matrices ---------*- C++ -*-===//
//
// Conjugate gradients for symmetric positive definite block sparse systems,
// as used by the runtime for `\` and by the benchmark scenes: start from the
// given x, stop after maxIterations or once r.r <= tolerance.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SOLVERS_H
#define SIMIT_RUNTIME_SOLVERS_H

#include "simit/Runtime/SparsityPattern.h"

#include "llvm/Support/Error.h"

namespace simit {

enum class Preconditioner { None, Jacobi };

struct SolverOptions {
  int maxIterations = 50;
  /// Stop once the residual's squared norm r.r is at most this.
  double tolerance = 1e-12;
  Preconditioner preconditioner = Preconditioner::None;
};

struct SolverResult {
  int iterations = 0;
  /// r.r of the recursively updated residual at the end.
  double residualNormSquared = 0;
  bool converged = false;
};

/// Solves A x = b for square blocks (blockRows == blockCols, rows == cols);
/// x holds the initial guess on entry and the solution on exit. Errors: a
/// non-square matrix; with Jacobi, a zero or missing diagonal entry (named
/// by its scalar row); p.Ap <= 0, which means A is not positive definite.
llvm::Expected<SolverResult> conjugateGradient(const BCSRMatrix &a,
                                               const double *b, double *x,
                                               const SolverOptions &options);

} // namespace simit

#endif // SIMIT_RUNTIME_SOLVERS_H
