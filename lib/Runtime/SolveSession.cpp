//===--- SolveSession.cpp - The solver of `x = A \ b` ---------------------===//
//
// Conjugate gradients is right only for symmetric positive definite
// matrices, and an iterative solve is only as good as its residual: so the
// symmetric methods check symmetry, every answer's true residual is
// computed, and the answer is accepted (direct methods), reported (an
// iterative solve the user capped) or refused (everything else).
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/SolveSession.h"

#include "SparseDirect.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <type_traits>

using namespace simit;

namespace {
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start)
      .count();
}

/// The tolerances of one precision, relative to ||b||: `auto`'s CG stop,
/// the default stop of the iterative methods, and the residual a direct
/// answer must meet; and, relative to A's largest entry, how far A(i, j)
/// and A(j, i) may differ for A to count as symmetric (an assembly computes
/// the two apart, so float32 rounds them differently).
template <typename T> struct Tolerances;
template <> struct Tolerances<double> {
  static constexpr double autoCG = 1e-12, iterative = 1e-10, accept = 1e-8,
                          symmetric = 1e-10;
};
template <> struct Tolerances<float> {
  static constexpr double autoCG = 1e-6, iterative = 1e-5, accept = 1e-3,
                          symmetric = 1e-5;
};

const std::pair<SolveMethod, llvm::StringRef> kMethodNames[] = {
    {SolveMethod::Auto, "auto"},
    {SolveMethod::ConjugateGradient, "cg"},
    {SolveMethod::JacobiCG, "pcg-jacobi"},
    {SolveMethod::BlockJacobiCG, "pcg-block-jacobi"},
    {SolveMethod::CholeskyCG, "pcg-cholesky"},
    {SolveMethod::Cholesky, "cholesky"},
    {SolveMethod::LDLT, "ldlt"},
    {SolveMethod::LU, "lu"},
    {SolveMethod::ShermanMorrison, "sherman-morrison"},
    {SolveMethod::BorderedLU, "bordered-lu"},
};

template <typename T> double dot(const T *u, const T *v, int64_t n) {
  double sum = 0;
  for (int64_t i = 0; i < n; ++i)
    sum += static_cast<double>(u[i]) * v[i];
  return sum;
}

template <typename T> double norm(const T *v, int64_t n) {
  double sum = 0;
  for (int64_t i = 0; i < n; ++i)
    sum += static_cast<double>(v[i]) * v[i];
  return std::sqrt(sum);
}

/// ||b - A x|| / bNorm in double.
template <typename T>
double relativeResidual(const SquareBCSRView<T> &a, const T *b, const T *x,
                        double bNorm) {
  std::vector<T> ax(static_cast<size_t>(a.size()));
  multiply(a, x, ax.data());
  double sum = 0;
  for (int64_t i = 0; i < a.size(); ++i) {
    double r = static_cast<double>(b[i]) - ax[i];
    sum += r * r;
  }
  return std::sqrt(sum) / bNorm;
}

llvm::Error notAccepted(double residual) {
  return llvm::createStringError(
      llvm::formatv("the relative residual ||b - A x|| / ||b|| of the "
                    "solution is {0:e3} (the matrix is singular or too "
                    "ill-conditioned)",
                    residual)
          .str());
}

std::optional<FactorKind> factorKindOf(SolveMethod method) {
  switch (method) {
  case SolveMethod::Cholesky:
    return FactorKind::Cholesky;
  case SolveMethod::LDLT:
    return FactorKind::LDLT;
  case SolveMethod::LU:
    return FactorKind::LU;
  default:
    return std::nullopt;
  }
}

Preconditioner preconditionerOf(SolveMethod method) {
  return method == SolveMethod::JacobiCG        ? Preconditioner::Jacobi
         : method == SolveMethod::BlockJacobiCG ? Preconditioner::BlockJacobi
                                                : Preconditioner::None;
}
} // namespace

llvm::StringRef simit::solveMethodName(SolveMethod method) {
  for (auto [m, name] : kMethodNames)
    if (m == method)
      return name;
  return "";
}

