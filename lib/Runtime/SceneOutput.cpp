//===--- SceneOutput.cpp - Writing a scene's outputs per frame ------------===//

#include "simit/Runtime/SceneOutput.h"

#include "simit/Runtime/CSV.h"
#include "simit/Runtime/VTK.h"

#include "AtomicFile.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"

#include <map>

using namespace simit;

static VTKOptions vtkOptions(const OutputSpec &output,
                             const SetRegistry &registry) {
  VTKOptions options;
  options.positionField = output.position;
  for (const std::string &cells : output.cells)
    options.cellSets.push_back(registry.find(cells));
  options.pointFields = output.fields;
  options.cellFields = output.cellFields;
  return options;
}

static bool collectsFrames(const OutputSpec &output) {
  return output.kind == OutputSpec::CSV &&
         output.path.find("{frame}") == std::string::npos;
}

llvm::Expected<std::unique_ptr<SceneOutputWriter>>
SceneOutputWriter::create(const SceneDescription &scene,
                          const SetRegistry &registry,
                          llvm::StringRef outputDirectory, int frames) {
  std::unique_ptr<SceneOutputWriter> writer(
      new SceneOutputWriter(scene, registry, outputDirectory.str(), frames));
  for (const OutputSpec &output : scene.outputs) {
    auto fail = [&](llvm::Error err) {
      return llvm::createStringError(scene.path + ": " + output.jsonPath +
                                     ": " + llvm::toString(std::move(err)));
    };
    const Set *set = registry.find(output.set);
    if (!set)
      return fail(llvm::createStringError("no set '" + output.set + "'"));
    if (output.kind == OutputSpec::VTK) {
      for (const std::string &cells : output.cells)
        if (!registry.find(cells))
          return fail(llvm::createStringError("no set '" + cells + "'"));
      if (llvm::Error err =
              checkVTKOptions(*set, vtkOptions(output, registry)))
        return fail(std::move(err));
    } else if (llvm::Error err = checkCSVFields(*set, output.fields)) {
      return fail(std::move(err));
    }
    // Create the folders the output's files go to.
    std::string first = writer->pathFor(output, 0);
    llvm::StringRef parent = llvm::sys::path::parent_path(first);
    if (!parent.empty())
      if (std::error_code ec = llvm::sys::fs::create_directories(parent))
        return fail(llvm::createStringError(parent + ": cannot create: " +
                                            ec.message()));
    std::unique_ptr<detail::AtomicFile> collected;
    if (collectsFrames(output)) {
      auto file = detail::AtomicFile::create(first);
      if (!file)
        return fail(file.takeError());
      collected = std::move(*file);
    }
    writer->collectedFiles.push_back(std::move(collected));
  }
  if (llvm::Error err = writer->checkCollisions())
    return err;
  return writer;
}

namespace {

/// The files an output writes in a run of `frames` frames: its path,
/// lexically normalised and absolute, cut at "{frame}" into a prefix and a
/// suffix, and the frames it writes.
struct OutputFiles {
  std::string prefix, suffix;
  bool perFrame;
  const OutputSpec *output;
  int frames;

  bool writes(long long frame) const {
    return output->lastOnly ? frame == frames
                            : frame % output->every == 0 && frame <= frames;
  }
  /// The number of files, and the k-th frame written.
  long long count() const {
    return !perFrame || output->lastOnly ? 1 : frames / output->every + 1;
  }
  long long frameNumber(long long k) const {
    return output->lastOnly ? frames : k * output->every;
  }
  std::string path(long long frame) const {
    return perFrame ? prefix + std::to_string(frame) + suffix : prefix;
  }
  /// Whether a file of each could have one name: the prefix of one starts
  /// the other's and the suffix of one ends the other's (a frame number
  /// fills the gap).
  bool mayMeet(const OutputFiles &other) const {
    llvm::StringRef p1 = prefix, p2 = other.prefix, s1 = suffix,
                    s2 = other.suffix;
    if (!perFrame || !other.perFrame)
      return true;
    return (p1.starts_with(p2) || p2.starts_with(p1)) &&
           (s1.ends_with(s2) || s2.ends_with(s1));
  }
  /// Is `path` one of the files?
  bool holds(llvm::StringRef path) const {
    if (!perFrame)
      return path == prefix;
    if (!path.consume_front(prefix) || !path.consume_back(suffix) ||
        path.empty() || (path.size() > 1 && path.front() == '0'))
      return false;
    long long frame;
    return !path.getAsInteger(10, frame) && frame >= 0 && writes(frame);
  }
};

} // namespace

