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

#include "llvm/Support/ErrorHandling.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/LU>

#include <memory>

using simit::abi::abandonRun;
using simit::abi::bcsrView;
using simit::abi::fail;
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

/// A row-major rows x cols matrix held in a memref<?xf64>.
RowMatrix asMatrix(MemRefDescriptor<double, 1> *m, int64_t rows, int64_t cols,
                   const char *who) {
  if (rows < 0 || cols < 0 || m->sizes[0] != rows * cols)
    llvm::report_fatal_error(llvm::Twine(who) +
                             ": operand size does not match its shape");
  RowMatrix result(rows, cols);
  auto flat = asVector(m);
  for (int64_t i = 0; i < rows; ++i)
    for (int64_t j = 0; j < cols; ++j)
      result(i, j) = flat[i * cols + j];
  return result;
}

void storeMatrix(const RowMatrix &value, MemRefDescriptor<double, 1> *m,
                 const char *who) {
  if (m->sizes[0] != value.size())
    llvm::report_fatal_error(llvm::Twine(who) + ": result size does not match");
  auto flat = asVector(m);
  for (int64_t i = 0; i < value.rows(); ++i)
    for (int64_t j = 0; j < value.cols(); ++j)
      flat[i * value.cols() + j] = value(i, j);
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

template <typename Solver>
Solver &solverOf(void *handle, const char *who, const char *kind) {
  if (!handle)
    llvm::report_fatal_error(llvm::Twine(who) + ": null factorisation");
  auto *factor =
      dynamic_cast<Factor<Solver> *>(static_cast<Factorisation *>(handle));
  if (!factor)
    llvm::report_fatal_error(llvm::Twine(who) + ": the handle is not " + kind);
  return factor->solver;
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
  handle = static_cast<Factorisation *>(held);
  return true;
}

/// lltsolve/lusolve of system vectors with a chol/lu handle, or false with
/// runFailure set.
bool solveSystem(void *handle, bool lu, MemRefDescriptor<double, 2> *b,
                 MemRefDescriptor<double, 2> *x, const char *where) {
  auto *held =
      handle
          ? dynamic_cast<SystemFactor *>(static_cast<Factorisation *>(handle))
          : nullptr;
  if (!held || (held->kind == simit::FactorKind::LU) != lu)
    return fail(where, lu ? "the handle is not a sparse LU factorisation"
                          : "the handle is not a sparse Cholesky "
                            "factorisation");
  if (!isContiguous(*b) || !isContiguous(*x) ||
      b->sizes[0] * b->sizes[1] != held->factorSize ||
      x->sizes[0] * x->sizes[1] != held->factorSize)
    return fail(where, "vector size does not match the matrix");
  auto report =
      solver().solveWith(*held->factor, b->data + b->offset,
                         x->data + x->offset, where ? where : "solve");
  return report ? true : fail(where, llvm::toString(report.takeError()));
}

} // namespace

extern "C" void *_mlir_ciface_simit_rt_lu(MemRefDescriptor<double, 1> *a,
                                          int64_t n) {
  auto *factor = new Factor<LU>;
  factor->solver.compute(Eigen::MatrixXd(asMatrix(a, n, n, "lu")));
  return static_cast<Factorisation *>(factor);
}

extern "C" void *_mlir_ciface_simit_rt_chol(MemRefDescriptor<double, 1> *a,
                                            int64_t n) {
  auto *factor = new Factor<LLT>;
  factor->solver.compute(Eigen::MatrixXd(asMatrix(a, n, n, "chol")));
  return static_cast<Factorisation *>(factor);
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
                                              MemRefDescriptor<double, 1> *x) {
  auto &lu = solverOf<LU>(handle, "lusolve", "a dense LU factorisation");
  RowMatrix rhs = asMatrix(b, lu.rows(), 1, "lusolve");
  storeMatrix(RowMatrix(lu.solve(Eigen::MatrixXd(rhs))), x, "lusolve");
}

extern "C" void _mlir_ciface_simit_rt_lltsolve(void *handle,
                                               MemRefDescriptor<double, 1> *b,
                                               MemRefDescriptor<double, 1> *x) {
  auto &llt =
      solverOf<LLT>(handle, "lltsolve", "a dense Cholesky factorisation");
  RowMatrix rhs = asMatrix(b, llt.rows(), 1, "lltsolve");
  storeMatrix(RowMatrix(llt.solve(Eigen::MatrixXd(rhs))), x, "lltsolve");
}

extern "C" void _mlir_ciface_simit_rt_lumatsolve(void *handle,
                                                 MemRefDescriptor<double, 1> *b,
                                                 MemRefDescriptor<double, 1> *x,
                                                 int64_t cols) {
  auto &lu = solverOf<LU>(handle, "lumatsolve", "a dense LU factorisation");
  RowMatrix rhs = asMatrix(b, lu.rows(), cols, "lumatsolve");
  storeMatrix(RowMatrix(lu.solve(Eigen::MatrixXd(rhs))), x, "lumatsolve");
}

extern "C" void
_mlir_ciface_simit_rt_lltmatsolve(void *handle, MemRefDescriptor<double, 1> *b,
                                  MemRefDescriptor<double, 1> *x,
                                  int64_t cols) {
  auto &llt =
      solverOf<LLT>(handle, "lltmatsolve", "a dense Cholesky factorisation");
  RowMatrix rhs = asMatrix(b, llt.rows(), cols, "lltmatsolve");
  storeMatrix(RowMatrix(llt.solve(Eigen::MatrixXd(rhs))), x, "lltmatsolve");
}

extern "C" void simit_rt_lufree(void *handle) {
  delete static_cast<Factorisation *>(handle);
}

extern "C" void simit_rt_cholfree(void *handle) {
  delete static_cast<Factorisation *>(handle);
}

extern "C" void _mlir_ciface_simit_rt_triangularSolve(
    MemRefDescriptor<double, 1> *a, MemRefDescriptor<double, 1> *b,
    MemRefDescriptor<double, 1> *x, int64_t n) {
  RowMatrix matrix = asMatrix(a, n, n, "triangularSolve");
  RowMatrix rhs = asMatrix(b, n, 1, "triangularSolve");
  RowMatrix solution = matrix.triangularView<Eigen::Lower>().solve(rhs);
  storeMatrix(solution, x, "triangularSolve");
}
