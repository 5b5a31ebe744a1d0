// C functions of the extern funcs of host-matrices.sim and
// host-matrices-blocked.sim: matrix results in the original Simit
// runtime's convention (docs/lowering.md, "Host functions"), three arrays
// the host mallocs and Simit frees.

#include "simit/ffi.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <initializer_list>

namespace {
// The original runtime's simit_malloc (what the process of simit-run
// defines) and plain malloc both serve.
template <typename T>
void allocate(int blockRows, int blocks, int blockSize, int **rowptr,
              int **colidx, T **values) {
  *rowptr = static_cast<int *>(
      simit::ffi::simit_malloc((blockRows + 1) * sizeof(int)));
  *colidx = static_cast<int *>(simit::ffi::simit_malloc(blocks * sizeof(int)));
  *values = static_cast<T *>(std::malloc(blocks * blockSize * sizeof(T)));
}

// -B on B's pattern, each row's blocks stored in descending column order
// (Simit sorts them).
template <typename T>
void negate(int rows, int, const int *rowptr, const int *colidx, int blockRows,
            int blockCols, const T *b, int, int, int **resultRowptr,
            int **resultColidx, int, int, T **result) {
  int n = rows / blockRows, blocks = rowptr[n], size = blockRows * blockCols;
  allocate(n, blocks, size, resultRowptr, resultColidx, result);
  std::memcpy(*resultRowptr, rowptr, (n + 1) * sizeof(int));
  for (int r = 0; r < n; ++r)
    for (int k = rowptr[r], to = rowptr[r + 1] - 1; k < rowptr[r + 1];
         ++k, --to) {
      (*resultColidx)[to] = colidx[k];
      for (int c = 0; c < size; ++c)
        (*result)[to * size + c] = -b[k * size + c];
    }
}

// Blocks of value 1 in row 0 only, at `columns`.
int firstRowOnly(int rows, std::initializer_list<int> columns, int **rowptr,
                 int **colidx, double **values) {
  int blocks = static_cast<int>(columns.size());
  allocate(rows, blocks, 1, rowptr, colidx, values);
  for (int r = 0; r <= rows; ++r)
    (*rowptr)[r] = r == 0 ? 0 : blocks;
  std::copy(columns.begin(), columns.end(), *colidx);
  std::fill(*values, *values + blocks, 1.0);
  return 0;
}
} // namespace

extern "C" {

// void, as the original runtime's test declares it.
void dmatrix_neg(int rows, int cols, int *rowptr, int *colidx, int blockRows,
                 int blockCols, double *b, int resultRows, int resultCols,
                 int **resultRowptr, int **resultColidx, int resultBlockRows,
                 int resultBlockCols, double **result) {
  negate(rows, cols, rowptr, colidx, blockRows, blockCols, b, resultRows,
         resultCols, resultRowptr, resultColidx, resultBlockRows,
         resultBlockCols, result);
}

void smatrix_neg(int rows, int cols, int *rowptr, int *colidx, int blockRows,
                 int blockCols, float *b, int resultRows, int resultCols,
                 int **resultRowptr, int **resultColidx, int resultBlockRows,
                 int resultBlockCols, float **result) {
  negate(rows, cols, rowptr, colidx, blockRows, blockCols, b, resultRows,
         resultCols, resultRowptr, resultColidx, resultBlockRows,
         resultBlockCols, result);
}

// The n x n tridiagonal matrix with 4 on the diagonal and -1 beside it.
int dtridiagonal(int rows, int, int **rowptr, int **colidx, int, int,
                 double **values) {
  allocate(rows, 3 * rows, 1, rowptr, colidx, values);
  int k = 0;
  for (int r = 0; r < rows; ++r) {
    (*rowptr)[r] = k;
    for (int c = r - 1; c <= r + 1; ++c)
      if (c >= 0 && c < rows) {
        (*colidx)[k] = c;
        (*values)[k++] = c == r ? 4.0 : -1.0;
      }
  }
  (*rowptr)[rows] = k;
  return 0;
}

// One block in row 0, at column `rows` (outside the matrix).
int doutside(int rows, int, int **rowptr, int **colidx, int, int,
             double **values) {
  return firstRowOnly(rows, {rows}, rowptr, colidx, values);
}

// A function without floats defined with the precision's prefix, as the
// original runtime's later versions name every host function.
int dseven(int *v) {
  *v = 7;
  return 0;
}

// Row 0 holds column 0 twice.
int dtwice(int rows, int, int **rowptr, int **colidx, int, int,
           double **values) {
  return firstRowOnly(rows, {0, 0}, rowptr, colidx, values);
}
}