std::optional<SolveMethod> simit::parseSolveMethod(llvm::StringRef name) {
  for (auto [m, text] : kMethodNames)
    if (text == name && m != SolveMethod::ShermanMorrison &&
        m != SolveMethod::BorderedLU)
      return m;
  return std::nullopt;
}

llvm::StringRef simit::solveMethodNames() {
  return "auto, cg, pcg-jacobi, pcg-block-jacobi, pcg-cholesky, cholesky, "
         "ldlt, lu";
}

SolveSettings SolveSettingsOverride::appliedTo(SolveSettings settings) const {
  if (method)
    settings.method = *method;
  if (tolerance)
    settings.tolerance = tolerance;
  if (maxIterations)
    settings.maxIterations = maxIterations;
  if (strict)
    settings.strict = *strict;
  if (warmStart)
    settings.warmStart = *warmStart;
  if (refactorIterations)
    settings.refactorIterations = refactorIterations;
  return settings;
}

llvm::Error simit::checkSolveSettings(const SolveSettings &settings,
                                      llvm::StringRef where) {
  if (settings.tolerance &&
      !(*settings.tolerance > 0 && *settings.tolerance < 1))
    return llvm::createStringError(
        where + ": the tolerance must lie between 0 and 1 (exclusive), "
                "found " +
        llvm::formatv("{0}", *settings.tolerance).str());
  if (settings.maxIterations && *settings.maxIterations < 1)
    return llvm::createStringError(
        where + ": the iteration cap must be at least 1, found " +
        llvm::Twine(*settings.maxIterations));
  if (settings.refactorIterations && *settings.refactorIterations < 1)
    return llvm::createStringError(
        where + ": the refactorisation threshold must be at least 1, found " +
        llvm::Twine(*settings.refactorIterations));
  return llvm::Error::success();
}

SolveSession::SolveSession(SolveSettings settings)
    : current(settings), cache(std::make_unique<FactorCache>()) {}

SolveSession::~SolveSession() = default;

SolveStatementStats &SolveSession::statsOf(llvm::StringRef statement) {
  auto it = statementIndex.find(statement);
  if (it == statementIndex.end()) {
    it = statementIndex.emplace(statement.str(), statements.size()).first;
    statements.emplace_back().statement = statement.str();
    warned.push_back(false);
    mirrors.emplace_back();
  }
  return statements[it->second];
}

BlockMirrors &SolveSession::mirrorsOf(const SolveStatementStats &stats) {
  return mirrors[statementIndex.find(stats.statement)->second];
}

void SolveSession::record(SolveStatementStats &stats,
                          const SolveReport &report) {
  if (!llvm::is_contained(stats.methods, report.method))
    stats.methods.push_back(report.method);
  ++stats.solves;
  stats.iterations += report.iterations;
  stats.maxIterations =
      std::max<int64_t>(stats.maxIterations, report.iterations);
  stats.notConverged += !report.converged;
  stats.lastRelativeResidual = report.relativeResidual;
  stats.maxRelativeResidual =
      std::max(stats.maxRelativeResidual, report.relativeResidual);
  stats.analyses += report.analysed;
  stats.factorisations += report.factorised;
  stats.reuses += report.reused;
  stats.analysisMs += report.analysisMs;
  stats.factorisationMs += report.factorisationMs;
  stats.solveMs += report.solveMs;
}

template <typename T>
llvm::Expected<SolveReport>
SolveSession::direct(llvm::Expected<FactorLookup> lookup, const T *b, T *x) {
  if (!lookup)
    return lookup.takeError();
  FactorKind kind = lookup->factor->kind();
  SolveReport report;
  report.method = kind == FactorKind::Cholesky ? SolveMethod::Cholesky
                  : kind == FactorKind::LDLT   ? SolveMethod::LDLT
                                               : SolveMethod::LU;
  report.analysed = lookup->analysed;
  report.factorised = lookup->factorised;
  report.reused = !lookup->factorised;
  report.analysisMs = lookup->analysisMs;
  report.factorisationMs = lookup->factorisationMs;
  Clock::time_point start = Clock::now();
  int64_t n = lookup->factor->size();
  std::vector<double> rhs(b, b + n), solution(static_cast<size_t>(n));
  if (llvm::Error err = lookup->factor->solve(rhs.data(), solution.data()))
    return std::move(err);
  for (int64_t i = 0; i < n; ++i)
    x[i] = static_cast<T>(solution[i]);
  report.solveMs = millisecondsSince(start);
  return report;
}

