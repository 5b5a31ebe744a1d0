//===--- SparseDirect.cpp - SuiteSparse factorisations of BCSR matrices ---===//
//
// The scalar rows of a BCSR matrix, read as compressed columns, are the
// columns of A^T: for the symmetric kinds that is A itself (the upper
// triangle is kept, CHOLMOD's stype 1), and UMFPACK solves with A^T's
// transpose (UMFPACK_At). So no transposition is ever made; a slot map says
// which BCSR value fills each compressed-column entry.
//
//===----------------------------------------------------------------------===//

#include "SparseDirect.h"

#include "SupernodalCholesky.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/FormatVariadic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <type_traits>

extern "C" {
#include <suitesparse/amd.h>
#include <suitesparse/cholmod.h>
#include <suitesparse/umfpack.h>
}

using namespace simit;

namespace simit::direct {

/// CHOLMOD's workspace and settings, shared by every analysis and factor
/// made with it (they must be freed with it).
struct Common {
  cholmod_common c;
  Common() {
    selectBlasKernels();
    cholmod_l_start(&c);
    c.print = 0; // errors come back as llvm::Error, not on stderr
    // LDL^T: simplicial, ordered by AMD on the block graph (blockOrdering),
    // postordered.
    c.supernodal = CHOLMOD_SIMPLICIAL;
    c.final_ll = false;
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_GIVEN;
    c.postorder = true;
  }
  ~Common() { cholmod_l_finish(&c); }
};

/// The symbolic analysis of one pattern for one kind.
struct Analysis {
  std::shared_ptr<Common> common;
  FactorKind kind = FactorKind::LU;
  int64_t rows = 0, blockSize = 1;
  std::vector<int32_t> rowptr, colidx;
  /// LU and LDLT: the compressed columns (A^T's) and, per entry, its BCSR
  /// value index.
  std::vector<SuiteSparse_long> columnPointers, rowIndices;
  std::vector<int64_t> slots;
  SupernodalSymbolic supernodal;      // Cholesky
  cholmod_factor *symbolic = nullptr; // LDLT
  void *umfpackSymbolic = nullptr;    // LU
  /// Cholesky: where each BCSR block lands in L's values.
  std::vector<direct::BlockPlacement> blockPlacements;

  int64_t size() const { return rows * blockSize; }
  ~Analysis() {
    if (symbolic)
      cholmod_l_free_factor(&symbolic, &common->c);
    if (umfpackSymbolic)
      umfpack_dl_free_symbolic(&umfpackSymbolic);
  }
  template <typename T>
  bool matches(FactorKind k, const SquareBCSRView<T> &a) const {
    size_t blocks = static_cast<size_t>(a.rowptr[a.rows]);
    return k == kind && a.rows == rows && a.blockSize == blockSize &&
           blocks == colidx.size() &&
           !std::memcmp(a.rowptr, rowptr.data(), rowptr.size() * 4) &&
           !std::memcmp(a.colidx, colidx.data(), blocks * 4);
  }
  /// A CHOLMOD view of the compressed columns holding `values`.
  cholmod_sparse view(double *values) {
    cholmod_sparse s{};
    s.nrow = s.ncol = static_cast<size_t>(size());
    s.nzmax = rowIndices.size();
    s.p = columnPointers.data();
    s.i = rowIndices.data();
    s.x = values;
    s.stype = 1;
    s.itype = CHOLMOD_LONG;
    s.xtype = CHOLMOD_REAL;
    s.dtype = CHOLMOD_DOUBLE;
    s.sorted = 1;
    s.packed = 1;
    return s;
  }
};

} // namespace simit::direct

using direct::Analysis;
using direct::SupernodalSymbolic;

namespace {
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start)
      .count();
}

const char *kindName(FactorKind kind) {
  switch (kind) {
  case FactorKind::Cholesky:
    return "Cholesky";
  case FactorKind::LDLT:
    return "LDL^T";
  case FactorKind::LU:
    return "LU";
  }
  return "";
}

