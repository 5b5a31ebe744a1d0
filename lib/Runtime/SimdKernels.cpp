//===--- SimdKernels.cpp - Vector-unit kernels of the runtime's solvers ---===//
//
// A 3x3 block times a 3-vector without shuffles of the block: its nine
// values, row-major, are loaded as (b00 b01 b02 b10), (b11 b12 b20 b21) and
// b22, and multiplied by (x0 x1 x2 x0), (x1 x2 x0 x1) and x2; a block row
// accumulates those three products over its blocks and adds their lanes
// into y0, y1, y2 once at the end. Per block that is two vector loads, a
// masked load of x, two permutes and three FMAs.
//
//===----------------------------------------------------------------------===//

#include "SimdKernels.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define SIMIT_HAVE_AVX2_KERNELS 1
#endif

using namespace simit;

#ifdef SIMIT_HAVE_AVX2_KERNELS
namespace {
bool hostHasAvx2Fma() {
  static const bool has =
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
}

__attribute__((target("avx2,fma"))) void
multiplyBlocks3Avx2(int64_t rows, const int32_t *__restrict rowptr,
                    const int32_t *__restrict colidx,
                    const double *__restrict values,
                    const double *__restrict x, double *__restrict y,
                    const double *__restrict dotWith, double *dot) {
  // Lanes 0..2 of x's block: x[3c + 3] may lie past the vector's end.
  const __m256i firstThree = _mm256_setr_epi64x(-1, -1, -1, 0);
  double sum = 0;
  for (int64_t r = 0; r < rows; ++r) {
    __m256d head = _mm256_setzero_pd(), middle = _mm256_setzero_pd();
    __m128d last = _mm_setzero_pd();
    for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k) {
      const double *block = values + static_cast<int64_t>(k) * 9;
      __m256d xc = _mm256_maskload_pd(
          x + static_cast<int64_t>(colidx[k]) * 3, firstThree);
      // (x0 x1 x2 x0) and (x1 x2 x0 x1).
      __m256d x0120 = _mm256_permute4x64_pd(xc, 0b00100100);
      __m256d x1201 = _mm256_permute4x64_pd(xc, 0b01001001);
      head = _mm256_fmadd_pd(_mm256_loadu_pd(block), x0120, head);
      middle = _mm256_fmadd_pd(_mm256_loadu_pd(block + 4), x1201, middle);
      last = _mm_fmadd_sd(_mm_load_sd(block + 8),
                          _mm256_extractf128_pd(xc, 1), last);
    }
    alignas(32) double h[4], m[4];
    _mm256_store_pd(h, head);
    _mm256_store_pd(m, middle);
    double *yr = y + r * 3;
    yr[0] = h[0] + h[1] + h[2];
    yr[1] = h[3] + m[0] + m[1];
    yr[2] = m[2] + m[3] + _mm_cvtsd_f64(last);
    // The row's three products are summed first: one addition per row
    // waits for the one before, not three.
    if (dotWith)
      sum += dotWith[r * 3] * yr[0] + dotWith[r * 3 + 1] * yr[1] +
             dotWith[r * 3 + 2] * yr[2];
  }
  if (dot)
    *dot = sum;
}
} // namespace
#endif

bool simd::multiplyBlocks3(int64_t rows, const int32_t *rowptr,
                           const int32_t *colidx, const double *values,
                           const double *x, double *y, const double *dotWith,
                           double *dot) {
#ifdef SIMIT_HAVE_AVX2_KERNELS
  if (hostHasAvx2Fma()) {
    multiplyBlocks3Avx2(rows, rowptr, colidx, values, x, y, dotWith, dot);
    return true;
  }
#endif
  (void)rows, (void)rowptr, (void)colidx, (void)values, (void)x, (void)y,
      (void)dotWith, (void)dot;
  return false;
}
