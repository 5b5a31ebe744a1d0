//===--- SceneRun.cpp - Running a program on a scene ----------------------===//

#include "SceneRun.h"

#include "simit/Engine/RuntimeFunctions.h"
#include "simit/Runtime/Scene.h"
#include "simit/Runtime/SceneOutput.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <chrono>

using namespace simit;

namespace {
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start)
      .count();
}

struct NamedFunction {
  std::string name;
  Function function;
};

/// Makes the set hold every field `function` reads or writes: a field the
/// scene did not mention is added zero-filled with the program's type and
/// shape, and a float64 field is narrowed when the program runs in single
/// precision. Other mismatches are left for Function::init to report.
llvm::Error provideFields(const SceneDescription &scene, SetRegistry &registry,
                          const NamedFunction &named) {
  for (const ArgumentBinding &arg : named.function.signature().arguments) {
    if (arg.kind != ArgumentBinding::Kind::Field)
      continue;
    Set *set = registry.find(arg.set);
    if (!set)
      continue; // reported when binding
    ComponentType type;
    if (!componentTypeFor(arg.type.scalar, type))
      continue;
    const FieldDescriptor *field = set->fieldDescriptor(arg.field);
    if (!field) {
      std::vector<int> shape;
      for (int64_t dim : llvm::drop_begin(arg.type.shape)) {
        if (dim == ValueType::kDynamic)
          return llvm::createStringError(
              scene.path + ": sets." + arg.set + ".fields." + arg.field +
              ": the program's function '" + named.name +
              "' uses this field with a shape only the scene can give");
        shape.push_back(static_cast<int>(dim));
      }
      if (llvm::Error err = set->addField(arg.field, type, shape))
        return llvm::createStringError(
            scene.path + ": sets." + arg.set + ": the program's function '" +
            named.name + "' uses field '" + arg.field + "': " +
            llvm::toString(std::move(err)));
      continue;
    }
    if (field->type == ComponentType::Float64 &&
        type == ComponentType::Float32) {
      std::vector<int> shape = field->shape;
      size_t count = set->size() * field->blockSize();
      const double *wide = static_cast<const double *>(set->fieldData(arg.field));
      std::vector<float> narrow(wide, wide + count);
      set->removeField(arg.field);
      if (llvm::Error err = set->addField(arg.field, type, shape))
        return err;
      std::copy(narrow.begin(), narrow.end(),
                static_cast<float *>(set->fieldData(arg.field)));
    }
  }
  return llvm::Error::success();
}

/// A scene field that the program's element type does not declare is a
/// typo or a leftover: either way the program would silently not see it.
llvm::Error checkSceneFields(const SceneDescription &scene, Program &program,
                             llvm::StringRef programPath) {
  auto declared = program.externSetFields();
  if (!declared)
    return declared.takeError();
  for (const SetSpec &set : scene.sets) {
    auto it = declared->find(set.name);
    if (it == declared->end())
      continue;
    for (const FieldSpec &field : set.fields)
      if (!llvm::is_contained(it->second, field.name))
        return llvm::createStringError(
            scene.path + ": " + field.jsonPath + ": the elements of set '" +
            set.name + "' in " + programPath + " have no field '" +
            field.name + "' (they have: " +
            (it->second.empty() ? std::string("none")
                                : llvm::join(it->second, ", ")) +
            ")");
  }
  return llvm::Error::success();
}

/// Where the scene gives the value bound to `arg`.
std::string jsonPathOf(const SceneDescription &scene,
                       const ArgumentBinding &arg) {
  if (arg.kind == ArgumentBinding::Kind::Extern)
    return "externs." + arg.name;
  std::string setPath = "sets." + arg.set;
  if (arg.kind != ArgumentBinding::Kind::Field)
    return setPath;
  if (const SetSpec *set = scene.findSet(arg.set))
    for (const FieldSpec &field : set->fields)
      if (field.name == arg.field)
        return field.jsonPath;
  return setPath;
}

