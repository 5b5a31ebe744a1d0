//===--- Factorisations.cpp - chol, lu and their solves -------------------===//
//
// Dense factorisations of small local matrices (Eigen) and sparse ones of
// system matrices through the run's SolveSession, behind opaque handles.
//
//===----------------------------------------------------------------------===//

#include "BCSRArrays.h"
#include "RunState.h"

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/SolveSession.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <type_traits>
#include <unordered_set>

using simit::abi::abandonRun;
using simit::abi::bcsrView;
using simit::abi::fail;
using simit::abi::failRun;
using simit::abi::isContiguous;
using simit::abi::MemRefDescriptor;
using simit::abi::solver;

namespace {
using RowMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// A memref<?xf64> as an Eigen vector (any stride).
Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<>>
asVector(MemRefDescriptor<double, 1> *m) {
  return {m->data + m->offset, m->sizes[0],
          Eigen::InnerStride<>(m->strides[0])};
}

/// A row-major rows x cols matrix held in a memref<?xf64>, or none (the
/// failure recorded) when the sizes differ.
std::optional<RowMatrix> asMatrix(MemRefDescriptor<double, 1> *m, int64_t rows,
                                  int64_t cols, const char *where) {
  if (rows < 0 || cols < 0 || m->sizes[0] != rows * cols) {
    fail(where, "operand size does not match its shape");
    return std::nullopt;
  }
  RowMatrix result(rows, cols);
  auto flat = asVector(m);
  for (int64_t i = 0; i < rows; ++i)
    for (int64_t j = 0; j < cols; ++j)
      result(i, j) = flat[i * cols + j];
  return result;
}

bool storeMatrix(const RowMatrix &value, MemRefDescriptor<double, 1> *m,
                 const char *where) {
  if (m->sizes[0] != value.size())
    return fail(where, "result size does not match");
  auto flat = asVector(m);
  for (int64_t i = 0; i < value.rows(); ++i)
    for (int64_t j = 0; j < value.cols(); ++j)
      flat[i * value.cols() + j] = value(i, j);
  return true;
}

/// A factorisation handle: lufree/cholfree delete dense and sparse ones
/// alike through the virtual destructor, and the solves check that a
/// handle is of their kind.
struct Factorisation {
  virtual ~Factorisation() = default;
};
template <typename Solver> struct Factor : Factorisation { Solver solver; };
using LU = Eigen::PartialPivLU<Eigen::MatrixXd>;
using LLT = Eigen::LLT<Eigen::MatrixXd>;
/// chol/lu of a system matrix: a factorisation the program's SolveSession
/// made (and may share with its cache and with `\`).
struct SystemFactor : Factorisation {
  simit::FactorKind kind;
  /// The scalar unknowns.
  int64_t factorSize;
  std::shared_ptr<const simit::SparseFactorisation> factor;
};

/// The handles made and not yet freed: a freed or foreign handle is an
/// error, not a read of freed memory.
std::mutex liveMutex;
std::unordered_set<const Factorisation *> live;

void *keep(Factorisation *factor) {
  std::lock_guard<std::mutex> lock(liveMutex);
  live.insert(factor);
  return static_cast<void *>(factor);
}

/// The factorisation behind `handle`, or null (the failure recorded) when
/// it is none the program holds.
Factorisation *held(void *handle, const char *where) {
  auto *factor = static_cast<Factorisation *>(handle);
  {
    std::lock_guard<std::mutex> lock(liveMutex);
    if (factor && live.count(factor))
      return factor;
  }
  fail(where, handle ? "the factorisation was freed (lufree/cholfree)"
                     : "no factorisation (a failed lu or chol)");
  return nullptr;
}

template <typename Solver>
Solver *solverOf(void *handle, const char *where, const char *kind) {
  Factorisation *factor = held(handle, where);
  if (!factor)
    return nullptr;
  auto *dense = dynamic_cast<Factor<Solver> *>(factor);
  if (!dense)
    fail(where, llvm::Twine("the handle is not ") + kind);
  return dense ? &dense->solver : nullptr;
}

/// Solves with the dense factorisation `Solver` of `handle` for a
/// right-hand side of `cols` columns; on a failure (recorded) every
/// component of x is NaN, which a parallel region keeps until it ends.
template <typename Solver>
bool denseSolve(void *handle, MemRefDescriptor<double, 1> *b,
                MemRefDescriptor<double, 1> *x, int64_t cols, const char *where,
                const char *kind) {
  Solver *factor = solverOf<Solver>(handle, where, kind);
  std::optional<RowMatrix> rhs =
      factor ? asMatrix(b, factor->rows(), cols, where) : std::nullopt;
  if (rhs &&
      storeMatrix(RowMatrix(factor->solve(Eigen::MatrixXd(*rhs))), x, where))
    return true;
  asVector(x).setConstant(std::numeric_limits<double>::quiet_NaN());
  return false;
}

/// lu or chol of a dense n x n matrix into `handle`, or false (recorded).
template <typename Solver>
bool denseFactorise(MemRefDescriptor<double, 1> *a, int64_t n,
                    const char *where, void *&handle) {
  std::optional<RowMatrix> matrix = asMatrix(a, n, n, where);
  if (!matrix)
    return false;
  auto factor = std::make_unique<Factor<Solver>>();
  factor->solver.compute(Eigen::MatrixXd(*matrix));
  // Eigen's LLT reads the lower triangle and stops at a pivot <= 0; its
  // partial-pivoting LU finishes, with a zero pivot where A is singular.
  if constexpr (std::is_same_v<Solver, LLT>) {
    if (factor->solver.info() != Eigen::Success)
      return fail(where, "the matrix is not positive definite");
  } else {
    auto pivots = factor->solver.matrixLU().diagonal();
    for (Eigen::Index i = 0; i < pivots.size(); ++i)
      if (pivots[i] == 0.0 || !std::isfinite(pivots[i]))
        return fail(where, "the matrix is singular (pivot " +
                               llvm::Twine(static_cast<int64_t>(i)) +
                               " is zero)");
  }
  handle = keep(factor.release());
  return true;
}

/// lufree and cholfree, or false (recorded) for a handle the program does
/// not hold (freed twice).
bool freeFactorisation(void *handle, const char *where) {
  Factorisation *factor = held(handle, where);
  if (!factor)
    return false;
  {
    std::lock_guard<std::mutex> lock(liveMutex);
    live.erase(factor);
  }
  delete factor;
  return true;
}

/// chol/lu of a system matrix into `handle`, or false with runFailure set.
bool factoriseSystem(simit::FactorKind kind,
                     MemRefDescriptor<int32_t, 1> *rowptr,
                     MemRefDescriptor<int32_t, 1> *colidx,
                     MemRefDescriptor<double, 3> *values, const char *where,
                     void *&handle) {
  simit::SquareBCSRView<double> view;
  if (!bcsrView(rowptr, colidx, values, where, view))
    return false;
  auto factor = solver().factorise(kind, view, where ? where : "factorise");
  if (!factor)
    return fail(where, llvm::toString(factor.takeError()));
  auto *held = new SystemFactor;
  held->kind = kind;
  held->factorSize = view.size();
  held->factor = std::move(*factor);
  handle = keep(held);
  return true;
}

/// lltsolve/lusolve of system vectors with a chol/lu handle, or false with
/// runFailure set.
bool solveSystem(void *handle, bool lu, MemRefDescriptor<double, 2> *b,
                 MemRefDescriptor<double, 2> *x, const char *where) {
  Factorisation *factor = held(handle, where);
  if (!factor)
    return false;
  auto *system = dynamic_cast<SystemFactor *>(factor);
  if (!system || (system->kind == simit::FactorKind::LU) != lu)
    return fail(where, lu ? "the handle is not a sparse LU factorisation"
                          : "the handle is not a sparse Cholesky "
                            "factorisation");
  if (!isContiguous(*b) || !isContiguous(*x) ||
      b->sizes[0] * b->sizes[1] != system->factorSize ||
      x->sizes[0] * x->sizes[1] != system->factorSize)
    return fail(where, "vector size does not match the matrix");
  auto solved =
      solver().solveWith(*system->factor, b->data + b->offset,
                         x->data + x->offset, where ? where : "solve");
  return solved ? true : fail(where, llvm::toString(solved.takeError()));
}

} // namespace

