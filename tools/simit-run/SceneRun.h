//===--- SceneRun.h - Running a program on a scene ------------------------===//

#ifndef SIMIT_TOOLS_SIMIT_RUN_SCENERUN_H
#define SIMIT_TOOLS_SIMIT_RUN_SCENERUN_H

#include "simit/Engine/Program.h"

#include "llvm/Support/Error.h"

#include <optional>
#include <string>

namespace simit {

struct SceneRunOptions {
  std::string scenePath;
  /// The program; empty to take the scene's "program".
  std::string programPath;
  std::string outputDirectory = ".";
  /// Overrides the scene's frame count.
  std::optional<int> frames;
  FloatPrecision precision = FloatPrecision::Double;
  bool printTimes = false;
  bool checkNumerics = false;
  /// ProgramOptions::cacheDirectory.
  std::string cacheDirectory;
  /// Progress lines on stderr once a run has taken a while.
  bool progress = true;
};

/// Builds the scene's sets, compiles the program, runs "init" once and
/// "step" per frame, and writes the outputs. Errors name the file and,
/// for the scene, the JSON path at fault.
llvm::Error runScene(const SceneRunOptions &options);

} // namespace simit

#endif // SIMIT_TOOLS_SIMIT_RUN_SCENERUN_H
