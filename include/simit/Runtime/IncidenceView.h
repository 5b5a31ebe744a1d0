//===--- IncidenceView.h - Incidence matrices row by row --------*- C++ -*-===//
//
// A matrix over (E, V) assembled from edge set E stores, for edge e, one
// block per endpoint position k in V at value position e * m + j, j the
// rank of k among the m positions in V: all c positions of a homogeneous
// edge set, some of a heterogeneous one (the loop lowering's incidence
// layout, docs/storage.md). Its transpose over (V, E)
// shares that array. A product with an incidence factor reads it row by
// row: the view lists each row's blocks with their columns and value
// positions, built once per binding. An edge that names a vertex twice
// keeps two blocks in that row, at the same column.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_INCIDENCEVIEW_H
#define SIMIT_RUNTIME_INCIDENCEVIEW_H

#include "simit/Runtime/SparsityPattern.h"

#include "llvm/Support/Error.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace simit {

struct IncidenceView {
  int rows = 0, cols = 0;
  /// Row r's blocks are rowPtr[r] .. rowPtr[r + 1] - 1: block k is at
  /// column colIdx[k] and value position positions[k].
  std::vector<int32_t> rowPtr, colIdx, positions;

  /// The view of the incidence of `edges` over (edges, endpoints), or of
  /// its transpose over (endpoints, edges), at the endpoint positions in
  /// `endpoints` (at least one).
  static llvm::Expected<std::shared_ptr<const IncidenceView>>
  get(const Set &edges, const Set &endpoints, bool transposed);

  /// The blocks as a pattern (columns sorted, repeated ones merged).
  std::shared_ptr<const SparsityPattern> pattern() const;
};

} // namespace simit

#endif // SIMIT_RUNTIME_INCIDENCEVIEW_H