extern "C" void *_mlir_ciface_simit_rt_lu(MemRefDescriptor<double, 1> *a,
                                          int64_t n, const char *where) {
  void *handle = nullptr;
  if (!denseFactorise<LU>(a, n, where, handle))
    failRun();
  return handle;
}

extern "C" void *_mlir_ciface_simit_rt_chol(MemRefDescriptor<double, 1> *a,
                                            int64_t n, const char *where) {
  void *handle = nullptr;
  if (!denseFactorise<LLT>(a, n, where, handle))
    failRun();
  return handle;
}

extern "C" void *_mlir_ciface_simit_rt_lu_bcsr(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<double, 3> *values, const char *where) {
  void *handle = nullptr;
  if (!factoriseSystem(simit::FactorKind::LU, rowptr, colidx, values, where,
                       handle))
    abandonRun();
  return handle;
}

extern "C" void *_mlir_ciface_simit_rt_chol_bcsr(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<double, 3> *values, const char *where) {
  void *handle = nullptr;
  if (!factoriseSystem(simit::FactorKind::Cholesky, rowptr, colidx, values,
                       where, handle))
    abandonRun();
  return handle;
}

extern "C" void
_mlir_ciface_simit_rt_lusolve_bcsr(void *handle, MemRefDescriptor<double, 2> *b,
                                   MemRefDescriptor<double, 2> *x,
                                   const char *where) {
  if (!solveSystem(handle, /*lu=*/true, b, x, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_lltsolve_bcsr(
    void *handle, MemRefDescriptor<double, 2> *b,
    MemRefDescriptor<double, 2> *x, const char *where) {
  if (!solveSystem(handle, /*lu=*/false, b, x, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_lusolve(void *handle,
                                              MemRefDescriptor<double, 1> *b,
                                              MemRefDescriptor<double, 1> *x,
                                              const char *where) {
  if (!denseSolve<LU>(handle, b, x, 1, where, "a dense LU factorisation"))
    failRun();
}

extern "C" void _mlir_ciface_simit_rt_lltsolve(void *handle,
                                               MemRefDescriptor<double, 1> *b,
                                               MemRefDescriptor<double, 1> *x,
                                               const char *where) {
  if (!denseSolve<LLT>(handle, b, x, 1, where,
                       "a dense Cholesky factorisation"))
    failRun();
}

extern "C" void _mlir_ciface_simit_rt_lumatsolve(void *handle,
                                                 MemRefDescriptor<double, 1> *b,
                                                 MemRefDescriptor<double, 1> *x,
                                                 int64_t cols,
                                                 const char *where) {
  if (!denseSolve<LU>(handle, b, x, cols, where, "a dense LU factorisation"))
    failRun();
}

extern "C" void
_mlir_ciface_simit_rt_lltmatsolve(void *handle, MemRefDescriptor<double, 1> *b,
                                  MemRefDescriptor<double, 1> *x, int64_t cols,
                                  const char *where) {
  if (!denseSolve<LLT>(handle, b, x, cols, where,
                       "a dense Cholesky factorisation"))
    failRun();
}

extern "C" void simit_rt_lufree(void *handle, const char *where) {
  if (!freeFactorisation(handle, where))
    failRun();
}

extern "C" void simit_rt_cholfree(void *handle, const char *where) {
  if (!freeFactorisation(handle, where))
    failRun();
}

extern "C" void _mlir_ciface_simit_rt_triangularSolve(
    MemRefDescriptor<double, 1> *a, MemRefDescriptor<double, 1> *b,
    MemRefDescriptor<double, 1> *x, int64_t n, const char *where) {
  bool solved = false;
  {
    std::optional<RowMatrix> matrix = asMatrix(a, n, n, where);
    std::optional<RowMatrix> rhs =
        matrix ? asMatrix(b, n, 1, where) : std::nullopt;
    solved =
        rhs && storeMatrix(matrix->triangularView<Eigen::Lower>().solve(*rhs),
                           x, where);
  }
  if (!solved)
    failRun();
}
