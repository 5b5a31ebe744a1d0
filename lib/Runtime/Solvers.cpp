//===--- Solvers.cpp - Conjugate gradients on BCSR matrices ---------------===//
//
// Preconditioned CG whose convergence is the true residual's, and forward
// substitution.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/Solvers.h"

#include "LaneSums.h"
#include "SimdKernels.h"

#include "llvm/Support/FormatVariadic.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

using namespace simit;

namespace {

/// The running sums of CG's vector passes (LaneSums.h).
constexpr int64_t kVectorLanes = 4;
using VectorSums = LaneSums<kVectorLanes>;

/// Dot products accumulate in double, also for float vectors.
template <typename T>
double dot(const std::vector<T> &u, const std::vector<T> &v) {
  VectorSums sums;
  inLanes<kVectorLanes>(static_cast<int64_t>(u.size()),
                        [&](int64_t i, int64_t l) {
                          sums.lane[l] += static_cast<double>(u[i]) * v[i];
                        });
  return sums.total();
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
/// row; computed in double, in `Block` (fixed 3x3 for points in space: no
/// allocation per block).
template <typename Block, typename T>
llvm::Expected<std::vector<T>>
inverseDiagonalBlocksAs(const SquareBCSRView<T> &a) {
  int64_t b = a.blockSize;
  std::vector<T> inverse(static_cast<size_t>(a.rows * b * b), T(0));
  Block block(b, b);
  for (int64_t r = 0; r < a.rows; ++r) {
    const int32_t *begin = a.colidx + a.rowptr[r];
    const int32_t *end = a.colidx + a.rowptr[r + 1];
    const int32_t *k = std::lower_bound(begin, end, r);
    block.setZero();
    if (k != end && *k == r)
      for (int64_t i = 0; i < b; ++i)
        for (int64_t j = 0; j < b; ++j)
          block(i, j) = a.values[((k - a.colidx) * b + i) * b + j];
    Eigen::FullPivLU<Block> lu(block);
    if (!lu.isInvertible())
      return llvm::createStringError(
          "block-Jacobi preconditioner: the diagonal block of block row " +
          llvm::Twine(r) + " is singular");
    Block blockInverse = lu.inverse();
    for (int64_t i = 0; i < b; ++i)
      for (int64_t j = 0; j < b; ++j)
        inverse[(r * b + i) * b + j] = static_cast<T>(blockInverse(i, j));
  }
  return inverse;
}

template <typename T>
llvm::Expected<std::vector<T>>
inverseDiagonalBlocks(const SquareBCSRView<T> &a) {
  if (a.blockSize == 3)
    return inverseDiagonalBlocksAs<Eigen::Matrix3d>(a);
  return inverseDiagonalBlocksAs<Eigen::MatrixXd>(a);
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
/// y = A x with blocks of `b` x `b`, and, when `dotWith` is given, returns
/// dotWith . y (summed in row order, in double) from the same pass. `b` is a
/// compile-time constant where the caller knows it: a block row's sums then
/// stay in registers and the block loops unroll.
template <int64_t StaticBlock, typename T>
double multiplyBlocks(const SquareBCSRView<T> &a, const T *__restrict x,
                      T *__restrict y, const T *__restrict dotWith) {
  constexpr int64_t kMaxStatic = StaticBlock ? StaticBlock : 1;
  int64_t b = StaticBlock ? StaticBlock : a.blockSize;
  double dot = 0;
  for (int64_t r = 0; r < a.rows; ++r) {
    T *yr = y + r * b;
    T local[kMaxStatic];
    T *sums = StaticBlock ? local : yr;
    std::fill(sums, sums + b, T(0));
    for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k) {
      const T *block = a.values + static_cast<int64_t>(k) * b * b;
      const T *xc = x + static_cast<int64_t>(a.colidx[k]) * b;
      for (int64_t i = 0; i < b; ++i) {
        T sum = 0;
        for (int64_t j = 0; j < b; ++j)
          sum += block[i * b + j] * xc[j];
        sums[i] += sum;
      }
    }
    if (StaticBlock)
      std::copy(sums, sums + b, yr);
    // The row's products are summed first, as in the vector kernel.
    if (dotWith) {
      double row = 0;
      for (int64_t i = 0; i < b; ++i)
        row += static_cast<double>(dotWith[r * b + i]) * yr[i];
      dot += row;
    }
  }
  return dot;
}

/// multiplyBlocks with the block size dispatched to a static one where it is
/// 1 or 3 (points in space); 3x3 blocks of doubles take the host's vector
/// unit where the runtime has a kernel for it (SimdKernels.h).
template <typename T>
double multiplyAndDot(const SquareBCSRView<T> &a, const T *x, T *y,
                      const T *dotWith) {
  switch (a.blockSize) {
  case 1:
    return multiplyBlocks<1>(a, x, y, dotWith);
  case 3:
    if constexpr (std::is_same_v<T, double>) {
      double dot = 0;
      if (simd::multiplyBlocks3(a.rows, a.rowptr, a.colidx, a.values, x, y,
                                dotWith, &dot))
        return dot;
    }
    return multiplyBlocks<3>(a, x, y, dotWith);
  default:
    return multiplyBlocks<0>(a, x, y, dotWith);
  }
}
} // namespace

template <typename T>
void simit::multiply(const SquareBCSRView<T> &a, const T *x, T *y) {
  multiplyAndDot<T>(a, x, y, nullptr);
}

const std::vector<int32_t> &BlockMirrors::of(int64_t rows,
                                             const int32_t *rowptrIn,
                                             const int32_t *colidxIn) {
  int32_t blocks = rowptrIn[rows];
  if (static_cast<int64_t>(rowptr.size()) == rows + 1 &&
      static_cast<int64_t>(colidx.size()) == blocks &&
      std::equal(rowptr.begin(), rowptr.end(), rowptrIn) &&
      std::equal(colidx.begin(), colidx.end(), colidxIn))
    return mirrors;
  rowptr.assign(rowptrIn, rowptrIn + rows + 1);
  colidx.assign(colidxIn, colidxIn + blocks);
  mirrors.assign(static_cast<size_t>(blocks), -1);
  // Rows are visited in increasing order and each row's columns are sorted,
  // so the mirror of (r, c) is at or after where row c's search stopped
  // for the rows before r: one cursor per row, moving forward only (a
  // binary search per block was dominated by mispredicted branches).
  std::vector<int32_t> cursor(rowptr.begin(), rowptr.end() - 1);
  for (int64_t r = 0; r < rows; ++r)
    for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k) {
      int32_t c = colidx[k];
      int32_t &at = cursor[c];
      while (at < rowptr[c + 1] && colidx[at] < r)
        ++at;
      if (at < rowptr[c + 1] && colidx[at] == r)
        mirrors[k] = at;
    }
  return mirrors;
}

