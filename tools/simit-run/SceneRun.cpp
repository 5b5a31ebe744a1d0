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
        return err;
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
      return err;
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
  return function.init();
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
  programOptions.cacheDirectory = options.cacheDirectory;
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
      SceneOutputWriter::create(*scene, registry, options.outputDirectory);
  if (!writer)
    return writer.takeError();

  Clock::time_point runStart = Clock::now();
  if (llvm::Error err = runAll(init, options.checkNumerics, 0))
    return err;
  double initMs = millisecondsSince(runStart);
  if (llvm::Error err = (*writer)->writeFrame(0, frames == 0))
    return err;

  std::vector<double> frameMs, assemblyMs, solveMs;
  Clock::time_point lastProgress = Clock::now();
  for (int frame = 1; frame <= frames; ++frame) {
    resetPhaseTimes();
    Clock::time_point frameStart = Clock::now();
    if (llvm::Error err = runAll(step, options.checkNumerics, frame))
      return err;
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

  if (options.printTimes) {
    llvm::raw_ostream &os = llvm::outs();
    const CompileTimes &times = program.compileTimes();
    if (times.cached)
      os << llvm::format("compile:   %10.2f ms (cached; load %.2f ms)\n",
                         compileMs, times.loadMs);
    else
      os << llvm::format("compile:   %10.2f ms (lowering %.2f, LLVM -O3 "
                         "%.2f, codegen %.2f, load %.2f ms)\n",
                         compileMs, times.loweringMs, times.optimizationMs,
                         times.codegenMs, times.loadMs);
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
    }
  }
  return llvm::Error::success();
}
