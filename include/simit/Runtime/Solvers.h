//===--- Solvers.h - Linear solvers on BCSR matrices ------------*- C++ -*-===//
//
// The solvers of the runtime, on square block sparse matrices whose arrays
// belong to a BCSRMatrix or to lowered code (SquareBCSRView):
//  - conjugateGradient: plain or Jacobi-preconditioned CG from the given x,
//    stopping after maxIterations or once r.r <= tolerance;
//  - solveChecked: `x = A \ b` of the language, which picks its method from
//    the matrix and cannot be silently wrong (see below).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SOLVERS_H
#define SIMIT_RUNTIME_SOLVERS_H

#include "simit/Runtime/SparsityPattern.h"

#include "llvm/Support/Error.h"

#include <cstdint>

namespace simit {

/// A square BCSR matrix in arrays owned elsewhere: `rows` block rows and
/// columns of blockSize x blockSize row-major blocks; row r's blocks are
/// values[rowptr[r] .. rowptr[r + 1]) at columns colidx[...], sorted.
template <typename T> struct SquareBCSRView {
  int64_t rows = 0;
  int64_t blockSize = 1;
  const int32_t *rowptr = nullptr;
  const int32_t *colidx = nullptr;
  const T *values = nullptr;

  /// The number of scalar unknowns.
  int64_t size() const { return rows * blockSize; }
};

/// The view of a BCSRMatrix with square blocks over a square pattern; an
/// error names the shape otherwise.
llvm::Expected<SquareBCSRView<double>> squareView(const BCSRMatrix &a);

/// y = A x.
template <typename T>
void multiply(const SquareBCSRView<T> &a, const T *x, T *y);

/// Whether A equals its transpose: every block (r, c) is the transpose of
/// block (c, r) to `relativeTolerance` times A's largest magnitude, a
/// missing block counting as zero.
template <typename T>
bool isSymmetric(const SquareBCSRView<T> &a, double relativeTolerance);

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

/// Solves A x = b by conjugate gradients; x holds the initial guess on entry
/// and the solution on exit. Dot products accumulate in double. Errors:
/// with Jacobi, a zero diagonal entry (named by its scalar row); p.Ap <= 0,
/// which means A is not positive definite.
template <typename T>
llvm::Expected<SolverResult> conjugateGradient(const SquareBCSRView<T> &a,
                                               const T *b, T *x,
                                               const SolverOptions &options);
/// The same on a BCSRMatrix, which must be square.
llvm::Expected<SolverResult> conjugateGradient(const BCSRMatrix &a,
                                               const double *b, double *x,
                                               const SolverOptions &options);

enum class SolveMethod { ConjugateGradient, SparseLU };

struct SolveReport {
  SolveMethod method = SolveMethod::ConjugateGradient;
  /// CG iterations (0 for LU).
  int iterations = 0;
  /// ||b - A x|| / ||b|| of the returned x, computed anew (0 when b = 0).
  double relativeResidual = 0;
};

/// x = A^-1 b, never silently wrong: conjugate gradients when A is
/// symmetric (to 1e-10), converging to ||r|| <= 1e-12 ||b|| (f32: 1e-6)
/// within 2n iterations; sparse LU (Eigen SparseLU, COLAMD, in double) when
/// A is not symmetric, or CG breaks down (A not positive definite) or does
/// not converge. The result's true residual is checked: above 1e-8 ||b||
/// (f32: 1e-3) it is an error that names the residual, as is a singular
/// matrix.
template <typename T>
llvm::Expected<SolveReport> solveChecked(const SquareBCSRView<T> &a,
                                         const T *b, T *x);

/// x = L^-1 b for L the lower triangle of A (scalar entries on and below
/// the diagonal, within blocks too), by forward substitution. A zero
/// diagonal entry is an error naming its row.
template <typename T>
llvm::Error solveLowerTriangular(const SquareBCSRView<T> &a, const T *b, T *x);

} // namespace simit

#endif // SIMIT_RUNTIME_SOLVERS_H
