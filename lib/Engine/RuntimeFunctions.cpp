//===--- RuntimeFunctions.cpp - Host functions of lowered Simit code ------===//

#include "simit/Engine/RuntimeFunctions.h"

#include "RuntimeSymbols.h"

#include "simit/Runtime/SolveSession.h"
#include "simit/Runtime/SparseProduct.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/InterleavedRange.h"
#include "llvm/Support/raw_ostream.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <csetjmp>
#include <cstdlib>
#include <cstring>

#include <vector>

// libomp's (omp.h is not among the installed headers of every system).
extern "C" int omp_get_level(void);

namespace {
/// Whether a memref's strides are the row-major strides of its sizes, so
/// its data can be walked as one flat array.
template <typename T, int N>
bool isContiguous(const StridedMemRefType<T, N> &m) {
  int64_t expected = 1;
  for (int d = N - 1; d >= 0; --d) {
    if (m.sizes[d] != 1 && m.strides[d] != expected)
      return false;
    expected *= m.sizes[d];
  }
  return true;
}

/// The run in progress on this thread, where simit_rt_fail returns to, and
/// the message of its failure.
thread_local std::jmp_buf *activeRun = nullptr;
/// The OpenMP nesting level at which that run began: deeper, its code is
/// inside one of its own parallel regions (a caller may run Simit functions
/// inside parallel regions of its own).
thread_local int activeRunLevel = 0;
thread_local std::string runFailure;

/// Ends the run in progress with the message recorded in runFailure. The
/// frames it unwinds are lowered code and the runtime function that failed,
/// which holds no object with a destructor when it calls this.
[[noreturn]] void abandonRun() {
  if (!activeRun)
    llvm::report_fatal_error(llvm::StringRef(runFailure));
  std::longjmp(*activeRun, 1);
}

/// The solver of the run in progress on this thread (its Program's), else
/// one of the process for lowered code run outside a Program.
thread_local simit::SolveSession *activeSolver = nullptr;

simit::SolveSession &solver() {
  if (activeSolver)
    return *activeSolver;
  static simit::SolveSession processSolver;
  return processSolver;
}

/// Records the failure of the statement `where` and returns false.
bool fail(const char *where, const llvm::Twine &message) {
  runFailure = (llvm::Twine(where ? where : "runtime") + ": " + message).str();
  return false;
}

/// A solve of the runtime on a square BCSR matrix, x = solve(A, b); null
/// for `\` (the SolveSession).
template <typename T>
using BCSRSolve = llvm::Error (*)(const simit::SquareBCSRView<T> &, const T *,
                                  T *);

/// x = solve(A, b) into x, or false with runFailure set; `where` names the
/// statement.
template <typename T>
bool solveInto(const simit::SquareBCSRView<T> &a,
               StridedMemRefType<T, 2> *b, StridedMemRefType<T, 2> *x,
               const char *where, BCSRSolve<T> solve) {
  if (!isContiguous(*b) || !isContiguous(*x) ||
      b->sizes[0] * b->sizes[1] != a.size() ||
      x->sizes[0] * x->sizes[1] != a.size())
    return fail(where, "vector size does not match the matrix");
  T *result = x->data + x->offset;
  if (!solve) {
    // `\`: the program's SolveSession, whose report goes to its statistics.
    auto report = solver().solve(a, b->data + b->offset, result,
                                 where ? where : "solve");
    return report ? true : fail(where, llvm::toString(report.takeError()));
  }
  if (llvm::Error err = solve(a, b->data + b->offset, result))
    return fail(where, llvm::toString(std::move(err)));
  return true;
}

/// The view of BCSR arrays with square blocks (values memref<?xBxBxT>).
template <typename T>
bool bcsrView(StridedMemRefType<int32_t, 1> *rowptr,
              StridedMemRefType<int32_t, 1> *colidx,
              StridedMemRefType<T, 3> *values, const char *where,
              simit::SquareBCSRView<T> &view) {
  if (!isContiguous(*rowptr) || !isContiguous(*colidx) ||
      !isContiguous(*values) || values->sizes[1] != values->sizes[2] ||
      rowptr->sizes[0] < 1)
    return fail(where, "malformed BCSR arrays of a square matrix");
  view.rows = rowptr->sizes[0] - 1;
  view.blockSize = values->sizes[1];
  view.rowptr = rowptr->data + rowptr->offset;
  view.colidx = colidx->data + colidx->offset;
  view.values = values->data + values->offset;
  return true;
}

template <typename T>
void solveBCSR(StridedMemRefType<int32_t, 1> *rowptr,
               StridedMemRefType<int32_t, 1> *colidx,
               StridedMemRefType<T, 3> *values, StridedMemRefType<T, 2> *b,
               StridedMemRefType<T, 2> *x, const char *where,
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
bool lowRankInto(StridedMemRefType<int32_t, 1> *rowptr,
                 StridedMemRefType<int32_t, 1> *colidx,
                 StridedMemRefType<T, 3> *values,
                 StridedMemRefType<T, 2> *const (&vectors)[3 * K + 3],
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
  auto report =
      K == 1 ? solver().shermanMorrison(view, data[0], data[1], b, data[3],
                                        c, x, statement)
             : solver().woodbury<T>(
                   view, llvm::ArrayRef<const T *>(all.slice(0, K)),
                   llvm::ArrayRef<const T *>(all.slice(K, K)), b,
                   llvm::ArrayRef<const T *>(all.slice(2 * K + 1, K)), c, x,
                   statement);
  return report ? true : fail(where, llvm::toString(report.takeError()));
}

/// A block diagonal matrix is the BCSR matrix of the identity pattern.
template <typename T>
bool solveDiagonalInto(StridedMemRefType<T, 3> *values,
                       StridedMemRefType<T, 2> *b, StridedMemRefType<T, 2> *x,
                       const char *where) {
  int64_t rows = values->sizes[0];
  std::vector<int32_t> rowptr(rows + 1), colidx(rows);
  for (int64_t r = 0; r <= rows; ++r)
    rowptr[r] = static_cast<int32_t>(r);
  for (int64_t r = 0; r < rows; ++r)
    colidx[r] = static_cast<int32_t>(r);
  StridedMemRefType<int32_t, 1> ptr{rowptr.data(), rowptr.data(), 0,
                                    {rows + 1}, {1}};
  StridedMemRefType<int32_t, 1> idx{colidx.data(), colidx.data(), 0,
                                    {rows}, {1}};
  simit::SquareBCSRView<T> view;
  return bcsrView(&ptr, &idx, values, where, view) &&
         solveInto<T>(view, b, x, where, nullptr);
}

template <typename T>
void solveDiagonal(StridedMemRefType<T, 3> *values, StridedMemRefType<T, 2> *b,
                   StridedMemRefType<T, 2> *x, const char *where) {
  if (!solveDiagonalInto(values, b, x, where))
    abandonRun();
}
/// The BlockMatrixView of lowered arrays: BCSR (layout 0) or block
/// diagonal (layout 1, index arrays unused).
template <typename T>
simit::BlockMatrixView<T> blockMatrix(int32_t layout,
                                      StridedMemRefType<int32_t, 1> *rowptr,
                                      StridedMemRefType<int32_t, 1> *colidx,
                                      StridedMemRefType<T, 3> *values) {
  simit::BlockMatrixView<T> view;
  view.blockRows = values->sizes[1];
  view.blockCols = values->sizes[2];
  view.values = values->data + values->offset;
  if (layout == 1) {
    view.rows = view.cols = values->sizes[0];
    return view;
  }
  view.rows = rowptr->sizes[0] - 1;
  view.rowptr = rowptr->data + rowptr->offset;
  view.colidx = colidx->data + colidx->offset;
  return view;
}

template <typename T>
bool multiplyMatrices(int32_t layoutA, StridedMemRefType<int32_t, 1> *rowptrA,
                      StridedMemRefType<int32_t, 1> *colidxA,
                      StridedMemRefType<T, 3> *a, int32_t layoutB,
                      StridedMemRefType<int32_t, 1> *rowptrB,
                      StridedMemRefType<int32_t, 1> *colidxB,
                      StridedMemRefType<T, 3> *b, int32_t layoutC,
                      StridedMemRefType<int32_t, 1> *rowptrC,
                      StridedMemRefType<int32_t, 1> *colidxC,
                      StridedMemRefType<T, 3> *c, int64_t cols,
                      const char *where) {
  for (auto *m : {rowptrA, colidxA, rowptrB, colidxB, rowptrC, colidxC})
    if (!isContiguous(*m))
      return fail(where, "index arrays must be contiguous");
  if (!isContiguous(*a) || !isContiguous(*b) || !isContiguous(*c))
    return fail(where, "value arrays must be contiguous");
  simit::BlockMatrixView<T> left = blockMatrix(layoutA, rowptrA, colidxA, a);
  simit::BlockMatrixView<T> right = blockMatrix(layoutB, rowptrB, colidxB, b);
  simit::BlockMatrixView<T> result =
      blockMatrix(layoutC, rowptrC, colidxC, c);
  left.cols = right.rows;
  right.cols = result.cols = cols;
  if (llvm::Error err = simit::multiplyInto(left, right, result))
    return fail(where, llvm::toString(std::move(err)));
  return true;
}
} // namespace

namespace {
/// A failure inside an OpenMP parallel region, raised when the region ends.
/// Of several, the least message is kept, so that which one is reported
/// does not depend on the threads' timing.
std::mutex parallelFailureMutex;
std::optional<std::string> parallelFailure;
} // namespace

extern "C" void simit_rt_fail(const char *message) {
  std::string text = message ? message : "the program failed";
  // Inside a parallel region of the run's code, on any of its threads (the
  // pool's threads run no run of their own).
  int level = omp_get_level();
  if (level > 0 && (!activeRun || level > activeRunLevel)) {
    std::lock_guard<std::mutex> lock(parallelFailureMutex);
    if (!parallelFailure || text < *parallelFailure)
      parallelFailure = std::move(text);
    return;
  }
  runFailure = std::move(text);
  abandonRun();
}

extern "C" void simit_rt_raise_parallel_failure() {
  std::optional<std::string> failure;
  {
    std::lock_guard<std::mutex> lock(parallelFailureMutex);
    failure.swap(parallelFailure);
  }
  if (failure) {
    runFailure = std::move(*failure);
    abandonRun();
  }
}

llvm::Error simit::runGuarded(void (*entry)(void **), void **args,
                              SolveSession *session) {
  std::jmp_buf buffer;
  std::jmp_buf *outer = activeRun;
  int outerLevel = activeRunLevel;
  SolveSession *outerSolver = activeSolver;
  activeRun = &buffer;
  activeRunLevel = omp_get_level();
  activeSolver = session;
  if (setjmp(buffer)) {
    activeRun = outer;
    activeRunLevel = outerLevel;
    activeSolver = outerSolver;
    return llvm::createStringError(runFailure);
  }
  entry(args);
  activeRun = outer;
  activeRunLevel = outerLevel;
  activeSolver = outerSolver;
  return llvm::Error::success();
}

extern "C" void _mlir_ciface_simit_rt_solve_bcsr(
    StridedMemRefType<int32_t, 1> *rowptr, StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<double, 3> *values, StridedMemRefType<double, 2> *b,
    StridedMemRefType<double, 2> *x, const char *where) {
  solveBCSR<double>(rowptr, colidx, values, b, x, where, nullptr);
}

extern "C" void _mlir_ciface_simit_rt_solve_bcsr_f32(
    StridedMemRefType<int32_t, 1> *rowptr, StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<float, 3> *values, StridedMemRefType<float, 2> *b,
    StridedMemRefType<float, 2> *x, const char *where) {
  solveBCSR<float>(rowptr, colidx, values, b, x, where, nullptr);
}

extern "C" void _mlir_ciface_simit_rt_sherman_morrison_bcsr(
    StridedMemRefType<int32_t, 1> *rowptr, StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<double, 3> *values, StridedMemRefType<double, 2> *u,
    StridedMemRefType<double, 2> *v, StridedMemRefType<double, 2> *b,
    StridedMemRefType<double, 2> *w, StridedMemRefType<double, 2> *c,
    StridedMemRefType<double, 2> *x, const char *where) {
  StridedMemRefType<double, 2> *const vectors[6] = {u, v, b, w, c, x};
  if (!lowRankInto<double, 1>(rowptr, colidx, values, vectors, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_sherman_morrison_bcsr_f32(
    StridedMemRefType<int32_t, 1> *rowptr, StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<float, 3> *values, StridedMemRefType<float, 2> *u,
    StridedMemRefType<float, 2> *v, StridedMemRefType<float, 2> *b,
    StridedMemRefType<float, 2> *w, StridedMemRefType<float, 2> *c,
    StridedMemRefType<float, 2> *x, const char *where) {
  StridedMemRefType<float, 2> *const vectors[6] = {u, v, b, w, c, x};
  if (!lowRankInto<float, 1>(rowptr, colidx, values, vectors, where))
    abandonRun();
}

// Ranks 2 to 4 (simit-sherman-morrison's Woodbury form): the same with
// u_1..u_k, v_1..v_k, b, w_1..w_k, c, x.
#define SIMIT_RT_WOODBURY(NAME, T, K, ...)                                     \
  extern "C" void NAME(StridedMemRefType<int32_t, 1> *rowptr,                  \
                       StridedMemRefType<int32_t, 1> *colidx,                  \
                       StridedMemRefType<T, 3> *values, __VA_ARGS__,           \
                       const char *where) {                                    \
    StridedMemRefType<T, 2> *const vectors[] = SIMIT_RT_WOODBURY_ARGS_##K;     \
    if (!lowRankInto<T, K>(rowptr, colidx, values, vectors, where))            \
      abandonRun();                                                            \
  }
#define SIMIT_RT_WOODBURY_ARGS_2 {u1, u2, v1, v2, b, w1, w2, c, x}
#define SIMIT_RT_WOODBURY_ARGS_3 {u1, u2, u3, v1, v2, v3, b, w1, w2, w3, c, x}
#define SIMIT_RT_WOODBURY_ARGS_4                                               \
  {u1, u2, u3, u4, v1, v2, v3, v4, b, w1, w2, w3, w4, c, x}
#define SIMIT_RT_WOODBURY_PARAMS_2(V)                                          \
  V u1, V u2, V v1, V v2, V b, V w1, V w2, V c, V x
#define SIMIT_RT_WOODBURY_PARAMS_3(V)                                          \
  V u1, V u2, V u3, V v1, V v2, V v3, V b, V w1, V w2, V w3, V c, V x
#define SIMIT_RT_WOODBURY_PARAMS_4(V)                                          \
  V u1, V u2, V u3, V u4, V v1, V v2, V v3, V v4, V b, V w1, V w2, V w3,    \
      V w4, V c, V x
using F64Vector = StridedMemRefType<double, 2> *;
using F32Vector = StridedMemRefType<float, 2> *;
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury2_bcsr, double, 2,
                  SIMIT_RT_WOODBURY_PARAMS_2(F64Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury3_bcsr, double, 3,
                  SIMIT_RT_WOODBURY_PARAMS_3(F64Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury4_bcsr, double, 4,
                  SIMIT_RT_WOODBURY_PARAMS_4(F64Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury2_bcsr_f32, float, 2,
                  SIMIT_RT_WOODBURY_PARAMS_2(F32Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury3_bcsr_f32, float, 3,
                  SIMIT_RT_WOODBURY_PARAMS_3(F32Vector))
SIMIT_RT_WOODBURY(_mlir_ciface_simit_rt_woodbury4_bcsr_f32, float, 4,
                  SIMIT_RT_WOODBURY_PARAMS_4(F32Vector))

extern "C" void _mlir_ciface_simit_rt_matmul_bcsr(
    int32_t layoutA, StridedMemRefType<int32_t, 1> *rowptrA,
    StridedMemRefType<int32_t, 1> *colidxA, StridedMemRefType<double, 3> *a,
    int32_t layoutB, StridedMemRefType<int32_t, 1> *rowptrB,
    StridedMemRefType<int32_t, 1> *colidxB, StridedMemRefType<double, 3> *b,
    int32_t layoutC, StridedMemRefType<int32_t, 1> *rowptrC,
    StridedMemRefType<int32_t, 1> *colidxC, StridedMemRefType<double, 3> *c,
    int64_t cols, const char *where) {
  if (!multiplyMatrices(layoutA, rowptrA, colidxA, a, layoutB, rowptrB,
                        colidxB, b, layoutC, rowptrC, colidxC, c, cols,
                        where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_matmul_bcsr_f32(
    int32_t layoutA, StridedMemRefType<int32_t, 1> *rowptrA,
    StridedMemRefType<int32_t, 1> *colidxA, StridedMemRefType<float, 3> *a,
    int32_t layoutB, StridedMemRefType<int32_t, 1> *rowptrB,
    StridedMemRefType<int32_t, 1> *colidxB, StridedMemRefType<float, 3> *b,
    int32_t layoutC, StridedMemRefType<int32_t, 1> *rowptrC,
    StridedMemRefType<int32_t, 1> *colidxC, StridedMemRefType<float, 3> *c,
    int64_t cols, const char *where) {
  if (!multiplyMatrices(layoutA, rowptrA, colidxA, a, layoutB, rowptrB,
                        colidxB, b, layoutC, rowptrC, colidxC, c, cols,
                        where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_triangular_solve_bcsr(
    StridedMemRefType<int32_t, 1> *rowptr, StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<double, 3> *values, StridedMemRefType<double, 2> *b,
    StridedMemRefType<double, 2> *x, const char *where) {
  solveBCSR(rowptr, colidx, values, b, x, where,
            &simit::solveLowerTriangular<double>);
}

extern "C" void _mlir_ciface_simit_rt_triangular_solve_bcsr_f32(
    StridedMemRefType<int32_t, 1> *rowptr, StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<float, 3> *values, StridedMemRefType<float, 2> *b,
    StridedMemRefType<float, 2> *x, const char *where) {
  solveBCSR(rowptr, colidx, values, b, x, where,
            &simit::solveLowerTriangular<float>);
}

extern "C" void _mlir_ciface_simit_rt_solve_diag(
    StridedMemRefType<double, 3> *values, StridedMemRefType<double, 2> *b,
    StridedMemRefType<double, 2> *x, const char *where) {
  solveDiagonal(values, b, x, where);
}

extern "C" void _mlir_ciface_simit_rt_solve_diag_f32(
    StridedMemRefType<float, 3> *values, StridedMemRefType<float, 2> *b,
    StridedMemRefType<float, 2> *x, const char *where) {
  solveDiagonal(values, b, x, where);
}

// print/println: through llvm::outs() so the output interleaves with the
// tools' own output in order. Floats like C %g, integers and bools as
// integers, strings as they are.
extern "C" void simit_rt_print_f64(double value) {
  llvm::outs() << llvm::format("%g", value);
}

extern "C" void simit_rt_print_i64(int64_t value) { llvm::outs() << value; }

extern "C" void simit_rt_print_str(const char *text) {
  llvm::outs() << (text ? text : "");
}

// Strings are NUL-terminated C strings; a concatenation allocates a new one
// that lives as long as the process.
extern "C" char *simit_rt_string_concat(const char *lhs, const char *rhs) {
  if (!lhs)
    lhs = "";
  if (!rhs)
    rhs = "";
  size_t n = std::strlen(lhs), m = std::strlen(rhs);
  char *result = static_cast<char *>(std::malloc(n + m + 1));
  std::memcpy(result, lhs, n);
  std::memcpy(result + n, rhs, m + 1);
  return result;
}

extern "C" int32_t simit_rt_string_compare(const char *lhs, const char *rhs) {
  int order = std::strcmp(lhs ? lhs : "", rhs ? rhs : "");
  return order < 0 ? -1 : order > 0 ? 1 : 0;
}

// clock(): a monotonic timestamp in microseconds. storeTime(slot, value)
// records a value in a host slot (slots 0..63); its result is 0.
extern "C" double simit_rt_clock() {
  using namespace std::chrono;
  return static_cast<double>(
      duration_cast<microseconds>(steady_clock::now().time_since_epoch())
          .count());
}

static double storedTimes[64];

extern "C" double simit_rt_storeTime(int32_t slot, double value) {
  if (slot >= 0 && slot < 64)
    storedTimes[slot] = value;
  return 0.0;
}

// The phase timer of simit-time-phases: begin/end pairs never nest, and a
// program's functions run one at a time.
static std::chrono::steady_clock::time_point phaseStart[2];
static double phaseMilliseconds[2];

extern "C" void simit_rt_phase_begin(int32_t phase) {
  if (phase >= 0 && phase < 2)
    phaseStart[phase] = std::chrono::steady_clock::now();
}

extern "C" void simit_rt_phase_end(int32_t phase) {
  if (phase >= 0 && phase < 2)
    phaseMilliseconds[phase] +=
        std::chrono::duration<double, std::milli>(
            std::chrono::steady_clock::now() - phaseStart[phase])
            .count();
}

simit::PhaseTimes simit::readPhaseTimes() {
  return {phaseMilliseconds[0], phaseMilliseconds[1]};
}

void simit::resetPhaseTimes() {
  phaseMilliseconds[0] = phaseMilliseconds[1] = 0.0;
}

// The check of --check-numerics. Lowered code cannot throw: the first
// problem of a run waits in this slot until the host takes it; later ones
// are left unscanned, since they usually follow from the first.
static std::optional<std::string> numericsProblem;

std::optional<std::string> simit::takeNumericsProblem() {
  std::optional<std::string> problem = std::move(numericsProblem);
  numericsProblem.reset();
  return problem;
}

namespace {
/// Where block `k` of `blocks` blocks sits: its row and column element
/// (column -1 for vectors) or, for stencils, its row and offset number.
std::pair<int64_t, int64_t> blockPosition(int32_t layout, int64_t perRow,
                                          const int32_t *rowptr,
                                          int64_t rows, const int32_t *colidx,
                                          int64_t k, int64_t blocks) {
  switch (layout) {
  case SIMIT_NUMERICS_DIAGONAL:
    return {k, k};
  case SIMIT_NUMERICS_PATTERN: {
    // The last row starting at or before k.
    const int32_t *row = std::upper_bound(rowptr, rowptr + rows + 1, k) - 1;
    return {row - rowptr, colidx[k]};
  }
  case SIMIT_NUMERICS_FIXED_ROWS:
    return {k / perRow, colidx[k]};
  case SIMIT_NUMERICS_STENCIL: {
    int64_t points = blocks / perRow;
    return {k % points, k / points};
  }
  default:
    return {k, -1};
  }
}

/// Whether all `n` values are finite: one branch-free pass that the
/// compiler vectorises (|x| <= max is false for NaN and infinities), so
/// that the search for the place below runs only on a problem.
template <typename T> bool allFinite(const T *values, int64_t n) {
  bool bad = false;
  for (int64_t i = 0; i < n; ++i)
    bad |= !(std::abs(values[i]) <= std::numeric_limits<T>::max());
  return !bad;
}

/// ", assembled from tets 3, 8": the elements of a mapped edge set (its
/// endpoint array, `cardinality` a row) that have `row` and, for a matrix
/// block (column >= 0), `column` among their endpoints, so that a NaN of a
/// vertex's block is traced to the tets that can have produced it.
std::string assembledFrom(const StridedMemRefType<int32_t, 1> &endpoints,
                          int64_t cardinality, const char *set, int64_t row,
                          int64_t column) {
  const int64_t listed = 32;
  llvm::SmallVector<int64_t> found;
  int64_t count = 0;
  for (int64_t e = 0; e < endpoints.sizes[0] / cardinality; ++e) {
    bool hasRow = false, hasColumn = column < 0;
    for (int64_t k = 0; k < cardinality; ++k) {
      int32_t end =
          endpoints.data[endpoints.offset +
                         (e * cardinality + k) * endpoints.strides[0]];
      hasRow |= end == row;
      hasColumn |= end == column;
    }
    if (!hasRow || !hasColumn)
      continue;
    if (++count <= listed)
      found.push_back(e);
  }
  if (found.empty())
    return "";
  std::string text = ", assembled from " + std::string(set) + " " +
                     llvm::join(llvm::map_range(found,
                                                [](int64_t e) {
                                                  return std::to_string(e);
                                                }),
                                ", ");
  if (count > listed)
    text += ", ... (" + std::to_string(count) + " in all)";
  return text;
}

template <typename T>
void checkNumerics(const UnrankedMemRefType<T> &values, int32_t layout,
                   int64_t perRow, const StridedMemRefType<int32_t, 1> &rowptr,
                   const StridedMemRefType<int32_t, 1> &colidx,
                   const char *what, const char *result, const char *rowSet,
                   const char *colSet,
                   const StridedMemRefType<int32_t, 1> &mapEndpoints,
                   int64_t mapCardinality, const char *mapSet) {
  DynamicMemRefType<T> array(values);
  if (numericsProblem || array.rank == 0)
    return;
  int64_t blocks = array.sizes[0], components = 1;
  for (int64_t d = 1; d < array.rank; ++d)
    components *= array.sizes[d];
  bool contiguous = true;
  for (int64_t d = array.rank - 1, stride = 1; d >= 0; --d) {
    contiguous &= array.sizes[d] == 1 || array.strides[d] == stride;
    stride *= array.sizes[d];
  }
  if (contiguous && allFinite(array.data + array.offset, blocks * components))
    return;
  for (int64_t k = 0; k < blocks; ++k)
    for (int64_t c = 0; c < components; ++c) {
      // Component c (row major) of block k, and its indices in the block.
      llvm::SmallVector<int64_t> indices(array.rank - 1);
      int64_t position = array.offset + k * array.strides[0];
      for (int64_t d = array.rank - 1, rest = c; d >= 1; --d) {
        indices[d - 1] = rest % array.sizes[d];
        position += indices[d - 1] * array.strides[d];
        rest /= array.sizes[d];
      }
      T value = array.data[position];
      if (std::isfinite(value))
        continue;
      auto [row, column] = blockPosition(
          layout, perRow, rowptr.data + rowptr.offset, rowptr.sizes[0] - 1,
          colidx.data + colidx.offset, k, blocks);
      std::string text;
      llvm::raw_string_ostream os(text);
      os << what << " produced "
         << (std::isnan(value) ? "nan" : value > 0 ? "inf" : "-inf") << ": "
         << result;
      if (layout == SIMIT_NUMERICS_VECTOR)
        os << " element (" << rowSet << " " << row << ")";
      else if (layout == SIMIT_NUMERICS_STENCIL)
        os << " block (" << rowSet << " " << row << ", stencil offset "
           << column << ")";
      else
        os << " block (" << rowSet << " " << row << ", " << colSet << " "
           << column << ")";
      if (indices.size() == 1)
        os << " component " << indices[0];
      else if (!indices.empty())
        os << " component (" << llvm::interleaved(indices) << ")";
      if (mapCardinality > 0)
        os << assembledFrom(mapEndpoints, mapCardinality, mapSet, row,
                            layout == SIMIT_NUMERICS_VECTOR ? -1 : column);
      numericsProblem = std::move(text);
      return;
    }
}
} // namespace

extern "C" void _mlir_ciface_simit_rt_check_numerics_f64(
    UnrankedMemRefType<double> *values, int32_t layout, int64_t perRow,
    StridedMemRefType<int32_t, 1> *rowptr,
    StridedMemRefType<int32_t, 1> *colidx, const char *what,
    const char *result, const char *rowSet, const char *colSet,
    StridedMemRefType<int32_t, 1> *mapEndpoints, int64_t mapCardinality,
    const char *mapSet) {
  checkNumerics(*values, layout, perRow, *rowptr, *colidx, what, result,
                rowSet, colSet, *mapEndpoints, mapCardinality, mapSet);
}

extern "C" void _mlir_ciface_simit_rt_check_numerics_f32(
    UnrankedMemRefType<float> *values, int32_t layout, int64_t perRow,
    StridedMemRefType<int32_t, 1> *rowptr,
    StridedMemRefType<int32_t, 1> *colidx, const char *what,
    const char *result, const char *rowSet, const char *colSet,
    StridedMemRefType<int32_t, 1> *mapEndpoints, int64_t mapCardinality,
    const char *mapSet) {
  checkNumerics(*values, layout, perRow, *rowptr, *colidx, what, result,
                rowSet, colSet, *mapEndpoints, mapCardinality, mapSet);
}

namespace {
using RowMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// A memref<?xf64> as an Eigen vector (any stride).
Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<>>
asVector(StridedMemRefType<double, 1> *m) {
  return {m->data + m->offset, m->sizes[0],
          Eigen::InnerStride<>(m->strides[0])};
}

/// A row-major rows x cols matrix held in a memref<?xf64>.
RowMatrix asMatrix(StridedMemRefType<double, 1> *m, int64_t rows,
                   int64_t cols, const char *who) {
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

void storeMatrix(const RowMatrix &value, StridedMemRefType<double, 1> *m,
                 const char *who) {
  if (m->sizes[0] != value.size())
    llvm::report_fatal_error(llvm::Twine(who) +
                             ": result size does not match");
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
template <typename Solver> struct Factor : Factorisation {
  Solver solver;
};
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
  auto *factor = dynamic_cast<Factor<Solver> *>(
      static_cast<Factorisation *>(handle));
  if (!factor)
    llvm::report_fatal_error(llvm::Twine(who) + ": the handle is not " + kind);
  return factor->solver;
}

/// chol/lu of a system matrix into `handle`, or false with runFailure set.
bool factoriseSystem(simit::FactorKind kind,
                     StridedMemRefType<int32_t, 1> *rowptr,
                     StridedMemRefType<int32_t, 1> *colidx,
                     StridedMemRefType<double, 3> *values, const char *where,
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
bool solveSystem(void *handle, bool lu, StridedMemRefType<double, 2> *b,
                 StridedMemRefType<double, 2> *x, const char *where) {
  auto *held = handle ? dynamic_cast<SystemFactor *>(
                            static_cast<Factorisation *>(handle))
                      : nullptr;
  if (!held || (held->kind == simit::FactorKind::LU) != lu)
    return fail(where, lu ? "the handle is not a sparse LU factorisation"
                          : "the handle is not a sparse Cholesky "
                            "factorisation");
  if (!isContiguous(*b) || !isContiguous(*x) ||
      b->sizes[0] * b->sizes[1] != held->factorSize ||
      x->sizes[0] * x->sizes[1] != held->factorSize)
    return fail(where, "vector size does not match the matrix");
  auto report = solver().solveWith(*held->factor, b->data + b->offset,
                                   x->data + x->offset,
                                   where ? where : "solve");
  return report ? true : fail(where, llvm::toString(report.takeError()));
}

} // namespace

extern "C" void *_mlir_ciface_simit_rt_lu(StridedMemRefType<double, 1> *a,
                                          int64_t n) {
  auto *factor = new Factor<LU>;
  factor->solver.compute(Eigen::MatrixXd(asMatrix(a, n, n, "lu")));
  return static_cast<Factorisation *>(factor);
}

extern "C" void *_mlir_ciface_simit_rt_chol(StridedMemRefType<double, 1> *a,
                                            int64_t n) {
  auto *factor = new Factor<LLT>;
  factor->solver.compute(Eigen::MatrixXd(asMatrix(a, n, n, "chol")));
  return static_cast<Factorisation *>(factor);
}

extern "C" void *_mlir_ciface_simit_rt_lu_bcsr(
    StridedMemRefType<int32_t, 1> *rowptr,
    StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<double, 3> *values, const char *where) {
  void *handle = nullptr;
  if (!factoriseSystem(simit::FactorKind::LU, rowptr, colidx, values, where,
                       handle))
    abandonRun();
  return handle;
}

extern "C" void *_mlir_ciface_simit_rt_chol_bcsr(
    StridedMemRefType<int32_t, 1> *rowptr,
    StridedMemRefType<int32_t, 1> *colidx,
    StridedMemRefType<double, 3> *values, const char *where) {
  void *handle = nullptr;
  if (!factoriseSystem(simit::FactorKind::Cholesky, rowptr, colidx, values,
                       where, handle))
    abandonRun();
  return handle;
}

extern "C" void _mlir_ciface_simit_rt_lusolve_bcsr(
    void *handle, StridedMemRefType<double, 2> *b,
    StridedMemRefType<double, 2> *x, const char *where) {
  if (!solveSystem(handle, /*lu=*/true, b, x, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_lltsolve_bcsr(
    void *handle, StridedMemRefType<double, 2> *b,
    StridedMemRefType<double, 2> *x, const char *where) {
  if (!solveSystem(handle, /*lu=*/false, b, x, where))
    abandonRun();
}

extern "C" void _mlir_ciface_simit_rt_lusolve(void *handle,
                                              StridedMemRefType<double, 1> *b,
                                              StridedMemRefType<double, 1> *x) {
  auto &lu = solverOf<LU>(handle, "lusolve", "a dense LU factorisation");
  RowMatrix rhs = asMatrix(b, lu.rows(), 1, "lusolve");
  storeMatrix(RowMatrix(lu.solve(Eigen::MatrixXd(rhs))), x, "lusolve");
}

extern "C" void _mlir_ciface_simit_rt_lltsolve(void *handle,
                                               StridedMemRefType<double, 1> *b,
                                               StridedMemRefType<double, 1> *x) {
  auto &llt = solverOf<LLT>(handle, "lltsolve",
                           "a dense Cholesky factorisation");
  RowMatrix rhs = asMatrix(b, llt.rows(), 1, "lltsolve");
  storeMatrix(RowMatrix(llt.solve(Eigen::MatrixXd(rhs))), x, "lltsolve");
}

extern "C" void _mlir_ciface_simit_rt_lumatsolve(
    void *handle, StridedMemRefType<double, 1> *b,
    StridedMemRefType<double, 1> *x, int64_t cols) {
  auto &lu = solverOf<LU>(handle, "lumatsolve", "a dense LU factorisation");
  RowMatrix rhs = asMatrix(b, lu.rows(), cols, "lumatsolve");
  storeMatrix(RowMatrix(lu.solve(Eigen::MatrixXd(rhs))), x, "lumatsolve");
}

extern "C" void _mlir_ciface_simit_rt_lltmatsolve(
    void *handle, StridedMemRefType<double, 1> *b,
    StridedMemRefType<double, 1> *x, int64_t cols) {
  auto &llt = solverOf<LLT>(handle, "lltmatsolve",
                           "a dense Cholesky factorisation");
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
    StridedMemRefType<double, 1> *a, StridedMemRefType<double, 1> *b,
    StridedMemRefType<double, 1> *x, int64_t n) {
  RowMatrix matrix = asMatrix(a, n, n, "triangularSolve");
  RowMatrix rhs = asMatrix(b, n, 1, "triangularSolve");
  RowMatrix solution =
      matrix.triangularView<Eigen::Lower>().solve(rhs);
  storeMatrix(solution, x, "triangularSolve");
}

llvm::orc::SymbolMap
simit::runtimeSymbolMap(llvm::orc::MangleAndInterner interner) {
  llvm::orc::SymbolMap symbols;
  auto add = [&](llvm::StringRef name, void *address) {
    symbols[interner(name)] = {llvm::orc::ExecutorAddr::fromPtr(address),
                               llvm::JITSymbolFlags::Exported};
  };
  add("simit_rt_fail", reinterpret_cast<void *>(&simit_rt_fail));
  add("simit_rt_raise_parallel_failure",
      reinterpret_cast<void *>(&simit_rt_raise_parallel_failure));
  add("_mlir_ciface_simit_rt_solve_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_solve_bcsr));
  add("_mlir_ciface_simit_rt_solve_bcsr_f32",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_solve_bcsr_f32));
  add("_mlir_ciface_simit_rt_sherman_morrison_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_sherman_morrison_bcsr));
  add("_mlir_ciface_simit_rt_sherman_morrison_bcsr_f32",
      reinterpret_cast<void *>(
          &_mlir_ciface_simit_rt_sherman_morrison_bcsr_f32));
  for (auto [name, entry] :
       {std::pair("_mlir_ciface_simit_rt_woodbury2_bcsr",
                  reinterpret_cast<void *>(
                      &_mlir_ciface_simit_rt_woodbury2_bcsr)),
        std::pair("_mlir_ciface_simit_rt_woodbury3_bcsr",
                  reinterpret_cast<void *>(
                      &_mlir_ciface_simit_rt_woodbury3_bcsr)),
        std::pair("_mlir_ciface_simit_rt_woodbury4_bcsr",
                  reinterpret_cast<void *>(
                      &_mlir_ciface_simit_rt_woodbury4_bcsr)),
        std::pair("_mlir_ciface_simit_rt_woodbury2_bcsr_f32",
                  reinterpret_cast<void *>(
                      &_mlir_ciface_simit_rt_woodbury2_bcsr_f32)),
        std::pair("_mlir_ciface_simit_rt_woodbury3_bcsr_f32",
                  reinterpret_cast<void *>(
                      &_mlir_ciface_simit_rt_woodbury3_bcsr_f32)),
        std::pair("_mlir_ciface_simit_rt_woodbury4_bcsr_f32",
                  reinterpret_cast<void *>(
                      &_mlir_ciface_simit_rt_woodbury4_bcsr_f32))})
    add(name, entry);
  add("_mlir_ciface_simit_rt_matmul_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_matmul_bcsr));
  add("_mlir_ciface_simit_rt_matmul_bcsr_f32",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_matmul_bcsr_f32));
  add("_mlir_ciface_simit_rt_triangular_solve_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_triangular_solve_bcsr));
  add("_mlir_ciface_simit_rt_triangular_solve_bcsr_f32",
      reinterpret_cast<void *>(
          &_mlir_ciface_simit_rt_triangular_solve_bcsr_f32));
  add("_mlir_ciface_simit_rt_solve_diag",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_solve_diag));
  add("_mlir_ciface_simit_rt_solve_diag_f32",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_solve_diag_f32));
  add("simit_rt_print_f64", reinterpret_cast<void *>(&simit_rt_print_f64));
  add("simit_rt_print_i64", reinterpret_cast<void *>(&simit_rt_print_i64));
  add("simit_rt_print_str", reinterpret_cast<void *>(&simit_rt_print_str));
  add("simit_rt_string_concat",
      reinterpret_cast<void *>(&simit_rt_string_concat));
  add("simit_rt_string_compare",
      reinterpret_cast<void *>(&simit_rt_string_compare));
  add("simit_rt_clock", reinterpret_cast<void *>(&simit_rt_clock));
  add("simit_rt_storeTime", reinterpret_cast<void *>(&simit_rt_storeTime));
  add("_mlir_memref_to_llvm_alloc",
      reinterpret_cast<void *>(&_mlir_memref_to_llvm_alloc));
  add("_mlir_memref_to_llvm_free",
      reinterpret_cast<void *>(&_mlir_memref_to_llvm_free));
  add("simit_rt_phase_begin", reinterpret_cast<void *>(&simit_rt_phase_begin));
  add("simit_rt_phase_end", reinterpret_cast<void *>(&simit_rt_phase_end));
  add("_mlir_ciface_simit_rt_check_numerics_f64",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_check_numerics_f64));
  add("_mlir_ciface_simit_rt_check_numerics_f32",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_check_numerics_f32));
  add("_mlir_ciface_simit_rt_lu",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lu));
  add("_mlir_ciface_simit_rt_chol",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_chol));
  add("_mlir_ciface_simit_rt_lusolve",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lusolve));
  add("_mlir_ciface_simit_rt_lltsolve",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lltsolve));
  add("_mlir_ciface_simit_rt_lumatsolve",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lumatsolve));
  add("_mlir_ciface_simit_rt_lltmatsolve",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lltmatsolve));
  add("_mlir_ciface_simit_rt_lu_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lu_bcsr));
  add("_mlir_ciface_simit_rt_chol_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_chol_bcsr));
  add("_mlir_ciface_simit_rt_lusolve_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lusolve_bcsr));
  add("_mlir_ciface_simit_rt_lltsolve_bcsr",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_lltsolve_bcsr));
  add("simit_rt_lufree", reinterpret_cast<void *>(&simit_rt_lufree));
  add("simit_rt_cholfree", reinterpret_cast<void *>(&simit_rt_cholfree));
  add("_mlir_ciface_simit_rt_triangularSolve",
      reinterpret_cast<void *>(&_mlir_ciface_simit_rt_triangularSolve));
  addGPURuntimeSymbols(add);
  return symbols;
}
