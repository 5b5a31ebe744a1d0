//===--- SystemSolves.cpp - Solves of system matrices ---------------------===//
//
// x = A \ b of the language, its Sherman-Morrison and Woodbury rewrites,
// triangularSolve and solves of block diagonal matrices.
//
//===----------------------------------------------------------------------===//

#include "BCSRArrays.h"
#include "RunState.h"

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/ArrayRef.h"

#include <vector>

using simit::abi::abandonRun;
using simit::abi::bcsrView;
using simit::abi::fail;
using simit::abi::isContiguous;
using simit::abi::MemRefDescriptor;
using simit::abi::solver;

namespace {
/// A solve of the runtime on a square BCSR matrix, x = solve(A, b); null
/// for `\` (the SolveSession).
template <typename T>
using BCSRSolve = llvm::Error (*)(const simit::SquareBCSRView<T> &, const T *,
                                  T *);

/// x = solve(A, b) into x, or false with runFailure set; `where` names the
/// statement.
template <typename T>
bool solveInto(const simit::SquareBCSRView<T> &a, MemRefDescriptor<T, 2> *b,
               MemRefDescriptor<T, 2> *x, const char *where,
               BCSRSolve<T> solve) {
  if (!isContiguous(*b) || !isContiguous(*x) ||
      b->sizes[0] * b->sizes[1] != a.size() ||
      x->sizes[0] * x->sizes[1] != a.size())
    return fail(where, "vector size does not match the matrix");
  T *result = x->data + x->offset;
  if (!solve) {
    // `\`: the program's SolveSession, whose report goes to its statistics.
    auto report =
        solver().solve(a, b->data + b->offset, result, where ? where : "solve");
    return report ? true : fail(where, llvm::toString(report.takeError()));
  }
  if (llvm::Error err = solve(a, b->data + b->offset, result))
    return fail(where, llvm::toString(std::move(err)));
  return true;
}

template <typename T>
void solveBCSR(MemRefDescriptor<int32_t, 1> *rowptr,
               MemRefDescriptor<int32_t, 1> *colidx,
               MemRefDescriptor<T, 3> *values, MemRefDescriptor<T, 2> *b,
               MemRefDescriptor<T, 2> *x, const char *where,
               BCSRSolve<T> solve) {
  simit::SquareBCSRView<T> view;
  if (!bcsrView(rowptr, colidx, values, where, view) ||
      !solveInto(view, b, x, where, solve))
    abandonRun();
}

/// The last step of the Sherman–Morrison rewrite of rank K into x, or false
/// with runFailure set. `vectors` are u_1..u_K, v_1..v_K, b, w_1..w_K, c,
/// x.
template <typename T, size_t K>
bool lowRankInto(MemRefDescriptor<int32_t, 1> *rowptr,
                 MemRefDescriptor<int32_t, 1> *colidx,
                 MemRefDescriptor<T, 3> *values,
                 MemRefDescriptor<T, 2> *const (&vectors)[3 * K + 3],
                 const char *where) {
  simit::SquareBCSRView<T> view;
  if (!bcsrView(rowptr, colidx, values, where, view))
    return false;
  T *data[3 * K + 3];
  for (size_t i = 0; i < 3 * K + 3; ++i) {
    if (!isContiguous(*vectors[i]) ||
        vectors[i]->sizes[0] * vectors[i]->sizes[1] != view.size())
      return fail(where, "vector size does not match the matrix");
    data[i] = vectors[i]->data + vectors[i]->offset;
  }
  llvm::ArrayRef<T *> all(data);
  const T *b = data[2 * K], *c = data[3 * K + 1];
  T *x = data[3 * K + 2];
  const char *statement = where ? where : "Sherman-Morrison";
  auto report = K == 1 ? solver().shermanMorrison(view, data[0], data[1], b,
                                                  data[3], c, x, statement)
                       : solver().woodbury<T>(
                             view, llvm::ArrayRef<const T *>(all.slice(0, K)),
                             llvm::ArrayRef<const T *>(all.slice(K, K)), b,
                             llvm::ArrayRef<const T *>(all.slice(2 * K + 1, K)),
                             c, x, statement);
  return report ? true : fail(where, llvm::toString(report.takeError()));
}

/// A block diagonal matrix is the BCSR matrix of the identity pattern.
template <typename T>
bool solveDiagonalInto(MemRefDescriptor<T, 3> *values,
                       MemRefDescriptor<T, 2> *b, MemRefDescriptor<T, 2> *x,
                       const char *where) {
  int64_t rows = values->sizes[0];
  std::vector<int32_t> rowptr(rows + 1), colidx(rows);
  for (int64_t r = 0; r <= rows; ++r)
    rowptr[r] = static_cast<int32_t>(r);
  for (int64_t r = 0; r < rows; ++r)
    colidx[r] = static_cast<int32_t>(r);
  MemRefDescriptor<int32_t, 1> ptr{
      rowptr.data(), rowptr.data(), 0, {rows + 1}, {1}};
  MemRefDescriptor<int32_t, 1> idx{
      colidx.data(), colidx.data(), 0, {rows}, {1}};
  simit::SquareBCSRView<T> view;
  return bcsrView(&ptr, &idx, values, where, view) &&
         solveInto<T>(view, b, x, where, nullptr);
}

template <typename T>
void solveDiagonal(MemRefDescriptor<T, 3> *values, MemRefDescriptor<T, 2> *b,
                   MemRefDescriptor<T, 2> *x, const char *where) {
  if (!solveDiagonalInto(values, b, x, where))
    abandonRun();
}
} // namespace