namespace {
/// A's largest magnitude, and the largest difference between a block and
/// its mirror's transpose (zero where it has none), in one pass. A block
/// below the diagonal with a mirror was compared from above. `StaticBlock`
/// as in multiplyBlocks; with it, each position in the block has running
/// maxima of its own, so that the comparisons do not wait on each other.
template <int64_t StaticBlock, typename T>
std::pair<double, double> asymmetry(const SquareBCSRView<T> &a,
                                    const std::vector<int32_t> &mirrors) {
  int64_t b = StaticBlock ? StaticBlock : a.blockSize, bb = b * b;
  constexpr int64_t kSlots = StaticBlock ? StaticBlock * StaticBlock : 1;
  auto slot = [](int64_t i) { return StaticBlock ? i : 0; };
  double largest[kSlots] = {}, worst[kSlots] = {};
  for (int64_t r = 0; r < a.rows; ++r)
    for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k) {
      const T *rc = a.values + k * bb;
      for (int64_t i = 0; i < bb; ++i)
        largest[slot(i)] =
            std::max(largest[slot(i)], std::abs(static_cast<double>(rc[i])));
      int32_t mirror = mirrors[k];
      if (a.colidx[k] < r && mirror >= 0)
        continue;
      const T *cr = mirror >= 0 ? a.values + mirror * bb : nullptr;
      for (int64_t i = 0; i < b; ++i)
        for (int64_t j = 0; j < b; ++j) {
          double other = cr ? cr[j * b + i] : 0.0;
          worst[slot(i * b + j)] =
              std::max(worst[slot(i * b + j)], std::abs(rc[i * b + j] - other));
        }
    }
  return {*std::max_element(largest, largest + kSlots),
          *std::max_element(worst, worst + kSlots)};
}
} // namespace

template <typename T>
bool simit::isSymmetric(const SquareBCSRView<T> &a, double relativeTolerance,
                        BlockMirrors &mirrorMap) {
  const std::vector<int32_t> &mirrors =
      mirrorMap.of(a.rows, a.rowptr, a.colidx);
  auto [largest, worst] =
      a.blockSize == 3 ? asymmetry<3>(a, mirrors) : asymmetry<0>(a, mirrors);
  return worst <= relativeTolerance * largest;
}

template <typename T>
bool simit::isSymmetric(const SquareBCSRView<T> &a, double relativeTolerance) {
  BlockMirrors mirrors;
  return isSymmetric(a, relativeTolerance, mirrors);
}

