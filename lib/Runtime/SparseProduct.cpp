//===--- SparseProduct.cpp - Products of block sparse matrices ------------===//
//
// Row by row (Gustavson): C's row r is zeroed, its columns are marked with
// their positions, and every A(r, m) B(m, c) adds into the marked block.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/SparseProduct.h"

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

using namespace simit;

/// sum + x y; int products wrap at 32 bits, as the language's `+` and `*`.
template <typename T> static T multiplyAdd(T sum, T x, T y) {
  if constexpr (std::is_integral_v<T>)
    return static_cast<T>(static_cast<uint32_t>(sum) +
                          static_cast<uint32_t>(x) * static_cast<uint32_t>(y));
  else
    return sum + x * y;
}

template <typename T>
llvm::Error simit::multiplyInto(const BlockMatrixView<T> &a,
                                const BlockMatrixView<T> &b,
                                const BlockMatrixView<T> &c) {
  if (c.positions)
    return llvm::createStringError(
        "matrix product: the result must be BCSR or block diagonal");
  if (a.cols != b.rows || a.blockCols != b.blockRows || c.rows != a.rows ||
      c.cols != b.cols || c.blockRows != a.blockRows ||
      c.blockCols != b.blockCols)
    return llvm::createStringError(
        "matrix product: shapes do not agree (" + llvm::Twine(a.rows) + "x" +
        llvm::Twine(a.cols) + " by " + llvm::Twine(b.rows) + "x" +
        llvm::Twine(b.cols) + " blocks into " + llvm::Twine(c.rows) + "x" +
        llvm::Twine(c.cols) + ")");
  int64_t br = a.blockRows, bm = a.blockCols, bc = b.blockCols;
  std::vector<int64_t> position(c.cols, -1);
  for (int64_t r = 0; r < a.rows; ++r) {
    for (int64_t p = c.begin(r); p < c.end(r); ++p) {
      position[c.column(p)] = p;
      std::fill(c.block(p), c.block(p) + br * bc, T(0));
    }
    for (int64_t ka = a.begin(r); ka < a.end(r); ++ka) {
      int64_t m = a.column(ka);
      const T *left = a.block(ka);
      for (int64_t kb = b.begin(m); kb < b.end(m); ++kb) {
        int64_t p = position[b.column(kb)];
        if (p < 0)
          return llvm::createStringError(
              "matrix product: block (" + llvm::Twine(r) + ", " +
              llvm::Twine(b.column(kb)) +
              ") of the product is not in the result's pattern");
        const T *right = b.block(kb);
        T *out = c.block(p);
        for (int64_t i = 0; i < br; ++i)
          for (int64_t k = 0; k < bm; ++k) {
            T x = left[i * bm + k];
            for (int64_t j = 0; j < bc; ++j)
              out[i * bc + j] =
                  multiplyAdd(out[i * bc + j], x, right[k * bc + j]);
          }
      }
    }
    for (int64_t p = c.begin(r); p < c.end(r); ++p)
      position[c.column(p)] = -1;
  }
  return llvm::Error::success();
}

template llvm::Error simit::multiplyInto(const BlockMatrixView<double> &,
                                         const BlockMatrixView<double> &,
                                         const BlockMatrixView<double> &);
template llvm::Error simit::multiplyInto(const BlockMatrixView<float> &,
                                         const BlockMatrixView<float> &,
                                         const BlockMatrixView<float> &);
template llvm::Error simit::multiplyInto(const BlockMatrixView<int32_t> &,
                                         const BlockMatrixView<int32_t> &,
                                         const BlockMatrixView<int32_t> &);