template <typename T>
llvm::Expected<SolverResult> SolveSession::factorPreconditioned(
    const SquareBCSRView<T> &a, const T *b, T *x, SolverOptions options,
    llvm::StringRef statement, SolveReport &report) {
  auto held = preconditionerFactors.find(statement);
  if (held == preconditionerFactors.end())
    held = preconditionerFactors.emplace(statement.str(),
                                         CholeskyPreconditioner())
               .first;
  CholeskyPreconditioner &preconditioner = held->second;
  auto factoriseA = [&]() -> llvm::Error {
    auto lookup = cache->factorise(FactorKind::Cholesky, a);
    if (!lookup)
      return lookup.takeError();
    preconditioner.factor = lookup->factor;
    report.analysed |= lookup->analysed;
    report.factorised |= lookup->factorised;
    report.reused |= !lookup->factorised;
    report.analysisMs += lookup->analysisMs;
    report.factorisationMs += lookup->factorisationMs;
    return llvm::Error::success();
  };
  // Any symmetric positive definite M is a valid preconditioner, so an
  // earlier matrix's factor (even of another pattern) only costs
  // iterations; one of another size cannot be applied.
  bool fresh = !preconditioner.factor ||
               preconditioner.factor->size() != a.size();
  if (fresh)
    if (llvm::Error err = factoriseA())
      return std::move(err);
  options.preconditioner = Preconditioner::Operator;
  options.apply = [&](const double *r, double *z) {
    return preconditioner.factor->solveRounded(r, z, preconditioner.scratch);
  };
  int cap = options.maxIterations;
  if (!fresh)
    options.maxIterations = static_cast<int>(std::min<int64_t>(
        cap,
        current.refactorIterations.value_or(kDefaultRefactorIterations)));
  llvm::Expected<SolverResult> lagged = conjugateGradient(a, b, x, options);
  if (!lagged || fresh || lagged->converged || lagged->iterations >= cap)
    return lagged;
  // The factor no longer describes A well enough: factorise A itself and go
  // on from the iterate reached.
  if (llvm::Error err = factoriseA())
    return std::move(err);
  options.maxIterations = cap - lagged->iterations;
  llvm::Expected<SolverResult> refreshed = conjugateGradient(a, b, x, options);
  if (refreshed)
    refreshed->iterations += lagged->iterations;
  return refreshed;
}

llvm::Expected<SolveReport>
SolveSession::countFailure(SolveStatementStats &stats, SolveMethod method,
                           llvm::Expected<SolveReport> result) {
  if (!result) {
    if (!llvm::is_contained(stats.methods, method))
      stats.methods.push_back(method);
    ++stats.failed;
  }
  return result;
}

