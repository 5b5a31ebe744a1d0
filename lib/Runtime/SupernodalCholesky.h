//===--- SupernodalCholesky.h - Numeric LL^T on a supernodal layout -------===//
//
// The numeric supernodal Cholesky factorisation and the triangular solves
// of the runtime's sparse direct solver, on the layout of CHOLMOD's
// symbolic analysis (which keeps choosing the ordering and the supernodes).
//
// CHOLMOD's own numeric factorisation calls BLAS once per supernode and per
// update, and transposes the permuted matrix on every call; on the small
// systems of a Newton loop (hundreds to a few thousand unknowns, supernodes
// a few columns wide) those calls cost more than the arithmetic. Here the
// matrix's entries are scattered straight into L by positions found once per
// pattern, small updates are dense loops the compiler vectorises, and only
// large ones go to BLAS.
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

/// For each entry of a matrix's upper triangle in compressed columns
/// (columnPointers, rowIndices; original numbering), its position in L's
/// values, where `permutation` maps L's columns to the matrix's.
std::vector<int64_t> entryPositions(const SupernodeLayout &layout,
                                    const int64_t *permutation,
                                    const int64_t *columnPointers,
                                    const int64_t *rowIndices);

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
