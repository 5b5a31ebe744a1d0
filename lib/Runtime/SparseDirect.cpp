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

#include "LaneSums.h"

#include "llvm/Support/FormatVariadic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>

extern "C" {
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
  }
  ~Common() { cholmod_l_finish(&c); }
  /// The settings of `kind`: supernodal LL^T for Cholesky, simplicial
  /// LDL^T otherwise.
  cholmod_common &configuredFor(FactorKind kind) {
    c.supernodal = kind == FactorKind::Cholesky ? CHOLMOD_SUPERNODAL
                                                : CHOLMOD_SIMPLICIAL;
    c.final_ll = kind == FactorKind::Cholesky;
    return c;
  }
};

/// The symbolic analysis of one pattern for one kind.
struct Analysis {
  std::shared_ptr<Common> common;
  FactorKind kind = FactorKind::LU;
  int64_t rows = 0, blockSize = 1;
  std::vector<int32_t> rowptr, colidx;
  /// The compressed columns (A^T's) and, per entry, its BCSR value index.
  std::vector<SuiteSparse_long> columnPointers, rowIndices;
  std::vector<int64_t> slots;
  cholmod_factor *symbolic = nullptr; // Cholesky, LDLT
  void *umfpackSymbolic = nullptr;    // LU

  int64_t size() const { return rows * blockSize; }
  ~Analysis() {
    if (symbolic)
      cholmod_l_free_factor(&symbolic, &common->c);
    if (umfpackSymbolic)
      umfpack_dl_free_symbolic(&umfpackSymbolic);
  }
  template <typename T> bool matches(FactorKind k, const SquareBCSRView<T> &a) {
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
  return llvm::createStringError(
      llvm::formatv("CHOLMOD {0} factorisation failed (status {1})",
                    kindName(kind), c.status)
          .str());
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
  cholmod_common &c = analysis->common->c;
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(n);
  rhs.ncol = 1;
  rhs.nzmax = rhs.d = static_cast<size_t>(n);
  rhs.x = const_cast<double *>(b);
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense *solution = cholmod_l_solve(
      CHOLMOD_A, static_cast<cholmod_factor *>(cholmodFactor), &rhs, &c);
  if (!solution)
    return llvm::createStringError(
        llvm::formatv("CHOLMOD solve failed (status {0})", c.status).str());
  std::memcpy(x, solution->x, static_cast<size_t>(n) * sizeof(double));
  cholmod_l_free_dense(&solution, &c);
  return llvm::Error::success();
}

namespace {
/// Columns of a panel taken together in the forward solve, so that the
/// rows below the diagonal block are loaded and stored once per group.
constexpr int64_t kColumnGroup = 4;
/// Running sums of a dot product with a panel column (LaneSums.h): enough
/// to fill vector registers.
constexpr int64_t kDotLanes = 16;

/// column . dense over `m` rows.
inline double panelDot(const float *__restrict column,
                       const double *__restrict dense, int64_t m) {
  LaneSums<kDotLanes> sums;
  inLanes<kDotLanes>(
      m, [&](int64_t i, int64_t l) { sums.lane[l] += column[i] * dense[i]; });
  return sums.total();
}

/// y = L^-T L^-1 y in place for a supernodal L in CHOLMOD's layout:
/// supernode s holds columns [first[s], first[s + 1]), its row indices at
/// rows[rowStart[s] .. rowStart[s + 1]) (the first ones its own columns),
/// and its values as a column-major panel of those rows at
/// values[valueStart[s] ..]. The rows of a panel below its diagonal block
/// go through `dense` (as many entries as L has rows), contiguous, so that
/// the products over them are dense loops the compiler vectorises, and the
/// gathers and scatters of y are made once per row, not once per column.
void solveSupernodal(int64_t supernodes, const SuiteSparse_long *first,
                     const SuiteSparse_long *rowStart,
                     const SuiteSparse_long *valueStart,
                     const SuiteSparse_long *rows, const float *values,
                     double *__restrict y, double *__restrict dense) {
  // L y' = y, supernode by supernode: the diagonal block's forward
  // substitution, then the rows below take the panel times its solution.
  for (int64_t s = 0; s < supernodes; ++s) {
    int64_t k1 = first[s], columns = first[s + 1] - k1;
    int64_t height = rowStart[s + 1] - rowStart[s], m = height - columns;
    const SuiteSparse_long *below = rows + rowStart[s] + columns;
    const float *panel = values + valueStart[s];
    for (int64_t j = 0; j < columns; ++j) {
      const float *column = panel + j * height;
      double yj = y[k1 + j] / column[j];
      y[k1 + j] = yj;
      for (int64_t i = j + 1; i < columns; ++i)
        y[k1 + i] -= column[i] * yj;
    }
    std::fill(dense, dense + m, 0.0);
    for (int64_t j = 0; j < columns; j += kColumnGroup) {
      int64_t group = std::min(kColumnGroup, columns - j);
      double solved[kColumnGroup] = {};
      const float *column[kColumnGroup];
      for (int64_t g = 0; g < kColumnGroup; ++g) {
        // A short last group repeats its last column, times zero.
        column[g] = panel + (j + std::min(g, group - 1)) * height + columns;
        solved[g] = g < group ? y[k1 + j + g] : 0.0;
      }
      for (int64_t i = 0; i < m; ++i)
        dense[i] += column[0][i] * solved[0] + column[1][i] * solved[1] +
                    column[2][i] * solved[2] + column[3][i] * solved[3];
    }
    for (int64_t i = 0; i < m; ++i)
      y[below[i]] -= dense[i];
  }
  // L^T x' = y', in reverse: each column subtracts the dot product of its
  // panel rows with the solution below, then the diagonal block's back
  // substitution.
  for (int64_t s = supernodes; s-- > 0;) {
    int64_t k1 = first[s], columns = first[s + 1] - k1;
    int64_t height = rowStart[s + 1] - rowStart[s], m = height - columns;
    const SuiteSparse_long *below = rows + rowStart[s] + columns;
    const float *panel = values + valueStart[s];
    for (int64_t i = 0; i < m; ++i)
      dense[i] = y[below[i]];
    for (int64_t j = 0; j < columns; ++j)
      y[k1 + j] -= panelDot(panel + j * height + columns, dense, m);
    for (int64_t j = columns; j-- > 0;) {
      const float *column = panel + j * height;
      double sum = y[k1 + j];
      for (int64_t i = j + 1; i < columns; ++i)
        sum -= column[i] * y[k1 + i];
      y[k1 + j] = sum / column[j];
    }
  }
}
} // namespace

llvm::Error SparseFactorisation::solveRounded(
    const double *b, double *x, std::vector<double> &scratch) const {
  const auto *l = static_cast<const cholmod_factor *>(cholmodFactor);
  bool supernodal = l && l->is_super && l->is_ll && l->xtype == CHOLMOD_REAL;
  if (supernodal)
    std::call_once(roundOnce, [&] {
      const auto *values = static_cast<const double *>(l->x);
      std::vector<float> rounded(l->xsize);
      for (size_t i = 0; i < l->xsize; ++i) {
        double magnitude = std::abs(values[i]);
        if (magnitude != 0 &&
            !(magnitude >= std::numeric_limits<float>::min() &&
              magnitude <= std::numeric_limits<float>::max()))
          return;
        rounded[i] = static_cast<float>(values[i]);
      }
      roundedL = std::move(rounded);
    });
  if (!supernodal || roundedL.empty())
    return solve(b, x);
  int64_t n = size();
  const auto *permutation = static_cast<const SuiteSparse_long *>(l->Perm);
  // y, then the dense rows of solveSupernodal.
  scratch.resize(2 * static_cast<size_t>(n));
  double *y = scratch.data();
  for (int64_t k = 0; k < n; ++k)
    y[k] = b[permutation[k]];
  solveSupernodal(static_cast<int64_t>(l->nsuper),
                  static_cast<const SuiteSparse_long *>(l->super),
                  static_cast<const SuiteSparse_long *>(l->pi),
                  static_cast<const SuiteSparse_long *>(l->px),
                  static_cast<const SuiteSparse_long *>(l->s), roundedL.data(),
                  y, y + n);
  for (int64_t k = 0; k < n; ++k)
    x[permutation[k]] = y[k];
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
llvm::Expected<FactorLookup>
FactorCache::factorise(FactorKind kind, const SquareBCSRView<T> &a) {
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
    buildColumns(a, *analysis);
    if (kind == FactorKind::LU) {
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
    } else {
      cholmod_common &c = common->configuredFor(kind);
      cholmod_sparse view = analysis->view(nullptr);
      view.xtype = CHOLMOD_PATTERN;
      analysis->symbolic = cholmod_l_analyze(&view, &c);
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

  if (entry->latest && entry->latest->holds(a)) {
    ++total.reuses;
    lookup.factor = entry->latest;
    return lookup;
  }

  Clock::time_point start = Clock::now();
  Analysis &analysis = *entry->analysis;
  // Refactorise in place when nothing else (a chol/lu handle) holds the
  // latest factorisation; else start from a copy of the symbolic one.
  std::shared_ptr<SparseFactorisation> factor = entry->latest;
  entry->latest = nullptr;
  if (!factor || factor.use_count() > 1) {
    factor.reset(new SparseFactorisation);
    factor->analysis = entry->analysis;
  }
  factor->single = std::is_same_v<T, float>;
  const auto *bytes = reinterpret_cast<const unsigned char *>(a.values);
  factor->valueBytes.assign(bytes, bytes + static_cast<size_t>(
                                               a.rowptr[a.rows]) *
                                               a.blockSize * a.blockSize *
                                               sizeof(T));
  factor->columnValues = columnValuesOf(a, analysis);
  if (kind == FactorKind::LU) {
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
  } else {
    cholmod_common &c = common->configuredFor(kind);
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

template llvm::Expected<FactorLookup>
FactorCache::factorise(FactorKind, const SquareBCSRView<double> &);
template llvm::Expected<FactorLookup>
FactorCache::factorise(FactorKind, const SquareBCSRView<float> &);
