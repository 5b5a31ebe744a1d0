//===--- SparseDirect.h - SuiteSparse factorisations of BCSR matrices -----===//
//
// Sparse direct solves of square BCSR matrices: supernodal Cholesky
// (SupernodalCholesky.h), simplicial LDL^T (CHOLMOD) and LU (UMFPACK), in
// double on OpenBLAS.
//
// A FactorCache keeps, per sparsity pattern and method, the symbolic
// analysis (fill-reducing ordering, elimination tree, supernodes) and the
// latest numeric factorisation. Both are found by content, never by address:
// the pattern's arrays and the matrix's values are kept as copies and
// compared bytewise, so a pattern freed and reallocated at the same place,
// or values changed in place, can never meet a stale factor.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_SPARSEDIRECT_H
#define SIMIT_LIB_RUNTIME_SPARSEDIRECT_H

#include "simit/Runtime/SolveSession.h"
#include "simit/Runtime/Solvers.h"

#include "llvm/Support/Error.h"

#include <list>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace simit {

namespace direct {
struct Common;
struct Analysis;
} // namespace direct

/// The numeric factorisation of one matrix value. It keeps that value (and,
/// through its analysis, the pattern), so a solve can check its residual
/// against the matrix it factorised whatever happened to the original.
class SparseFactorisation {
public:
  ~SparseFactorisation();
  SparseFactorisation(const SparseFactorisation &) = delete;
  SparseFactorisation &operator=(const SparseFactorisation &) = delete;

  FactorKind kind() const;
  /// The number of scalar unknowns.
  int64_t size() const;
  /// x = A^-1 b in double.
  llvm::Error solve(const double *b, double *x) const;
  /// x ~ A^-1 b for preconditioning (pcg-cholesky): a supernodal Cholesky
  /// factor's triangular solves with L rounded to float, summed in double.
  /// A solve with one right-hand side reads every value of L once, so it
  /// runs at memory speed, and float halves the bytes; CG corrects the
  /// rounding. The float copy is made on the first call and kept, so every
  /// statement preconditioned by this factorisation shares it. Other
  /// factorisations, and an L with values outside float's normal range,
  /// solve exactly. `scratch` is the caller's reused storage.
  llvm::Error solveRounded(const double *b, double *x,
                           std::vector<double> &scratch) const;
  /// ||b - A x|| / ||b|| with the factorised matrix, in double; 0 for b = 0.
  double relativeResidual(const double *b, const double *x) const;

private:
  friend class FactorCache;
  SparseFactorisation() = default;
  /// Whether `values` (as T) is the value this factorises.
  template <typename T> bool holds(const SquareBCSRView<T> &a) const;

  std::shared_ptr<direct::Analysis> analysis;
  /// The factorised matrix's values, bytewise, and whether they are float.
  std::vector<unsigned char> valueBytes;
  bool single = false;
  /// The values in the analysis's compressed-column order (UMFPACK's solve
  /// reads them for its iterative refinement).
  std::vector<double> columnValues;
  /// Cholesky: L's values in the analysis's supernodal layout.
  std::vector<double> choleskyValues;
  void *cholmodFactor = nullptr;  // cholmod_factor, LDLT
  void *umfpackNumeric = nullptr; // LU
  /// solveRounded's copy of a supernodal L in float; empty when it does not
  /// apply.
  mutable std::once_flag roundOnce;
  mutable std::vector<float> roundedL;
};

/// What FactorCache::factorise did.
struct FactorLookup {
  std::shared_ptr<const SparseFactorisation> factor;
  bool analysed = false, factorised = false;
  double analysisMs = 0, factorisationMs = 0;
};

class FactorCache {
public:
  FactorCache();
  ~FactorCache();
  FactorCache(const FactorCache &) = delete;
  FactorCache &operator=(const FactorCache &) = delete;

  /// The factorisation of `a` by `kind`: the cached one when `a` holds the
  /// same values, else a new numeric factorisation on the cached analysis of
  /// its pattern (analysed first if new). Errors: a matrix that is not
  /// positive definite (Cholesky), has a zero pivot (LDLT) or is singular
  /// (LU), naming the first column at fault. Symmetric kinds read the upper
  /// triangle: the caller checks symmetry.
  template <typename T>
  llvm::Expected<FactorLookup> factorise(FactorKind kind,
                                         const SquareBCSRView<T> &a);

  /// factorise() for values that reuse() has just not found.
  template <typename T>
  llvm::Expected<FactorLookup> factoriseAnew(FactorKind kind,
                                             const SquareBCSRView<T> &a);

  /// The latest factorisation by `kind` of a's pattern when it is of a's
  /// values (what factorise would reuse, counted as a reuse), else none.
  /// A caller that checks new values first (symmetry) asks this, then
  /// calls factoriseAnew when there is none.
  template <typename T>
  std::optional<FactorLookup> reuse(FactorKind kind,
                                    const SquareBCSRView<T> &a);

  /// Analyses and numeric factorisations done, and numeric ones saved by
  /// finding the same matrix value.
  FactorisationCounts counts() const { return total; }

private:
  std::shared_ptr<direct::Common> common;
  struct Entry {
    std::shared_ptr<direct::Analysis> analysis;
    std::shared_ptr<SparseFactorisation> latest;
  };
  /// Most recently used first; at most kCapacity patterns.
  std::list<Entry> entries;
  static constexpr size_t kCapacity = 8;
  FactorisationCounts total;
};

} // namespace simit

#endif // SIMIT_LIB_RUNTIME_SPARSEDIRECT_H
