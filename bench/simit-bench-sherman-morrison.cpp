//===--- simit-bench-sherman-morrison.cpp - Rank-one Newton solves --------===//
//
// The seed's table (shared/seeds/003_0af6eb45af1efb0d.txt) on the pressure
// chamber's own Newton systems (examples/chamber): for each scene it runs the
// chamber program until the Newton step asked for, takes the system
// (H_s + u v^T) d = r that the program hands the runtime, and times, side by
// side in this process,
//   slow: forming the dense H_s + u v^T and solving it by LU with partial
//         pivoting (LAPACK dgetrf/dgetrs of OpenBLAS);
//   fast: what simit-sherman-morrison makes of it: H_s w = u and H_s c = r
//         solved with one sparse factorisation, and the last step
//         d = c - w (v.c) / (1 + v.w), timed twice:
//         cold:   a fresh SolveSession, which analyses the pattern (fill-
//                 reducing ordering, elimination tree) before factorising,
//                 as the dense path starts from nothing;
//         Newton: a SolveSession that has solved the next Newton step's
//                 system (same pattern, other values), as in the program's
//                 Newton loop: the analysis is reused, the numeric
//                 factorisation is not.
// Both answers, and the step the program itself took, are compared. Run
// with OPENBLAS_NUM_THREADS=1 for one thread on both paths (bench/sherman-
// morrison does).
//
//===----------------------------------------------------------------------===//

#include "simit/Engine/SceneRun.h"
#include "simit/Runtime/OpenMPThreads.h"
#include "simit/Runtime/Scene.h"
#include "simit/Runtime/Set.h"
#include "simit/Runtime/SolveSession.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/TargetSelect.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <vector>

extern "C" {
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv,
             int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs,
             const double *a, const int *lda, const int *ipiv, double *b,
             const int *ldb, int *info, size_t transLength);
int openblas_get_num_threads();
}

using namespace simit;

namespace {

llvm::cl::list<std::string>
    cases(llvm::cl::Positional, llvm::cl::OneOrMore,
          llvm::cl::desc("<n>:<chamber scene.json>... (n: the seed's size "
                         "whose speedup the row is compared with, or 0)"));
llvm::cl::opt<int> newtonStep(
    "newton-step", llvm::cl::init(2),
    llvm::cl::desc("The Newton step whose system is solved (default 2)"));
llvm::cl::opt<int> repetitions("reps", llvm::cl::init(3),
                               llvm::cl::desc("Timed runs per path; the "
                                              "median is reported (default 3)"));
llvm::cl::opt<std::string> solverName(
    "solver",
    llvm::cl::desc("The fast path's method (default: the scene's \"solver\")"));
llvm::cl::opt<std::string> csvPath("csv",
                                   llvm::cl::desc("Also write the table here"));

/// The seed's speedups (dense LU of A + u v^T over Sherman–Morrison).
const std::map<int, double> kSeedSpeedup = {
    {500, 1.65}, {1000, 1.93}, {2000, 1.94},
    {5000, 2.12}, {10000, 2.75}, {30000, 3.34}};

/// A copy of one system the runtime was given.
struct System {
  int64_t blocks = 0, blockSize = 0;
  std::vector<int32_t> rowptr, colidx;
  std::vector<double> values, u, v, b;

  SquareBCSRView<double> view() const {
    SquareBCSRView<double> a;
    a.rows = blocks;
    a.blockSize = blockSize;
    a.rowptr = rowptr.data();
    a.colidx = colidx.data();
    a.values = values.data();
    return a;
  }
  int64_t size() const { return blocks * blockSize; }
  int64_t nonzeros() const {
    return static_cast<int64_t>(values.size());
  }
};

System copyOf(const RankOneSystem &s) {
  System out;
  out.blocks = s.a.rows;
  out.blockSize = s.a.blockSize;
  int64_t n = s.a.size(), blockValues = s.a.blockSize * s.a.blockSize;
  out.rowptr.assign(s.a.rowptr, s.a.rowptr + s.a.rows + 1);
  out.colidx.assign(s.a.colidx, s.a.colidx + out.rowptr.back());
  out.values.assign(s.a.values, s.a.values + out.rowptr.back() * blockValues);
  out.u.assign(s.u, s.u + n);
  out.v.assign(s.v, s.v + n);
  out.b.assign(s.b, s.b + n);
  return out;
}

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                       start)
      .count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  size_t m = values.size() / 2;
  return values.size() % 2 ? values[m] : 0.5 * (values[m - 1] + values[m]);
}

