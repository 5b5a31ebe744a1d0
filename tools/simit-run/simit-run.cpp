//===--- simit-run.cpp - JIT-runs Simit programs --------------------------===//
//
//   simit-run PROGRAM --scene SCENE.json [--output-dir DIR] [--time]
//             [--no-cache | --cache-dir DIR] [--threads N] [--stats]
//             [--solver METHOD] [--tol T] [--max-iters N] [--solver-strict]
//             [--refactor-iters N]
//             [--no-warm-start] [--no-sherman-morrison]
//             [--no-skip-uncalled] [--no-skip-unused-fields]
//             [--no-fold-constants] [--no-dead-assemblies] [--no-simd]
//   simit-run --test FILE.sim
//   simit-run FILE.sim --eval 'f(1.0, [1, 2]')'
//   simit-run FILE.sim --emit=simit|loops|llvm
//   simit-run --cuda-device
// Every mode takes --target cpu|gpu.
//
// docs/simit-run.md describes the modes and options.
//
//===----------------------------------------------------------------------===//

#include "TestRun.h"

#include "simit/Engine/Program.h"
#include "simit/Engine/SceneRun.h"
#include "simit/Engine/ThreadsOption.h"
#include "simit/Runtime/CudaDriver.h"
#include "simit/Runtime/OpenMPThreads.h"

#include "llvm/ADT/SmallString.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"

#include <optional>
#include <vector>

using namespace simit;

namespace cl = llvm::cl;

static cl::OptionCategory runCategory("simit-run options");

static cl::opt<std::string> programPath(cl::cat(runCategory), cl::Positional,
                                        cl::desc("<program .sim or .mlir>"),
                                        cl::init(""));
static cl::opt<std::string> scenePath(cl::cat(runCategory), "scene", cl::desc("Run on a scene file"),
                                      cl::value_desc("scene.json"));
static cl::opt<std::string> outputDirectory(
    cl::cat(runCategory), "output-dir",
    cl::desc("Where scene outputs are written (default: "
             "simit-output/<scene file name without .json>)"),
    cl::value_desc("dir"));
static cl::opt<int> frames(cl::cat(runCategory), "frames",
                           cl::desc("Override the scene's frame count"),
                           cl::init(-1));
static cl::opt<bool> testMode(cl::cat(runCategory), "test",
                              cl::desc("Run the file's %! assertions"));
static cl::opt<std::string> evalCall(cl::cat(runCategory), "eval",
                                     cl::desc("Call one function with literal "
                                              "arguments and print the results"),
                                     cl::value_desc("f(args)"));
static cl::opt<Stage> emitStage(cl::cat(runCategory), 
    "emit", cl::desc("Print the IR at a stage instead of running"),
    cl::values(clEnumValN(Stage::Simit, "simit", "the simit dialect"),
               clEnumValN(Stage::Loops, "loops",
                          "loops over sets (after convert-simit-to-loops)"),
               clEnumValN(Stage::LLVM, "llvm", "the LLVM dialect")));
static cl::opt<bool> printTimes(cl::cat(runCategory), "time",
                                cl::desc("Print compile, bind/init and "
                                         "per-frame times"));
static cl::opt<bool> checkNumerics(cl::cat(runCategory), 
    "check-numerics",
    cl::desc("Stop at the first NaN or infinity an assembly, a solve or a "
             "function leaves (the default)"));
static cl::opt<bool>
    noCheck(cl::cat(runCategory), "no-check",
            cl::desc("Do not scan assemblies, solves and the state for NaN "
                     "or infinity (for benchmarks)"));
static cl::opt<bool> float32(cl::cat(runCategory), "float32",
                             cl::desc("Compile `float` as single precision"));
static cl::opt<bool> noCache(cl::cat(runCategory), "no-cache",
                             cl::desc("Compile the program even when the "
                                      "compile cache holds it, and store "
                                      "nothing"));
static cl::opt<std::string> cacheDir(
    cl::cat(runCategory), "cache-dir",
    cl::desc("The compile cache (default: $XDG_CACHE_HOME/simit, else "
             "~/.cache/simit)"),
    cl::value_desc("dir"));
