//===--- simit-bench-eigen.cpp - Runs the Eigen benchmark scenes ----------===//
//
// Runs springs-bunny, fem-dragon or fem-bar of bench/scenes.md for N frames
// and reports set-up times, per-frame assembly and solve times, their median
// over frames 2..N, CG iteration counts and, on request, the error against
// an exact (direct) solve of the same scene; can write the final positions.
//
//===----------------------------------------------------------------------===//

#include "Scenes.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

using namespace simit::bench;
namespace cl = llvm::cl;

static cl::OptionCategory benchCategory("simit-bench-eigen options");

static cl::opt<std::string> sceneName("scene", cl::Required,
                                      cl::cat(benchCategory),
                                      cl::desc("springs-bunny, fem-dragon "
                                               "or fem-bar"));
static cl::opt<int> frames("frames", cl::init(10), cl::cat(benchCategory),
                           cl::desc("Time steps to simulate (default 10)"));
static cl::opt<int> cgMaxIters(
    "cg-max-iters", cl::init(0), cl::cat(benchCategory),
    cl::desc("CG iteration cap (default: the scene's, 50 or 100)"));
static cl::opt<double> cgTol("cg-tol", cl::init(1e-12), cl::cat(benchCategory),
                             cl::desc("CG stops when r.r <= this"));
static cl::opt<int> refine("refine", cl::init(0), cl::cat(benchCategory),
                           cl::desc("1-to-8 tet refinements (FEM scenes)"));
static cl::opt<std::string>
    solverName("solver", cl::init("cg"), cl::cat(benchCategory),
               cl::desc("cg, jacobi-cg or direct (sparse LDL^T)"));
static cl::opt<std::string> meshDir("meshes", cl::init(SIMIT_DEFAULT_MESH_DIR),
                                    cl::cat(benchCategory),
                                    cl::desc("Directory of the mesh files"));
static cl::opt<std::string>
    outPath("out", cl::cat(benchCategory),
            cl::desc("Write the final positions, x,y,z per vertex"));
static cl::opt<bool> useFloat("float32", cl::cat(benchCategory),
                              cl::desc("Simulate in single precision"));
static cl::opt<bool> referenceDirect(
    "reference-direct", cl::cat(benchCategory),
    cl::desc("Also run the scene with the direct solver in double precision "
             "and report |x - x_ref| / |x_ref - x_0|"));
static cl::opt<std::string> errorOf(
    "error-of", cl::cat(benchCategory),
    cl::desc("Report the error of the positions in this file (x,y,z per "
             "vertex) measured against this run's final positions"));

static cl::opt<double> maxError(
    "max-error", cl::cat(benchCategory), cl::init(-1.0),
    cl::desc("With --error-of: exit with status 1 when the error exceeds "
             "this (for tests)"));

using Positions = Eigen::VectorXd;

static double median(std::vector<double> values) {
  if (values.empty())
    return 0;
  size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  double upper = values[mid];
  if (values.size() % 2)
    return upper;
  double lower = *std::max_element(values.begin(), values.begin() + mid);
  return (lower + upper) / 2;
}

/// |x - reference| / |reference - initial|.
static double relativeError(const Positions &x, const Positions &reference,
                            const Positions &initial) {
  return (x - reference).norm() / (reference - initial).norm();
}

static bool writePositions(const std::string &path, const Positions &x) {
  FILE *file = std::fopen(path.c_str(), "w");
  if (!file)
    return false;
  for (Eigen::Index v = 0; v < x.size() / 3; ++v)
    std::fprintf(file, "%.17g,%.17g,%.17g\n", x[3 * v], x[3 * v + 1],
                 x[3 * v + 2]);
  return std::fclose(file) == 0;
}