extern "C" void _mlir_ciface_simit_rt_solve_bcsr(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<double, 3> *values, MemRefDescriptor<double, 2> *b,
    MemRefDescriptor<double, 2> *x, const char *where) {
  solveBCSR<double>(rowptr, colidx, values, b, x, where, nullptr);
}

extern "C" void _mlir_ciface_simit_rt_solve_bcsr_f32(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<float, 3> *values, MemRefDescriptor<float, 2> *b,
    MemRefDescriptor<float, 2> *x, const char *where) {
  solveBCSR<float>(rowptr, colidx, values, b, x, where, nullptr);
}

extern "C" void _mlir_ciface_simit_rt_sherman_morrison_bcsr(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<double, 3> *values, MemRefDescriptor<double, 2> *u,
    MemRefDescriptor<double, 2> *v, MemRefDescriptor<double, 2> *b,
    MemRefDescriptor<double, 2> *w, MemRefDescriptor<double, 2> *c,
    MemRefDescriptor<double, 2> *x, const char *where) {
  MemRefDescriptor<double, 2> *const vectors[6] = {u, v, b, w, c, x};
  if (!lowRankInto<double, 1>(rowptr, colidx, values, vectors, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_sherman_morrison_bcsr_f32(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<float, 3> *values, MemRefDescriptor<float, 2> *u,
    MemRefDescriptor<float, 2> *v, MemRefDescriptor<float, 2> *b,
    MemRefDescriptor<float, 2> *w, MemRefDescriptor<float, 2> *c,
    MemRefDescriptor<float, 2> *x, const char *where) {
  MemRefDescriptor<float, 2> *const vectors[6] = {u, v, b, w, c, x};
  if (!lowRankInto<float, 1>(rowptr, colidx, values, vectors, where))
    abandonRun();
}

// Ranks 2 to 4 (simit-sherman-morrison's Woodbury form): the same with
// u_1..u_k, v_1..v_k, b, w_1..w_k, c, x.
#define SIMIT_RT_WOODBURY(NAME, T, K, ...)                                     \
  extern "C" void NAME(MemRefDescriptor<int32_t, 1> *rowptr,                   \
                       MemRefDescriptor<int32_t, 1> *colidx,                   \
                       MemRefDescriptor<T, 3> *values, __VA_ARGS__,            \
                       const char *where) {                                    \
    MemRefDescriptor<T, 2> *const vectors[] = SIMIT_RT_WOODBURY_ARGS_##K;      \
    if (!lowRankInto<T, K>(rowptr, colidx, values, vectors, where))            \
      abandonRun();                                                            \
  }
#define SIMIT_RT_WOODBURY_ARGS_2                                               \
  { u1, u2, v1, v2, b, w1, w2, c, x }
#define SIMIT_RT_WOODBURY_ARGS_3                                               \
  { u1, u2, u3, v1, v2, v3, b, w1, w2, w3, c, x }
#define SIMIT_RT_WOODBURY_ARGS_4                                               \
  { u1, u2, u3, u4, v1, v2, v3, v4, b, w1, w2, w3, w4, c, x }
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury2_bcsr, double, 2,
                  SIMIT_RT_WOODBURY_PARAMS_2(SimitF64Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury3_bcsr, double, 3,
                  SIMIT_RT_WOODBURY_PARAMS_3(SimitF64Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury4_bcsr, double, 4,
                  SIMIT_RT_WOODBURY_PARAMS_4(SimitF64Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury2_bcsr_f32, float, 2,
                  SIMIT_RT_WOODBURY_PARAMS_2(SimitF32Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury3_bcsr_f32, float, 3,
                  SIMIT_RT_WOODBURY_PARAMS_3(SimitF32Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury4_bcsr_f32, float, 4,
                  SIMIT_RT_WOODBURY_PARAMS_4(SimitF32Vector))

extern "C" void _mlir_ciface_simit_rt_triangular_solve_bcsr(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<double, 3> *values, MemRefDescriptor<double, 2> *b,
    MemRefDescriptor<double, 2> *x, const char *where) {
  solveBCSR(rowptr, colidx, values, b, x, where,
            &simit::solveLowerTriangular<double>);
}

extern "C" void _mlir_ciface_simit_rt_triangular_solve_bcsr_f32(
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    MemRefDescriptor<float, 3> *values, MemRefDescriptor<float, 2> *b,
    MemRefDescriptor<float, 2> *x, const char *where) {
  solveBCSR(rowptr, colidx, values, b, x, where,
            &simit::solveLowerTriangular<float>);
}

extern "C" void _mlir_ciface_simit_rt_solve_diag(
    MemRefDescriptor<double, 3> *values, MemRefDescriptor<double, 2> *b,
    MemRefDescriptor<double, 2> *x, const char *where) {
  solveDiagonal(values, b, x, where);
}

extern "C" void _mlir_ciface_simit_rt_solve_diag_f32(
    MemRefDescriptor<float, 3> *values, MemRefDescriptor<float, 2> *b,
    MemRefDescriptor<float, 2> *x, const char *where) {
  solveDiagonal(values, b, x, where);
}