static cl::opt<bool> noProgress(cl::cat(runCategory), "no-progress",
                                cl::desc("No progress lines on long runs"));
static cl::list<std::string>
    externLibraries(cl::cat(runCategory), "extern-lib",
                    cl::desc("A shared library with the C functions of the "
                             "program's extern funcs (repeatable)"),
                    cl::value_desc("lib.so"));
static cl::opt<std::string> solverMethod(
    cl::cat(runCategory), "solver",
    cl::desc("How `x = A \\ b` solves: auto, cg, pcg-jacobi, "
             "pcg-block-jacobi, pcg-cholesky, cholesky, ldlt or lu "
             "(overrides the scene's \"solver\")"),
    cl::value_desc("method"));
static cl::opt<double> solverTolerance(
    cl::cat(runCategory), "tol",
    cl::desc("Iterative solves stop at ||b - A x|| <= tol ||b||"),
    cl::value_desc("tol"));
static cl::opt<int64_t> solverMaxIterations(
    cl::cat(runCategory), "max-iters",
    cl::desc("The iteration cap of iterative solves"), cl::value_desc("n"));
static cl::opt<int64_t> solverRefactorIterations(
    cl::cat(runCategory), "refactor-iters",
    cl::desc("pcg-cholesky: a solve not converged after n iterations "
             "factorises its matrix anew (default 20)"),
    cl::value_desc("n"));
static cl::opt<bool> solverStrict(
    cl::cat(runCategory), "solver-strict",
    cl::desc("An iterative solve stopped by the cap is an error, not a "
             "warning"));
static cl::opt<bool> noWarmStart(
    cl::cat(runCategory), "no-warm-start",
    cl::desc("Iterative solves start from zero, not from the statement's "
             "previous answer"));
static cl::opt<bool> noShermanMorrison(
    cl::cat(runCategory), "no-sherman-morrison",
    cl::desc("Solve (A + u*v') \\ b as written instead of by "
             "Sherman-Morrison"));
static cl::opt<bool> noSkipUncalled(
    cl::cat(runCategory), "no-skip-uncalled",
    cl::desc("Compile every exported function, not only the scene's init "
             "and step functions"));
static cl::opt<bool> noSkipUnusedFields(
    cl::cat(runCategory), "no-skip-unused-fields",
    cl::desc("Build every field the scene gives, also those no function "
             "uses and no output names"));
static cl::opt<bool> noFoldConstants(
    cl::cat(runCategory), "no-fold-constants",
    cl::desc("Bind the externs the scene marks constant and the fields it "
             "gives one value instead of folding them into the code"));
static cl::opt<bool> noDeadAssemblies(
    cl::cat(runCategory), "no-dead-assemblies",
    cl::desc("Assemble map results that nothing uses"));
static cl::opt<bool> noSimd(
    cl::cat(runCategory), "no-simd",
    cl::desc("Run element kernels one element at a time, not one element "
             "per vector lane (the results are the same)"));
static cl::opt<Target> target(
    cl::cat(runCategory), "target",
    cl::desc("Where the program's set loops run (default: cpu)"),
    cl::values(clEnumValN(Target::CPU, "cpu", "the host CPU"),
               clEnumValN(Target::GPU, "gpu",
                          "CUDA kernels on the first NVIDIA GPU")),
    cl::init(Target::CPU));
static cl::opt<bool> cudaDevice(
    cl::cat(runCategory), "cuda-device",
    cl::desc("Print the CUDA device --target gpu runs on, or why there is "
             "none (then exit 1)"));
/// --stats: registered in main, in place of LLVM's -stats (pass statistics,
/// which this tool has no use for).
static std::optional<cl::opt<bool>> printStats;

static int fail(llvm::Error err) {
  llvm::errs() << "simit-run: " << llvm::toString(std::move(err)) << "\n";
  return 1;
}

