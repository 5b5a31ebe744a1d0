//===- StencilPattern.h - A grid stencil as a BCSR pattern -------*- C++ -*-===//
//
// A matrix assembled through a grid is stored by stencil offset: block
// k * |P| + r is (r, r + offset_k), periodic (docs/lowering.md). The
// runtime's sparse solvers take BCSR: this is the stencil's pattern, built
// once per binding, with the BCSR position of each stencil block; offsets
// that name one point (a grid narrower than them) share a position.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_STENCILPATTERN_H
#define SIMIT_RUNTIME_STENCILPATTERN_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace simit {

struct StencilPattern {
  /// BCSR over the grid's points: sorted, unique columns per row.
  std::vector<int32_t> rowPtr, colIdx;
  /// Per stencil block k * points + r, its position in colIdx.
  std::vector<int32_t> positions;

  /// The pattern of the stencil with `offsets` (each of the grid's rank) on
  /// the periodic grid of extents `dims` (the last axis varies fastest).
  static llvm::Expected<std::shared_ptr<const StencilPattern>>
  get(llvm::ArrayRef<int> dims,
      llvm::ArrayRef<std::vector<int64_t>> offsets);
};

} // namespace simit

#endif // SIMIT_RUNTIME_STENCILPATTERN_H