namespace {
/// out = b - A x, returning its r.r.
template <typename T>
double trueResidual(const SquareBCSRView<T> &a, const T *b, const T *x,
                    std::vector<T> &out) {
  multiply(a, x, out.data());
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = b[i] - out[i];
  return dot(out, out);
}

/// The sums of one pass of CG over its vectors.
struct ResidualDots {
  double rr = 0, rz = 0;
};

/// x += alpha dir and r -= alpha ad, element i; adds r_i^2 to `rr`.
template <typename T>
inline void updateElement(int64_t i, T alpha, const T *__restrict dir,
                          const T *__restrict ad, T *__restrict x,
                          T *__restrict r, double &rr) {
  x[i] += alpha * dir[i];
  r[i] -= alpha * ad[i];
  rr += static_cast<double>(r[i]) * r[i];
}

/// With `Update`, x += alpha dir and r -= alpha ad; then z = D r for D
/// block diagonal (`rows` inverse blocks of `b` x `b`, row-major, one after
/// the other), block row by block row. `StaticBlock` as in multiplyBlocks.
/// The sums are local so that no store through x, r or z can touch them.
template <bool Update, int64_t StaticBlock, typename T>
ResidualDots blockJacobiPass(int64_t rows, int64_t blockSize, T alpha,
                             const T *__restrict dir, const T *__restrict ad,
                             const T *__restrict inverse, T *__restrict x,
                             T *__restrict r, T *__restrict z) {
  int64_t b = StaticBlock ? StaticBlock : blockSize;
  VectorSums rr, rz;
  inLanes<kVectorLanes>(rows, [&](int64_t row, int64_t l) {
    int64_t first = row * b;
    if (Update)
      for (int64_t i = first; i < first + b; ++i)
        updateElement(i, alpha, dir, ad, x, r, rr.lane[l]);
    // r.z from the sums in registers: reading z back just after its
    // scalar stores stalled on store forwarding.
    const T *d = inverse + first * b;
    for (int64_t i = 0; i < b; ++i) {
      T sum = 0;
      for (int64_t j = 0; j < b; ++j)
        sum += d[i * b + j] * r[first + j];
      z[first + i] = sum;
      rz.lane[l] += static_cast<double>(r[first + i]) * sum;
    }
  });
  return {rr.total(), rz.total()};
}

/// The same for Jacobi (z = D r, D diagonal), or, without `inverse`, for
/// no preconditioner (z is r: r.z = r.r).
template <bool Update, typename T>
ResidualDots diagonalPass(int64_t n, T alpha, const T *__restrict dir,
                          const T *__restrict ad, const T *__restrict inverse,
                          T *__restrict x, T *__restrict r, T *__restrict z) {
  VectorSums rr, rz;
  inLanes<kVectorLanes>(n, [&](int64_t i, int64_t l) {
    if (Update)
      updateElement(i, alpha, dir, ad, x, r, rr.lane[l]);
    if (inverse) {
      z[i] = inverse[i] * r[i];
      rz.lane[l] += static_cast<double>(r[i]) * z[i];
    }
  });
  return {rr.total(), inverse ? rz.total() : rr.total()};
}

/// The preconditioned residual z = M^-1 r of CG, and the update of x and r
/// fused with it: each is one pass over the vectors.
template <typename T> class PreconditionedResidual {
public:
  PreconditionedResidual(const SquareBCSRView<T> &a,
                         const SolverOptions &options, std::vector<T> inverse)
      : n(a.size()), rows(a.rows), b(a.blockSize),
        kind(options.preconditioner), apply(options.apply),
        inverse(std::move(inverse)),
        z(kind == Preconditioner::None ? 0 : static_cast<size_t>(n)) {}

  /// z = M^-1 r (r itself without a preconditioner); returns r.z.
  llvm::Expected<double> precondition(std::vector<T> &r) {
    if (kind == Preconditioner::None)
      return dot(r, r);
    if (kind == Preconditioner::Operator)
      return applyOperator(r);
    return pass<false>(T(0), nullptr, nullptr, nullptr, r).rz;
  }

  /// x += alpha dir, r -= alpha ad, then as precondition; returns r.r and
  /// r.z.
  llvm::Expected<ResidualDots> update(T alpha, const std::vector<T> &dir,
                                      const std::vector<T> &ad, T *x,
                                      std::vector<T> &r) {
    ResidualDots dots = pass<true>(alpha, dir.data(), ad.data(), x, r);
    if (kind == Preconditioner::Operator) {
      llvm::Expected<double> rz = applyOperator(r);
      if (!rz)
        return rz.takeError();
      dots.rz = *rz;
    }
    return dots;
  }

  /// The preconditioned residual of the last call.
  const std::vector<T> &residual(const std::vector<T> &r) const {
    return kind == Preconditioner::None ? r : z;
  }

private:
  template <bool Update>
  ResidualDots pass(T alpha, const T *dir, const T *ad, T *x,
                    std::vector<T> &r) {
    switch (kind) {
    case Preconditioner::BlockJacobi:
      if (b == 3)
        return blockJacobiPass<Update, 3>(rows, b, alpha, dir, ad,
                                          inverse.data(), x, r.data(),
                                          z.data());
      return blockJacobiPass<Update, 0>(rows, b, alpha, dir, ad,
                                        inverse.data(), x, r.data(), z.data());
    case Preconditioner::Jacobi:
      return diagonalPass<Update>(n, alpha, dir, ad, inverse.data(), x,
                                  r.data(), z.data());
    case Preconditioner::None:
    case Preconditioner::Operator:
      // The operator runs after the pass.
      return diagonalPass<Update, T>(n, alpha, dir, ad, nullptr, x, r.data(),
                                     nullptr);
    }
    return {};
  }

  llvm::Expected<double> applyOperator(const std::vector<T> &r) {
    if constexpr (std::is_same_v<T, double>) {
      if (llvm::Error err = apply(r.data(), z.data()))
        return std::move(err);
    } else {
      wideResidual.assign(r.begin(), r.end());
      wideZ.resize(static_cast<size_t>(n));
      if (llvm::Error err = apply(wideResidual.data(), wideZ.data()))
        return std::move(err);
      std::transform(wideZ.begin(), wideZ.end(), z.begin(),
                     [](double value) { return static_cast<T>(value); });
    }
    return dot(r, z);
  }

  int64_t n, rows, b;
  Preconditioner kind;
  const PreconditionerOperator &apply;
  std::vector<T> inverse, z;
  /// Operator on float vectors: r and z in double.
  std::vector<double> wideResidual, wideZ;
};
} // namespace