/// A scene's outputs go to --output-dir, else to a folder of their own
/// named after the scene, so that a run never scatters files over the
/// current directory.
static std::string sceneOutputDirectory() {
  if (!outputDirectory.empty())
    return outputDirectory;
  llvm::SmallString<128> directory("simit-output");
  llvm::sys::path::append(directory, llvm::sys::path::stem(scenePath));
  return std::string(directory);
}

static void printTimeSummary(const SceneTimeSummary &times,
                             const CompileTimes &compile, int frames,
                             const SolveSession &solver) {
  llvm::raw_ostream &os = llvm::outs();
  if (compile.cached)
    os << llvm::format("compile:   %10.2f ms (cached; load %.2f ms)\n",
                       times.compileMs, compile.loadMs);
  else
    os << llvm::format("compile:   %10.2f ms (lowering %.2f, LLVM -O3 "
                       "%.2f, codegen %.2f, load %.2f ms)\n",
                       times.compileMs, compile.loweringMs,
                       compile.optimizationMs, compile.codegenMs,
                       compile.loadMs);
  os << llvm::format("bind/init: %10.2f ms (sets %.2f ms)\n", times.bindMs,
                     times.setsMs);
  os << llvm::format("init:      %10.2f ms\n", times.initMs);
  if (times.frames == 0)
    return;
  os << llvm::format("frame:     %10.3f ms (median of frames %d..%d; "
                     "frame 1 %.3f ms)\n",
                     times.frameMs, times.frames > 1 ? 2 : 1, frames,
                     times.firstFrameMs);
  os << llvm::format("  assembly:%10.3f ms (map and apply statements)\n",
                     times.assemblyMs);
  os << llvm::format("  solve:   %10.3f ms (solves, and while loops "
                     "without assemblies)\n",
                     times.solveMs);
  if (times.checkMs > 0)
    os << llvm::format("  check:   %10.3f ms (the scan of the state for NaN "
                       "and infinity)\n",
                       times.checkMs);
  // The solver's own time, over the whole run (init included).
  double symbolic = 0, numeric = 0, solve = 0;
  int64_t solves = 0;
  for (const SolveStatementStats &stats : solver.statistics()) {
    symbolic += stats.analysisMs;
    numeric += stats.factorisationMs;
    solve += stats.solveMs;
    solves += stats.solves;
  }
  if (solves > 0)
    os << llvm::format("solver:    %10.3f ms in %lld solves (symbolic %.3f, "
                       "numeric %.3f, solve %.3f ms; the whole run)\n",
                       symbolic + numeric + solve,
                       static_cast<long long>(solves), symbolic, numeric,
                       solve);
}

/// The command line's solver settings, over the scene's.
static llvm::Expected<SolveSettingsOverride> solverOverride() {
  SolveSettingsOverride settings;
  if (solverMethod.getNumOccurrences()) {
    settings.method = parseSolveMethod(solverMethod);
    if (!settings.method)
      return llvm::createStringError("--solver: unknown method '" +
                                     solverMethod + "' (expected one of " +
                                     solveMethodNames() + ")");
  }
  if (solverTolerance.getNumOccurrences())
    settings.tolerance = solverTolerance;
  if (solverMaxIterations.getNumOccurrences())
    settings.maxIterations = solverMaxIterations;
  if (solverRefactorIterations.getNumOccurrences())
    settings.refactorIterations = solverRefactorIterations;
  if (solverStrict)
    settings.strict = true;
  if (noWarmStart)
    settings.warmStart = false;
  if (llvm::Error err = checkSolveSettings(settings.appliedTo({}),
                                           "--tol/--max-iters/"
                                           "--refactor-iters"))
    return std::move(err);
  return settings;
}

