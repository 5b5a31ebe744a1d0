//===--- SceneOutput.h - Writing a scene's outputs per frame ----*- C++ -*-===//
//
// Carries out the "outputs" of a scene: after frame f (0 is the state after
// "init", f >= 1 after f steps), each output whose stride divides f (or,
// with "last", only the final frame) writes its VTK file or CSV rows. A CSV
// path without {frame} collects every written frame in one file with a
// frame column.
//
// Every file is written under a temporary name in its folder and renamed
// to its final name when complete (a file that collects frames, when the
// run finishes), so a run that fails or is killed leaves no truncated file
// under a final name and keeps what an earlier run wrote there.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SCENEOUTPUT_H
#define SIMIT_RUNTIME_SCENEOUTPUT_H

#include "simit/Runtime/Scene.h"

#include "llvm/Support/Error.h"
#include "llvm/Support/raw_ostream.h"

#include <memory>
#include <string>
#include <vector>

namespace simit {
namespace detail {
class AtomicFile;
} // namespace detail

class SceneOutputWriter {
public:
  /// Checks the outputs against the built sets (fields, cells, position)
  /// and against each other (no two may write one file in a run of
  /// `frames` frames), and creates `outputDirectory` when needed.
  static llvm::Expected<std::unique_ptr<SceneOutputWriter>>
  create(const SceneDescription &scene, const SetRegistry &registry,
         llvm::StringRef outputDirectory, int frames);
  ~SceneOutputWriter();

  /// Writes the outputs due after `frame`; `isLast` marks the final frame.
  llvm::Error writeFrame(int frame, bool isLast);

  /// Completes the files that collect frames; without it (a failed run)
  /// they are dropped and earlier files of the same name stay.
  llvm::Error finish();

  /// The files written so far, in order.
  const std::vector<std::string> &writtenFiles() const { return written; }

private:
  SceneOutputWriter(const SceneDescription &scene,
                    const SetRegistry &registry, std::string directory,
                    int frames);
  std::string pathFor(const OutputSpec &output, int frame) const;
  llvm::Error writeOutput(size_t index, int frame);
  llvm::Error checkCollisions() const;

  const SceneDescription &scene;
  const SetRegistry &registry;
  std::string directory;
  int frameCount;
  /// Per output: the open file of a CSV output that gathers every frame.
  std::vector<std::unique_ptr<detail::AtomicFile>> collectedFiles;
  std::vector<std::string> written;
};

} // namespace simit

#endif // SIMIT_RUNTIME_SCENEOUTPUT_H
