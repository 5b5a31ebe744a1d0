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

#include "SceneRun.h"
#include "TestRun.h"

#include "simit/Engine/Program.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/raw_ostream.h"

using namespace simit;

namespace cl = llvm::cl;

static cl::OptionCategory runCategory("simit-run options");

static cl::opt<std::string> programPath(cl::cat(runCategory), cl::Positional,
                                        cl::desc("<program .sim or .mlir>"),
                                        cl::init(""));
static cl::opt<std::string> scenePath(cl::cat(runCategory), "scene", cl::desc("Run on a scene file"),
                                      cl::value_desc("scene.json"));
static cl::opt<std::string>
    outputDirectory(cl::cat(runCategory), "output-dir", cl::desc("Where scene outputs are written"),
                    cl::init("."));
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
    cl::desc("Stop at the first NaN or infinity a function leaves in a bound "
             "field or extern"));
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

static int fail(llvm::Error err) {
  llvm::errs() << "simit-run: " << llvm::toString(std::move(err)) << "\n";
  return 1;
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
    return runTests({programPath, precision, cacheDirectory}, llvm::outs());
  }
  if (!evalCall.empty()) {
    if (programPath.empty())
      return fail(llvm::createStringError("--eval needs a program file"));
    return runEval({programPath, evalCall, precision, cacheDirectory},
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
  SceneRunOptions options;
  options.scenePath = scenePath;
  options.programPath = programPath;
  options.outputDirectory = outputDirectory;
  if (frames >= 0)
    options.frames = frames;
  options.precision = precision;
  options.printTimes = printTimes;
  options.checkNumerics = checkNumerics;
  options.progress = !noProgress;
  options.cacheDirectory = cacheDirectory;
  if (llvm::Error err = runScene(options))
    return fail(std::move(err));
  return 0;
}