/// The compressed columns of `a`'s scalar rows (the upper triangle only
/// for the symmetric kinds).
template <typename T>
void buildColumns(const SquareBCSRView<T> &a, Analysis &analysis) {
  int64_t bs = a.blockSize;
  bool upper = analysis.kind != FactorKind::LU;
  analysis.columnPointers.assign(1, 0);
  analysis.columnPointers.reserve(static_cast<size_t>(a.size()) + 1);
  size_t entries = static_cast<size_t>(a.rowptr[a.rows]) * bs * bs;
  analysis.rowIndices.reserve(entries);
  analysis.slots.reserve(entries);
  for (int64_t r = 0; r < a.rows; ++r)
    for (int64_t i = 0; i < bs; ++i) {
      int64_t column = r * bs + i;
      for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k)
        for (int64_t j = 0; j < bs; ++j) {
          int64_t row = static_cast<int64_t>(a.colidx[k]) * bs + j;
          if (upper && row > column)
            continue;
          analysis.rowIndices.push_back(row);
          analysis.slots.push_back((static_cast<int64_t>(k) * bs + i) * bs +
                                   j);
        }
      analysis.columnPointers.push_back(
          static_cast<SuiteSparse_long>(analysis.rowIndices.size()));
    }
}

template <typename T>
std::vector<double> columnValuesOf(const SquareBCSRView<T> &a,
                                   const Analysis &analysis) {
  std::vector<double> values(analysis.slots.size());
  for (size_t p = 0; p < values.size(); ++p)
    values[p] = static_cast<double>(a.values[analysis.slots[p]]);
  return values;
}

/// A fill-reducing ordering of `a`'s scalar unknowns: AMD's on the graph
/// of its blocks, each block's unknowns kept together. The block graph has
/// blockSize^2 times fewer edges than the scalar one, and a block's unknowns
/// are eliminated together anyway.
template <typename T>
std::vector<SuiteSparse_long> blockOrdering(const SquareBCSRView<T> &a) {
  std::vector<SuiteSparse_long> ordering;
  ordering.reserve(static_cast<size_t>(a.size()));
  for (int32_t block : direct::minimumDegreeOrder(a.rows, a.rowptr, a.colidx))
    for (int64_t i = 0; i < a.blockSize; ++i)
      ordering.push_back(block * a.blockSize + i);
  return ordering;
}

/// The error of a Cholesky (or LDL^T) factorisation whose pivot at the
/// matrix's scalar column `column` is not positive (or is zero).
llvm::Error notFactorisable(FactorKind kind, int64_t column) {
  return llvm::createStringError(
      kind == FactorKind::Cholesky
          ? llvm::formatv("the matrix is not positive definite (Cholesky "
                          "factorisation fails at scalar column {0}; "
                          "choose ldlt or lu for indefinite matrices)",
                          column)
                .str()
          : llvm::formatv("the matrix is singular or needs pivoting (LDL^T "
                          "factorisation has a zero pivot at scalar column "
                          "{0}; choose lu)",
                          column)
                .str());
}

llvm::Error cholmodError(FactorKind kind, const cholmod_common &c,
                         const cholmod_factor *factor) {
  if (c.status == CHOLMOD_NOT_POSDEF || (factor && factor->minor < factor->n)) {
    // CHOLMOD counts the failed column in its fill-reducing order; the user
    // knows the matrix's own.
    size_t column = 0;
    if (factor && factor->minor < factor->n)
      column = factor->Perm
                   ? static_cast<size_t>(static_cast<const SuiteSparse_long *>(
                         factor->Perm)[factor->minor])
                   : factor->minor;
    return notFactorisable(kind, static_cast<int64_t>(column));
  }
  return llvm::createStringError(
      llvm::formatv("CHOLMOD {0} factorisation failed (status {1})",
                    kindName(kind), c.status)
          .str());
}

/// x = A^-1 b with the supernodal LL^T of A(p, p) whose values are
/// `values` (L's own, or rounded to float).
template <typename T>
void permutedSolve(const SupernodalSymbolic &symbolic, const T *values,
                   const double *b, double *x, std::vector<double> &scratch) {
  int64_t n = static_cast<int64_t>(symbolic.permutation.size());
  const int64_t *permutation = symbolic.permutation.data();
  // y, then the dense rows of direct::solve.
  scratch.resize(2 * static_cast<size_t>(n));
  double *y = scratch.data();
  for (int64_t k = 0; k < n; ++k)
    y[k] = b[permutation[k]];
  direct::solve(symbolic.layout(), values, y, y + n);
  for (int64_t k = 0; k < n; ++k)
    x[permutation[k]] = y[k];
}

} // namespace

// --- SparseFactorisation ---------------------------------------------------

