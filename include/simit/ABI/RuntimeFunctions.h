//===--- RuntimeFunctions.h - Functions lowered code calls ------*- C++ -*-===//
//
// Functions JIT-compiled Simit code calls, with C linkage: the runtime
// library SimitRuntimeABI (lib/ABI), which does not depend on MLIR. Lowered
// code declares them as `func.func private` and calls them by the names of
// simit/ABI/RuntimeFunctionNames.h, which the engine binds to these
// functions in every JIT it links code into (docs/api.md lists the MLIR
// declarations). Memrefs arrive as the descriptors of simit/ABI/MemRef.h.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ABI_RUNTIMEFUNCTIONS_H
#define SIMIT_ABI_RUNTIMEFUNCTIONS_H

#include "simit/ABI/MemRef.h"
#include "simit/ABI/NumericsLayout.h"

#include "llvm/Support/Error.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

extern "C" {

/// x = A \ b of the language (the SolveSession of the run: the method the
/// user chose, `auto` by default, the true residual checked; see
/// docs/solvers.md) for a BCSR matrix with square blocks of B x B:
///   rowptr: memref<?xi32> (rows + 1), colidx: memref<?xi32> (blocks),
///   values: memref<?xBxBxf64>, b and x: memref<?xBxf64>, `where` the
///   statement's "file:line:col: x = A \ b" (a C string).
/// A failure (singular matrix, residual too large, an iterative solve
/// stopped by the cap under strict settings) ends the run with an error
/// naming `where` (simit_rt_fail); `where` also names the statement in
/// warnings and statistics.
/// MLIR: func.func private @simit_rt_solve_bcsr(memref<?xi32>,
///   memref<?xi32>, memref<?x?x?xf64>, memref<?x?xf64>, memref<?x?xf64>,
///   !llvm.ptr) attributes {llvm.emit_c_interface}
void _mlir_ciface_simit_rt_solve_bcsr(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<double, 3> *values,
    simit::abi::MemRefDescriptor<double, 2> *b,
    simit::abi::MemRefDescriptor<double, 2> *x, const char *where);
/// The same on f32 components (@simit_rt_solve_bcsr_f32).
void _mlir_ciface_simit_rt_solve_bcsr_f32(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<float, 3> *values,
    simit::abi::MemRefDescriptor<float, 2> *b,
    simit::abi::MemRefDescriptor<float, 2> *x, const char *where);
/// The last step of `(A + u v^T) \ b` rewritten by simit-sherman-morrison
/// (SolveSession::shermanMorrison): given w = A^-1 u and c = A^-1 b, x =
/// c - w (v.c) / (1 + v.w), or the bordered system [A u; v^T -1] by LU when
/// 1 + v.w is tiny; the residual checked. A BCSR as for @simit_rt_solve_bcsr,
/// the vectors memref<?xBxf64>, `where` "Sherman-Morrison (file:line:col)".
/// MLIR: @simit_rt_sherman_morrison_bcsr(memref<?xi32>, memref<?xi32>,
///   memref<?x?x?xf64>, memref<?x?xf64> u, v, b, w, c, x, !llvm.ptr), and
///   _f32.
void _mlir_ciface_simit_rt_sherman_morrison_bcsr(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<double, 3> *values,
    simit::abi::MemRefDescriptor<double, 2> *u,
    simit::abi::MemRefDescriptor<double, 2> *v,
    simit::abi::MemRefDescriptor<double, 2> *b,
    simit::abi::MemRefDescriptor<double, 2> *w,
    simit::abi::MemRefDescriptor<double, 2> *c,
    simit::abi::MemRefDescriptor<double, 2> *x, const char *where);
void _mlir_ciface_simit_rt_sherman_morrison_bcsr_f32(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<float, 3> *values,
    simit::abi::MemRefDescriptor<float, 2> *u,
    simit::abi::MemRefDescriptor<float, 2> *v,
    simit::abi::MemRefDescriptor<float, 2> *b,
    simit::abi::MemRefDescriptor<float, 2> *w,
    simit::abi::MemRefDescriptor<float, 2> *c,
    simit::abi::MemRefDescriptor<float, 2> *x, const char *where);
/// Ranks 2 to 4 of the rewrite (the Woodbury form): the same with
/// u_1..u_k, v_1..v_k, b, w_1..w_k, c, x.
/// MLIR: @simit_rt_woodbury<k>_bcsr(memref<?xi32>, memref<?xi32>,
///   memref<?x?x?xf64>, memref<?x?xf64> x (3k + 3), !llvm.ptr), and _f32.
typedef simit::abi::MemRefDescriptor<double, 2> *SimitF64Vector;
typedef simit::abi::MemRefDescriptor<float, 2> *SimitF32Vector;
#define SIMIT_RT_WOODBURY_PARAMS_2(V)                                          \
  V u1, V u2, V v1, V v2, V b, V w1, V w2, V c, V x
#define SIMIT_RT_WOODBURY_PARAMS_3(V)                                          \
  V u1, V u2, V u3, V v1, V v2, V v3, V b, V w1, V w2, V w3, V c, V x
#define SIMIT_RT_WOODBURY_PARAMS_4(V)                                          \
  V u1, V u2, V u3, V u4, V v1, V v2, V v3, V v4, V b, V w1, V w2, V w3,    \
      V w4, V c, V x
#define SIMIT_RT_DECLARE_WOODBURY(NAME, T, PARAMS)                             \
  void NAME(simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,                  \
            simit::abi::MemRefDescriptor<int32_t, 1> *colidx,                  \
            simit::abi::MemRefDescriptor<T, 3> *values, PARAMS,                \
            const char *where);
SIMIT_RT_DECLARE_WOODBURY(_mlir_ciface_simit_rt_woodbury2_bcsr, double,
                          SIMIT_RT_WOODBURY_PARAMS_2(SimitF64Vector))
SIMIT_RT_DECLARE_WOODBURY(_mlir_ciface_simit_rt_woodbury3_bcsr, double,
                          SIMIT_RT_WOODBURY_PARAMS_3(SimitF64Vector))
SIMIT_RT_DECLARE_WOODBURY(_mlir_ciface_simit_rt_woodbury4_bcsr, double,
                          SIMIT_RT_WOODBURY_PARAMS_4(SimitF64Vector))
SIMIT_RT_DECLARE_WOODBURY(_mlir_ciface_simit_rt_woodbury2_bcsr_f32, float,
                          SIMIT_RT_WOODBURY_PARAMS_2(SimitF32Vector))
SIMIT_RT_DECLARE_WOODBURY(_mlir_ciface_simit_rt_woodbury3_bcsr_f32, float,
                          SIMIT_RT_WOODBURY_PARAMS_3(SimitF32Vector))
SIMIT_RT_DECLARE_WOODBURY(_mlir_ciface_simit_rt_woodbury4_bcsr_f32, float,
                          SIMIT_RT_WOODBURY_PARAMS_4(SimitF32Vector))
#undef SIMIT_RT_DECLARE_WOODBURY
/// triangularSolve(A, b) on a square BCSR system matrix (arguments as for
/// @simit_rt_solve_bcsr): forward substitution with A's lower triangle; a
/// zero diagonal entry ends the run with `where`.
/// MLIR: @simit_rt_triangular_solve_bcsr(...), and _f32.
void _mlir_ciface_simit_rt_triangular_solve_bcsr(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<double, 3> *values,
    simit::abi::MemRefDescriptor<double, 2> *b,
    simit::abi::MemRefDescriptor<double, 2> *x, const char *where);
void _mlir_ciface_simit_rt_triangular_solve_bcsr_f32(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<float, 3> *values,
    simit::abi::MemRefDescriptor<float, 2> *b,
    simit::abi::MemRefDescriptor<float, 2> *x, const char *where);
/// x = A \ b for a block diagonal A (values memref<?xBxBxT>, block r at
/// (r, r)): @simit_rt_solve_diag(memref<?x?x?xf64>, memref<?x?xf64>,
/// memref<?x?xf64>, !llvm.ptr), and @simit_rt_solve_diag_f32.
void _mlir_ciface_simit_rt_solve_diag(
    simit::abi::MemRefDescriptor<double, 3> *values,
    simit::abi::MemRefDescriptor<double, 2> *b,
    simit::abi::MemRefDescriptor<double, 2> *x, const char *where);
void _mlir_ciface_simit_rt_solve_diag_f32(
    simit::abi::MemRefDescriptor<float, 3> *values,
    simit::abi::MemRefDescriptor<float, 2> *b,
    simit::abi::MemRefDescriptor<float, 2> *x, const char *where);

/// C = A B for system matrices: each of A, B and C BCSR (layout 0: rowptr,
/// colidx, values memref<?xBrxBcxT>) or block diagonal (layout 1: index
/// arrays unused) or dense (layout 3: every block row by row, index arrays
/// unused); A and B may also be incidences read row by row (layout 2: the
/// rowptr, colidx and value positions of simit::IncidenceView).
/// C's pattern holds the product (simit::productPattern), `cols` is its
/// number of block columns. A block of the product outside C's pattern
/// ends the run with `where`.
/// MLIR: @simit_rt_matmul_bcsr(i32, memref<?xi32>, memref<?xi32>,
///   memref<?xi32>, memref<?x?x?xf64>, i32, memref<?xi32>, memref<?xi32>,
///   memref<?xi32>, memref<?x?x?xf64>, i32, memref<?xi32>, memref<?xi32>,
///   memref<?x?x?xf64>, i64, !llvm.ptr), @simit_rt_matmul_bcsr_f32, and
///   @simit_rt_matmul_bcsr_i32 (int products wrap at 32 bits).
#define SIMIT_RT_DECLARE_MATMUL_BCSR(NAME, T)                                  \
  void NAME(                                                                   \
      int32_t layoutA, simit::abi::MemRefDescriptor<int32_t, 1> *rowptrA,      \
      simit::abi::MemRefDescriptor<int32_t, 1> *colidxA,                       \
      simit::abi::MemRefDescriptor<int32_t, 1> *positionsA,                    \
      simit::abi::MemRefDescriptor<T, 3> *a, int32_t layoutB,                  \
      simit::abi::MemRefDescriptor<int32_t, 1> *rowptrB,                       \
      simit::abi::MemRefDescriptor<int32_t, 1> *colidxB,                       \
      simit::abi::MemRefDescriptor<int32_t, 1> *positionsB,                    \
      simit::abi::MemRefDescriptor<T, 3> *b, int32_t layoutC,                  \
      simit::abi::MemRefDescriptor<int32_t, 1> *rowptrC,                       \
      simit::abi::MemRefDescriptor<int32_t, 1> *colidxC,                       \
      simit::abi::MemRefDescriptor<T, 3> *c, int64_t cols, const char *where);
SIMIT_RT_DECLARE_MATMUL_BCSR(_mlir_ciface_simit_rt_matmul_bcsr, double)
SIMIT_RT_DECLARE_MATMUL_BCSR(_mlir_ciface_simit_rt_matmul_bcsr_f32, float)
SIMIT_RT_DECLARE_MATMUL_BCSR(_mlir_ciface_simit_rt_matmul_bcsr_i32, int32_t)

/// Ends the run of the exported function in progress (simit::runGuarded)
/// with `message` as its error; outside a guarded run, a fatal error.
/// Inside an OpenMP parallel region it records the failure and returns.
/// MLIR: func.func private @simit_rt_fail(!llvm.ptr)
void simit_rt_fail(const char *message);

/// Ends the run with the failure recorded inside the parallel region that
/// just ended, if any (simit-parallel-loops-to-openmp calls it after each
/// region that may fail).
/// MLIR: func.func private @simit_rt_raise_parallel_failure()
void simit_rt_raise_parallel_failure();

/// A matrix result of a host function (`extern func`), BCSR arrays the
/// host allocated with malloc: row pointers (rowBlocks + 1), column
/// indices and blocks (rowptr[rowBlocks] each). Checks the arrays (row
/// pointers from 0 and non-decreasing, columns in [0, colBlocks), no
/// column twice in a row) and returns the number of blocks; a malformed
/// matrix frees them and ends the run with an error naming `where`.
/// MLIR: func.func private @simit_rt_host_matrix_blocks(!llvm.ptr,
///   !llvm.ptr, !llvm.ptr, i64, i64, !llvm.ptr) -> i64
int64_t simit_rt_host_matrix_blocks(int32_t *rowptr, int32_t *colidx,
                                    void *blocks, int64_t rowBlocks,
                                    int64_t colBlocks, const char *where);
/// Copies those arrays into the lowered code's own (`rowptrOut`,
/// `colidxOut`, `blocksOut`, blockBytes per block), each row's blocks in
/// ascending column order, and frees the host's. Returns 0: lowered code
/// calls it through the shim of host functions (LowerHostCalls.cpp).
/// MLIR: func.func private @simit_rt_host_matrix_adopt(!llvm.ptr, !llvm.ptr,
///   !llvm.ptr, i64, i64, !llvm.ptr, !llvm.ptr, !llvm.ptr) -> i32
int32_t simit_rt_host_matrix_adopt(int32_t *rowptr, int32_t *colidx,
                                   void *blocks, int64_t rowBlocks,
                                   int64_t blockBytes, int32_t *rowptrOut,
                                   int32_t *colidxOut, void *blocksOut);

/// The pattern of A B (product) or A + B (union) of matrices whose
/// patterns are known only at run time (a host function's matrix in them):
/// rowptr and colidx of A and B (BCSR), A over rows x mid blocks and B
/// over mid x cols for the product, both over rows x cols for the union.
/// Returns a handle to the pattern for simit_rt_pattern_blocks (its number
/// of blocks) and simit_rt_pattern_take (which copies it into the lowered
/// code's arrays, rows + 1 and blocks long, and frees it).
/// MLIR: func.func private @simit_rt_product_pattern(memref<?xi32>,
///   memref<?xi32>, memref<?xi32>, memref<?xi32>, i64) -> !llvm.ptr
///   attributes {llvm.emit_c_interface}; @simit_rt_union_pattern alike;
///   @simit_rt_pattern_blocks(!llvm.ptr) -> i64;
///   @simit_rt_pattern_take(!llvm.ptr, memref<?xi32>, memref<?xi32>)
///   attributes {llvm.emit_c_interface}
void *_mlir_ciface_simit_rt_product_pattern(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptrA,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidxA,
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptrB,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidxB, int64_t cols);
void *_mlir_ciface_simit_rt_union_pattern(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptrA,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidxA,
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptrB,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidxB, int64_t cols);
/// The pattern of A' for A (rowptr, colidx) of `cols` block columns.
/// MLIR: func.func private @simit_rt_transpose_pattern(memref<?xi32>,
///   memref<?xi32>, i64) -> !llvm.ptr attributes {llvm.emit_c_interface}
void *_mlir_ciface_simit_rt_transpose_pattern(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx, int64_t cols);
int64_t simit_rt_pattern_blocks(void *pattern);
void _mlir_ciface_simit_rt_pattern_take(
    void *pattern, simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx);

/// print/println of scalars and strings (lowered simit.print).
void simit_rt_print_f64(double value);
void simit_rt_print_i64(int64_t value);
void simit_rt_print_str(const char *text);
/// String concatenation (a fresh malloc'd string) and comparison (-1, 0, 1).
char *simit_rt_string_concat(const char *lhs, const char *rhs);
int32_t simit_rt_string_compare(const char *lhs, const char *rhs);

/// clock() in microseconds (monotonic) and storeTime(slot, value).
double simit_rt_clock();
double simit_rt_storeTime(int32_t slot, double value);

/// Heap memory of lowered code (memref.alloc/dealloc with the pipeline's
/// runtime-allocator option): freed blocks of 64 KiB and more are kept for
/// reuse by size, so per-frame temporaries are not page-faulted in anew.
void *_mlir_memref_to_llvm_alloc(size_t size);
void _mlir_memref_to_llvm_free(void *pointer);

/// The phase timer that simit-time-phases brackets assemblies (phase 0) and
/// solves (phase 1) with; simit::readPhaseTimes() reads it.
void simit_rt_phase_begin(int32_t phase);
void simit_rt_phase_end(int32_t phase);

/// The check of --check-numerics (simit-check-numerics): scans a result
/// array (memref<*xf64> / memref<*xf32>, dimension 0 the blocks) and, if it
/// holds a NaN or infinity and no problem of this run is recorded yet,
/// records the first one for simit::takeNumericsProblem():
///   "<what> produced nan: <result> block (<rowSet> r, <colSet> c)
///    component (i, j)" (vectors: "element (<rowSet> r)"; scalar blocks
///   name no component).
/// rowptr and colidx are read only by the layouts that name them. For an
/// assembly over an edge set whose endpoints are the result's row (and
/// column) set, mapEndpoints is its endpoint array (mapCardinality a row,
/// memref<?xi32>) and mapSet its name, and the message ends with the
/// elements that have the block's row (and column) as endpoints:
///   ", assembled from tets 3, 8"; otherwise mapCardinality is 0.
/// MLIR: func.func private @simit_rt_check_numerics_f64(memref<*xf64>, i32,
///   i64, memref<?xi32>, memref<?xi32>, !llvm.ptr, !llvm.ptr, !llvm.ptr,
///   !llvm.ptr, memref<?xi32>, i64, !llvm.ptr)
///   attributes {llvm.emit_c_interface}, likewise _f32.
void _mlir_ciface_simit_rt_check_numerics_f64(
    simit::abi::UnrankedMemRefDescriptor<double> *values, int32_t layout,
    int64_t perRow, simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx, const char *what,
    const char *result, const char *rowSet, const char *colSet,
    simit::abi::MemRefDescriptor<int32_t, 1> *mapEndpoints,
    int64_t mapCardinality, const char *mapSet);
void _mlir_ciface_simit_rt_check_numerics_f32(
    simit::abi::UnrankedMemRefDescriptor<float> *values, int32_t layout,
    int64_t perRow, simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx, const char *what,
    const char *result, const char *rowSet, const char *colSet,
    simit::abi::MemRefDescriptor<int32_t, 1> *mapEndpoints,
    int64_t mapCardinality, const char *mapSet);

/// Dense solvers of small local f64 matrices (Eigen). Matrices and vectors
/// are row-major memref<?xf64>; a factorisation is an opaque heap handle
/// (!llvm.ptr) that lufree/cholfree delete. Each takes `where`, the call's
/// "lusolve (file:line:col)": a size that does not match, chol of a matrix
/// that is not positive definite, a handle of the other kind, one already
/// freed or none (a failed factorisation) end the run naming it (inside a
/// parallel region, at the region's end; the solution is NaN until then).
/// MLIR (each attributes {llvm.emit_c_interface} except the frees):
///   @simit_rt_lu(memref<?xf64> A, i64 n, !llvm.ptr where) -> !llvm.ptr
///       (PartialPivLU), likewise @simit_rt_chol (LLT)
///   @simit_rt_lusolve(!llvm.ptr, memref<?xf64> b, memref<?xf64> x,
///       !llvm.ptr where), likewise @simit_rt_lltsolve
///   @simit_rt_lumatsolve(!llvm.ptr, memref<?xf64> B, memref<?xf64> X, i64 k,
///       !llvm.ptr where), likewise @simit_rt_lltmatsolve
///   @simit_rt_lufree(!llvm.ptr, !llvm.ptr where), likewise
///       @simit_rt_cholfree
///   @simit_rt_triangularSolve(memref<?xf64> A, memref<?xf64> b,
///       memref<?xf64> x, i64 n, !llvm.ptr where)   (A's lower triangle,
///       forward substitution)
void *_mlir_ciface_simit_rt_lu(simit::abi::MemRefDescriptor<double, 1> *a,
                               int64_t n, const char *where);
void *_mlir_ciface_simit_rt_chol(simit::abi::MemRefDescriptor<double, 1> *a,
                                 int64_t n, const char *where);
void _mlir_ciface_simit_rt_lusolve(void *handle,
                                   simit::abi::MemRefDescriptor<double, 1> *b,
                                   simit::abi::MemRefDescriptor<double, 1> *x,
                                   const char *where);
void _mlir_ciface_simit_rt_lltsolve(void *handle,
                                    simit::abi::MemRefDescriptor<double, 1> *b,
                                    simit::abi::MemRefDescriptor<double, 1> *x,
                                    const char *where);
void _mlir_ciface_simit_rt_lumatsolve(
    void *handle, simit::abi::MemRefDescriptor<double, 1> *b,
    simit::abi::MemRefDescriptor<double, 1> *x, int64_t cols,
    const char *where);
void _mlir_ciface_simit_rt_lltmatsolve(
    void *handle, simit::abi::MemRefDescriptor<double, 1> *b,
    simit::abi::MemRefDescriptor<double, 1> *x, int64_t cols,
    const char *where);
/// Sparse factorisations of square system matrices through the SolveSession
/// of the run (UMFPACK LU, CHOLMOD supernodal Cholesky; symbolic analysis
/// once per pattern, a factorisation reused for the same values), BCSR
/// arrays as for `\` and system vectors memref<?xBxf64>. chol fails on a
/// matrix that is not symmetric or not positive definite, lu on a singular
/// one, a solve on a residual above 1e-8: each ends the run with `where`
/// (the call's "chol (file:line:col)"). The handles are freed by
/// lufree/cholfree like the dense ones.
/// MLIR (attributes {llvm.emit_c_interface}):
///   @simit_rt_lu_bcsr(memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>,
///       !llvm.ptr where) -> !llvm.ptr, likewise @simit_rt_chol_bcsr
///   @simit_rt_lusolve_bcsr(!llvm.ptr, memref<?x?xf64> b, memref<?x?xf64> x,
///       !llvm.ptr where), likewise @simit_rt_lltsolve_bcsr
void *
_mlir_ciface_simit_rt_lu_bcsr(simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
                              simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
                              simit::abi::MemRefDescriptor<double, 3> *values,
                              const char *where);
void *_mlir_ciface_simit_rt_chol_bcsr(
    simit::abi::MemRefDescriptor<int32_t, 1> *rowptr,
    simit::abi::MemRefDescriptor<int32_t, 1> *colidx,
    simit::abi::MemRefDescriptor<double, 3> *values, const char *where);
void _mlir_ciface_simit_rt_lusolve_bcsr(
    void *handle, simit::abi::MemRefDescriptor<double, 2> *b,
    simit::abi::MemRefDescriptor<double, 2> *x, const char *where);
void _mlir_ciface_simit_rt_lltsolve_bcsr(
    void *handle, simit::abi::MemRefDescriptor<double, 2> *b,
    simit::abi::MemRefDescriptor<double, 2> *x, const char *where);
void simit_rt_lufree(void *handle, const char *where);
void simit_rt_cholfree(void *handle, const char *where);
void _mlir_ciface_simit_rt_triangularSolve(
    simit::abi::MemRefDescriptor<double, 1> *a,
    simit::abi::MemRefDescriptor<double, 1> *b,
    simit::abi::MemRefDescriptor<double, 1> *x, int64_t n, const char *where);

/// What the host code of simit-gpu-pipeline calls (GPUFunctions.cpp), over
/// the CUDA driver loaded at run time (simit/Runtime/CudaDriver.h): the
/// statement of the launches that follow, for messages, and the mgpu*
/// functions MLIR's gpu-to-llvm lowering emits. A failing driver call ends
/// the run through simit_rt_fail.
void simit_rt_gpu_statement(const char *where);
void *mgpuModuleLoadJIT(void *ptx, int optLevel);
void mgpuModuleUnload(void *module);
void *mgpuModuleGetFunction(void *module, const char *name);
void mgpuLaunchKernel(void *function, intptr_t gridX, intptr_t gridY,
                      intptr_t gridZ, intptr_t blockX, intptr_t blockY,
                      intptr_t blockZ, int32_t sharedBytes, void *stream,
                      void **params, void **extra, size_t paramCount);
void *mgpuStreamCreate();
void mgpuStreamDestroy(void *stream);
void mgpuStreamSynchronize(void *stream);
void *mgpuMemAlloc(uint64_t bytes, void *stream, bool hostShared);
void mgpuMemFree(void *pointer, void *stream);
void mgpuMemcpy(void *dst, void *src, size_t bytes, void *stream);

} // extern "C"

namespace simit {

class SolveSession;

/// Milliseconds spent in the timed phases of programs compiled with
/// ProgramOptions::timePhases, since the last resetPhaseTimes().
struct PhaseTimes {
  double assemblyMs = 0.0; // map, apply and assembly statements
  double solveMs = 0.0;    // solves, and while loops without assemblies
};
PhaseTimes readPhaseTimes();
void resetPhaseTimes();

/// The first NaN or infinity that an assembly or solve of a program
/// compiled with ProgramOptions::checkNumerics produced since the last call
/// (the message of simit_rt_check_numerics_*), and forgets it; nullopt when
/// there was none.
std::optional<std::string> takeNumericsProblem();

/// Calls the packed entry point `entry(args)` of lowered code; a runtime
/// failure inside it (simit_rt_fail) returns here as the error instead of
/// ending the process. What the failed run wrote stays as it was. `solver`
/// (the Program's) serves the run's solves; null: one of the process.
llvm::Error runGuarded(void (*entry)(void **), void **args,
                       SolveSession *solver = nullptr);

} // namespace simit

#endif // SIMIT_ABI_RUNTIMEFUNCTIONS_H
