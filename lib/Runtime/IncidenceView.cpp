//===--- IncidenceView.cpp - Incidence matrices row by row ----------------===//

#include "simit/Runtime/IncidenceView.h"

#include <algorithm>

using namespace simit;

llvm::Expected<std::shared_ptr<const IncidenceView>>
IncidenceView::get(const Set &edges, const Set &endpoints, bool transposed) {
  int c = edges.cardinality();
  if (c == 0)
    return llvm::createStringError("'" + edges.name() +
                                   "' is not an edge set");
  std::vector<int> held;
  for (int k = 0; k < c; ++k)
    if (&edges.endpointSet(k) == &endpoints)
      held.push_back(k);
  if (held.empty())
    return llvm::createStringError("no endpoint of '" + edges.name() +
                                   "' is in '" + endpoints.name() + "'");
  auto view = std::make_shared<IncidenceView>();
  int numEdges = edges.size();
  int m = static_cast<int>(held.size());
  size_t numBlocks = static_cast<size_t>(numEdges) * m;
  const int32_t *endpointData = edges.endpointData();
  // Block b = e * m + j is edge e's endpoint at position held[j].
  auto endpointOf = [&](size_t block) {
    return endpointData[block / m * c + held[block % m]];
  };
  if (!transposed) {
    // Row e is edge e's blocks in endpoint order.
    view->rows = numEdges;
    view->cols = endpoints.size();
    view->rowPtr.resize(numEdges + 1);
    for (int e = 0; e <= numEdges; ++e)
      view->rowPtr[e] = e * m;
    view->colIdx.resize(numBlocks);
    view->positions.resize(numBlocks);
    for (size_t k = 0; k < numBlocks; ++k) {
      view->colIdx[k] = endpointOf(k);
      view->positions[k] = static_cast<int32_t>(k);
    }
    return view;
  }
  // Row v holds block e * m + j of every edge e whose held[j]-th endpoint
  // is v, by increasing edge (a counting sort on v, stable in e and j).
  view->rows = endpoints.size();
  view->cols = numEdges;
  view->rowPtr.assign(view->rows + 1, 0);
  for (size_t k = 0; k < numBlocks; ++k)
    ++view->rowPtr[endpointOf(k) + 1];
  for (int v = 0; v < view->rows; ++v)
    view->rowPtr[v + 1] += view->rowPtr[v];
  std::vector<int32_t> next(view->rowPtr.begin(), view->rowPtr.end() - 1);
  view->colIdx.resize(numBlocks);
  view->positions.resize(numBlocks);
  for (size_t k = 0; k < numBlocks; ++k) {
    int32_t at = next[endpointOf(k)]++;
    view->colIdx[at] = static_cast<int32_t>(k / m);
    view->positions[at] = static_cast<int32_t>(k);
  }
  return view;
}

std::shared_ptr<const SparsityPattern> IncidenceView::pattern() const {
  std::vector<int32_t> patternRows{0}, patternCols;
  patternCols.reserve(colIdx.size());
  for (int r = 0; r < rows; ++r) {
    size_t first = patternCols.size();
    patternCols.insert(patternCols.end(), colIdx.begin() + rowPtr[r],
                       colIdx.begin() + rowPtr[r + 1]);
    std::sort(patternCols.begin() + first, patternCols.end());
    patternCols.erase(
        std::unique(patternCols.begin() + first, patternCols.end()),
        patternCols.end());
    patternRows.push_back(static_cast<int32_t>(patternCols.size()));
  }
  return SparsityPattern::fromArrays(rows, cols, std::move(patternRows),
                                     std::move(patternCols));
}
