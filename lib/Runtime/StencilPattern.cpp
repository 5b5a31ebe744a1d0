//===--- StencilPattern.cpp - A grid stencil as a BCSR pattern ------------===//

#include "simit/Runtime/StencilPattern.h"

#include <algorithm>
#include <limits>

using namespace simit;

llvm::Expected<std::shared_ptr<const StencilPattern>>
StencilPattern::get(llvm::ArrayRef<int> dims,
                    llvm::ArrayRef<std::vector<int64_t>> offsets) {
  int64_t points = 1;
  for (int extent : dims) {
    if (extent < 1)
      return llvm::createStringError("a grid extent must be positive");
    points *= extent;
  }
  int64_t blocks = points * static_cast<int64_t>(offsets.size());
  if (blocks > std::numeric_limits<int32_t>::max())
    return llvm::createStringError(
        "the stencil has more blocks than 32-bit indices hold");
  for (const std::vector<int64_t> &offset : offsets)
    if (offset.size() != dims.size())
      return llvm::createStringError(
          "a stencil offset does not have the grid's rank");
  auto pattern = std::make_shared<StencilPattern>();
  pattern->rowPtr.reserve(points + 1);
  pattern->rowPtr.push_back(0);
  pattern->positions.assign(blocks, -1);
  std::vector<int32_t> columns(offsets.size()), coordinates(dims.size());
  for (int64_t r = 0; r < points; ++r) {
    // The row's coordinates, the last axis fastest.
    int64_t rest = r;
    for (size_t a = dims.size(); a-- > 0;) {
      coordinates[a] = rest % dims[a];
      rest /= dims[a];
    }
    for (size_t k = 0; k < offsets.size(); ++k) {
      int64_t column = 0;
      for (size_t a = 0; a < dims.size(); ++a) {
        int64_t moved = (coordinates[a] + offsets[k][a]) % dims[a];
        column = column * dims[a] + (moved + dims[a]) % dims[a];
      }
      columns[k] = static_cast<int32_t>(column);
    }
    std::vector<int32_t> unique(columns);
    std::sort(unique.begin(), unique.end());
    unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
    int32_t first = pattern->rowPtr.back();
    for (size_t k = 0; k < offsets.size(); ++k)
      pattern->positions[k * points + r] =
          first + static_cast<int32_t>(
                      std::lower_bound(unique.begin(), unique.end(),
                                       columns[k]) -
                      unique.begin());
    pattern->colIdx.insert(pattern->colIdx.end(), unique.begin(), unique.end());
    pattern->rowPtr.push_back(static_cast<int32_t>(pattern->colIdx.size()));
  }
  return pattern;
}
