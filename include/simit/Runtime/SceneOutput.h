//===--- SceneOutput.h - Writing a scene's outputs per frame ----*- C++ -*-===//
//
// Carries out the "outputs" of a scene: after frame f (0 is the state after
// "init", f >= 1 after f steps), each output whose stride divides f (or,
// with "last", only the final frame) writes its VTK file or CSV rows. A CSV
// path without {frame} collects every written frame in one file with a
// frame column.
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

class SceneOutputWriter {
public:
  /// Checks the outputs against the built sets (fields, cells, position) and
  /// creates `outputDirectory` when needed.
  static llvm::Expected<std::unique_ptr<SceneOutputWriter>>
  create(const SceneDescription &scene, const SetRegistry &registry,
         llvm::StringRef outputDirectory);

  /// Writes the outputs due after `frame`; `isLast` marks the final frame.
  llvm::Error writeFrame(int frame, bool isLast);

  /// The files written so far, in order.
  const std::vector<std::string> &writtenFiles() const { return written; }

private:
  SceneOutputWriter(const SceneDescription &scene,
                    const SetRegistry &registry, std::string directory)
      : scene(scene), registry(registry), directory(std::move(directory)) {}
  std::string pathFor(const OutputSpec &output, int frame) const;
  llvm::Error writeOutput(size_t index, int frame);

  const SceneDescription &scene;
  const SetRegistry &registry;
  std::string directory;
  /// Open streams of CSV outputs that gather every frame in one file.
  std::vector<std::unique_ptr<llvm::raw_fd_ostream>> csvStreams;
  std::vector<std::string> written;
};

} // namespace simit

#endif // SIMIT_RUNTIME_SCENEOUTPUT_H