template <typename T>
llvm::Expected<SolverResult>
simit::conjugateGradient(const SquareBCSRView<T> &a, const T *bIn, T *x,
                         const SolverOptions &options) {
  size_t n = static_cast<size_t>(a.size());
  // Diagonal (Jacobi) or block diagonal (block-Jacobi) inverse.
  std::vector<T> inverse;
  if (options.preconditioner == Preconditioner::Jacobi ||
      options.preconditioner == Preconditioner::BlockJacobi) {
    auto d = options.preconditioner == Preconditioner::Jacobi
                 ? inverseDiagonal(a)
                 : inverseDiagonalBlocks(a);
    if (!d)
      return d.takeError();
    inverse = std::move(*d);
  }
  PreconditionedResidual<T> preconditioned(a, options, std::move(inverse));

  std::vector<T> r(n), dir(n), ad(n);
  SolverResult result;
  result.residualNormSquared = trueResidual(a, bIn, x, r);
  // Whether r is b - A x computed anew rather than updated.
  bool exact = true;
  double rz = 0;
  auto restart = [&]() -> llvm::Error {
    llvm::Expected<double> next = preconditioned.precondition(r);
    if (!next)
      return next.takeError();
    rz = *next;
    dir = preconditioned.residual(r);
    return llvm::Error::success();
  };
  if (llvm::Error err = restart())
    return std::move(err);
  while (true) {
    if (result.residualNormSquared <= options.tolerance) {
      if (exact)
        break;
      result.residualNormSquared = trueResidual(a, bIn, x, r);
      exact = true;
      if (result.residualNormSquared <= options.tolerance)
        break;
      if (llvm::Error err = restart())
        return std::move(err);
    }
    if (result.iterations >= options.maxIterations)
      break;
    double curvature = multiplyAndDot(a, dir.data(), ad.data(), dir.data());
    if (!(curvature > 0))
      return llvm::createStringError(
          "conjugate gradients: p.Ap = " + llvm::formatv("{0:e2}", curvature) +
          " at iteration " + llvm::Twine(result.iterations) +
          "; the matrix is not positive definite");
    T alpha = static_cast<T>(rz / curvature);
    llvm::Expected<ResidualDots> dots =
        preconditioned.update(alpha, dir, ad, x, r);
    if (!dots)
      return dots.takeError();
    T beta = static_cast<T>(dots->rz / rz);
    rz = dots->rz;
    const std::vector<T> &z = preconditioned.residual(r);
    for (size_t i = 0; i < n; ++i)
      dir[i] = z[i] + beta * dir[i];
    ++result.iterations;
    result.residualNormSquared = dots->rr;
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
  template bool simit::isSymmetric(const SquareBCSRView<T> &, double,          \
                                   BlockMirrors &);                            \
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