SparseFactorisation::~SparseFactorisation() {
  if (cholmodFactor) {
    auto *factor = static_cast<cholmod_factor *>(cholmodFactor);
    cholmod_l_free_factor(&factor, &analysis->common->c);
  }
  if (umfpackNumeric)
    umfpack_dl_free_numeric(&umfpackNumeric);
}

FactorKind SparseFactorisation::kind() const { return analysis->kind; }

int64_t SparseFactorisation::size() const { return analysis->size(); }

template <typename T>
bool SparseFactorisation::holds(const SquareBCSRView<T> &a) const {
  return single == std::is_same_v<T, float> &&
         valueBytes.size() ==
             static_cast<size_t>(a.rowptr[a.rows]) * a.blockSize *
                 a.blockSize * sizeof(T) &&
         !std::memcmp(valueBytes.data(), a.values, valueBytes.size());
}

llvm::Error SparseFactorisation::solve(const double *b, double *x) const {
  int64_t n = size();
  if (n == 0)
    return llvm::Error::success();
  if (umfpackNumeric) {
    double info[UMFPACK_INFO];
    SuiteSparse_long status = umfpack_dl_solve(
        UMFPACK_At, analysis->columnPointers.data(),
        analysis->rowIndices.data(), columnValues.data(), x, b,
        umfpackNumeric, nullptr, info);
    if (status != UMFPACK_OK)
      return llvm::createStringError(
          status == UMFPACK_WARNING_singular_matrix
              ? std::string("the matrix is singular (UMFPACK)")
              : llvm::formatv("UMFPACK solve failed (status {0})", status)
                    .str());
    return llvm::Error::success();
  }
  if (kind() == FactorKind::Cholesky) {
    std::vector<double> scratch;
    permutedSolve(analysis->supernodal, choleskyValues.data(), b, x, scratch);
    return llvm::Error::success();
  }
  const auto *l = static_cast<const cholmod_factor *>(cholmodFactor);
  cholmod_common &c = analysis->common->c;
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(n);
  rhs.ncol = 1;
  rhs.nzmax = rhs.d = static_cast<size_t>(n);
  rhs.x = const_cast<double *>(b);
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense *solution =
      cholmod_l_solve(CHOLMOD_A, const_cast<cholmod_factor *>(l), &rhs, &c);
  if (!solution)
    return llvm::createStringError(
        llvm::formatv("CHOLMOD solve failed (status {0})", c.status).str());
  std::memcpy(x, solution->x, static_cast<size_t>(n) * sizeof(double));
  cholmod_l_free_dense(&solution, &c);
  return llvm::Error::success();
}

llvm::Error SparseFactorisation::solveRounded(
    const double *b, double *x, std::vector<double> &scratch) const {
  bool supernodal = kind() == FactorKind::Cholesky;
  if (supernodal)
    std::call_once(roundOnce, [&] {
      std::vector<float> rounded(choleskyValues.size());
      for (size_t i = 0; i < choleskyValues.size(); ++i) {
        double magnitude = std::abs(choleskyValues[i]);
        if (magnitude != 0 &&
            !(magnitude >= std::numeric_limits<float>::min() &&
              magnitude <= std::numeric_limits<float>::max()))
          return;
        rounded[i] = static_cast<float>(choleskyValues[i]);
      }
      roundedL = std::move(rounded);
    });
  if (!supernodal || roundedL.empty())
    return solve(b, x);
  permutedSolve(analysis->supernodal, roundedL.data(), b, x, scratch);
  return llvm::Error::success();
}

double SparseFactorisation::relativeResidual(const double *b,
                                             const double *x) const {
  // The matrix from the kept copies: the pattern of the analysis and the
  // values of this factorisation.
  auto residual = [&](auto *values) {
    using T = std::remove_const_t<std::remove_pointer_t<decltype(values)>>;
    SquareBCSRView<T> a;
    a.rows = analysis->rows;
    a.blockSize = analysis->blockSize;
    a.rowptr = analysis->rowptr.data();
    a.colidx = analysis->colidx.data();
    a.values = values;
    int64_t n = a.size();
    std::vector<T> xt(x, x + n), ax(static_cast<size_t>(n));
    multiply(a, xt.data(), ax.data());
    double rr = 0, bb = 0;
    for (int64_t i = 0; i < n; ++i) {
      double r = b[i] - static_cast<double>(ax[i]);
      rr += r * r;
      bb += b[i] * b[i];
    }
    return bb == 0 ? 0.0 : std::sqrt(rr / bb);
  };
  if (single)
    return residual(reinterpret_cast<const float *>(valueBytes.data()));
  return residual(reinterpret_cast<const double *>(valueBytes.data()));
}

