//===--- SparsityPattern.h - BCSR index of assembled matrices ---*- C++ -*-===//
//
// The block sparsity of a matrix assembled by mapping over an edge set
// (paper, section 6.1, "K index"): block row r holds the columns of every
// element of the column set that shares an edge with r through the chosen
// endpoint sets. Layout (shared with JIT-compiled code):
//  - rowPtr has numRows() + 1 int32 entries; the blocks of row r are
//    rowPtr[r] .. rowPtr[r+1]-1, with their block columns in colIdx, sorted
//    ascending without duplicates.
//  - The value array of a matrix with b_r x b_c blocks holds numBlocks()
//    blocks, block k at values[k * b_r * b_c], each block row-major.
//  - The location table has size() * c * c int32 entries for an edge set of
//    cardinality c: locations[(e * c + i) * c + j] is the block index k of
//    (endpoint_i(e), endpoint_j(e)) when endpoint i belongs to the row set
//    and endpoint j to the column set, and -1 otherwise. Assembly stores
//    into values[k * b_r * b_c] without searching.
//  - When the row and column sets are the same set, every diagonal block
//    (r, r) is present, also for rows no edge touches, so vertex-set
//    contributions M(p, p) can be added into the same matrix.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SPARSITYPATTERN_H
#define SIMIT_RUNTIME_SPARSITYPATTERN_H

#include "simit/Runtime/Set.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace simit {

class SparsityPattern {
public:
  /// The pattern of the matrix over (rows, cols) assembled from `edges`;
  /// rows and cols must be endpoint sets of `edges`. Built once and cached
  /// on the edge set; rebuilt when any of the three sets changed structure
  /// since. Matrices assembled from the same sets share the result.
  static llvm::Expected<std::shared_ptr<const SparsityPattern>>
  get(const Set &edges, const Set &rows, const Set &cols);

  /// The diagonal pattern of a matrix over (set, set) assembled from a map
  /// over `set` itself: block r is (r, r). Not cached (it is trivial).
  static std::shared_ptr<const SparsityPattern> diagonal(const Set &set);

  /// A pattern from explicit arrays (no location table); for tests and for
  /// matrices built outside assembly. The arrays must be well formed.
  static std::shared_ptr<const SparsityPattern>
  fromArrays(int numRows, int numCols, std::vector<int32_t> rowPtr,
             std::vector<int32_t> colIdx);

  int numRows() const { return rows; }
  int numCols() const { return cols; }
  int numBlocks() const { return static_cast<int>(colIdx.size()); }
  llvm::ArrayRef<int32_t> rowPointers() const { return rowPtr; }
  llvm::ArrayRef<int32_t> columnIndices() const { return colIdx; }
  /// The per-edge location table (empty for diagonal and explicit
  /// patterns); see the layout above.
  llvm::ArrayRef<int32_t> locations() const { return locationTable; }
  /// Endpoints per edge of the table (c), 0 without one.
  int locationCardinality() const { return cardinality; }
  int location(int edge, int i, int j) const {
    return locationTable[(static_cast<size_t>(edge) * cardinality + i) *
                             cardinality +
                         j];
  }
  /// The block index of (row, col), or -1 when it is not in the pattern
  /// (binary search; assembly uses the location table instead).
  int findBlock(int row, int col) const;

  /// Whether the pattern was built from these sets at their current
  /// versions.
  bool isCurrent(const Set &edges, const Set &rows, const Set &cols) const;

private:
  SparsityPattern() = default;
  static std::shared_ptr<const SparsityPattern>
  build(const Set &edges, const Set &rows, const Set &cols);

  int rows = 0, cols = 0, cardinality = 0;
  std::vector<int32_t> rowPtr, colIdx, locationTable;
  uint64_t edgesVersion = 0, rowsVersion = 0, colsVersion = 0;
};

/// A block sparse matrix: a shared pattern and its values, blocks of
/// blockRows x blockCols doubles (layout above).
struct BCSRMatrix {
  std::shared_ptr<const SparsityPattern> pattern;
  int blockRows = 1, blockCols = 1;
  std::vector<double> values;

  BCSRMatrix() = default;
  /// A zero matrix over `pattern`.
  BCSRMatrix(std::shared_ptr<const SparsityPattern> pattern, int blockRows,
             int blockCols);
  size_t blockSize() const {
    return static_cast<size_t>(blockRows) * blockCols;
  }
  double *block(int k) { return values.data() + k * blockSize(); }
  const double *block(int k) const { return values.data() + k * blockSize(); }
};

/// y = A x for a BCSR matrix: x has numCols() * blockCols entries, y gets
/// numRows() * blockRows. The reference SpMV of tests and solvers.
void multiply(const BCSRMatrix &a, const double *x, double *y);

} // namespace simit

#endif // SIMIT_RUNTIME_SPARSITYPATTERN_H
