//===--- PatternAlgebra.cpp - Sparsity of sums and products ---------------===//

#include "simit/Runtime/PatternAlgebra.h"
#include "simit/Runtime/IncidenceView.h"

#include <algorithm>
#include <cassert>
#include <cstdint>

using namespace simit;

llvm::Expected<std::shared_ptr<const SparsityPattern>>
simit::unionPattern(llvm::ArrayRef<const Set *> edgeSets, const Set &rows,
                    const Set &cols) {
  std::vector<std::shared_ptr<const SparsityPattern>> owned;
  std::vector<const SparsityPattern *> members;
  for (const Set *edges : edgeSets) {
    // Over (E, V) or (V, E), E's own pattern is its incidence's.
    if (edges == &rows || edges == &cols) {
      bool transposed = edges == &cols;
      auto view =
          IncidenceView::get(*edges, transposed ? rows : cols, transposed);
      if (!view)
        return view.takeError();
      owned.push_back((*view)->pattern());
      members.push_back(owned.back().get());
      continue;
    }
    auto pattern = SparsityPattern::get(*edges, rows, cols);
    if (!pattern)
      return pattern.takeError();
    owned.push_back(*pattern);
    members.push_back(pattern->get());
  }
  if (owned.size() == 1)
    return owned.front();
  return unionPattern(members);
}

std::shared_ptr<const SparsityPattern>
simit::unionPattern(llvm::ArrayRef<const SparsityPattern *> members) {
  int rows = members.front()->numRows(), cols = members.front()->numCols();
  std::vector<int32_t> rowPtr{0}, colIdx;
  // Row by row, merge the members' sorted columns.
  std::vector<int32_t> cursor(members.size());
  for (int r = 0; r < rows; ++r) {
    for (size_t m = 0; m < members.size(); ++m)
      cursor[m] = members[m]->rowPointers()[r];
    while (true) {
      int32_t next = INT32_MAX;
      for (size_t m = 0; m < members.size(); ++m)
        if (cursor[m] < members[m]->rowPointers()[r + 1])
          next = std::min(next, members[m]->columnIndices()[cursor[m]]);
      if (next == INT32_MAX)
        break;
      colIdx.push_back(next);
      for (size_t m = 0; m < members.size(); ++m)
        if (cursor[m] < members[m]->rowPointers()[r + 1] &&
            members[m]->columnIndices()[cursor[m]] == next)
          ++cursor[m];
    }
    rowPtr.push_back(static_cast<int32_t>(colIdx.size()));
  }
  return SparsityPattern::fromArrays(rows, cols, std::move(rowPtr),
                                     std::move(colIdx));
}

std::vector<int32_t> simit::gatherPositions(const SparsityPattern &whole,
                                            const SparsityPattern &part) {
  std::vector<int32_t> positions(whole.numBlocks(), -1);
  llvm::ArrayRef<int32_t> wholePtr = whole.rowPointers(),
                          wholeCols = whole.columnIndices(),
                          partPtr = part.rowPointers(),
                          partCols = part.columnIndices();
  // Both rows are sorted: one merge per row.
  for (int r = 0; r < whole.numRows(); ++r) {
    int32_t k = partPtr[r];
    for (int32_t p = wholePtr[r]; p < wholePtr[r + 1]; ++p) {
      while (k < partPtr[r + 1] && partCols[k] < wholeCols[p])
        ++k;
      if (k < partPtr[r + 1] && partCols[k] == wholeCols[p])
        positions[p] = k;
    }
  }
  return positions;
}

std::vector<int32_t>
simit::gatherTransposedPositions(const SparsityPattern &whole,
                                 const SparsityPattern &part) {
  std::vector<int32_t> positions(whole.numBlocks(), -1);
  llvm::ArrayRef<int32_t> rowPtr = whole.rowPointers(),
                          cols = whole.columnIndices();
  for (int r = 0; r < whole.numRows(); ++r)
    for (int32_t p = rowPtr[r]; p < rowPtr[r + 1]; ++p)
      positions[p] = part.findBlock(cols[p], r);
  return positions;
}

std::shared_ptr<const SparsityPattern>
simit::productPattern(const SparsityPattern &a, const SparsityPattern &b,
                      bool withDiagonal) {
  std::vector<int32_t> rowPtr{0}, colIdx, columns;
  // Whether column c is already in the row being built.
  std::vector<bool> present(b.numCols(), false);
  for (int r = 0; r < a.numRows(); ++r) {
    columns.clear();
    auto add = [&](int32_t c) {
      if (!present[c]) {
        present[c] = true;
        columns.push_back(c);
      }
    };
    if (withDiagonal)
      add(r);
    for (int32_t ka = a.rowPointers()[r]; ka < a.rowPointers()[r + 1]; ++ka) {
      int32_t m = a.columnIndices()[ka];
      for (int32_t kb = b.rowPointers()[m]; kb < b.rowPointers()[m + 1]; ++kb)
        add(b.columnIndices()[kb]);
    }
    std::sort(columns.begin(), columns.end());
    for (int32_t c : columns)
      present[c] = false;
    colIdx.insert(colIdx.end(), columns.begin(), columns.end());
    rowPtr.push_back(static_cast<int32_t>(colIdx.size()));
  }
  return SparsityPattern::fromArrays(a.numRows(), b.numCols(),
                                     std::move(rowPtr), std::move(colIdx));
}

std::shared_ptr<const SparsityPattern>
simit::chainProductPattern(llvm::ArrayRef<const SparsityPattern *> factors,
                           llvm::ArrayRef<std::string> sets) {
  size_t k = factors.size();
  assert(k >= 2 && sets.size() == k + 1 && "a set between each two factors");
  // part[l][r]: the pattern of factors l..r (interval dynamic programming;
  // chains are short), the ones made here held in `made`.
  std::vector<std::vector<const SparsityPattern *>> part(
      k, std::vector<const SparsityPattern *>(k));
  std::vector<std::shared_ptr<const SparsityPattern>> made;
  for (size_t i = 0; i < k; ++i)
    part[i][i] = factors[i];
  for (size_t length = 2; length <= k; ++length)
    for (size_t l = 0; l + length <= k; ++l) {
      size_t r = l + length - 1;
      bool square = sets[l] == sets[r + 1];
      std::vector<std::shared_ptr<const SparsityPattern>> splits;
      std::vector<const SparsityPattern *> members;
      for (size_t m = l; m < r; ++m) {
        splits.push_back(
            productPattern(*part[l][m], *part[m + 1][r], square));
        members.push_back(splits.back().get());
      }
      made.push_back(splits.size() == 1 ? splits.front()
                                        : unionPattern(members));
      part[l][r] = made.back().get();
    }
  // The whole chain is the last part made (k >= 2).
  return made.back();
}