/// --stats: what the solves of each statement did.
static void printSolveStats(const SolveSession &solver) {
  llvm::raw_ostream &os = llvm::outs();
  const SolveSettings &settings = solver.settings();
  os << "solver: " << solveMethodName(settings.method);
  if (settings.tolerance)
    os << llvm::format(", tol %g", *settings.tolerance);
  if (settings.maxIterations)
    os << ", max-iters " << *settings.maxIterations;
  if (settings.refactorIterations)
    os << ", refactor-iters " << *settings.refactorIterations;
  if (settings.strict)
    os << ", strict";
  if (!settings.warmStart)
    os << ", no warm start";
  os << " (direct solvers on " << sparseDirectBLAS() << ")\n";
  for (const SolveStatementStats &stats : solver.statistics()) {
    os << "solve statement: " << stats.statement << "\n";
    os << "  method:            ";
    for (size_t i = 0; i < stats.methods.size(); ++i)
      os << (i ? ", " : "") << solveMethodName(stats.methods[i]);
    os << "\n  solves:            " << stats.solves << "\n";
    os << "  iterations:        " << stats.iterations << " (largest "
       << stats.maxIterations << ")\n";
    os << llvm::format("  relative residual: %.3e (largest %.3e)\n",
                       stats.lastRelativeResidual,
                       stats.maxRelativeResidual);
    os << "  not converged:     " << stats.notConverged << "\n";
    os << "  failed:            " << stats.failed << "\n";
    os << llvm::format("  symbolic:          %lld (%.3f ms)\n",
                       static_cast<long long>(stats.analyses),
                       stats.analysisMs);
    os << llvm::format("  numeric:           %lld (%.3f ms)\n",
                       static_cast<long long>(stats.factorisations),
                       stats.factorisationMs);
    os << "  reused:            " << stats.reuses << "\n";
    os << llvm::format("  solve:             %.3f ms\n", stats.solveMs);
  }
}

