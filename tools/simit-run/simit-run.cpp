//===--- simit-run.cpp - JIT-runs Simit programs --------------------------===//
//
//   simit-run PROGRAM --scene SCENE.json [--output-dir DIR] [--time]
//             [--no-cache | --cache-dir DIR]
//   simit-run --test FILE.sim
//   simit-run FILE.sim --eval 'f(1.0, [1, 2]')'
//   simit-run FILE.sim --emit=simit|loops|llvm
//
// docs/simit-run.md describes the modes and options.
//
//===----------------------------------------------------------------------===//

#include "TestRun.h"

#include "simit/Engine/Program.h"
#include "simit/Engine/SceneRun.h"

#include "llvm/ADT/SmallString.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"

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
                             const CompileTimes &compile, int frames) {
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
}

/// Builds the scene's sets, compiles the program, runs "init" once and
/// "step" per frame, and writes the outputs.
static int runSceneFile(FloatPrecision precision,
                        const std::string &cacheDirectory) {
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
  options.hostLibraries = externLibraries;
  auto runner = SceneRunner::create(std::move(*scene), options);
  if (!runner)
    return fail(runner.takeError());
  if (llvm::Error err = (*runner)->run())
    return fail(std::move(err));
  if (printTimes)
    printTimeSummary((*runner)->times().summarize(),
                     (*runner)->compileTimes(), (*runner)->frames());
  return 0;
}

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  cl::HideUnrelatedOptions(runCategory);
  cl::ParseCommandLineOptions(argc, argv, "Simit JIT runner\n");
  FloatPrecision precision =
      float32 ? FloatPrecision::Single : FloatPrecision::Double;
  if (noCache && cacheDir.getNumOccurrences())
    return fail(
        llvm::createStringError("--no-cache and --cache-dir contradict"));
  std::string cacheDirectory =
      noCache ? ""
      : cacheDir.getNumOccurrences() ? std::string(cacheDir)
                                     : defaultCompileCacheDirectory();

  if (testMode) {
    if (programPath.empty())
      return fail(llvm::createStringError("--test needs a .sim file"));
    return runTests({programPath, precision, cacheDirectory, externLibraries},
                    llvm::outs());
  }
  if (!evalCall.empty()) {
    if (programPath.empty())
      return fail(llvm::createStringError("--eval needs a program file"));
    return runEval(
        {programPath, evalCall, precision, cacheDirectory, externLibraries},
        llvm::outs());
  }
  if (emitStage.getNumOccurrences()) {
    if (programPath.empty())
      return fail(llvm::createStringError("--emit needs a program file"));
    Program program(ProgramOptions{precision, {}});
    if (llvm::Error err = program.loadFile(programPath))
      return fail(std::move(err));
    llvm::Expected<std::string> text = program.emit(emitStage);
    if (!text)
      return fail(text.takeError());
    llvm::outs() << *text;
    return 0;
  }
  if (scenePath.empty())
    return fail(llvm::createStringError(
        "nothing to do: give --scene, --test, --eval or --emit"));
  return runSceneFile(precision, cacheDirectory);
}
