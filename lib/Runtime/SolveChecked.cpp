//===--- SolveChecked.cpp - Direct solves that cannot be silently wrong ---===//
//
// Conjugate gradients is right only for symmetric positive definite
// matrices; on anything else it returns a vector with no warning. So the
// method follows from the matrix: symmetric matrices try CG (positive
// definiteness shows as a breakdown, p.Ap <= 0), everything else and every
// CG failure goes to a sparse LU, and the true residual of the answer is
// checked whatever the method.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/Solvers.h"

#include "llvm/Support/FormatVariadic.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include <cmath>
#include <vector>

using namespace simit;

namespace {

/// The tolerances of one precision: CG's stopping test and the acceptance
/// test of the returned x, both relative to ||b||.
template <typename T> struct Tolerances;
template <> struct Tolerances<double> {
  static constexpr double cg = 1e-12, accept = 1e-8;
};
template <> struct Tolerances<float> {
  static constexpr double cg = 1e-6, accept = 1e-3;
};

template <typename T> double norm(const T *v, int64_t n) {
  double sum = 0;
  for (int64_t i = 0; i < n; ++i)
    sum += static_cast<double>(v[i]) * v[i];
  return std::sqrt(sum);
}

/// ||b - A x|| in double.
template <typename T>
double residualNorm(const SquareBCSRView<T> &a, const T *b, const T *x) {
  std::vector<T> ax(static_cast<size_t>(a.size()));
  multiply(a, x, ax.data());
  double sum = 0;
  for (int64_t i = 0; i < a.size(); ++i) {
    double r = static_cast<double>(b[i]) - ax[i];
    sum += r * r;
  }
  return std::sqrt(sum);
}

/// x = A^-1 b by Eigen's SparseLU in double; an error when A is singular.
template <typename T>
llvm::Error sparseLU(const SquareBCSRView<T> &a, const T *b, T *x) {
  using Matrix = Eigen::SparseMatrix<double>;
  int64_t bs = a.blockSize;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(a.rowptr[a.rows]) * bs * bs);
  for (int64_t r = 0; r < a.rows; ++r)
    for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k)
      for (int64_t i = 0; i < bs; ++i)
        for (int64_t j = 0; j < bs; ++j)
          entries.emplace_back(
              r * bs + i, a.colidx[k] * bs + j,
              a.values[(static_cast<int64_t>(k) * bs + i) * bs + j]);
  Matrix matrix(a.size(), a.size());
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseLU<Matrix, Eigen::COLAMDOrdering<int>> lu;
  lu.analyzePattern(matrix);
  lu.factorize(matrix);
  if (lu.info() != Eigen::Success)
    return llvm::createStringError(
        "the matrix is singular (its sparse LU factorisation has a zero "
        "pivot)");
  Eigen::VectorXd rhs(a.size());
  for (int64_t i = 0; i < a.size(); ++i)
    rhs[i] = b[i];
  Eigen::VectorXd solution = lu.solve(rhs);
  for (int64_t i = 0; i < a.size(); ++i)
    x[i] = static_cast<T>(solution[i]);
  return llvm::Error::success();
}

} // namespace

template <typename T>
llvm::Expected<SolveReport> simit::solveChecked(const SquareBCSRView<T> &a,
                                                const T *b, T *x) {
  int64_t n = a.size();
  SolveReport report;
  double bNorm = norm(b, n);
  if (!std::isfinite(bNorm))
    return llvm::createStringError(
        "the right-hand side holds a NaN or an infinity");
  std::fill(x, x + n, T(0));
  if (bNorm == 0)
    return report;

  bool solved = false;
  if (isSymmetric(a, 1e-10)) {
    SolverOptions options;
    options.maxIterations = static_cast<int>(std::min<int64_t>(2 * n, 1 << 30));
    double stop = Tolerances<T>::cg * bNorm;
    options.tolerance = stop * stop;
    llvm::Expected<SolverResult> cg = conjugateGradient(a, b, x, options);
    if (cg && cg->converged) {
      report.iterations = cg->iterations;
      solved = true;
    } else {
      // Not positive definite, or too ill-conditioned for CG: start over.
      llvm::consumeError(cg.takeError());
      std::fill(x, x + n, T(0));
    }
  }
  if (!solved) {
    report.method = SolveMethod::SparseLU;
    if (llvm::Error err = sparseLU(a, b, x))
      return std::move(err);
  }
  report.relativeResidual = residualNorm(a, b, x) / bNorm;
  if (!(report.relativeResidual <= Tolerances<T>::accept))
    return llvm::createStringError(
        llvm::formatv("the relative residual ||b - A x|| / ||b|| of the "
                      "solution is {0:e3} (the matrix is singular or too "
                      "ill-conditioned)",
                      report.relativeResidual)
            .str());
  return report;
}

template llvm::Expected<SolveReport>
simit::solveChecked(const SquareBCSRView<double> &, const double *, double *);
template llvm::Expected<SolveReport>
simit::solveChecked(const SquareBCSRView<float> &, const float *, float *);

template <typename T>
llvm::Error simit::solveLowerTriangular(const SquareBCSRView<T> &a,
                                        const T *b, T *x) {
  int64_t bs = a.blockSize;
  for (int64_t r = 0; r < a.rows; ++r) {
    for (int64_t i = 0; i < bs; ++i) {
      int64_t row = r * bs + i;
      double sum = b[row], diagonal = 0;
      for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k) {
        int64_t c = a.colidx[k];
        if (c > r)
          break; // columns are sorted: the rest is above the diagonal
        const T *block = a.values + (static_cast<int64_t>(k) * bs + i) * bs;
        for (int64_t j = 0; j < bs; ++j) {
          int64_t col = c * bs + j;
          if (col < row)
            sum -= static_cast<double>(block[j]) * x[col];
          else if (col == row)
            diagonal = block[j];
        }
      }
      if (diagonal == 0)
        return llvm::createStringError(
            "the lower triangle is singular: its diagonal entry of row " +
            llvm::Twine(row) + " is zero");
      x[row] = static_cast<T>(sum / diagonal);
    }
  }
  return llvm::Error::success();
}

template llvm::Error
simit::solveLowerTriangular(const SquareBCSRView<double> &, const double *,
                            double *);
template llvm::Error
simit::solveLowerTriangular(const SquareBCSRView<float> &, const float *,
                            float *);