/// Builds the scene's sets, compiles the program, runs "init" once and
/// "step" per frame, and writes the outputs.
static int runSceneFile(FloatPrecision precision,
                        const std::string &cacheDirectory, int threads) {
  llvm::Expected<SceneDescription> scene = loadScene(scenePath);
  if (!scene)
    return fail(scene.takeError());
  SceneRunOptions options;
  options.programPath = programPath;
  options.outputDirectory = sceneOutputDirectory();
  if (frames >= 0)
    options.frames = frames;
  options.precision = precision;
  options.timePhases = printTimes;
  if (checkNumerics && noCheck)
    return fail(
        llvm::createStringError("--check-numerics and --no-check contradict"));
  // Checked by default: every assembly and solve, then what each function
  // leaves in the state (--check-numerics only says so explicitly).
  options.checkNumerics = !noCheck;
  options.checkFrames = !noCheck;
  options.progress = !noProgress;
  options.cacheDirectory = cacheDirectory;
  options.threads = threads;
  options.hostLibraries = externLibraries;
  auto solver = solverOverride();
  if (!solver)
    return fail(solver.takeError());
  options.solver = *solver;
  options.shermanMorrison = !noShermanMorrison;
  options.target = target;
  options.skipUncalledFunctions = !noSkipUncalled;
  options.skipUnusedFields = !noSkipUnusedFields;
  options.foldConstantExterns = !noFoldConstants;
  options.foldUniformFields = !noFoldConstants;
  options.eliminateDeadAssemblies = !noDeadAssemblies;
  options.vectorizeElements = !noSimd;
  auto runner = SceneRunner::create(std::move(*scene), options);
  if (!runner)
    return fail(runner.takeError());
  llvm::Error runError = (*runner)->run();
  // The statistics also tell what the solves did before a failure.
  if (*printStats)
    printSolveStats((*runner)->solver());
  if (runError)
    return fail(std::move(runError));
  if (printTimes)
    printTimeSummary((*runner)->times().summarize(),
                     (*runner)->compileTimes(), (*runner)->frames(),
                     (*runner)->solver());
  return 0;
}

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  cl::opt<int> &threads = threadsOption(
      runCategory, "Threads that run the set loops (default: "
                   "$SIMIT_NUM_THREADS, else every core); the results are the "
                   "same for every count");
  cl::HideUnrelatedOptions(runCategory);
  if (cl::Option *llvmStats = cl::getRegisteredOptions().lookup("stats"))
    llvmStats->removeArgument();
  printStats.emplace(cl::cat(runCategory), "stats",
                     cl::desc("Print per solve statement: method, "
                              "iterations, relative residual, "
                              "factorisations and their times"));
  cl::ParseCommandLineOptions(argc, argv, "Simit JIT runner\n");
  FloatPrecision precision =
      float32 ? FloatPrecision::Single : FloatPrecision::Double;
  if (threads.getNumOccurrences() && threads < 1)
    return fail(llvm::createStringError(
        "--threads must be a positive number of threads, not " +
        llvm::Twine(threads)));
  // $SIMIT_NUM_THREADS is checked before anything is loaded.
  llvm::Expected<int> threadCount = resolveThreadCount(threads);
  if (!threadCount)
    return fail(threadCount.takeError());
  // Libraries' parallel loops (CHOLMOD's) too run on at most that many.
  capOpenMPThreads(*threadCount);
  if (noCache && cacheDir.getNumOccurrences())
    return fail(
        llvm::createStringError("--no-cache and --cache-dir contradict"));
  std::string cacheDirectory =
      noCache ? ""
      : cacheDir.getNumOccurrences() ? std::string(cacheDir)
                                     : defaultCompileCacheDirectory();

  // One mode per run: a second one would be silently ignored.
  std::vector<const char *> modes;
  if (cudaDevice)
    modes.push_back("--cuda-device");
  if (emitStage.getNumOccurrences())
    modes.push_back("--emit");
  if (testMode)
    modes.push_back("--test");
  if (!evalCall.empty())
    modes.push_back("--eval");
  if (!scenePath.empty())
    modes.push_back("--scene");
  if (modes.size() > 1)
    return fail(llvm::createStringError(
        llvm::Twine(modes[0]) + " and " + modes[1] +
        " contradict: give one of --scene, --test, --eval, --emit and "
        "--cuda-device"));
  if (frames.getNumOccurrences() && frames < 0)
    return fail(
        llvm::createStringError("--frames=" + llvm::Twine(frames) +
                                ": expected a frame count of at least 0"));
  if (cudaDevice) {
    llvm::Expected<cuda::Device &> device = cuda::defaultDevice();
    if (!device)
      return fail(llvm::createStringError("no CUDA device: " +
                                          llvm::toString(device.takeError())));
    llvm::outs() << "CUDA device: " << cuda::describeDevice(*device) << "\n";
    return 0;
  }
  if (emitStage.getNumOccurrences()) {
    if (programPath.empty())
      return fail(llvm::createStringError("--emit needs a program file"));
    // Lowering needs no device: without one, kernels are for sm_90.
    ProgramOptions programOptions;
    programOptions.precision = precision;
    programOptions.threads = *threadCount;
    programOptions.target = target;
    programOptions.vectorizeElements = !noSimd;
    Program program(programOptions);
    if (llvm::Error err = program.loadFile(programPath))
      return fail(std::move(err));
    llvm::Expected<std::string> text = program.emit(emitStage);
    if (!text)
      return fail(text.takeError());
    llvm::outs() << *text;
    return 0;
  }
  // Running needs the device: say so in one line before compiling anything.
  if (target == Target::GPU)
    if (llvm::Expected<cuda::Device &> device = cuda::defaultDevice(); !device)
      return fail(llvm::createStringError(
          "no CUDA device: " + llvm::toString(device.takeError())));
  // The Program of --test's sections and of --eval.
  ProgramOptions programOptions;
  programOptions.precision = precision;
  programOptions.threads = *threadCount;
  programOptions.cacheDirectory = cacheDirectory;
  programOptions.hostLibraries = externLibraries;
  programOptions.target = target;
  if (testMode) {
    if (programPath.empty())
      return fail(llvm::createStringError("--test needs a .sim file"));
    return runTests({programPath, programOptions}, llvm::outs());
  }
  if (!evalCall.empty()) {
    if (programPath.empty())
      return fail(llvm::createStringError("--eval needs a program file"));
    return runEval({programPath, evalCall, programOptions}, llvm::outs());
  }
  if (scenePath.empty())
    return fail(llvm::createStringError(
        "nothing to do: give --scene, --test, --eval or --emit"));
  return runSceneFile(precision, cacheDirectory, *threadCount);
}
