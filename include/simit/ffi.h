//===--- ffi.h - For the C functions of extern funcs ------------*- C++ -*-===//
//
// Host libraries implementing a Simit program's `extern func`s may include
// this header (docs/lowering.md, "Host functions"). A function with a
// matrix result allocates its three BCSR arrays with simit_malloc (the
// original Simit runtime's name; std::malloc serves as well): Simit frees
// them once it has copied them. convertToCSR expands a BCSR argument into
// scalar CSR, as the original's helper of that name does. Depends on
// nothing but the C++ library.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FFI_H
#define SIMIT_FFI_H

#include <cstddef>
#include <cstdlib>

namespace simit {
namespace ffi {

/// Memory Simit frees with std::free: the arrays of a matrix result.
void *simit_malloc(std::size_t bytes);
/// Frees memory of simit_malloc.
void simit_free(void *memory);

/// The scalar CSR arrays of a BCSR matrix of `rows` x `cols` components in
/// blocks of blockRows x blockCols (the arguments a host function receives
/// for a matrix): row pointers (rows + 1), column indices and values, each
/// block's every component, columns ascending; allocated with std::malloc
/// for the caller to free.
template <typename T>
void convertToCSR(const T *blocks, const int *rowptr, const int *colidx,
                  int rows, int cols, int blockRows, int blockCols,
                  int **csrRowptr, int **csrColidx, T **csrValues) {
  (void)cols;
  int blockRowCount = rows / blockRows;
  int entries = rowptr[blockRowCount] * blockRows * blockCols;
  *csrRowptr = static_cast<int *>(std::malloc((rows + 1) * sizeof(int)));
  *csrColidx = static_cast<int *>(std::malloc(entries * sizeof(int)));
  *csrValues = static_cast<T *>(std::malloc(entries * sizeof(T)));
  int k = 0;
  for (int r = 0; r < blockRowCount; ++r)
    for (int i = 0; i < blockRows; ++i) {
      (*csrRowptr)[r * blockRows + i] = k;
      for (int b = rowptr[r]; b < rowptr[r + 1]; ++b)
        for (int j = 0; j < blockCols; ++j, ++k) {
          (*csrColidx)[k] = colidx[b] * blockCols + j;
          (*csrValues)[k] = blocks[(b * blockRows + i) * blockCols + j];
        }
    }
  (*csrRowptr)[rows] = k;
}

} // namespace ffi
} // namespace simit

#endif // SIMIT_FFI_H
