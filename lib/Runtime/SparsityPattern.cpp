//===--- SparsityPattern.cpp - BCSR index of assembled matrices -----------===//

#include "simit/Runtime/SparsityPattern.h"

#include <algorithm>

using namespace simit;

llvm::Expected<std::shared_ptr<const SparsityPattern>>
SparsityPattern::get(const Set &edges, const Set &rows, const Set &cols) {
  auto isEndpoint = [&](const Set &set) {
    return llvm::is_contained(edges.endpointSetList(), &set);
  };
  if (!isEndpoint(rows) || !isEndpoint(cols))
    return llvm::createStringError(
        "sparsity pattern over (" + rows.name() + ", " + cols.name() +
        ") from set '" + edges.name() +
        "': expected endpoint sets of '" + edges.name() + "'");
  auto &cached = edges.patternCache[{&rows, &cols}];
  if (!cached || !cached->isCurrent(edges, rows, cols))
    cached = build(edges, rows, cols);
  return cached;
}

bool SparsityPattern::isCurrent(const Set &edges, const Set &rowSet,
                                const Set &colSet) const {
  return edges.version() == edgesVersion && rowSet.version() == rowsVersion &&
         colSet.version() == colsVersion;
}

std::shared_ptr<const SparsityPattern>
SparsityPattern::build(const Set &edges, const Set &rowSet,
                       const Set &colSet) {
  auto pattern = std::shared_ptr<SparsityPattern>(new SparsityPattern());
  int c = edges.cardinality();
  int n = edges.size();
  pattern->rows = rowSet.size();
  pattern->cols = colSet.size();
  pattern->cardinality = c;
  pattern->edgesVersion = edges.version();
  pattern->rowsVersion = rowSet.version();
  pattern->colsVersion = colSet.version();
  bool square = &rowSet == &colSet;

  // Which endpoint positions index rows and which index columns.
  std::vector<int> rowEnds, colEnds;
  for (int i = 0; i < c; ++i) {
    if (&edges.endpointSet(i) == &rowSet)
      rowEnds.push_back(i);
    if (&edges.endpointSet(i) == &colSet)
      colEnds.push_back(i);
  }

  // Incidence lists row -> edges touching it through a row endpoint.
  const int32_t *ends = edges.endpointData();
  std::vector<int32_t> incidenceStart(pattern->rows + 1, 0);
  for (int e = 0; e < n; ++e)
    for (int i : rowEnds)
      ++incidenceStart[ends[static_cast<size_t>(e) * c + i] + 1];
  for (int r = 0; r < pattern->rows; ++r)
    incidenceStart[r + 1] += incidenceStart[r];
  std::vector<int32_t> incidence(incidenceStart.back());
  std::vector<int32_t> fill(incidenceStart.begin(), incidenceStart.end() - 1);
  for (int e = 0; e < n; ++e)
    for (int i : rowEnds)
      incidence[fill[ends[static_cast<size_t>(e) * c + i]]++] = e;

  // Columns of each row: the column endpoints of its edges, plus (r, r).
  std::vector<int32_t> &rowPtr = pattern->rowPtr;
  std::vector<int32_t> &colIdx = pattern->colIdx;
  rowPtr.assign(1, 0);
  rowPtr.reserve(pattern->rows + 1);
  std::vector<int32_t> columns;
  for (int r = 0; r < pattern->rows; ++r) {
    columns.clear();
    if (square)
      columns.push_back(r);
    for (int k = incidenceStart[r]; k < incidenceStart[r + 1]; ++k) {
      const int32_t *edge = ends + static_cast<size_t>(incidence[k]) * c;
      for (int j : colEnds)
        columns.push_back(edge[j]);
    }
    std::sort(columns.begin(), columns.end());
    columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
    colIdx.insert(colIdx.end(), columns.begin(), columns.end());
    rowPtr.push_back(static_cast<int32_t>(colIdx.size()));
  }

  // The location of every (endpoint i, endpoint j) block of every edge.
  pattern->locationTable.assign(static_cast<size_t>(n) * c * c, -1);
  for (int e = 0; e < n; ++e) {
    const int32_t *edge = ends + static_cast<size_t>(e) * c;
    for (int i : rowEnds)
      for (int j : colEnds)
        pattern->locationTable[(static_cast<size_t>(e) * c + i) * c + j] =
            pattern->findBlock(edge[i], edge[j]);
  }
  return pattern;
}

std::shared_ptr<const SparsityPattern>
SparsityPattern::diagonal(const Set &set) {
  auto pattern = std::shared_ptr<SparsityPattern>(new SparsityPattern());
  pattern->rows = pattern->cols = set.size();
  pattern->rowPtr.resize(set.size() + 1);
  pattern->colIdx.resize(set.size());
  for (int r = 0; r <= set.size(); ++r)
    pattern->rowPtr[r] = r;
  for (int r = 0; r < set.size(); ++r)
    pattern->colIdx[r] = r;
  pattern->rowsVersion = pattern->colsVersion = set.version();
  return pattern;
}

std::shared_ptr<const SparsityPattern>
SparsityPattern::fromArrays(int numRows, int numCols,
                            std::vector<int32_t> rowPtr,
                            std::vector<int32_t> colIdx) {
  auto pattern = std::shared_ptr<SparsityPattern>(new SparsityPattern());
  pattern->rows = numRows;
  pattern->cols = numCols;
  pattern->rowPtr = std::move(rowPtr);
  pattern->colIdx = std::move(colIdx);
  return pattern;
}

int SparsityPattern::findBlock(int row, int col) const {
  if (row < 0 || row >= rows)
    return -1;
  auto begin = colIdx.begin() + rowPtr[row];
  auto end = colIdx.begin() + rowPtr[row + 1];
  auto it = std::lower_bound(begin, end, col);
  return it != end && *it == col ? static_cast<int>(it - colIdx.begin()) : -1;
}

BCSRMatrix::BCSRMatrix(std::shared_ptr<const SparsityPattern> pattern,
                       int blockRows, int blockCols)
    : pattern(std::move(pattern)), blockRows(blockRows),
      blockCols(blockCols),
      values(this->pattern->numBlocks() * blockSize(), 0.0) {}

void simit::multiply(const BCSRMatrix &a, const double *x, double *y) {
  const SparsityPattern &p = *a.pattern;
  int br = a.blockRows, bc = a.blockCols;
  llvm::ArrayRef<int32_t> rowPtr = p.rowPointers(), colIdx = p.columnIndices();
  for (int r = 0; r < p.numRows(); ++r) {
    double *yr = y + static_cast<size_t>(r) * br;
    std::fill(yr, yr + br, 0.0);
    for (int k = rowPtr[r]; k < rowPtr[r + 1]; ++k) {
      const double *block = a.block(k);
      const double *xc = x + static_cast<size_t>(colIdx[k]) * bc;
      for (int i = 0; i < br; ++i) {
        double sum = 0;
        for (int j = 0; j < bc; ++j)
          sum += block[i * bc + j] * xc[j];
        yr[i] += sum;
      }
    }
  }
}