// --- FactorCache -------------------------------------------------------------

FactorCache::FactorCache() : common(std::make_shared<direct::Common>()) {}

FactorCache::~FactorCache() = default;

template <typename T>
std::optional<FactorLookup> FactorCache::reuse(FactorKind kind,
                                               const SquareBCSRView<T> &a) {
  auto entry = llvm::find_if(entries, [&](const Entry &entry) {
    return entry.analysis->matches(kind, a);
  });
  if (entry == entries.end() || !entry->latest || !entry->latest->holds(a))
    return std::nullopt;
  entries.splice(entries.begin(), entries, entry);
  ++total.reuses;
  FactorLookup lookup;
  lookup.factor = entry->latest;
  return lookup;
}

template <typename T>
llvm::Expected<FactorLookup>
FactorCache::factorise(FactorKind kind, const SquareBCSRView<T> &a) {
  if (std::optional<FactorLookup> reused = reuse(kind, a))
    return std::move(*reused);
  return factoriseAnew(kind, a);
}

template <typename T>
llvm::Expected<FactorLookup>
FactorCache::factoriseAnew(FactorKind kind, const SquareBCSRView<T> &a) {
  FactorLookup lookup;
  auto entry = entries.begin();
  while (entry != entries.end() && !entry->analysis->matches(kind, a))
    ++entry;
  if (entry != entries.end()) {
    entries.splice(entries.begin(), entries, entry);
  } else {
    Clock::time_point start = Clock::now();
    auto analysis = std::make_shared<Analysis>();
    analysis->common = common;
    analysis->kind = kind;
    analysis->rows = a.rows;
    analysis->blockSize = a.blockSize;
    analysis->rowptr.assign(a.rowptr, a.rowptr + a.rows + 1);
    analysis->colidx.assign(a.colidx, a.colidx + a.rowptr[a.rows]);
    if (kind != FactorKind::Cholesky)
      buildColumns(a, *analysis);
    if (kind == FactorKind::LU) {
      // UMFPACK refuses a 0 x 0 matrix (an empty set): there is nothing to
      // factorise or solve (solve() returns at once).
      if (a.size() > 0) {
        double info[UMFPACK_INFO];
        SuiteSparse_long status = umfpack_dl_symbolic(
            a.size(), a.size(), analysis->columnPointers.data(),
            analysis->rowIndices.data(), nullptr, &analysis->umfpackSymbolic,
            nullptr, info);
        if (status != UMFPACK_OK)
          return llvm::createStringError(
              llvm::formatv("UMFPACK symbolic analysis failed (status {0})",
                            status)
                  .str());
      }
    } else if (kind == FactorKind::Cholesky) {
      analysis->supernodal =
          direct::analyse(a.rows, a.blockSize, a.rowptr, a.colidx);
      analysis->blockPlacements =
          direct::blockPlacements(analysis->supernodal.layout(),
                                  analysis->supernodal.permutation.data(),
                                  a.rows, a.blockSize, a.rowptr, a.colidx);
    } else {
      cholmod_common &c = common->c;
      cholmod_sparse view = analysis->view(nullptr);
      view.xtype = CHOLMOD_PATTERN;
      std::vector<SuiteSparse_long> ordering = blockOrdering(a);
      analysis->symbolic =
          cholmod_l_analyze_p(&view, ordering.data(), nullptr, 0, &c);
      if (!analysis->symbolic)
        return cholmodError(kind, c, nullptr);
    }
    entries.push_front({std::move(analysis), nullptr});
    if (entries.size() > kCapacity)
      entries.pop_back();
    entry = entries.begin();
    lookup.analysed = true;
    lookup.analysisMs = millisecondsSince(start);
    ++total.analyses;
  }

  Clock::time_point start = Clock::now();
  Analysis &analysis = *entry->analysis;
  // Refactorise in place when nothing else (a chol/lu handle) holds the
  // latest factorisation and it has no float copy of L (made once per
  // object); else start from a copy of the symbolic one.
  std::shared_ptr<SparseFactorisation> factor = entry->latest;
  entry->latest = nullptr;
  if (!factor || factor.use_count() > 1 || !factor->roundedL.empty()) {
    factor.reset(new SparseFactorisation);
    factor->analysis = entry->analysis;
  }
  factor->single = std::is_same_v<T, float>;
  const auto *bytes = reinterpret_cast<const unsigned char *>(a.values);
  factor->valueBytes.assign(bytes, bytes + static_cast<size_t>(
                                               a.rowptr[a.rows]) *
                                               a.blockSize * a.blockSize *
                                               sizeof(T));
  if (kind == FactorKind::Cholesky)
    factor->columnValues.clear();
  else
    factor->columnValues = columnValuesOf(a, analysis);
  if (kind == FactorKind::LU) {
    if (a.size() > 0) {
      if (factor->umfpackNumeric)
        umfpack_dl_free_numeric(&factor->umfpackNumeric);
      double info[UMFPACK_INFO];
      SuiteSparse_long status = umfpack_dl_numeric(
          analysis.columnPointers.data(), analysis.rowIndices.data(),
          factor->columnValues.data(), analysis.umfpackSymbolic,
          &factor->umfpackNumeric, nullptr, info);
      if (status != UMFPACK_OK)
        return llvm::createStringError(
            status == UMFPACK_WARNING_singular_matrix
                ? std::string("the matrix is singular (its LU factorisation "
                              "has a zero pivot)")
                : llvm::formatv("UMFPACK numeric factorisation failed "
                                "(status {0})",
                                status)
                      .str());
    }
  } else if (kind == FactorKind::Cholesky) {
    // The values of A(p, p)'s lower triangle at their places in L, zeros
    // elsewhere, factorised in place: the blocks on and below the diagonal
    // (the lower triangle of a diagonal one).
    const SupernodalSymbolic &symbolic = analysis.supernodal;
    factor->choleskyValues.assign(static_cast<size_t>(symbolic.values()), 0.0);
    double *lx = factor->choleskyValues.data();
    int64_t bs = a.blockSize;
    for (int64_t r = 0; r < a.rows; ++r)
      for (int32_t k = a.rowptr[r]; k < a.rowptr[r + 1]; ++k) {
        if (a.colidx[k] > r)
          continue;
        const direct::BlockPlacement &place = analysis.blockPlacements[k];
        const T *block = a.values + static_cast<int64_t>(k) * bs * bs;
        for (int64_t i = 0; i < bs; ++i)
          for (int64_t j = 0; j < (a.colidx[k] == r ? i + 1 : bs); ++j)
            lx[place.position + i * place.rowStride + j * place.columnStride] =
                static_cast<double>(block[i * bs + j]);
      }
    int64_t failed = direct::factorise(symbolic.layout(), lx);
    if (failed < a.size())
      return notFactorisable(kind, symbolic.permutation[failed]);
  } else {
    cholmod_common &c = common->c;
    if (!factor->cholmodFactor)
      factor->cholmodFactor = cholmod_l_copy_factor(analysis.symbolic, &c);
    auto *cholmodFactor = static_cast<cholmod_factor *>(factor->cholmodFactor);
    cholmod_sparse view = analysis.view(factor->columnValues.data());
    if (!cholmodFactor || !cholmod_l_factorize(&view, cholmodFactor, &c) ||
        c.status != CHOLMOD_OK || cholmodFactor->minor < cholmodFactor->n)
      return cholmodError(kind, c, cholmodFactor);
  }
  entry->latest = factor;
  lookup.factor = std::move(factor);
  lookup.factorised = true;
  lookup.factorisationMs = millisecondsSince(start);
  ++total.factorisations;
  return lookup;
}

#define SIMIT_FACTOR_CACHE_INSTANTIATE(T)                                      \
  template std::optional<FactorLookup> FactorCache::reuse(                     \
      FactorKind, const SquareBCSRView<T> &);                                  \
  template llvm::Expected<FactorLookup> FactorCache::factorise(                \
      FactorKind, const SquareBCSRView<T> &);                                  \
  template llvm::Expected<FactorLookup> FactorCache::factoriseAnew(            \
      FactorKind, const SquareBCSRView<T> &);
SIMIT_FACTOR_CACHE_INSTANTIATE(double)
SIMIT_FACTOR_CACHE_INSTANTIATE(float)
#undef SIMIT_FACTOR_CACHE_INSTANTIATE
