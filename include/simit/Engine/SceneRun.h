//===--- SceneRun.h - Running a program on a scene --------------*- C++ -*-===//
//
// What simit-run --scene does, as a library: a SceneRunner compiles the
// program, builds the scene's sets (docs/scene-format.md), binds every
// function the scene runs, then runs "init" once and "step" once per frame,
// writing the scene's outputs after each. The Python module drives it frame
// by frame and reads the sets between frames.
//
//   auto runner = SceneRunner::create(*loadScene("springs-bunny.json"), {});
//   if (!runner) ...
//   if (llvm::Error err = (*runner)->run()) ...
//   SceneTimeSummary times = (*runner)->times().summarize();
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ENGINE_SCENERUN_H
#define SIMIT_ENGINE_SCENERUN_H

#include "simit/Engine/Program.h"
#include "simit/Runtime/Scene.h"

#include "llvm/Support/Error.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace simit {

class SceneOutputWriter;

struct SceneRunOptions {
  /// The program; empty to take the scene's "program".
  std::string programPath;
  /// Where the scene's outputs are written; nullopt writes none.
  std::optional<std::string> outputDirectory;
  /// Overrides the scene's frame count.
  std::optional<int> frames;
  FloatPrecision precision = FloatPrecision::Double;
  /// Compile with the phase timer, so frames are split into assembly and
  /// solve (ProgramOptions::timePhases).
  bool timePhases = false;
  bool checkNumerics = false;
  /// Scan the float fields and externs the functions use for NaN and
  /// infinity after init and after every frame (simit-run's default;
  /// --no-check). Implied by checkNumerics, which finds the statement.
  bool checkFrames = true;
  /// Progress lines on stderr once a run has taken a while.
  bool progress = false;
  /// ProgramOptions::threads (0: $SIMIT_NUM_THREADS, else every core).
  int threads = 0;
  /// ProgramOptions::cacheDirectory (empty: no compile cache).
  std::string cacheDirectory;
  /// Overrides the scene's "solver" (simit-run --solver, --tol, ...).
  SolveSettingsOverride solver;
  /// ProgramOptions::shermanMorrison (simit-run --no-sherman-morrison).
  bool shermanMorrison = true;
  /// ProgramOptions::hostLibraries, with the scene's "libraries" after them.
  std::vector<std::string> hostLibraries;
  /// ProgramOptions::target (simit-run --target).
  Target target = Target::CPU;
  /// What the scene lets the compiler skip (docs/scene-specialisation.md):
  /// exported functions that are neither init nor step are not compiled
  /// (simit-run --no-skip-uncalled);
  bool skipUncalledFunctions = true;
  /// scene fields that no init or step function binds and no output names
  /// are not built (--no-skip-unused-fields);
  bool skipUnusedFields = true;
  /// externs the scene marks constant are folded (--no-fold-constants);
  bool foldConstantExterns = true;
  /// fields the scene gives one value for the whole set (a constant, or no
  /// initialiser) are folded where no function writes them
  /// (--no-fold-constants); neither for more than 64 components;
  bool foldUniformFields = true;
  /// ProgramOptions::eliminateDeadAssemblies (--no-dead-assemblies).
  bool eliminateDeadAssemblies = true;
  /// ProgramOptions::vectorizeElements (--no-simd).
  bool vectorizeElements = true;
};

/// The medians of SceneTimes, as simit-run --time prints them.
struct SceneTimeSummary {
  double compileMs = 0, bindMs = 0, setsMs = 0, initMs = 0;
  int frames = 0;
  /// Medians over frames 2..N (frame 1 pays first-touch costs), or frame 1
  /// alone when it is the only one; zero without frames.
  double frameMs = 0, assemblyMs = 0, solveMs = 0;
  /// The scan of the state after each frame (SceneRunOptions::checkFrames).
  double checkMs = 0;
  double firstFrameMs = 0;
};

/// Milliseconds spent by a SceneRunner.
struct SceneTimes {
  double compileMs = 0; // frontend, lowering and JIT
  double bindMs = 0;    // building the sets, binding, sparsity patterns
  double setsMs = 0;    // the part of bindMs that built the sets
  double initMs = 0;    // the init functions
  /// Per frame run: the whole step, and its assembly and solve phases
  /// (zero unless SceneRunOptions::timePhases).
  std::vector<double> frameMs, assemblyMs, solveMs;
  /// Per frame run with SceneRunOptions::checkFrames: the scan of the state.
  std::vector<double> checkMs;

  SceneTimeSummary summarize() const;
};

class SceneRunner {
public:
  /// Compiles the program, builds the sets, binds every init and step
  /// function, and prepares the outputs. Errors name the file and, for the
  /// scene, the JSON path at fault.
  static llvm::Expected<std::unique_ptr<SceneRunner>>
  create(SceneDescription scene, const SceneRunOptions &options);
  ~SceneRunner();

  /// Runs the init functions and writes frame 0; once.
  llvm::Error init();
  /// Runs `count` more frames (init first when it has not run).
  llvm::Error step(int count = 1);
  /// init, then the remaining frames up to frames().
  llvm::Error run();

  /// The frames run so far (0 after init).
  int frame() const { return currentFrame; }
  /// The frame count of the scene or the options; outputs marked "last" are
  /// written after this frame.
  int frames() const { return frameCount; }
  bool initialized() const { return initDone; }

  const SceneDescription &scene() const { return description; }
  SetRegistry &sets() { return registry; }
  const SceneTimes &times() const { return timings; }
  /// How the program was compiled (the compile cache, the phases).
  const CompileTimes &compileTimes() const { return program.compileTimes(); }
  /// The program's solver: its settings and statistics (--stats).
  SolveSession &solver() { return program.solver(); }
  /// The output files written so far.
  const std::vector<std::string> &writtenFiles() const;

  /// An init or step function of the scene.
  struct NamedFunction {
    std::string name;
    Function function;
  };

private:
  SceneRunner(SceneDescription scene, const SceneRunOptions &options);
  llvm::Error runAll(std::vector<NamedFunction> &group, int frame);
  /// Time runAll spent scanning the state with checkNumerics (ms).
  double stateScanMs = 0;
  /// Scans what the functions of a frame left in their float fields and
  /// externs; the error names the frame, the field or extern and the
  /// element, and how to find the statement that produced the value.
  llvm::Error checkFrame(const std::vector<NamedFunction> &group, int frame);
  bool checksFrames() const {
    return options.checkFrames && !options.checkNumerics;
  }
  /// Writes the outputs of `frame`, completing them after the last one.
  llvm::Error writeFrame(int frame);

  SceneDescription description;
  SceneRunOptions options;
  SetRegistry registry;
  Program program;
  std::vector<NamedFunction> initFunctions, stepFunctions;
  std::unique_ptr<SceneOutputWriter> writer;
  SceneTimes timings;
  int frameCount = 0;
  int currentFrame = 0;
  bool initDone = false;
};

} // namespace simit

#endif // SIMIT_ENGINE_SCENERUN_H