/// Reads three numbers per line, separated by commas or blanks; a first
/// line that is not numeric is taken as a header.
static llvm::Expected<Positions> readPositions(const std::string &path,
                                               Eigen::Index numVertices) {
  std::ifstream in(path);
  if (!in)
    return llvm::createStringError(path + ": cannot open");
  std::vector<double> values;
  std::string line;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double xyz[3];
    if (!(fields >> xyz[0] >> xyz[1] >> xyz[2]) || !(fields >> std::ws).eof()) {
      if (lineNo == 1 || line.find_first_not_of(" \t\r") == std::string::npos)
        continue;
      return llvm::createStringError(path + ":" + std::to_string(lineNo) +
                                     ": expected three numbers x,y,z");
    }
    values.insert(values.end(), xyz, xyz + 3);
  }
  if (static_cast<Eigen::Index>(values.size()) != 3 * numVertices)
    return llvm::createStringError(
        path + ": expected " + std::to_string(numVertices) +
        " vertices, read " + std::to_string(values.size() / 3));
  return Eigen::Map<Positions>(values.data(), values.size());
}

static const char *solverLabel(SolverKind kind) {
  switch (kind) {
  case SolverKind::CG:
    return "cg";
  case SolverKind::JacobiCG:
    return "jacobi-cg";
  case SolverKind::Direct:
    return "direct";
  }
  return "";
}

/// The scene's final positions after `frames` steps with the direct solver,
/// in double precision.
static llvm::Expected<Positions> directSolution(const SceneOptions &options) {
  SceneOptions exact = options;
  exact.solver.kind = SolverKind::Direct;
  llvm::Expected<LoadedScene<double>> loaded = createScene<double>(exact);
  if (!loaded)
    return loaded.takeError();
  for (int frame = 1; frame <= frames; ++frame)
    if (!loaded->scene->step().succeeded)
      return llvm::createStringError(
          "the reference's direct factorisation failed at frame " +
          std::to_string(frame));
  return loaded->scene->positions();
}

