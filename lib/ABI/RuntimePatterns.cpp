//===--- RuntimePatterns.cpp - Patterns known only at run time ------------===//
//
// A host function (`extern func`) returns a system matrix as BCSR arrays it
// allocated itself, in the original Simit runtime's convention. Lowered code
// checks them here before it trusts a single index, then copies them into
// arrays of its own (rows sorted by column, as every BCSR consumer of the
// runtime expects) and frees the host's. Products, sums and transposes of
// such a matrix get their patterns here too, each time they are computed.
//
//===----------------------------------------------------------------------===//

#include "RunState.h"

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/PatternAlgebra.h"
#include "simit/Runtime/SparsityPattern.h"
#include "simit/ffi.h"

#include "llvm/Support/FormatVariadic.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <numeric>
#include <vector>

using simit::abi::abandonRun;
using simit::abi::fail;
using simit::abi::MemRefDescriptor;

void *simit::ffi::simit_malloc(std::size_t bytes) { return std::malloc(bytes); }

void simit::ffi::simit_free(void *memory) { std::free(memory); }

namespace {
void freeHostArrays(int32_t *rowptr, int32_t *colidx, void *blocks) {
  std::free(rowptr);
  std::free(colidx);
  std::free(blocks);
}

/// The message for the first way the arrays are malformed, else empty.
std::string checkArrays(const int32_t *rowptr, const int32_t *colidx,
                        const void *blocks, int64_t rowBlocks,
                        int64_t colBlocks) {
  if (!rowptr)
    return "returned a matrix without row pointers";
  if (rowptr[0] != 0)
    return llvm::formatv("returned a matrix whose row pointers start at {0}, "
                         "not 0",
                         rowptr[0]);
  for (int64_t r = 0; r < rowBlocks; ++r)
    if (rowptr[r + 1] < rowptr[r])
      return llvm::formatv("returned a matrix whose row pointers decrease at "
                           "block row {0} ({1} then {2})",
                           r, rowptr[r], rowptr[r + 1]);
  if (rowptr[rowBlocks] > 0 && (!colidx || !blocks))
    return llvm::formatv("returned a matrix of {0} blocks without column "
                         "indices or blocks",
                         rowptr[rowBlocks]);
  std::vector<int32_t> columns;
  for (int64_t r = 0; r < rowBlocks; ++r) {
    columns.assign(colidx + rowptr[r], colidx + rowptr[r + 1]);
    for (int32_t c : columns)
      if (c < 0 || c >= colBlocks)
        return llvm::formatv("returned a matrix with a block at (block row "
                             "{0}, block column {1}) outside its {2} block "
                             "columns",
                             r, c, colBlocks);
    std::sort(columns.begin(), columns.end());
    auto twice = std::adjacent_find(columns.begin(), columns.end());
    if (twice != columns.end())
      return llvm::formatv("returned a matrix with two blocks at (block row "
                           "{0}, block column {1})",
                           r, *twice);
  }
  return {};
}
} // namespace

/// Whether the arrays are well formed; if not, frees them and records the
/// failure (before abandonRun, which runs no destructors).
static bool acceptArrays(int32_t *rowptr, int32_t *colidx, void *blocks,
                         int64_t rowBlocks, int64_t colBlocks,
                         const char *where) {
  std::string problem =
      checkArrays(rowptr, colidx, blocks, rowBlocks, colBlocks);
  if (problem.empty())
    return true;
  freeHostArrays(rowptr, colidx, blocks);
  return fail(where, problem);
}

extern "C" int64_t simit_rt_host_matrix_blocks(int32_t *rowptr, int32_t *colidx,
                                               void *blocks, int64_t rowBlocks,
                                               int64_t colBlocks,
                                               const char *where) {
  if (!acceptArrays(rowptr, colidx, blocks, rowBlocks, colBlocks, where))
    abandonRun();
  return rowptr[rowBlocks];
}

