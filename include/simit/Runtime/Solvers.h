//===--- Solvers.h - Linear solvers on BCSR matrices ------------*- C++ -*-===//
//
// The solvers of the runtime, on square block sparse matrices whose arrays
// belong to a BCSRMatrix or to lowered code (SquareBCSRView):
//  - conjugateGradient: plain, Jacobi-, block-Jacobi- or caller-
//    preconditioned CG from the given x, stopping after maxIterations or
//    once the true residual's r.r <= tolerance;
//  - solveLowerTriangular: forward substitution.
// `x = A \ b` of the language chooses among these and the sparse direct
// solvers in a SolveSession (SolveSession.h).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SOLVERS_H
#define SIMIT_RUNTIME_SOLVERS_H

#include "simit/Runtime/SparsityPattern.h"

#include "llvm/Support/Error.h"

#include <cstdint>
#include <functional>
#include <vector>

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

/// For each block of a square pattern, the index of its mirror (block
/// (c, r) of block (r, c)), or -1 where the pattern has none. The pattern
/// is kept and compared on each call, so that the map is built once per
/// pattern rather than per solve (on springs-bunny the check took 1.05 ms
/// building the map, 0.3 ms with it kept: about ten matrix-vector products
/// saved per solve).
class BlockMirrors {
public:
  const std::vector<int32_t> &of(int64_t rows, const int32_t *rowptr,
                                 const int32_t *colidx);

private:
  std::vector<int32_t> rowptr, colidx, mirrors;
};

/// Whether A equals its transpose: every block (r, c) is the transpose of
/// block (c, r) to `relativeTolerance` times A's largest magnitude, a
/// missing block counting as zero. `mirrors` keeps the map of A's pattern
/// for the next call.
template <typename T>
bool isSymmetric(const SquareBCSRView<T> &a, double relativeTolerance,
                 BlockMirrors &mirrors);
template <typename T>
bool isSymmetric(const SquareBCSRView<T> &a, double relativeTolerance);

/// Jacobi scales by 1 / A(i, i); block-Jacobi multiplies by the inverse of
/// each blockSize x blockSize diagonal block (3x3 for the usual vectors of
/// points), which also undoes the coupling of a point's components;
/// Operator is the caller's (SolverOptions::apply).
enum class Preconditioner { None, Jacobi, BlockJacobi, Operator };

/// z = M^-1 r for a symmetric positive definite M, in double.
using PreconditionerOperator =
    std::function<llvm::Error(const double *r, double *z)>;

struct SolverOptions {
  int maxIterations = 50;
  /// Stop once the residual's squared norm r.r is at most this. The
  /// recursively updated residual drifts from b - A x; when it passes, the
  /// true residual is computed and, if it does not pass too, replaces it and
  /// the iteration restarts from there (within maxIterations).
  double tolerance = 1e-12;
  Preconditioner preconditioner = Preconditioner::None;
  /// The preconditioner when `preconditioner` is Operator; its errors end
  /// the solve.
  PreconditionerOperator apply;
};

struct SolverResult {
  int iterations = 0;
  /// r.r of the residual at the end: the true one when converged.
  double residualNormSquared = 0;
  /// The true residual passed the tolerance.
  bool converged = false;
};

/// Solves A x = b by conjugate gradients; x holds the initial guess on entry
/// and the solution on exit. Dot products accumulate in double. Errors:
/// with Jacobi, a zero diagonal entry (named by its scalar row); with
/// block-Jacobi, a singular diagonal block (named by its block row); p.Ap <=
/// 0, which means A is not positive definite.
template <typename T>
llvm::Expected<SolverResult> conjugateGradient(const SquareBCSRView<T> &a,
                                               const T *b, T *x,
                                               const SolverOptions &options);
/// The same on a BCSRMatrix, which must be square.
llvm::Expected<SolverResult> conjugateGradient(const BCSRMatrix &a,
                                               const double *b, double *x,
                                               const SolverOptions &options);

/// x = L^-1 b for L the lower triangle of A (scalar entries on and below
/// the diagonal, within blocks too), by forward substitution. A zero
/// diagonal entry is an error naming its row.
template <typename T>
llvm::Error solveLowerTriangular(const SquareBCSRView<T> &a, const T *b, T *x);

} // namespace simit

#endif // SIMIT_RUNTIME_SOLVERS_H
