//===--- CheckNumerics.cpp - The scan of --check-numerics -----------------===//

#include "simit/ABI/RuntimeFunctions.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/InterleavedRange.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

using simit::abi::DynamicMemRefView;
using simit::abi::MemRefDescriptor;
using simit::abi::UnrankedMemRefDescriptor;

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
                                          const int32_t *rowptr, int64_t rows,
                                          const int32_t *colidx, int64_t k,
                                          int64_t blocks) {
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
  case SIMIT_NUMERICS_DENSE:
    return {k / perRow, k % perRow};
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
std::string assembledFrom(const MemRefDescriptor<int32_t, 1> &endpoints,
                          int64_t cardinality, const char *set, int64_t row,
                          int64_t column) {
  const int64_t listed = 32;
  llvm::SmallVector<int64_t> found;
  int64_t count = 0;
  for (int64_t e = 0; e < endpoints.sizes[0] / cardinality; ++e) {
    bool hasRow = false, hasColumn = column < 0;
    for (int64_t k = 0; k < cardinality; ++k) {
      int32_t end = endpoints.data[endpoints.offset + (e * cardinality + k) *
                                                          endpoints.strides[0]];
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
  std::string text =
      ", assembled from " + std::string(set) + " " +
      llvm::join(
          llvm::map_range(found, [](int64_t e) { return std::to_string(e); }),
          ", ");
  if (count > listed)
    text += ", ... (" + std::to_string(count) + " in all)";
  return text;
}

template <typename T>
void checkNumerics(const UnrankedMemRefDescriptor<T> &values, int32_t layout,
                   int64_t perRow, const MemRefDescriptor<int32_t, 1> &rowptr,
                   const MemRefDescriptor<int32_t, 1> &colidx, const char *what,
                   const char *result, const char *rowSet, const char *colSet,
                   const MemRefDescriptor<int32_t, 1> &mapEndpoints,
                   int64_t mapCardinality, const char *mapSet) {
  DynamicMemRefView<T> array(values);
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
         << (std::isnan(value) ? "nan"
             : value > 0       ? "inf"
                               : "-inf")
         << ": " << result;
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
    UnrankedMemRefDescriptor<double> *values, int32_t layout, int64_t perRow,
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    const char *what, const char *result, const char *rowSet,
    const char *colSet, MemRefDescriptor<int32_t, 1> *mapEndpoints,
    int64_t mapCardinality, const char *mapSet) {
  checkNumerics(*values, layout, perRow, *rowptr, *colidx, what, result, rowSet,
                colSet, *mapEndpoints, mapCardinality, mapSet);
}

extern "C" void _mlir_ciface_simit_rt_check_numerics_f32(
    UnrankedMemRefDescriptor<float> *values, int32_t layout, int64_t perRow,
    MemRefDescriptor<int32_t, 1> *rowptr, MemRefDescriptor<int32_t, 1> *colidx,
    const char *what, const char *result, const char *rowSet,
    const char *colSet, MemRefDescriptor<int32_t, 1> *mapEndpoints,
    int64_t mapCardinality, const char *mapSet) {
  checkNumerics(*values, layout, perRow, *rowptr, *colidx, what, result, rowSet,
                colSet, *mapEndpoints, mapCardinality, mapSet);
}