double relativeDifference(const std::vector<double> &x,
                          const std::vector<double> &reference) {
  double dd = 0, rr = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    dd += (x[i] - reference[i]) * (x[i] - reference[i]);
    rr += reference[i] * reference[i];
  }
  return std::sqrt(dd / rr);
}

/// The slow path: dense H_s + u v^T (column-major), LU, solve.
llvm::Expected<std::vector<double>> denseSolve(const System &s) {
  int n = static_cast<int>(s.size());
  std::vector<double> dense(static_cast<size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      dense[static_cast<size_t>(j) * n + i] = s.u[i] * s.v[j];
  int64_t bs = s.blockSize;
  for (int64_t br = 0; br < s.blocks; ++br)
    for (int32_t k = s.rowptr[br]; k < s.rowptr[br + 1]; ++k)
      for (int64_t i = 0; i < bs; ++i)
        for (int64_t j = 0; j < bs; ++j)
          dense[static_cast<size_t>(s.colidx[k] * bs + j) * n + br * bs + i] +=
              s.values[(k * bs + i) * bs + j];
  std::vector<int> pivots(n);
  std::vector<double> x = s.b;
  int info = 0, one = 1;
  dgetrf_(&n, &n, dense.data(), &n, pivots.data(), &info);
  if (info != 0)
    return llvm::createStringError(
        llvm::formatv("dense LU: dgetrf reports {0}", info).str());
  dgetrs_("N", &n, &one, dense.data(), &n, pivots.data(), x.data(), &n,
          &info, 1);
  return x;
}

/// Where the fast path's time went, in seconds.
struct FastParts {
  double analysis = 0, factorisation = 0, solves = 0;
};

/// The fast path: the Sherman–Morrison rewrite's runtime calls.
llvm::Expected<std::vector<double>>
shermanMorrisonSolve(SolveSession &session, const System &s,
                     FastParts &parts) {
  session.resetStatistics();
  int64_t n = s.size();
  std::vector<double> w(n), c(n), x(n);
  SquareBCSRView<double> a = s.view();
  if (auto r = session.solve(a, s.u.data(), w.data(), "A^-1 u"); !r)
    return r.takeError();
  if (auto r = session.solve(a, s.b.data(), c.data(), "A^-1 b"); !r)
    return r.takeError();
  if (auto r = session.shermanMorrison(a, s.u.data(), s.v.data(), s.b.data(),
                                       w.data(), c.data(), x.data(), "last");
      !r)
    return r.takeError();
  parts = FastParts();
  for (const SolveStatementStats &stats : session.statistics()) {
    parts.analysis += stats.analysisMs / 1000;
    parts.factorisation += stats.factorisationMs / 1000;
    parts.solves += stats.solveMs / 1000;
  }
  return x;
}

struct Row {
  int seedSize = 0;
  int64_t n = 0, nonzeros = 0, coupled = 0;
  double slow = 0, fastCold = 0, fastNewton = 0, differenceFastSlow = 0,
         differenceProgramSlow = 0;
  /// Medians of the cold fast path's parts.
  FastParts fastParts;
};

/// The systems of two successive Newton steps of the chamber, and the
/// step the program took in the first.
struct Captured {
  System system, next;
  std::vector<double> step;
};

/// Runs the chamber scene through Newton steps newtonStep and newtonStep+1.
llvm::Expected<Captured> chamberSystems(const std::string &scenePath) {
  auto scene = loadScene(scenePath);
  if (!scene)
    return scene.takeError();
  SceneRunOptions options;
  options.frames = newtonStep + 1;
  auto runner = SceneRunner::create(std::move(*scene), options);
  if (!runner)
    return runner.takeError();
  std::optional<System> captured;
  (*runner)->solver().observeRankOneSystems(
      [&](const RankOneSystem &s) { captured = copyOf(s); });
  if (llvm::Error err = (*runner)->init())
    return std::move(err);
  if (newtonStep > 1)
    if (llvm::Error err = (*runner)->step(newtonStep - 1))
      return std::move(err);
  Set *verts = (*runner)->sets().find("verts");
  if (!verts)
    return llvm::createStringError("the scene has no set \"verts\"");
  auto positions = [&] {
    const double *x = static_cast<const double *>(verts->fieldData("x"));
    return std::vector<double>(x, x + 3 * verts->size());
  };
  // One frame is one Newton step; `step` is its number, for the message.
  auto nextSystem = [&](int64_t step) -> llvm::Expected<System> {
    captured.reset();
    if (llvm::Error err = (*runner)->step(1))
      return std::move(err);
    if (!captured)
      return llvm::createStringError(
          llvm::formatv("Newton step {0} solved no (A + u v^T) system (the "
                        "iteration had converged?)",
                        step)
              .str());
    return std::move(*captured);
  };
  std::vector<double> before = positions();
  llvm::Expected<System> system = nextSystem(newtonStep);
  if (!system)
    return system.takeError();
  std::vector<double> step = positions();
  for (size_t i = 0; i < step.size(); ++i)
    step[i] -= before[i];
  if (static_cast<int64_t>(step.size()) != system->size())
    return llvm::createStringError("the system's unknowns are not verts.x");
  llvm::Expected<System> next = nextSystem(newtonStep + 1);
  if (!next)
    return next.takeError();
  return Captured{std::move(*system), std::move(*next), std::move(step)};
}

llvm::Expected<Row> measure(int seedSize, const std::string &scenePath) {
  auto captured = chamberSystems(scenePath);
  if (!captured)
    return captured.takeError();
  const System &s = captured->system;
  SolveMethod method = SolveMethod::LU;
  if (!solverName.empty()) {
    auto parsed = parseSolveMethod(solverName);
    if (!parsed)
      return llvm::createStringError("unknown --solver " + solverName);
    method = *parsed;
  } else if (auto scene = loadScene(scenePath)) {
    method = scene->solver.method;
  } else {
    return scene.takeError();
  }
  Row row;
  row.seedSize = seedSize;
  row.n = s.size();
  row.nonzeros = s.nonzeros();
  row.coupled = std::count_if(s.u.begin(), s.u.end(),
                              [](double x) { return x != 0; });
  std::vector<double> slowTimes, coldTimes, newtonTimes, analysisTimes,
      numericTimes, solveTimes, slow, fast;
  SolveSession newton(SolveSettings{method});
  FastParts parts;
  if (auto warm = shermanMorrisonSolve(newton, captured->next, parts); !warm)
    return warm.takeError();
  // Alternate the paths so that a change in the machine's load hits both.
  for (int rep = 0; rep < repetitions; ++rep) {
    auto start = std::chrono::steady_clock::now();
    auto dense = denseSolve(s);
    if (!dense)
      return dense.takeError();
    slowTimes.push_back(seconds(start));
    start = std::chrono::steady_clock::now();
    auto rewritten = [&] {
      SolveSession cold(SolveSettings{method});
      return shermanMorrisonSolve(cold, s, parts);
    }();
    if (!rewritten)
      return rewritten.takeError();
    coldTimes.push_back(seconds(start));
    analysisTimes.push_back(parts.analysis);
    numericTimes.push_back(parts.factorisation);
    solveTimes.push_back(parts.solves);
    // The warm session's latest factorisation is the next step's: this one
    // is factorised anew on the analysis kept.
    start = std::chrono::steady_clock::now();
    auto inLoop = shermanMorrisonSolve(newton, s, parts);
    if (!inLoop)
      return inLoop.takeError();
    newtonTimes.push_back(seconds(start));
    if (parts.analysis != 0 || parts.factorisation == 0)
      return llvm::createStringError(
          "the warm session did not reuse the analysis and factorise anew");
    if (auto next = shermanMorrisonSolve(newton, captured->next, parts); !next)
      return next.takeError();
    if (relativeDifference(*inLoop, *rewritten) > 1e-12)
      return llvm::createStringError("the warm and cold answers differ");
    slow = std::move(*dense);
    fast = std::move(*rewritten);
  }
  row.slow = median(slowTimes);
  row.fastCold = median(coldTimes);
  row.fastNewton = median(newtonTimes);
  row.fastParts = {median(analysisTimes), median(numericTimes),
                   median(solveTimes)};
  row.differenceFastSlow = relativeDifference(fast, slow);
  row.differenceProgramSlow = relativeDifference(captured->step, slow);
  return row;
}

} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  llvm::InitializeNativeTarget();
  llvm::InitializeNativeTargetAsmPrinter();
  llvm::cl::ParseCommandLineOptions(
      argc, argv,
      "Dense LU of H_s + u v^T against the Sherman-Morrison rewrite on the "
      "pressure chamber's Newton systems\n");
  // Both paths on one thread (CHOLMOD's OpenMP loops included) and on the
  // kernels the runtime's factorisations use.
  simit::capOpenMPThreads(1);
  std::string kernels = simit::selectBlasKernels();
  llvm::outs() << llvm::formatv(
      "OpenBLAS threads: {0}, kernels {1}; Newton step {2}; median of {3} "
      "runs\n",
      openblas_get_num_threads(), kernels, newtonStep.getValue(),
      repetitions.getValue());
  llvm::outs() << llvm::formatv(
      "{0,6} {1,8} {2,6} {3,10} {4,10} {5,10} {6,22} {7,7} {8,7} {9,5} "
      "{10,7} {11,9} {12,9} {13}\n",
      "n", "nnz(H_s)", "cavity", "slow (s)", "cold (s)", "Newton (s)",
      "cold: analyse/fact/sol", "x cold", "x Newton", "seed", "5x seed",
      "fast-slow", "prog-slow", "verdict (cold, Newton)");
  std::string csv = "seed_n,n,nnz,cavity_unknowns,slow_s,fast_cold_s,"
                    "fast_newton_s,speedup_cold,speedup_newton,seed_speedup,"
                    "diff_fast_slow,diff_program_slow\n";
  bool allEqual = true, allColdFaster = true, allNewtonFaster = true;
  for (const std::string &item : cases) {
    auto [sizeText, scenePath] = llvm::StringRef(item).split(':');
    int seedSize = 0;
    if (scenePath.empty() || sizeText.getAsInteger(10, seedSize)) {
      llvm::errs() << "simit-bench-sherman-morrison: expected <n>:<scene>, "
                      "found '"
                   << item << "'\n";
      return 2;
    }
    auto row = measure(seedSize, scenePath.str());
    if (!row) {
      llvm::errs() << "simit-bench-sherman-morrison: " << scenePath << ": "
                   << llvm::toString(row.takeError()) << "\n";
      return 1;
    }
    double cold = row->slow / row->fastCold;
    double newton = row->slow / row->fastNewton;
    auto seed = kSeedSpeedup.find(seedSize);
    double target = seed == kSeedSpeedup.end() ? 0 : 5 * seed->second;
    bool equal = row->differenceFastSlow <= 1e-9 &&
                 row->differenceProgramSlow <= 1e-9;
    allEqual &= equal;
    allColdFaster &= cold >= target;
    allNewtonFaster &= newton >= target;
    auto verdict = [&](double speedup) {
      return seed == kSeedSpeedup.end() ? "-"
             : speedup >= target        ? "ok"
                                        : "below";
    };
    std::string seedText =
        seed == kSeedSpeedup.end()
            ? "-"
            : llvm::formatv("{0:F2}", seed->second).str();
    std::string targetText =
        seed == kSeedSpeedup.end() ? "-"
                                   : llvm::formatv("{0:F2}", target).str();
    llvm::outs() << llvm::formatv(
        "{0,6} {1,8} {2,6} {3,10:F5} {4,10:F5} {5,10:F5} {6,22} {7,7:F2} "
        "{8,7:F2} {9,5} {10,7} {11,9:E1} {12,9:E1} {13}\n",
        row->n, row->nonzeros, row->coupled, row->slow, row->fastCold,
        row->fastNewton,
        llvm::formatv("{0:F2}/{1:F2}/{2:F2} ms",
                      1000 * row->fastParts.analysis,
                      1000 * row->fastParts.factorisation,
                      1000 * row->fastParts.solves)
            .str(),
        cold, newton, seedText, targetText, row->differenceFastSlow,
        row->differenceProgramSlow,
        equal ? (std::string(verdict(cold)) + ", " + verdict(newton))
              : std::string("DIFFERENT"));
    csv += llvm::formatv("{0},{1},{2},{3},{4:E6},{5:E6},{6:E6},{7:F3},{8:F3},"
                         "{9},{10:E3},{11:E3}\n",
                         seedSize, row->n, row->nonzeros, row->coupled,
                         row->slow, row->fastCold, row->fastNewton, cold,
                         newton,
                         seed == kSeedSpeedup.end() ? 0.0 : seed->second,
                         row->differenceFastSlow, row->differenceProgramSlow)
               .str();
    llvm::outs().flush();
  }
  if (!csvPath.empty()) {
    std::error_code ec;
    llvm::raw_fd_ostream out(csvPath, ec, llvm::sys::fs::OF_Text);
    if (ec) {
      llvm::errs() << "simit-bench-sherman-morrison: " << csvPath << ": "
                   << ec.message() << "\n";
      return 1;
    }
    out << csv;
  }
  llvm::outs() << "answers equal to 1e-9: " << (allEqual ? "yes" : "NO")
               << "\nat least 5x the seed's speedup, cold: "
               << (allColdFaster ? "yes" : "no")
               << "; in the Newton loop: " << (allNewtonFaster ? "yes" : "no")
               << "\n";
  return allEqual ? 0 : 1;
}
