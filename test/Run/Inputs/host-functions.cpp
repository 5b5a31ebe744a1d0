// C functions of the extern funcs of host-functions.sim, with the original
// Simit runtime's conventions (docs/lowering.md, "Host functions"): a 'd'
// prefix for float64, an int status, parameters then results.

#include <cmath>

extern "C" {

static int calls = 0;

// No float crosses: no prefix.
int count_calls(int *count) {
  *count = ++calls;
  return 0;
}

int dscaled(double a, int n, const double *v, int wn, double *w, double *sum) {
  if (n != 3 || wn != 3)
    return 1;
  *sum = 0;
  for (int i = 0; i < n; ++i) {
    w[i] = a * v[i];
    *sum += w[i];
  }
  return 0;
}

// y = A x on BCSR blocks of blockRows x blockCols; rows, cols and vector
// lengths count components, as the original runtime passes them.
int dgemv(int rows, int cols, const int *rowptr, const int *colidx,
          int blockRows, int blockCols, const double *blocks, int xn,
          const double *x, int yn, double *y) {
  if (xn != cols || yn != rows || rows % blockRows || cols % blockCols)
    return 2;
  for (int i = 0; i < rows; ++i)
    y[i] = 0;
  for (int r = 0; r < rows / blockRows; ++r)
    for (int k = rowptr[r]; k < rowptr[r + 1]; ++k)
      for (int i = 0; i < blockRows; ++i)
        for (int j = 0; j < blockCols; ++j)
          y[r * blockRows + i] +=
              blocks[(k * blockRows + i) * blockCols + j] *
              x[colidx[k] * blockCols + j];
  return 0;
}

// An opaque handle: a result and a parameter by the address of the handle
// (the original runtime's ffi/opaque test's convention).
int make_counter(int start, void **handle) {
  static int counter;
  counter = start;
  *handle = &counter;
  return 0;
}

int bump_counter(void **handle, int *n) {
  *n = ++*static_cast<int *>(*handle);
  return 0;
}

// A status other than 0 ends the run.
int dfails(double a, double *b) {
  *b = a;
  return 7;
}
}