extern "C" int32_t simit_rt_host_matrix_adopt(int32_t *rowptr, int32_t *colidx,
                                              void *blocks, int64_t rowBlocks,
                                              int64_t blockBytes,
                                              int32_t *rowptrOut,
                                              int32_t *colidxOut,
                                              void *blocksOut) {
  std::memcpy(rowptrOut, rowptr, (rowBlocks + 1) * sizeof(int32_t));
  const char *from = static_cast<const char *>(blocks);
  char *to = static_cast<char *>(blocksOut);
  std::vector<int32_t> order;
  for (int64_t r = 0; r < rowBlocks; ++r) {
    order.resize(rowptr[r + 1] - rowptr[r]);
    std::iota(order.begin(), order.end(), rowptr[r]);
    std::sort(order.begin(), order.end(),
              [&](int32_t a, int32_t b) { return colidx[a] < colidx[b]; });
    for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k) {
      int32_t source = order[k - rowptr[r]];
      colidxOut[k] = colidx[source];
      std::memcpy(to + k * blockBytes, from + source * blockBytes, blockBytes);
    }
  }
  freeHostArrays(rowptr, colidx, blocks);
  return 0;
}

namespace {
using IndexArray = MemRefDescriptor<int32_t, 1>;

/// A BCSR pattern of lowered code's arrays, as the runtime's pattern
/// algebra takes it.
std::shared_ptr<const simit::SparsityPattern>
patternOf(const IndexArray *rowptr, const IndexArray *colidx, int64_t cols) {
  const int32_t *r = rowptr->data + rowptr->offset;
  const int32_t *c = colidx->data + colidx->offset;
  int64_t rows = rowptr->sizes[0] - 1;
  return simit::SparsityPattern::fromArrays(
      static_cast<int>(rows), static_cast<int>(cols),
      std::vector<int32_t>(r, r + rows + 1),
      std::vector<int32_t>(c, c + r[rows]));
}

/// What simit_rt_product_pattern and simit_rt_union_pattern return.
struct PatternHandle {
  std::shared_ptr<const simit::SparsityPattern> pattern;
};
} // namespace

extern "C" void *_mlir_ciface_simit_rt_product_pattern(IndexArray *rowptrA,
                                                       IndexArray *colidxA,
                                                       IndexArray *rowptrB,
                                                       IndexArray *colidxB,
                                                       int64_t cols) {
  int64_t mid = rowptrB->sizes[0] - 1;
  return new PatternHandle{simit::productPattern(
      *patternOf(rowptrA, colidxA, mid), *patternOf(rowptrB, colidxB, cols),
      /*withDiagonal=*/false)};
}

extern "C" void *_mlir_ciface_simit_rt_union_pattern(IndexArray *rowptrA,
                                                     IndexArray *colidxA,
                                                     IndexArray *rowptrB,
                                                     IndexArray *colidxB,
                                                     int64_t cols) {
  auto a = patternOf(rowptrA, colidxA, cols);
  auto b = patternOf(rowptrB, colidxB, cols);
  return new PatternHandle{simit::unionPattern({a.get(), b.get()})};
}

extern "C" void *_mlir_ciface_simit_rt_transpose_pattern(IndexArray *rowptr,
                                                         IndexArray *colidx,
                                                         int64_t cols) {
  const int32_t *r = rowptr->data + rowptr->offset;
  const int32_t *c = colidx->data + colidx->offset;
  int64_t rows = rowptr->sizes[0] - 1;
  // Counting sort by column; rows visited in order keep each transposed
  // row sorted.
  std::vector<int32_t> start(cols + 1, 0), columns(r[rows]);
  for (int32_t k = 0; k < r[rows]; ++k)
    ++start[c[k] + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int32_t> next(start.begin(), start.end() - 1);
  for (int64_t row = 0; row < rows; ++row)
    for (int32_t k = r[row]; k < r[row + 1]; ++k)
      columns[next[c[k]]++] = static_cast<int32_t>(row);
  return new PatternHandle{simit::SparsityPattern::fromArrays(
      static_cast<int>(cols), static_cast<int>(rows), std::move(start),
      std::move(columns))};
}

extern "C" int64_t simit_rt_pattern_blocks(void *handle) {
  return static_cast<PatternHandle *>(handle)->pattern->numBlocks();
}

extern "C" void _mlir_ciface_simit_rt_pattern_take(void *handle,
                                                   IndexArray *rowptr,
                                                   IndexArray *colidx) {
  auto *pattern = static_cast<PatternHandle *>(handle);
  llvm::ArrayRef<int32_t> r = pattern->pattern->rowPointers();
  llvm::ArrayRef<int32_t> c = pattern->pattern->columnIndices();
  std::copy(r.begin(), r.end(), rowptr->data + rowptr->offset);
  std::copy(c.begin(), c.end(), colidx->data + colidx->offset);
  delete pattern;
}