llvm::Error SceneOutputWriter::checkCollisions() const {
  std::vector<OutputFiles> files;
  for (const OutputSpec &output : scene.outputs) {
    if (output.path == "-") // standard output may be shared
      continue;
    // Resolved as pathFor does, with "{frame}" kept.
    llvm::SmallString<256> full;
    if (!directory.empty() && !llvm::sys::path::is_absolute(output.path))
      full = directory;
    llvm::sys::path::append(full, output.path);
    llvm::sys::fs::make_absolute(full);
    llvm::sys::path::remove_dots(full, /*remove_dot_dot=*/true);
    llvm::StringRef text = full;
    size_t at = text.find("{frame}");
    OutputFiles entry{text.str(), "", at != llvm::StringRef::npos, &output,
                      frameCount};
    if (entry.perFrame) {
      entry.prefix = text.take_front(at).str();
      entry.suffix = text.drop_front(at + 7).str();
    }
    files.push_back(std::move(entry));
  }
  for (size_t j = 0; j < files.size(); ++j)
    for (size_t i = 0; i < j; ++i) {
      // Walk the output with fewer files, asking the other about each.
      const OutputFiles &few =
          files[i].count() <= files[j].count() ? files[i] : files[j];
      const OutputFiles &many = &few == &files[i] ? files[j] : files[i];
      if (!few.mayMeet(many))
        continue;
      for (long long k = 0; k < few.count(); ++k) {
        std::string path = few.path(few.frameNumber(k));
        if (many.holds(path))
          return llvm::createStringError(
              scene.path + ": " + files[j].output->jsonPath +
              ".path: writes " + path + ", which " +
              files[i].output->jsonPath + " writes too");
      }
    }
  return llvm::Error::success();
}

std::string SceneOutputWriter::pathFor(const OutputSpec &output,
                                       int frame) const {
  std::string path = output.path;
  if (path == "-") // standard output
    return path;
  size_t at = path.find("{frame}");
  if (at != std::string::npos)
    path.replace(at, 7, std::to_string(frame));
  if (directory.empty() || llvm::sys::path::is_absolute(path))
    return path;
  llvm::SmallString<256> full(directory);
  llvm::sys::path::append(full, path);
  return std::string(full);
}

llvm::Error SceneOutputWriter::writeOutput(size_t index, int frame) {
  const OutputSpec &output = scene.outputs[index];
  const Set &set = *registry.find(output.set);
  // The program's print statements go through llvm::outs(); keep the order.
  if (output.path == "-")
    llvm::outs().flush();
  if (detail::AtomicFile *file = collectedFiles[index].get()) {
    // The header goes with the first rows (frame 0, or the only frame of a
    // "last" output), after whatever the program printed before them.
    if (output.lastOnly || frame == 0)
      file->stream() << csvHeader(set, output.fields, /*withFrame=*/true);
    if (llvm::Error err =
            writeCSVRows(file->stream(), set, output.fields, frame))
      return err;
    return file->flush();
  }
  std::string path = pathFor(output, frame);
  // "{frame}" may name a folder of its own per frame.
  llvm::StringRef parent = llvm::sys::path::parent_path(path);
  if (!parent.empty())
    if (std::error_code ec = llvm::sys::fs::create_directories(parent))
      return llvm::createStringError(parent +
                                     ": cannot create: " + ec.message());
  if (llvm::Error err = output.kind == OutputSpec::VTK
                            ? writeVTU(path, set, vtkOptions(output, registry))
                            : writeCSV(path, set, output.fields))
    return err;
  written.push_back(path);
  return llvm::Error::success();
}

llvm::Error SceneOutputWriter::finish() {
  for (size_t i = 0; i < scene.outputs.size(); ++i) {
    std::unique_ptr<detail::AtomicFile> &file = collectedFiles[i];
    if (!file)
      continue;
    if (llvm::Error err = file->commit())
      return llvm::createStringError(scene.path + ": " +
                                     scene.outputs[i].jsonPath + ": " +
                                     llvm::toString(std::move(err)));
    written.push_back(pathFor(scene.outputs[i], 0));
    file.reset();
  }
  return llvm::Error::success();
}

SceneOutputWriter::SceneOutputWriter(const SceneDescription &scene,
                                     const SetRegistry &registry,
                                     std::string directory, int frames)
    : scene(scene), registry(registry), directory(std::move(directory)),
      frameCount(frames) {}

SceneOutputWriter::~SceneOutputWriter() = default;

llvm::Error SceneOutputWriter::writeFrame(int frame, bool isLast) {
  for (size_t i = 0; i < scene.outputs.size(); ++i) {
    const OutputSpec &output = scene.outputs[i];
    bool due = output.lastOnly ? isLast : frame % output.every == 0;
    if (!due)
      continue;
    if (llvm::Error err = writeOutput(i, frame))
      return llvm::createStringError(scene.path + ": " + output.jsonPath +
                                     ": " + llvm::toString(std::move(err)));
  }
  return llvm::Error::success();
}