template <typename T>
llvm::Expected<SolveReport>
SolveSession::iterative(const SquareBCSRView<T> &a, const T *b, T *x,
                        double bNorm, SolveStatementStats &stats) {
  SolveMethod method = current.method;
  bool automatic = method == SolveMethod::Auto;
  double tolerance = current.tolerance.value_or(
      automatic ? Tolerances<T>::autoCG : Tolerances<T>::iterative);
  SolverOptions options;
  options.maxIterations = static_cast<int>(std::min<int64_t>(
      current.maxIterations.value_or(2 * a.size()), 1 << 30));
  options.tolerance = tolerance * bNorm * tolerance * bNorm;
  options.preconditioner = preconditionerOf(method);
  Clock::time_point start = Clock::now();
  if (current.warmStart) {
    auto previous = previousAnswers.find(stats.statement);
    if (previous != previousAnswers.end() &&
        previous->second.size() == static_cast<size_t>(a.size()))
      std::transform(previous->second.begin(), previous->second.end(), x,
                     [](double value) { return static_cast<T>(value); });
  }
  SolveReport report;
  llvm::Expected<SolverResult> cg =
      method == SolveMethod::CholeskyCG
          ? factorPreconditioned(a, b, x, options, stats.statement, report)
          : conjugateGradient(a, b, x, options);
  if (!cg)
    return cg.takeError();
  report.method = automatic ? SolveMethod::ConjugateGradient : method;
  report.iterations = cg->iterations;
  report.converged = cg->converged;
  // pcg-cholesky's factorisations are counted apart, as a direct solve's.
  report.solveMs = millisecondsSince(start) - report.analysisMs -
                   report.factorisationMs;
  if (report.converged || automatic) {
    report.relativeResidual = std::sqrt(cg->residualNormSquared) / bNorm;
    return report;
  }
  // At the cap CG holds its recursively updated residual, which can be
  // far below the true one (a factor 10 on stiffness ratios of 1e8): the
  // warning and the error report the true one, as --stats does.
  report.relativeResidual = relativeResidual(a, b, x, bNorm);
  std::string message = llvm::formatv(
      "{0} stopped at the iteration cap of {1} with relative residual "
      "{2:e2} (tolerance {3:e2})",
      solveMethodName(method), cg->iterations, report.relativeResidual,
      tolerance);
  if (current.strict) {
    // Counted by --stats too, which prints after a failed run.
    record(stats, report);
    return llvm::createStringError(message + " (strict solver settings)");
  }
  size_t index = statementIndex.find(stats.statement)->second;
  if (!warned[index]) {
    warned[index] = true;
    llvm::errs() << "warning: " << stats.statement << ": " << message
                 << "; the answer is not converged (warned once per "
                    "statement; --stats counts every such solve)\n";
  }
  return report;
}

template <typename T>
llvm::Expected<SolveReport>
SolveSession::solve(const SquareBCSRView<T> &a, const T *b, T *x,
                    llvm::StringRef statement) {
  SolveStatementStats &stats = statsOf(statement);
  SolveMethod attempted = current.method;
  llvm::Expected<SolveReport> result = solveRecorded(a, b, x, stats, attempted);
  return countFailure(stats, attempted, std::move(result));
}

template <typename T>
llvm::Expected<SolveReport>
SolveSession::solveRecorded(const SquareBCSRView<T> &a, const T *b, T *x,
                            SolveStatementStats &stats,
                            SolveMethod &attempted) {
  int64_t n = a.size();
  double bNorm = norm(b, n);
  if (!std::isfinite(bNorm))
    return llvm::createStringError(
        "the right-hand side holds a NaN or an infinity");
  std::fill(x, x + n, T(0));
  SolveMethod method = current.method;
  if (bNorm == 0) {
    SolveReport zero;
    zero.method = method;
    record(stats, zero);
    return zero;
  }

  bool symmetricMethod = method != SolveMethod::Auto &&
                         method != SolveMethod::LU;
  // A symmetric kind's factorisation of these very values was made after
  // they passed this check (at this tolerance): a Newton step's solves
  // with one matrix check it once, and find the factorisation once.
  std::optional<FactorKind> kind = factorKindOf(method);
  std::optional<FactorLookup> reused;
  if (kind)
    reused = cache->reuse(*kind, a);
  bool symmetric = false;
  if (symmetricMethod || method == SolveMethod::Auto)
    symmetric = (reused && *kind != FactorKind::LU) ||
                isSymmetric(a, Tolerances<T>::symmetric, mirrorsOf(stats));
  if (symmetricMethod && !symmetric)
    return llvm::createStringError(
        "the matrix is not symmetric, and " + solveMethodName(method) +
        " needs a symmetric matrix (choose lu, or auto)");

  std::optional<SolveReport> report;
  if (kind) {
    auto solved = direct(
        reused ? std::move(*reused) : cache->factoriseAnew(*kind, a), b, x);
    if (!solved)
      return solved.takeError();
    report = *solved;
  } else if (method != SolveMethod::Auto || symmetric) {
    auto solved = iterative(a, b, x, bNorm, stats);
    if (!solved) {
      if (method != SolveMethod::Auto)
        return solved.takeError();
      // Not positive definite: `auto` starts over with LU.
      llvm::consumeError(solved.takeError());
    } else if (solved->converged || method != SolveMethod::Auto) {
      report = *solved;
    }
  }
  if (!report) {
    // `auto` on a non-symmetric matrix, or after CG failed.
    attempted = SolveMethod::LU;
    std::fill(x, x + n, T(0));
    auto solved = direct(cache->factorise(FactorKind::LU, a), b, x);
    if (!solved)
      return solved.takeError();
    report = *solved;
  }
  report->relativeResidual = relativeResidual(a, b, x, bNorm);
  if (!(report->relativeResidual <= Tolerances<T>::accept) &&
      (factorKindOf(report->method) || method == SolveMethod::Auto))
    return notAccepted(report->relativeResidual);
  if (!std::isfinite(report->relativeResidual))
    return llvm::createStringError("the solution holds a NaN or an infinity");
  if (current.warmStart && !factorKindOf(method))
    previousAnswers[stats.statement].assign(x, x + n);
  record(stats, *report);
  return *report;
}