template <typename Scalar> static int run(const SceneOptions &options) {
  llvm::Expected<LoadedScene<Scalar>> loaded = createScene<Scalar>(options);
  if (!loaded) {
    llvm::errs() << "simit-bench-eigen: " << llvm::toString(loaded.takeError())
                 << "\n";
    return 1;
  }
  ImplicitScene<Scalar> &scene = *loaded->scene;
  const auto &matrix = scene.systemMatrix().matrix();
  const char *precision = sizeof(Scalar) == 4 ? "float32" : "double";
  std::printf("scene      %s (%s): %d vertices, %d free, %d %s, %s\n",
              options.name.c_str(), loaded->meshPath.c_str(),
              scene.numVertices(), scene.numFreeVertices(),
              loaded->numElements,
              options.name == "springs-bunny" ? "springs" : "tets", precision);
  if (options.solver.kind == SolverKind::Direct)
    std::printf("solver     direct (sparse LDL^T)\n");
  else
    std::printf("solver     %s, at most %d iterations, r.r <= %g\n",
                solverLabel(options.solver.kind), options.solver.maxIterations,
                options.solver.tolerance);
  const SetupTimes &setup = scene.setupTimes();
  std::printf("set-up     mesh load %.3f ms, refinement %.3f ms, rest shapes "
              "%.3f ms, masses %.3f ms, sparsity %.3f ms\n",
              loaded->meshLoadMs, loaded->refineMs, setup.restShapeMs,
              setup.massMs, setup.sparsityMs);
  std::printf("matrix     %lld x %lld, %lld nonzeros (%d 3x3 blocks)\n",
              static_cast<long long>(matrix.rows()),
              static_cast<long long>(matrix.cols()),
              static_cast<long long>(matrix.nonZeros()),
              scene.systemMatrix().numBlocks());
  std::printf("%6s %14s %12s %12s %11s %12s\n", "frame", "assembly_ms",
              "solve_ms", "total_ms", "iterations", "r.r");

  std::vector<double> assembly, solve, total, iterations;
  for (int frame = 1; frame <= frames; ++frame) {
    FrameStats stats = scene.step();
    if (!stats.succeeded) {
      std::fprintf(stderr,
                   "simit-bench-eigen: the direct factorisation failed at "
                   "frame %d (the system is not positive definite)\n",
                   frame);
      return 1;
    }
    std::printf("%6d %14.3f %12.3f %12.3f %11d %12.3e\n", frame,
                stats.assemblyMs, stats.solveMs,
                stats.assemblyMs + stats.solveMs, stats.iterations,
                stats.residualNormSq);
    if (frame == 1)
      continue;
    assembly.push_back(stats.assemblyMs);
    solve.push_back(stats.solveMs);
    total.push_back(stats.assemblyMs + stats.solveMs);
    iterations.push_back(stats.iterations);
  }
  std::printf("median     frames 2..%d: assembly %.3f ms, solve %.3f ms, total "
              "%.3f ms, %g CG iterations\n",
              frames.getValue(), median(assembly), median(solve), median(total),
              median(iterations));

  Positions x = scene.positions().template cast<double>();
  Positions x0 = scene.initialPositions().template cast<double>();
  double error = 0;
  if (referenceDirect) {
    llvm::Expected<Positions> reference = directSolution(options);
    if (!reference) {
      llvm::errs() << "simit-bench-eigen: "
                   << llvm::toString(reference.takeError()) << "\n";
      return 1;
    }
    error = relativeError(x, *reference, x0);
    std::printf("error      |x - x_direct| / |x_direct - x_0| after %d frames "
                "= %.6e\n",
                frames.getValue(), error);
  }
  if (!errorOf.empty()) {
    llvm::Expected<Positions> other = readPositions(errorOf, x.size() / 3);
    if (!other) {
      llvm::errs() << "simit-bench-eigen: " << llvm::toString(other.takeError())
                   << "\n";
      return 1;
    }
    double error = relativeError(*other, x, x0);
    std::printf("error      of %s against this run: %.6e\n", errorOf.c_str(),
                error);
    if (maxError >= 0 && !(error <= maxError)) {
      std::printf("error      exceeds --max-error %.3e\n", maxError.getValue());
      return 1;
    }
  }
  if (!outPath.empty() && !writePositions(outPath, x)) {
    llvm::errs() << "simit-bench-eigen: " << outPath << ": cannot write\n";
    return 1;
  }
  // One line for scripts (run-bench.sh); error is "-" without
  // --reference-direct.
  char errorText[32] = "-";
  if (referenceDirect)
    std::snprintf(errorText, sizeof errorText, "%.3e", error);
  std::printf("RESULT scene=%s precision=%s solver=%s cap=%d frames=%d "
              "mesh_ms=%.3f setup_ms=%.3f assembly_ms=%.3f solve_ms=%.3f "
              "total_ms=%.3f iterations=%g error=%s\n",
              options.name.c_str(), precision,
              solverLabel(options.solver.kind), options.solver.maxIterations,
              frames.getValue(), loaded->meshLoadMs + loaded->refineMs,
              setup.restShapeMs + setup.massMs + setup.sparsityMs,
              median(assembly), median(solve), median(total),
              median(iterations), errorText);
  return 0;
}

int main(int argc, char **argv) {
  cl::HideUnrelatedOptions(benchCategory);
  cl::ParseCommandLineOptions(argc, argv,
                              "Eigen reference implementation of the Simit "
                              "benchmark scenes\n");
  SceneOptions options;
  options.name = sceneName;
  options.meshDirectory = meshDir;
  options.refinements = refine;
  if (solverName == "cg")
    options.solver.kind = SolverKind::CG;
  else if (solverName == "jacobi-cg")
    options.solver.kind = SolverKind::JacobiCG;
  else if (solverName == "direct")
    options.solver.kind = SolverKind::Direct;
  else {
    llvm::errs() << "simit-bench-eigen: unknown solver '" << solverName
                 << "'; expected cg, jacobi-cg or direct\n";
    return 1;
  }
  options.solver.maxIterations =
      cgMaxIters > 0 ? cgMaxIters.getValue() : defaultIterationCap(sceneName);
  options.solver.tolerance = cgTol;
  if (frames < 1 || refine < 0) {
    llvm::errs() << "simit-bench-eigen: --frames must be at least 1 and "
                    "--refine at least 0\n";
    return 1;
  }
  return useFloat ? run<float>(options) : run<double>(options);
}
