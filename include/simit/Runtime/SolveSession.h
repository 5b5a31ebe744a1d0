//===--- SolveSession.h - The solver of `x = A \ b` -------------*- C++ -*-===//
//
// Every `x = A \ b` on a system matrix, and chol/lu with their solves, goes
// through the SolveSession of the program that runs it (docs/solvers.md):
//  - the method is the user's choice (SolveSettings: a scene's "solver", or
//    simit-run --solver/--tol/--max-iters), `auto` by default;
//  - direct methods (CHOLMOD Cholesky and LDL^T, UMFPACK LU) analyse each
//    sparsity pattern once, factorise each new matrix value once and reuse
//    a factorisation for every solve with the same value;
//  - answers are never silently wrong: the true residual of every solve is
//    checked or reported, a singular or indefinite matrix is an error, and
//    an iterative solve stopped by the user's iteration cap is reported;
//  - statistics per statement (method, iterations, residual, factorisation
//    times) for simit-run --stats.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SOLVESESSION_H
#define SIMIT_RUNTIME_SOLVESESSION_H

#include "simit/Runtime/Solvers.h"

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace simit {

enum class SolveMethod {
  /// Conjugate gradients when A is symmetric, else (or when CG fails) LU;
  /// the answer always meets the acceptance residual.
  Auto,
  ConjugateGradient,
  JacobiCG,
  BlockJacobiCG,
  /// CG preconditioned by the Cholesky factorisation of an earlier matrix
  /// of the same statement, factorised anew when a solve needs more than
  /// SolveSettings::refactorIterations iterations.
  CholeskyCG,
  Cholesky,
  LDLT,
  LU,
  /// Reported, not chosen: the two ways of the Sherman–Morrison rewrite's
  /// last step (x from A^-1 u and A^-1 b, or the bordered system).
  ShermanMorrison,
  BorderedLU,
};

/// "auto", "cg", "pcg-jacobi", "pcg-block-jacobi", "pcg-cholesky",
/// "cholesky", "ldlt", "lu" (the methods a user chooses),
/// "sherman-morrison", "bordered-lu".
llvm::StringRef solveMethodName(SolveMethod method);
std::optional<SolveMethod> parseSolveMethod(llvm::StringRef name);
/// The names above, comma separated, for messages.
llvm::StringRef solveMethodNames();

struct SolveSettings {
  SolveMethod method = SolveMethod::Auto;
  /// Iterative methods: stop once ||b - A x|| <= tolerance ||b|| (the true
  /// residual). Default 1e-10 (f64) / 1e-5 (f32); `auto`'s CG 1e-12 / 1e-6.
  std::optional<double> tolerance;
  /// Iterative methods: the iteration cap. Default 2n, n the unknowns.
  std::optional<int64_t> maxIterations;
  /// A solve stopped by the cap is an error rather than a warning.
  bool strict = false;
  /// Iterative methods: start from the previous answer of the same
  /// statement (when it has the same size) instead of from zero.
  bool warmStart = true;
  /// pcg-cholesky: a solve not converged after this many iterations with
  /// the statement's factorisation factorises its own matrix and goes on
  /// with that. Default kDefaultRefactorIterations.
  std::optional<int64_t> refactorIterations;
};

constexpr int64_t kDefaultRefactorIterations = 20;

/// Settings given on top of others (the command line over a scene's).
struct SolveSettingsOverride {
  std::optional<SolveMethod> method;
  std::optional<double> tolerance;
  std::optional<int64_t> maxIterations;
  std::optional<bool> strict;
  std::optional<bool> warmStart;
  std::optional<int64_t> refactorIterations;

  SolveSettings appliedTo(SolveSettings settings) const;
};

/// A settings error (tolerance not in (0, 1), cap or refactorisation
/// threshold below 1), naming `where`.
llvm::Error checkSolveSettings(const SolveSettings &settings,
                               llvm::StringRef where);

enum class FactorKind { Cholesky, LDLT, LU };

struct FactorisationCounts {
  int64_t analyses = 0, factorisations = 0, reuses = 0;
};

/// What one solve did.
struct SolveReport {
  /// The method that produced x (`auto` reports CG or LU).
  SolveMethod method = SolveMethod::ConjugateGradient;
  int iterations = 0;
  /// ||b - A x|| / ||b|| of the returned x, computed anew (0 when b = 0).
  double relativeResidual = 0;
  /// False only for an iterative solve stopped by the iteration cap.
  bool converged = true;
  bool analysed = false, factorised = false, reused = false;
  double analysisMs = 0, factorisationMs = 0, solveMs = 0;
};

/// The solves of one statement (its `where` text) so far.
struct SolveStatementStats {
  std::string statement;
  /// The methods its solves used, in first-use order.
  std::vector<SolveMethod> methods;
  int64_t solves = 0, iterations = 0, maxIterations = 0, notConverged = 0;
  /// Solves that stopped the program (singular, indefinite, ...): their
  /// method is among `methods`, their figures are not counted above.
  int64_t failed = 0;
  double lastRelativeResidual = 0, maxRelativeResidual = 0;
  int64_t analyses = 0, factorisations = 0, reuses = 0;
  double analysisMs = 0, factorisationMs = 0, solveMs = 0;
};

class FactorCache;
struct FactorLookup;
class SparseFactorisation;

/// A system `(A + u v^T) x = b` as the Sherman–Morrison rewrite hands it to
/// the runtime; the pointers live only during the observer's call.
struct RankOneSystem {
  llvm::StringRef statement;
  SquareBCSRView<double> a;
  const double *u = nullptr, *v = nullptr, *b = nullptr;
};
using RankOneSystemObserver = std::function<void(const RankOneSystem &)>;

class SolveSession {
public:
  explicit SolveSession(SolveSettings settings = {});
  ~SolveSession();
  SolveSession(const SolveSession &) = delete;
  SolveSession &operator=(const SolveSession &) = delete;

  const SolveSettings &settings() const { return current; }
  void setSettings(const SolveSettings &settings) { current = settings; }

  /// x = A^-1 b by the settings' method; `statement` names the statement in
  /// errors, warnings and statistics. Errors: a NaN or infinity in b, a
  /// singular or (for CG, Cholesky) indefinite matrix, a symmetric method
  /// on a non-symmetric matrix, a direct answer whose relative residual is
  /// above 1e-8 (f32: 1e-3), and, with `strict`, an iterative solve stopped
  /// by the cap. Without `strict` such a solve warns on stderr once per
  /// statement and counts in notConverged. With `warmStart`, an iterative
  /// method starts from the statement's previous answer (x's contents on
  /// entry are never read).
  template <typename T>
  llvm::Expected<SolveReport> solve(const SquareBCSRView<T> &a, const T *b,
                                    T *x, llvm::StringRef statement);

  /// The factorisation of chol (Cholesky) or lu (LU) on a system matrix,
  /// shared with the cache; reused when the values are the same.
  llvm::Expected<std::shared_ptr<const SparseFactorisation>>
  factorise(FactorKind kind, const SquareBCSRView<double> &a,
            llvm::StringRef statement);
  /// lltsolve / lusolve with a factorisation, residual checked.
  llvm::Expected<SolveReport> solveWith(const SparseFactorisation &factor,
                                        const double *b, double *x,
                                        llvm::StringRef statement);

  /// The last step of `(A + u v^T) \ b` rewritten by simit-sherman-morrison:
  /// given w = A^-1 u and c = A^-1 b (solved with A's one factorisation),
  /// x = c - w (v.c) / (1 + v.w). When |1 + v.w| <= 1e-8 |v| |w| (f32:
  /// 1e-3) that division would lose the answer (or A + u v^T is near
  /// singular): x comes from the bordered system [A u; v^T -1] [x; y] =
  /// [b; 0] by LU instead. The residual ||b - (A + u v^T) x|| / ||b|| is
  /// checked like a direct solve's unless the settings' method is
  /// iterative (w and c are then only as good as its tolerance).
  template <typename T>
  llvm::Expected<SolveReport>
  shermanMorrison(const SquareBCSRView<T> &a, const T *u, const T *v,
                  const T *b, const T *w, const T *c, T *x,
                  llvm::StringRef statement);
  /// The rank-k form (Woodbury): `(A + U V^T) \ b` given W = A^-1 U and
  /// c = A^-1 b, x = c - W (I + V^T W)^-1 V^T c, the k x k system solved by
  /// LU with partial pivoting. A pivot at most 1e-8 (f32: 1e-3) times the
  /// largest |v_i| |w_j| means that solve would lose the answer: x comes
  /// from the bordered system [A U; V^T -I] [x; y] = [b; 0] by LU instead.
  /// The residual is checked as for shermanMorrison, which is its k = 1.
  template <typename T>
  llvm::Expected<SolveReport>
  woodbury(const SquareBCSRView<T> &a, llvm::ArrayRef<const T *> u,
           llvm::ArrayRef<const T *> v, const T *b,
           llvm::ArrayRef<const T *> w, const T *c, T *x,
           llvm::StringRef statement);

  /// Calls `observer` (empty: none) with every double-precision system that
  /// shermanMorrison solves, before solving it: a host keeps the systems a
  /// program solves (bench/sherman-morrison takes the pressure chamber's
  /// Newton systems from it).
  void observeRankOneSystems(RankOneSystemObserver observer) {
    rankOneObserver = std::move(observer);
  }

  /// Per statement, in the order they first ran.
  std::vector<SolveStatementStats> statistics() const;
  /// All analyses, factorisations and reuses of the session.
  FactorisationCounts factorisationCounts() const;
  void resetStatistics();

private:
  SolveStatementStats &statsOf(llvm::StringRef statement);
  /// The mirror map of the matrices `stats`'s statement solves.
  BlockMirrors &mirrorsOf(const SolveStatementStats &stats);
  void record(SolveStatementStats &stats, const SolveReport &report);
  /// Counts `result` in `stats` as a failure of `method` when it is an
  /// error (a successful one was recorded where it was made).
  llvm::Expected<SolveReport> countFailure(SolveStatementStats &stats,
                                           SolveMethod method,
                                           llvm::Expected<SolveReport> result);
  /// solve() but for counting its failure: `attempted` becomes the method
  /// that failed (LU when `auto` fell back to it).
  template <typename T>
  llvm::Expected<SolveReport>
  solveRecorded(const SquareBCSRView<T> &a, const T *b, T *x,
                SolveStatementStats &stats, SolveMethod &attempted);
  /// woodbury() but for counting its failure (as `attempted`).
  template <typename T>
  llvm::Expected<SolveReport>
  woodburyRecorded(const SquareBCSRView<T> &a, llvm::ArrayRef<const T *> u,
                   llvm::ArrayRef<const T *> v, const T *b,
                   llvm::ArrayRef<const T *> w, const T *c, T *x,
                   SolveStatementStats &stats, SolveMethod &attempted);
  template <typename T>
  llvm::Expected<SolveReport> iterative(const SquareBCSRView<T> &a,
                                        const T *b, T *x, double bNorm,
                                        SolveStatementStats &stats);
  /// pcg-cholesky (SolveMethod::CholeskyCG): CG from x with `options`,
  /// preconditioned by the statement's factorisation; the factorisations
  /// it makes are added to `report`.
  template <typename T>
  llvm::Expected<SolverResult>
  factorPreconditioned(const SquareBCSRView<T> &a, const T *b, T *x,
                       SolverOptions options, llvm::StringRef statement,
                       SolveReport &report);
  /// Solves with the factorisation `lookup` found or made.
  template <typename T>
  llvm::Expected<SolveReport> direct(llvm::Expected<FactorLookup> lookup,
                                     const T *b, T *x);

  SolveSettings current;
  std::unique_ptr<FactorCache> cache;
  std::map<std::string, size_t, std::less<>> statementIndex;
  std::vector<SolveStatementStats> statements;
  /// Statements whose cap warning was printed.
  std::vector<bool> warned;
  /// Per statement, as statements.
  std::vector<BlockMirrors> mirrors;
  /// The latest answer of each statement solved iteratively, the starting
  /// point of its next solve (SolveSettings::warmStart).
  std::map<std::string, std::vector<double>, std::less<>> previousAnswers;
  /// pcg-cholesky's preconditioner of one statement: the factorisation of
  /// an earlier matrix, and the storage of its rounded solves.
  struct CholeskyPreconditioner {
    std::shared_ptr<const SparseFactorisation> factor;
    std::vector<double> scratch;
  };
  std::map<std::string, CholeskyPreconditioner, std::less<>>
      preconditionerFactors;
  RankOneSystemObserver rankOneObserver;
};

/// OpenBLAS's version, build and kernels: the BLAS the direct solvers run
/// on.
std::string sparseDirectBLAS();

/// Makes OpenBLAS use the widest kernels the CPU's features allow where it
/// fell back to its generic ones (a CPU newer than it knows), unless
/// OPENBLAS_CORETYPE is set or SIMIT_BLAS_CORETYPE=keep; once per process,
/// before any BLAS call it should speed up. Returns the kernels' name.
std::string selectBlasKernels();

} // namespace simit

#endif // SIMIT_RUNTIME_SOLVESESSION_H