template llvm::Expected<SolveReport>
SolveSession::solve(const SquareBCSRView<double> &, const double *, double *,
                    llvm::StringRef);
template llvm::Expected<SolveReport>
SolveSession::solve(const SquareBCSRView<float> &, const float *, float *,
                    llvm::StringRef);

/// The scalar matrix [A u; v^T -1] in BCSR arrays of 1x1 blocks.
/// The bordered matrix [A U; V^T -I] of a rank-k update A + U V^T, k
/// border rows and columns, as scalar CSR.
template <typename T> struct BorderedMatrix {
  std::vector<int32_t> rowptr{0}, colidx;
  std::vector<T> values;
  SquareBCSRView<T> view;

  BorderedMatrix(const SquareBCSRView<T> &a, llvm::ArrayRef<const T *> u,
                 llvm::ArrayRef<const T *> v) {
    int64_t bs = a.blockSize, n = a.size(), k = u.size();
    for (int64_t r = 0; r < a.rows; ++r)
      for (int64_t i = 0; i < bs; ++i) {
        for (int32_t p = a.rowptr[r]; p < a.rowptr[r + 1]; ++p)
          for (int64_t j = 0; j < bs; ++j) {
            colidx.push_back(static_cast<int32_t>(a.colidx[p] * bs + j));
            values.push_back(a.values[(static_cast<int64_t>(p) * bs + i) * bs +
                                      j]);
          }
        for (int64_t t = 0; t < k; ++t) {
          colidx.push_back(static_cast<int32_t>(n + t));
          values.push_back(u[t][r * bs + i]);
        }
        rowptr.push_back(static_cast<int32_t>(colidx.size()));
      }
    for (int64_t t = 0; t < k; ++t) {
      for (int64_t j = 0; j < n + k; ++j) {
        colidx.push_back(static_cast<int32_t>(j));
        values.push_back(j < n ? v[t][j] : (j - n == t ? T(-1) : T(0)));
      }
      rowptr.push_back(static_cast<int32_t>(colidx.size()));
    }
    view.rows = n + k;
    view.rowptr = rowptr.data();
    view.colidx = colidx.data();
    view.values = values.data();
  }
};

/// Solves the k x k system `m` y = `rhs` (row major, overwritten) by LU
/// with partial pivoting; false when a pivot is at most `tiny`.
bool solveSmall(std::vector<double> &m, std::vector<double> &rhs,
                double tiny) {
  int64_t k = rhs.size();
  for (int64_t col = 0; col < k; ++col) {
    int64_t pivot = col;
    for (int64_t r = col + 1; r < k; ++r)
      if (std::abs(m[r * k + col]) > std::abs(m[pivot * k + col]))
        pivot = r;
    if (!(std::abs(m[pivot * k + col]) > tiny))
      return false;
    for (int64_t j = 0; j < k; ++j)
      std::swap(m[col * k + j], m[pivot * k + j]);
    std::swap(rhs[col], rhs[pivot]);
    for (int64_t r = col + 1; r < k; ++r) {
      double f = m[r * k + col] / m[col * k + col];
      for (int64_t j = col; j < k; ++j)
        m[r * k + j] -= f * m[col * k + j];
      rhs[r] -= f * rhs[col];
    }
  }
  for (int64_t r = k; r-- > 0;) {
    for (int64_t j = r + 1; j < k; ++j)
      rhs[r] -= m[r * k + j] * rhs[j];
    rhs[r] /= m[r * k + r];
  }
  return true;
}