/// Binds the sets and extern tensors `named` needs from the registry.
llvm::Error bindFromScene(const SceneDescription &scene, SetRegistry &registry,
                          NamedFunction &named) {
  Function &function = named.function;
  for (const std::string &setName : function.requiredSets()) {
    Set *set = registry.find(setName);
    if (!set)
      return llvm::createStringError(
          scene.path + ": sets: the program's function '" + named.name +
          "' uses set '" + setName + "', which the scene does not define");
    if (llvm::Error err = function.bind(setName, *set))
      return llvm::createStringError(scene.path + ": sets." + setName + ": " +
                                     llvm::toString(std::move(err)));
  }
  for (const ArgumentBinding &arg : function.signature().arguments) {
    if (arg.kind == ArgumentBinding::Kind::Parameter)
      return llvm::createStringError(
          "function '" + named.name + "' takes parameters; a scene can only "
          "run functions without parameters");
    if (arg.kind != ArgumentBinding::Kind::Extern)
      continue;
    ExternTensor *tensor = registry.findExtern(arg.name);
    if (!tensor)
      return llvm::createStringError(
          scene.path + ": externs: the program's function '" + named.name +
          "' uses extern '" + arg.name + "', which the scene does not give");
    ComponentType type;
    if (componentTypeFor(arg.type.scalar, type) && tensor->type != type)
      if (llvm::Error err = tensor->convertTo(type))
        return llvm::createStringError(scene.path + ": externs." + arg.name +
                                       ": " + llvm::toString(std::move(err)));
    if (llvm::Error err =
            function.bind(arg.name, tensor->data(), tensor->type, tensor->shape))
      return err;
  }
  return llvm::handleErrors(
      function.init(), [&](const ArgumentError &err) -> llvm::Error {
        return llvm::createStringError(scene.path + ": " +
                                       jsonPathOf(scene, err.argument()) +
                                       ": " + err.message());
      });
}

/// Scans what the functions of a frame left in their float fields and
/// externs; the error names the frame, and the field or extern and the
/// element, and how to find the statement that produced the value.
llvm::Error checkFrame(const SceneDescription &scene,
                       const std::vector<NamedFunction> &group, int frame) {
  for (const NamedFunction &named : group) {
    std::string problem = named.function.findNonFinite();
    if (!problem.empty())
      return llvm::createStringError(
          scene.path + ": frame " + llvm::Twine(frame) + ": after function '" +
          named.name + "': " + problem +
          " (rerun with --check-numerics to find the statement that "
          "produced it, or --no-check to run on)");
  }
  return llvm::Error::success();
}

/// Runs every function of `group` in order.
llvm::Error runAll(std::vector<NamedFunction> &group, bool checkNumerics,
                   int frame) {
  for (NamedFunction &named : group) {
    if (llvm::Error err = named.function.run())
      return err;
    if (!checkNumerics)
      continue;
    // First the assembly or solve that produced a NaN or infinity, then
    // what the function left in the fields and externs (from work that is
    // neither, e.g. a solver written in Simit).
    std::string where =
        "function '" + named.name + "' (frame " + std::to_string(frame) + ")";
    if (std::optional<std::string> problem = takeNumericsProblem())
      return llvm::createStringError("check-numerics: " + where + ": " +
                                     *problem);
    std::string problem = named.function.findNonFinite();
    if (!problem.empty())
      return llvm::createStringError("check-numerics: after " + where + ": " +
                                     problem);
  }
  return llvm::Error::success();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}
} // namespace

