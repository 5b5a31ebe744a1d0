//===--- SceneOutput.cpp - Writing a scene's outputs per frame ------------===//

#include "simit/Runtime/SceneOutput.h"

#include "simit/Runtime/CSV.h"
#include "simit/Runtime/VTK.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"

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
                          llvm::StringRef outputDirectory) {
  std::unique_ptr<SceneOutputWriter> writer(
      new SceneOutputWriter(scene, registry, outputDirectory.str()));
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
    std::unique_ptr<llvm::raw_fd_ostream> stream;
    if (collectsFrames(output)) {
      std::error_code ec;
      stream = std::make_unique<llvm::raw_fd_ostream>(first, ec,
                                                      llvm::sys::fs::OF_Text);
      if (ec)
        return fail(llvm::createStringError(first + ": cannot write: " +
                                            ec.message()));
      *stream << csvHeader(*set, output.fields, /*withFrame=*/true);
      writer->written.push_back(first);
    }
    writer->csvStreams.push_back(std::move(stream));
  }
  return writer;
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
  if (llvm::raw_fd_ostream *stream = csvStreams[index].get()) {
    if (llvm::Error err = writeCSVRows(*stream, set, output.fields, frame))
      return err;
    stream->flush();
    if (stream->has_error())
      return llvm::createStringError("cannot write: " +
                                     stream->error().message());
    return llvm::Error::success();
  }
  std::string path = pathFor(output, frame);
  if (llvm::Error err = output.kind == OutputSpec::VTK
                            ? writeVTU(path, set, vtkOptions(output, registry))
                            : writeCSV(path, set, output.fields))
    return err;
  written.push_back(path);
  return llvm::Error::success();
}

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