template <typename T>
llvm::Expected<SolveReport>
SolveSession::shermanMorrison(const SquareBCSRView<T> &a, const T *u,
                              const T *v, const T *b, const T *w, const T *c,
                              T *x, llvm::StringRef statement) {
  if constexpr (std::is_same_v<T, double>)
    if (rankOneObserver)
      rankOneObserver(RankOneSystem{statement, a, u, v, b});
  return woodbury<T>(a, {u}, {v}, b, {w}, c, x, statement);
}

template <typename T>
llvm::Expected<SolveReport>
SolveSession::woodbury(const SquareBCSRView<T> &a, llvm::ArrayRef<const T *> u,
                       llvm::ArrayRef<const T *> v, const T *b,
                       llvm::ArrayRef<const T *> w, const T *c, T *x,
                       llvm::StringRef statement) {
  SolveStatementStats &stats = statsOf(statement);
  SolveMethod attempted = SolveMethod::ShermanMorrison;
  llvm::Expected<SolveReport> result =
      woodburyRecorded(a, u, v, b, w, c, x, stats, attempted);
  return countFailure(stats, attempted, std::move(result));
}

template <typename T>
llvm::Expected<SolveReport> SolveSession::woodburyRecorded(
    const SquareBCSRView<T> &a, llvm::ArrayRef<const T *> u,
    llvm::ArrayRef<const T *> v, const T *b, llvm::ArrayRef<const T *> w,
    const T *c, T *x, SolveStatementStats &stats, SolveMethod &attempted) {
  int64_t n = a.size(), k = u.size();
  Clock::time_point start = Clock::now();
  // The capacitance matrix I + V^T W and V^T c; a pivot of it small
  // against |v_i| |w_j| would amplify rounding as 1 + v.w does for rank 1.
  std::vector<double> capacitance(k * k), y(k);
  double scale = 0;
  for (int64_t i = 0; i < k; ++i) {
    for (int64_t j = 0; j < k; ++j) {
      capacitance[i * k + j] = (i == j) + dot(v[i], w[j], n);
      scale = std::max(scale, norm(v[i], n) * norm(w[j], n));
    }
    y[i] = dot(v[i], c, n);
  }
  bool finite = llvm::all_of(capacitance, [](double e) {
    return std::isfinite(e);
  });
  SolveReport report;
  if (finite && solveSmall(capacitance, y, Tolerances<T>::accept * scale)) {
    report.method = SolveMethod::ShermanMorrison;
    for (int64_t i = 0; i < n; ++i) {
      double xi = c[i];
      for (int64_t j = 0; j < k; ++j)
        xi -= w[j][i] * y[j];
      x[i] = static_cast<T>(xi);
    }
    report.solveMs = millisecondsSince(start);
  } else {
    // Solve the bordered system instead, whose LU pivots around it.
    attempted = SolveMethod::BorderedLU;
    BorderedMatrix<T> bordered(a, u, v);
    std::vector<T> rhs(b, b + n), solution(static_cast<size_t>(n + k));
    rhs.resize(n + k, T(0));
    auto solved = direct(cache->factorise(FactorKind::LU, bordered.view),
                         rhs.data(), solution.data());
    if (!solved)
      return solved.takeError();
    report = *solved;
    report.method = SolveMethod::BorderedLU;
    std::copy(solution.begin(), solution.begin() + n, x);
  }
  // ||b - A x - U (V^T x)|| / ||b||.
  std::vector<T> ax(static_cast<size_t>(n));
  multiply(a, x, ax.data());
  std::vector<double> vx(k);
  for (int64_t j = 0; j < k; ++j)
    vx[j] = dot(v[j], x, n);
  double rr = 0, bNorm = norm(b, n);
  for (int64_t i = 0; i < n; ++i) {
    double r = static_cast<double>(b[i]) - ax[i];
    for (int64_t j = 0; j < k; ++j)
      r -= u[j][i] * vx[j];
    rr += r * r;
  }
  report.relativeResidual = bNorm == 0 ? std::sqrt(rr) : std::sqrt(rr) / bNorm;
  bool iterativeParts = !factorKindOf(current.method) &&
                        current.method != SolveMethod::Auto;
  if (!std::isfinite(report.relativeResidual) ||
      (!iterativeParts && !(report.relativeResidual <= Tolerances<T>::accept)))
    return notAccepted(report.relativeResidual);
  record(stats, report);
  return report;
}