llvm::Error simit::runScene(const SceneRunOptions &options) {
  llvm::Expected<SceneDescription> scene = loadScene(options.scenePath);
  if (!scene)
    return scene.takeError();
  std::string programPath =
      options.programPath.empty() ? scene->program : options.programPath;
  if (programPath.empty())
    return llvm::createStringError(
        scene->path + ": no program: give one on the command line or as "
                      "\"program\" in the scene");
  int frames = options.frames.value_or(scene->frames);
  if (frames > 0 && scene->step.empty())
    return llvm::createStringError(scene->path + ": " + llvm::Twine(frames) +
                                   " frames need a \"step\" function");

  Clock::time_point compileStart = Clock::now();
  ProgramOptions programOptions;
  programOptions.precision = options.precision;
  programOptions.timePhases = options.printTimes;
  programOptions.checkNumerics = options.checkNumerics;
  Program program(programOptions);
  if (llvm::Error err = program.loadFile(programPath))
    return err;
  if (llvm::Error err = checkSceneFields(*scene, program, programPath))
    return err;
  std::vector<NamedFunction> init, step;
  for (auto [names, group] : {std::pair(&scene->init, &init),
                              std::pair(&scene->step, &step)}) {
    for (const std::string &name : *names) {
      llvm::Expected<Function> function = program.compile(name);
      if (!function)
        return llvm::createStringError(programPath + ": " +
                                       llvm::toString(function.takeError()));
      group->push_back({name, std::move(*function)});
    }
  }
  double compileMs = millisecondsSince(compileStart);

  Clock::time_point bindStart = Clock::now();
  SetRegistry registry;
  if (llvm::Error err = buildSets(*scene, registry))
    return err;
  double setsMs = millisecondsSince(bindStart);
  for (std::vector<NamedFunction> *group : {&init, &step})
    for (NamedFunction &named : *group)
      if (llvm::Error err = provideFields(*scene, registry, named))
        return err;
  for (std::vector<NamedFunction> *group : {&init, &step})
    for (NamedFunction &named : *group)
      if (llvm::Error err = bindFromScene(*scene, registry, named))
        return err;
  double bindMs = millisecondsSince(bindStart);

  auto writer =
      SceneOutputWriter::create(*scene, registry, options.outputDirectory,
                                frames);
  if (!writer)
    return writer.takeError();
  bool checkFrames = options.checkFrames && !options.checkNumerics;

  Clock::time_point runStart = Clock::now();
  if (llvm::Error err = runAll(init, options.checkNumerics, 0))
    return err;
  if (checkFrames)
    if (llvm::Error err = checkFrame(*scene, init, 0))
      return err;
  double initMs = millisecondsSince(runStart);
  if (llvm::Error err = (*writer)->writeFrame(0, frames == 0))
    return err;

  std::vector<double> frameMs, assemblyMs, solveMs, checkMs;
  Clock::time_point lastProgress = Clock::now();
  for (int frame = 1; frame <= frames; ++frame) {
    resetPhaseTimes();
    Clock::time_point frameStart = Clock::now();
    if (llvm::Error err = runAll(step, options.checkNumerics, frame))
      return err;
    if (checkFrames) {
      Clock::time_point checkStart = Clock::now();
      if (llvm::Error err = checkFrame(*scene, step, frame))
        return err;
      checkMs.push_back(millisecondsSince(checkStart));
    }
    frameMs.push_back(millisecondsSince(frameStart));
    PhaseTimes phases = readPhaseTimes();
    assemblyMs.push_back(phases.assemblyMs);
    solveMs.push_back(phases.solveMs);
    if (llvm::Error err = (*writer)->writeFrame(frame, frame == frames))
      return err;
    if (options.progress && millisecondsSince(runStart) > 2000 &&
        millisecondsSince(lastProgress) > 1000) {
      llvm::errs() << "frame " << frame << " of " << frames << " ("
                   << llvm::format("%.2f", frameMs.back()) << " ms)\n";
      lastProgress = Clock::now();
    }
  }
  if (llvm::Error err = (*writer)->finish())
    return err;

  if (options.printTimes) {
    llvm::raw_ostream &os = llvm::outs();
    os << llvm::format("compile:   %10.2f ms\n", compileMs);
    os << llvm::format("bind/init: %10.2f ms (sets %.2f ms)\n", bindMs,
                       setsMs);
    os << llvm::format("init:      %10.2f ms\n", initMs);
    if (!frameMs.empty()) {
      // Frame 1 includes first-touch costs; the median leaves it out.
      auto steady = [](const std::vector<double> &perFrame) {
        return median(perFrame.size() > 1
                          ? std::vector<double>(perFrame.begin() + 1,
                                                perFrame.end())
                          : perFrame);
      };
      os << llvm::format("frame:     %10.3f ms (median of frames %d..%d; "
                         "frame 1 %.3f ms)\n",
                         steady(frameMs), frameMs.size() > 1 ? 2 : 1, frames,
                         frameMs.front());
      os << llvm::format("  assembly:%10.3f ms (map and apply statements)\n",
                         steady(assemblyMs));
      os << llvm::format("  solve:   %10.3f ms (solves, and while loops "
                         "without assemblies)\n",
                         steady(solveMs));
      if (!checkMs.empty())
        os << llvm::format("  check:   %10.3f ms (the scan of the state for "
                           "NaN and infinity)\n",
                           steady(checkMs));
    }
  }
  return llvm::Error::success();
}
