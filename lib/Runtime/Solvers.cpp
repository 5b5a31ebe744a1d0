//===--- Solvers.cpp - Conjugate gradients on BCSR matrices ---------------===//
//
// Preconditioned CG whose convergence is the true residual's, and forward
// substitution.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/Solvers.h"

#include "llvm/Support/FormatVariadic.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace simit;

namespace {

/// Dot products accumulate in double, also for float vectors.
template <typename T>
double dot(const std::vector<T> &u, const std::vector<T> &v) {
  double sum = 0;
  for (size_t i = 0; i < u.size(); ++i)
    sum += static_cast<double>(u[i]) * v[i];
  return sum;
}

/// 1 / A(i, i) for every scalar row i.
template <typename T>
llvm::Expected<std::vector<T>> inverseDiagonal(const SquareBCSRView<T> &a) {
  int64_t b = a.blockSize;
  std::vector<T> inverse(static_cast<size_t>(a.size()), T(0));
  for (int64_t r = 0; r < a.rows; ++r) {
    const int32_t *begin = a.colidx + a.rowptr[r];
    const int32_t *end = a.colidx + a.rowptr[r + 1];
    const int32_t *k = std::lower_bound(begin, end, r);
    for (int64_t i = 0; i < b; ++i) {
      T d = k != end && *k == r ? a.values[((k - a.colidx) * b + i) * b + i]
                                : T(0);
      if (d == T(0))
        return llvm::createStringError(
            "Jacobi preconditioner: the diagonal entry of row " +
            llvm::Twine(r * b + i) + " is zero");
      inverse[r * b + i] = T(1) / d;
    }
  }
  return inverse;
}

/// The inverse of every diagonal block, row-major, block row after block
/// row; computed in double.
template <typename T>
llvm::Expected<std::vector<T>>
inverseDiagonalBlocks(const SquareBCSRView<T> &a) {
  int64_t b = a.blockSize;
  std::vector<T> inverse(static_cast<size_t>(a.rows * b * b), T(0));
  Eigen::MatrixXd block(b, b);
  for (int64_t r = 0; r < a.rows; ++r) {
    const int32_t *begin = a.colidx + a.rowptr[r];
    const int32_t *end = a.colidx + a.rowptr[r + 1];
    const int32_t *k = std::lower_bound(begin, end, r);
    block.setZero();
    if (k != end && *k == r)
      for (int64_t i = 0; i < b; ++i)
        for (int64_t j = 0; j < b; ++j)
          block(i, j) = a.values[((k - a.colidx) * b + i) * b + j];
    Eigen::FullPivLU<Eigen::MatrixXd> lu(block);
    if (!lu.isInvertible())
      return llvm::createStringError(
          "block-Jacobi preconditioner: the diagonal block of block row " +
          llvm::Twine(r) + " is singular");
    Eigen::MatrixXd blockInverse = lu.inverse();
    for (int64_t i = 0; i < b; ++i)
      for (int64_t j = 0; j < b; ++j)
        inverse[(r * b + i) * b + j] = static_cast<T>(blockInverse(i, j));
  }
  return inverse;
}

/// out = D res for D block diagonal (`rows` blocks of `b` x `b`, row-major,
/// one after the other); `StaticBlock` as in multiplyBlocks.
template <int64_t StaticBlock, typename T>
void multiplyDiagonalBlocks(const std::vector<T> &d, const std::vector<T> &res,
                            std::vector<T> &out, int64_t rows,
                            int64_t blockSize) {
  int64_t b = StaticBlock ? StaticBlock : blockSize;
  for (int64_t r = 0; r < rows; ++r)
    for (int64_t i = 0; i < b; ++i) {
      T sum = 0;
      for (int64_t j = 0; j < b; ++j)
        sum += d[(r * b + i) * b + j] * res[r * b + j];
      out[r * b + i] = sum;
    }
}

/// out = b - A x, returning its r.r.
template <typename T>
double trueResidual(const SquareBCSRView<T> &a, const T *b, const T *x,
                    std::vector<T> &out) {
  multiply(a, x, out.data());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = b[i] - out[i];
  return dot(out, out);
}

} // namespace

llvm::Expected<SquareBCSRView<double>> simit::squareView(const BCSRMatrix &a) {
  const SparsityPattern &p = *a.pattern;
  if (a.blockRows != a.blockCols || p.numRows() != p.numCols())
    return llvm::createStringError(
        "expected a square matrix, found " + llvm::Twine(p.numRows()) + "x" +
        llvm::Twine(p.numCols()) + " blocks of " + llvm::Twine(a.blockRows) +
        "x" + llvm::Twine(a.blockCols));
  SquareBCSRView<double> view;
  view.rows = p.numRows();
  view.blockSize = a.blockRows;
  view.rowptr = p.rowPointers().data();
  view.colidx = p.columnIndices().data();
  view.values = a.values.data();
  return view;
}

namespace {
/// y = A x with blocks of `b` x `b`; `b` a compile-time constant where the
/// caller knows it (the block loops then unroll), else `blockSize`.
template <int64_t StaticBlock, typename T>
void multiplyBlocks(const SquareBCSRView<T> &a, const T *x, T *y) {
  int64_t b = StaticBlock ? StaticBlock : a.blockSize;
  for (int64_t r = 0; r < a.rows; ++r) {
    T *yr = y + r * b;
    std::fill(yr, yr + b, T(0));
    for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k) {
      const T *block = a.values + static_cast<int64_t>(k) * b * b;
      const T *xc = x + static_cast<int64_t>(a.colidx[k]) * b;
      for (int64_t i = 0; i < b; ++i) {
        T sum = 0;
        for (int64_t j = 0; j < b; ++j)
          sum += block[i * b + j] * xc[j];
        yr[i] += sum;
      }
    }
  }
}
} // namespace