template llvm::Expected<SolveReport> SolveSession::shermanMorrison(
    const SquareBCSRView<double> &, const double *, const double *,
    const double *, const double *, const double *, double *,
    llvm::StringRef);
template llvm::Expected<SolveReport> SolveSession::shermanMorrison(
    const SquareBCSRView<float> &, const float *, const float *,
    const float *, const float *, const float *, float *, llvm::StringRef);
template llvm::Expected<SolveReport> SolveSession::woodbury(
    const SquareBCSRView<double> &, llvm::ArrayRef<const double *>,
    llvm::ArrayRef<const double *>, const double *,
    llvm::ArrayRef<const double *>, const double *, double *,
    llvm::StringRef);
template llvm::Expected<SolveReport> SolveSession::woodbury(
    const SquareBCSRView<float> &, llvm::ArrayRef<const float *>,
    llvm::ArrayRef<const float *>, const float *,
    llvm::ArrayRef<const float *>, const float *, float *, llvm::StringRef);

llvm::Expected<std::shared_ptr<const SparseFactorisation>>
SolveSession::factorise(FactorKind kind, const SquareBCSRView<double> &a,
                        llvm::StringRef statement) {
  SolveStatementStats &stats = statsOf(statement);
  if (kind != FactorKind::LU && !isSymmetric(a, 1e-10, mirrorsOf(stats)))
    return llvm::createStringError(
        "the matrix is not symmetric, and a Cholesky factorisation needs a "
        "symmetric matrix (use lu)");
  auto lookup = cache->factorise(kind, a);
  if (!lookup)
    return lookup.takeError();
  stats.analyses += lookup->analysed;
  stats.factorisations += lookup->factorised;
  stats.reuses += !lookup->factorised;
  stats.analysisMs += lookup->analysisMs;
  stats.factorisationMs += lookup->factorisationMs;
  return std::move(lookup->factor);
}

llvm::Expected<SolveReport>
SolveSession::solveWith(const SparseFactorisation &factor, const double *b,
                        double *x, llvm::StringRef statement) {
  SolveStatementStats &stats = statsOf(statement);
  int64_t n = factor.size();
  SolveReport report;
  report.method = factor.kind() == FactorKind::LU ? SolveMethod::LU
                                                   : SolveMethod::Cholesky;
  if (!std::isfinite(norm(b, n)))
    return countFailure(stats, report.method,
                        llvm::createStringError(
                            "the right-hand side holds a NaN or an infinity"));
  report.reused = true;
  Clock::time_point start = Clock::now();
  if (llvm::Error err = factor.solve(b, x))
    return countFailure(stats, report.method, std::move(err));
  report.solveMs = millisecondsSince(start);
  report.relativeResidual = factor.relativeResidual(b, x);
  if (!(report.relativeResidual <= Tolerances<double>::accept))
    return countFailure(stats, report.method,
                        notAccepted(report.relativeResidual));
  // The factorisation was counted where it was made.
  report.reused = false;
  record(stats, report);
  return report;
}

std::vector<SolveStatementStats> SolveSession::statistics() const {
  return statements;
}

FactorisationCounts SolveSession::factorisationCounts() const {
  return cache->counts();
}

void SolveSession::resetStatistics() {
  statementIndex.clear();
  statements.clear();
  warned.clear();
  mirrors.clear();
}
