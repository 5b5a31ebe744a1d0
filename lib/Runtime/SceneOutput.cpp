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
      collected->stream() << csvHeader(*set, output.fields,
                                       /*withFrame=*/true);
    }
    writer->collectedFiles.push_back(std::move(collected));
  }
  if (llvm::Error err = writer->checkCollisions())
    return err;
  return writer;
}

/// The frames after which `output` writes: every `every`-th of 0..frames,
/// or only the last.
static std::vector<int> framesWritten(const OutputSpec &output, int frames) {
  if (output.lastOnly)
    return {frames};
  std::vector<int> list;
  for (int frame = 0; frame <= frames; frame += output.every)
    list.push_back(frame);
  return list;
}

llvm::Error SceneOutputWriter::checkCollisions() const {
  // Every file each output writes, by its lexically normalised absolute
  // path; standard output may be shared.
  std::map<std::string, size_t> owner;
  for (size_t i = 0; i < scene.outputs.size(); ++i) {
    const OutputSpec &output = scene.outputs[i];
    if (output.path == "-")
      continue;
    std::vector<int> frames = output.path.find("{frame}") == std::string::npos
                                  ? std::vector<int>{0}
                                  : framesWritten(output, frameCount);
    for (int frame : frames) {
      llvm::SmallString<256> path(pathFor(output, frame));
      llvm::sys::fs::make_absolute(path);
      llvm::sys::path::remove_dots(path, /*remove_dot_dot=*/true);
      auto [it, inserted] = owner.try_emplace(std::string(path), i);
      if (!inserted && it->second != i)
        return llvm::createStringError(
            scene.path + ": " + output.jsonPath + ".path: writes " +
            it->first + ", which " + scene.outputs[it->second].jsonPath +
            " writes too");
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
    if (llvm::Error err =
            writeCSVRows(file->stream(), set, output.fields, frame))
      return err;
    return file->flush();
  }
  std::string path = pathFor(output, frame);
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
