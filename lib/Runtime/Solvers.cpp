//===--- Solvers.cpp - Iterative solvers on BCSR matrices -----------------===//

#include "simit/Runtime/Solvers.h"

#include "llvm/Support/FormatVariadic.h"

#include <vector>

using namespace simit;

namespace {

double dot(const std::vector<double> &a, const std::vector<double> &b) {
  double sum = 0;
  for (size_t i = 0; i < a.size(); ++i)
    sum += a[i] * b[i];
  return sum;
}

/// 1 / A(i, i) for every scalar row i.
llvm::Expected<std::vector<double>> inverseDiagonal(const BCSRMatrix &a) {
  const SparsityPattern &p = *a.pattern;
  int b = a.blockRows;
  std::vector<double> inverse(static_cast<size_t>(p.numRows()) * b, 0.0);
  for (int r = 0; r < p.numRows(); ++r) {
    int k = p.findBlock(r, r);
    for (int i = 0; i < b; ++i) {
      double d = k < 0 ? 0.0 : a.block(k)[i * b + i];
      if (d == 0.0)
        return llvm::createStringError(
            "Jacobi preconditioner: the diagonal entry of row " +
            llvm::Twine(r * b + i) + " is zero");
      inverse[static_cast<size_t>(r) * b + i] = 1.0 / d;
    }
  }
  return inverse;
}

} // namespace

llvm::Expected<SolverResult>
simit::conjugateGradient(const BCSRMatrix &a, const double *bIn, double *x,
                         const SolverOptions &options) {
  const SparsityPattern &p = *a.pattern;
  if (a.blockRows != a.blockCols || p.numRows() != p.numCols())
    return llvm::createStringError(
        "conjugate gradients: expected a square matrix, found " +
        llvm::Twine(p.numRows()) + "x" + llvm::Twine(p.numCols()) +
        " blocks of " + llvm::Twine(a.blockRows) + "x" +
        llvm::Twine(a.blockCols));
  size_t n = static_cast<size_t>(p.numRows()) * a.blockRows;

  std::vector<double> inverseDiag;
  bool jacobi = options.preconditioner == Preconditioner::Jacobi;
  if (jacobi) {
    auto d = inverseDiagonal(a);
    if (!d)
      return d.takeError();
    inverseDiag = std::move(*d);
  }

  std::vector<double> r(n), z, dir(n), ad(n);
  multiply(a, x, ad.data());
  for (size_t i = 0; i < n; ++i)
    r[i] = bIn[i] - ad[i];
  auto precondition = [&](const std::vector<double> &res,
                          std::vector<double> &out) {
    out.resize(n);
    for (size_t i = 0; i < n; ++i)
      out[i] = jacobi ? inverseDiag[i] * res[i] : res[i];
  };
  precondition(r, z);
  dir = z;
  double rz = dot(r, z);

  SolverResult result;
  result.residualNormSquared = dot(r, r);
  while (result.residualNormSquared > options.tolerance &&
         result.iterations < options.maxIterations) {
    multiply(a, dir.data(), ad.data());
    double curvature = dot(dir, ad);
    if (!(curvature > 0))
      return llvm::createStringError(
          "conjugate gradients: p.Ap = " + llvm::formatv("{0:g}", curvature) +
          " at iteration " + llvm::Twine(result.iterations) +
          "; the matrix is not positive definite");
    double alpha = rz / curvature;
    for (size_t i = 0; i < n; ++i) {
      x[i] += alpha * dir[i];
      r[i] -= alpha * ad[i];
    }
    precondition(r, z);
    double rzNext = dot(r, z);
    double beta = rzNext / rz;
    rz = rzNext;
    for (size_t i = 0; i < n; ++i)
      dir[i] = z[i] + beta * dir[i];
    ++result.iterations;
    result.residualNormSquared = dot(r, r);
  }
  result.converged = result.residualNormSquared <= options.tolerance;
  return result;
}
