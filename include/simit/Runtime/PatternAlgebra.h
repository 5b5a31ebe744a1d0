//===--- PatternAlgebra.h - Sparsity of sums and products -------*- C++ -*-===//
//
// Assembled patterns are fixed per set binding, and so are the patterns of
// sums and products of assembled matrices: they are built once per binding.
//  - `A + B`, with A and B assembled from different edge sets over the same
//    (rows, cols), is stored on the union of their patterns, with gather
//    maps: for every block position p of the union, the position of the same
//    (row, col) block in a part (a member's pattern, or a smaller union), or
//    -1 where the part has none. Lowered code reads every part along the
//    union's rows with one load and a select, without searching or merging
//    columns in each frame.
//  - `A * B` is stored on the pattern of the product (symbolic SpGEMM).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_PATTERNALGEBRA_H
#define SIMIT_RUNTIME_PATTERNALGEBRA_H

#include "simit/Runtime/SparsityPattern.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"

#include <memory>
#include <string>
#include <vector>

namespace simit {

/// The union of the patterns of the matrices over (rows, cols) assembled
/// from each of `edgeSets` (each must have rows and cols among its endpoint
/// sets); the pattern itself for one edge set. An edge set E over (E, V)
/// or (V, E) stands for its incidence matrix or its transpose
/// (IncidenceView), the factors of products like D * A or D * D'.
llvm::Expected<std::shared_ptr<const SparsityPattern>>
unionPattern(llvm::ArrayRef<const Set *> edgeSets, const Set &rows,
             const Set &cols);

/// The union of explicit patterns with the same numbers of rows and columns.
std::shared_ptr<const SparsityPattern>
unionPattern(llvm::ArrayRef<const SparsityPattern *> members);

/// For each block position of `whole`, the position of the same block in
/// `part`, or -1; `part` has whole's rows and columns.
std::vector<int32_t> gatherPositions(const SparsityPattern &whole,
                                     const SparsityPattern &part);

/// For each block (r, c) of `whole`, the position of block (c, r) in
/// `part`, or -1; `part` has whole's columns as rows and rows as columns
/// (it is read transposed).
std::vector<int32_t> gatherTransposedPositions(const SparsityPattern &whole,
                                               const SparsityPattern &part);

/// The pattern of A * B for A over (R, M) and B over (M, C): block (r, c)
/// where some m has (r, m) in A and (m, c) in B; with `withDiagonal` (R and
/// C are one set) every (r, r) too, as assembled square patterns have.
std::shared_ptr<const SparsityPattern>
productPattern(const SparsityPattern &a, const SparsityPattern &b,
               bool withDiagonal);

/// The pattern of the product F1 F2 ... Fk (k >= 2) of `factors`, Fi over
/// (sets[i-1], sets[i]), that holds the product's blocks however it is
/// associated: the union over the ways to split each part in two of the
/// products of the halves, where a part from a set to itself also holds
/// its diagonal (productPattern's withDiagonal, as a stored intermediate
/// product has). With two factors it is productPattern(F1, F2, sets[0] ==
/// sets[2]).
std::shared_ptr<const SparsityPattern>
chainProductPattern(llvm::ArrayRef<const SparsityPattern *> factors,
                    llvm::ArrayRef<std::string> sets);

} // namespace simit

#endif // SIMIT_RUNTIME_PATTERNALGEBRA_H
