//===--- SimdKernels.h - Vector-unit kernels of the runtime's solvers -----===//
//
// Kernels written for a vector extension, chosen at run time when the host
// has it, so that the runtime library stays buildable for any x86-64 (or
// other) target and still uses the host's vector unit. Each returns false
// (and does nothing) where its extension is missing; the caller then runs
// its portable loop.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_SIMDKERNELS_H
#define SIMIT_LIB_RUNTIME_SIMDKERNELS_H

#include <cstdint>

namespace simit::simd {

/// y = A x for A of `rows` block rows of 3x3 row-major blocks (rowptr,
/// colidx as in SquareBCSRView); when `dotWith` is non-null, `*dot` =
/// dotWith . y summed in row order. AVX2 with FMA; the sums of a row are
/// taken in another order than the portable loop's.
bool multiplyBlocks3(int64_t rows, const int32_t *rowptr,
                     const int32_t *colidx, const double *values,
                     const double *x, double *y, const double *dotWith,
                     double *dot);

} // namespace simit::simd

#endif // SIMIT_LIB_RUNTIME_SIMDKERNELS_H