template <typename T>
void simit::multiply(const SquareBCSRView<T> &a, const T *x, T *y) {
  // The same sums in the same order for every block size: 3 (points in
  // space) and 1 only unroll.
  switch (a.blockSize) {
  case 1:
    return multiplyBlocks<1>(a, x, y);
  case 3:
    return multiplyBlocks<3>(a, x, y);
  default:
    return multiplyBlocks<0>(a, x, y);
  }
}

template <typename T>
bool simit::isSymmetric(const SquareBCSRView<T> &a, double relativeTolerance) {
  int64_t b = a.blockSize, blocks = a.rows ? a.rowptr[a.rows] : 0;
  double largest = 0;
  for (int64_t i = 0; i < blocks * b * b; ++i)
    largest = std::max(largest, std::abs(static_cast<double>(a.values[i])));
  double tolerance = relativeTolerance * largest;
  auto block = [&](int64_t k) { return a.values + k * b * b; };
  for (int64_t r = 0; r < a.rows; ++r) {
    for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k) {
      int64_t c = a.colidx[k];
      const int32_t *begin = a.colidx + a.rowptr[c];
      const int32_t *end = a.colidx + a.rowptr[c + 1];
      const int32_t *mirror = std::lower_bound(begin, end, r);
      bool present = mirror != end && *mirror == r;
      const T *rc = block(k);
      const T *cr = present ? block(mirror - a.colidx) : nullptr;
      for (int64_t i = 0; i < b; ++i)
        for (int64_t j = 0; j < b; ++j) {
          double other = present ? cr[j * b + i] : 0.0;
          if (std::abs(rc[i * b + j] - other) > tolerance)
            return false;
        }
    }
  }
  return true;
}

template <typename T>
llvm::Expected<SolverResult>
simit::conjugateGradient(const SquareBCSRView<T> &a, const T *bIn, T *x,
                         const SolverOptions &options) {
  size_t n = static_cast<size_t>(a.size());
  int64_t bs = a.blockSize;
  // Diagonal (Jacobi) or block diagonal (block-Jacobi) inverse.
  std::vector<T> inverse;
  if (options.preconditioner != Preconditioner::None) {
    auto d = options.preconditioner == Preconditioner::Jacobi
                 ? inverseDiagonal(a)
                 : inverseDiagonalBlocks(a);
    if (!d)
      return d.takeError();
    inverse = std::move(*d);
  }
  auto precondition = [&](const std::vector<T> &res, std::vector<T> &out) {
    switch (options.preconditioner) {
    case Preconditioner::None:
      out = res;
      return;
    case Preconditioner::Jacobi:
      for (size_t i = 0; i < n; ++i)
        out[i] = inverse[i] * res[i];
      return;
    case Preconditioner::BlockJacobi:
      if (bs == 3)
        return multiplyDiagonalBlocks<3>(inverse, res, out, a.rows, bs);
      return multiplyDiagonalBlocks<0>(inverse, res, out, a.rows, bs);
    }
  };

  std::vector<T> r(n), z(n), dir(n), ad(n);
  SolverResult result;
  result.residualNormSquared = trueResidual(a, bIn, x, r);
  // Whether r is b - A x computed anew rather than updated.
  bool exact = true;
  double rz = 0;
  auto restart = [&] {
    precondition(r, z);
    dir = z;
    rz = dot(r, z);
  };
  restart();
  while (true) {
    if (result.residualNormSquared <= options.tolerance) {
      if (exact)
        break;
      result.residualNormSquared = trueResidual(a, bIn, x, r);
      exact = true;
      if (result.residualNormSquared <= options.tolerance)
        break;
      restart();
    }
    if (result.iterations >= options.maxIterations)
      break;
    multiply(a, dir.data(), ad.data());
    double curvature = dot(dir, ad);
    if (!(curvature > 0))
      return llvm::createStringError(
          "conjugate gradients: p.Ap = " + llvm::formatv("{0:g}", curvature) +
          " at iteration " + llvm::Twine(result.iterations) +
          "; the matrix is not positive definite");
    T alpha = static_cast<T>(rz / curvature);
    for (size_t i = 0; i < n; ++i) {
      x[i] += alpha * dir[i];
      r[i] -= alpha * ad[i];
    }
    precondition(r, z);
    double rzNext = dot(r, z);
    T beta = static_cast<T>(rzNext / rz);
    rz = rzNext;
    for (size_t i = 0; i < n; ++i)
      dir[i] = z[i] + beta * dir[i];
    ++result.iterations;
    result.residualNormSquared = dot(r, r);
    exact = false;
  }
  result.converged = exact && result.residualNormSquared <= options.tolerance;
  return result;
}

llvm::Expected<SolverResult>
simit::conjugateGradient(const BCSRMatrix &a, const double *b, double *x,
                         const SolverOptions &options) {
  auto view = squareView(a);
  if (!view)
    return llvm::createStringError("conjugate gradients: " +
                                   llvm::toString(view.takeError()));
  return conjugateGradient(*view, b, x, options);
}

#define SIMIT_INSTANTIATE_SOLVERS(T)                                           \
  template void simit::multiply(const SquareBCSRView<T> &, const T *, T *);    \
  template bool simit::isSymmetric(const SquareBCSRView<T> &, double);         \
  template llvm::Expected<SolverResult> simit::conjugateGradient(              \
      const SquareBCSRView<T> &, const T *, T *, const SolverOptions &);
SIMIT_INSTANTIATE_SOLVERS(double)
SIMIT_INSTANTIATE_SOLVERS(float)

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
