//===--- SupernodalCholesky.h - Sparse LL^T of BCSR matrices -------------===//
//
// The runtime's sparse Cholesky factorisation of BCSR matrices: symbolic
// analysis on the graph of blocks, left-looking supernodal numeric
// factorisation, and the triangular solves, in CHOLMOD's layout of a
// supernodal L.
//
// CHOLMOD's analysis works on the scalar graph (nine times the entries for
// 3x3 blocks), and its numeric factorisation calls BLAS once per supernode
// and per update and transposes the permuted matrix on every call; on the
// small systems of a Newton loop (hundreds to a few thousand unknowns,
// supernodes a few columns wide) those costs exceed the arithmetic. Here
// the matrix's entries are scattered straight into L by positions found
// once per pattern, small updates are dense loops the compiler vectorises,
// and only large ones go to BLAS.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_SUPERNODALCHOLESKY_H
#define SIMIT_LIB_RUNTIME_SUPERNODALCHOLESKY_H

#include <cstdint>
#include <vector>

namespace simit::direct {

/// A supernodal L in CHOLMOD's layout. Supernode s has the columns
/// [first[s], first[s + 1]) and the rows rows[rowStart[s] ..
/// rowStart[s + 1]) (its own columns first, then the rows below in
/// increasing order); its values are a column-major panel of those rows at
/// valueStart[s].
struct SupernodeLayout {
  int64_t supernodes = 0;
  const int64_t *first = nullptr, *rowStart = nullptr, *valueStart = nullptr,
                *rows = nullptr;

  int64_t size() const { return first[supernodes]; }
};

/// A fill-reducing order of a square pattern's rows (AMD on A + A^T):
/// order[k] is the row eliminated k-th.
std::vector<int32_t> minimumDegreeOrder(int64_t rows, const int32_t *rowptr,
                                        const int32_t *colidx);

/// The symbolic LL^T of a square block pattern: the order of the unknowns
/// (L's column k is the matrix's unknown permutation[k]) and the
/// supernodes with the storage of their values (layout()).
struct SupernodalSymbolic {
  std::vector<int64_t> permutation, first, rowStart, valueStart, rows;

  SupernodeLayout layout() const;
  int64_t values() const { return valueStart.back(); }
};

/// The analysis of a pattern of blockRows x blockRows blocks of
/// blockSize x blockSize (rowptr, colidx as in BCSR; the pattern of
/// A + A^T is used): AMD on the block graph, the elimination tree in
/// postorder, the structure of L and its supernodes (fundamental ones,
/// then narrow neighbours merged where that adds few zeros), all on the
/// blocks and expanded to scalars at the end.
SupernodalSymbolic analyse(int64_t blockRows, int64_t blockSize,
                           const int32_t *rowptr, const int32_t *colidx);

/// Where a block of the matrix lands in L's values: its entry (i, j) at
/// position + i * rowStride + j * columnStride; a position of -1 for a
/// block above the diagonal, whose mirror below it gives L its values.
struct BlockPlacement {
  int64_t position = -1, rowStride = 0, columnStride = 0;
};

/// The placement of each block of a pattern of blockRows x blockRows blocks
/// (rowptr, colidx as in BCSR) in L, where `permutation` maps L's columns
/// to the matrix's unknowns and keeps each block's unknowns together and
/// in order (as analyse's does). A diagonal block gives its lower
/// triangle, a block below the diagonal all its entries.
std::vector<BlockPlacement>
blockPlacements(const SupernodeLayout &layout, const int64_t *permutation,
                int64_t blockRows, int64_t blockSize, const int32_t *rowptr,
                const int32_t *colidx);

/// L L^T = A in place: `values` holds A's entries at their positions and
/// zeros elsewhere, and holds L on return. Returns L's column (in its own
/// order) whose pivot is not positive, or the size on success.
int64_t factorise(const SupernodeLayout &layout, double *values);

/// y = L^-T L^-1 y in place, summed in double whatever T. `dense` has room
/// for as many entries as L has rows.
template <typename T>
void solve(const SupernodeLayout &layout, const T *values, double *y,
           double *dense);

} // namespace simit::direct

#endif // SIMIT_LIB_RUNTIME_SUPERNODALCHOLESKY_H
