//===--- SceneRun.cpp - Running a program on a scene ----------------------===//

#include "simit/Engine/SceneRun.h"

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/Scene.h"
#include "simit/Runtime/SceneOutput.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/Format.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <set>

using namespace simit;

namespace {
using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start)
      .count();
}

/// Makes the set hold every field `function` reads or writes: a field the
/// scene did not mention is added zero-filled with the program's type and
/// shape, and a float64 field is narrowed when the program runs in single
/// precision. Other mismatches are left for Function::init to report.
llvm::Error provideFields(const SceneDescription &scene, SetRegistry &registry,
                          const std::string &name, const Function &function) {
  for (const ArgumentBinding &arg : function.signature().arguments) {
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
      std::vector<int64_t> hostShape = arg.type.hostShape();
      for (int64_t dim : llvm::drop_begin(hostShape)) {
        if (dim == ValueType::kDynamic)
          return llvm::createStringError(
              scene.path + ": sets." + arg.set + ".fields." + arg.field +
              ": the program's function '" + name +
              "' uses this field with a shape only the scene can give");
        shape.push_back(static_cast<int>(dim));
      }
      if (llvm::Error err = set->addField(arg.field, type, shape))
        return llvm::createStringError(
            scene.path + ": sets." + arg.set + ": the program's function '" +
            name + "' uses field '" + arg.field + "': " +
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

/// The declaration of field `name` among `fields`, or null.
const DeclaredField *findField(const std::vector<DeclaredField> &fields,
                               llvm::StringRef name) {
  for (const DeclaredField &field : fields)
    if (field.name == name)
      return &field;
  return nullptr;
}

/// What a set holds per element for a declared field.
struct FieldBlock {
  ComponentType type;
  std::vector<int> shape;
};

/// The block of a declared field (its array's type without the set
/// dimension; a complex field's block ends in its (re, im) pairs); none for
/// components no set field holds.
std::optional<FieldBlock> blockOf(const DeclaredField &field) {
  FieldBlock block;
  const ValueType &array = field.type;
  if (!array.isMemRef || !componentTypeFor(array.scalar, block.type))
    return std::nullopt;
  std::vector<int64_t> shape = array.hostShape();
  block.shape.assign(shape.begin() + 1, shape.end());
  return block;
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
    std::vector<std::string> names;
    for (const DeclaredField &field : it->second)
      names.push_back(field.name);
    for (const FieldSpec &field : set.fields) {
      const DeclaredField *declaration = findField(it->second, field.name);
      if (!declaration)
        return llvm::createStringError(
            scene.path + ": " + field.jsonPath + ": the elements of set '" +
            set.name + "' in " + programPath + " have no field '" + field.name +
            "' (they have: " +
            (names.empty() ? std::string("none") : llvm::join(names, ", ")) +
            ")");
      // Also a field no called function uses must be what the program
      // says, as the outputs write it. Float fields may be either width:
      // the run's precision narrows them.
      std::optional<FieldBlock> declared = blockOf(*declaration);
      if (!declared)
        continue;
      auto isFloat = [](ComponentType type) {
        return type == ComponentType::Float64 || type == ComponentType::Float32;
      };
      bool typeFits = field.type == declared->type ||
                      (isFloat(field.type) && isFloat(declared->type));
      if (!typeFits || field.shape != declared->shape)
        return llvm::createStringError(
            scene.path + ": " + field.jsonPath + ": field '" + field.name +
            "' of set '" + set.name + "' in " + programPath + " holds " +
            componentTypeName(declared->type).str() + " components of shape " +
            shapeString(declared->shape) + ", but the scene gives " +
            componentTypeName(field.type).str() + " of shape " +
            shapeString(field.shape) +
            (typeFits ? "" : " (give its \"type\")"));
    }
  }
  return llvm::Error::success();
}

/// The (set, field) pairs the scene's outputs write.
std::set<std::pair<std::string, std::string>>
outputFields(const SceneDescription &scene) {
  std::set<std::pair<std::string, std::string>> fields;
  for (const OutputSpec &output : scene.outputs) {
    for (const std::string &field : output.fields)
      fields.insert({output.set, field});
    if (output.kind == OutputSpec::VTK)
      fields.insert({output.set, output.position});
    for (const std::string &cells : output.cells)
      for (const std::string &field : output.cellFields)
        fields.insert({cells, field});
  }
  return fields;
}

/// Adds, zero-filled with their declared type, the fields that an output
/// names and the program declares but neither the scene nor any called
/// function gives (a field the program never uses is zero throughout).
llvm::Error provideOutputFields(const SceneDescription &scene,
                                SetRegistry &registry, Program &program) {
  auto declared = program.externSetFields();
  if (!declared)
    return declared.takeError();
  auto provide = [&](const std::string &setName,
                     const std::string &fieldName) -> llvm::Error {
    Set *set = registry.find(setName);
    auto fields = declared->find(setName);
    if (!set || set->fieldDescriptor(fieldName) || fields == declared->end())
      return llvm::Error::success();
    const DeclaredField *field = findField(fields->second, fieldName);
    std::optional<FieldBlock> block = field ? blockOf(*field) : std::nullopt;
    if (!block)
      return llvm::Error::success();
    if (llvm::Error err = set->addField(fieldName, block->type, block->shape))
      return llvm::createStringError(scene.path + ": outputs: field '" +
                                     fieldName + "' of set '" + setName +
                                     "': " + llvm::toString(std::move(err)));
    return llvm::Error::success();
  };
  for (const auto &[set, field] : outputFields(scene))
    if (llvm::Error err = provide(set, field))
      return err;
  return llvm::Error::success();
}

/// An edge set or grid of the scene whose endpoints are other sets than the
/// program declares would have its endpoint indices read as positions in
/// the declared sets: out of their bounds, or silently the wrong elements.
llvm::Error checkSceneEndpoints(const SceneDescription &scene,
                                const SetRegistry &registry, Program &program,
                                llvm::StringRef programPath) {
  auto declared = program.externSetEndpoints();
  if (!declared)
    return declared.takeError();
  for (const auto &[name, expected] : *declared) {
    Set *set = registry.find(name);
    if (!set || expected.empty())
      continue;
    std::vector<std::string> given;
    for (Set *endpoints : set->endpointSetList())
      given.push_back(endpoints->name().str());
    if (given != expected)
      return llvm::createStringError(
          scene.path + ": sets." + name + ".endpoints: set '" + name + "' in " +
          programPath + " has endpoints in (" + llvm::join(expected, ", ") +
          "), but the scene gives (" + llvm::join(given, ", ") + ")");
  }
  return llvm::Error::success();
}

/// A scene extern the program does not declare (a misspelt name) would
/// silently leave the program's own extern unbound or zero.
llvm::Error checkSceneExterns(
    const SceneDescription &scene,
    llvm::ArrayRef<const std::vector<SceneRunner::NamedFunction> *> groups,
    Program &program, llvm::StringRef programPath) {
  auto declared = program.externTensorNames();
  if (!declared)
    return declared.takeError();
  // Lowered IR declares its externs only through its functions' bindings.
  for (const std::vector<SceneRunner::NamedFunction> *group : groups)
    for (const SceneRunner::NamedFunction &named : *group)
      for (const ArgumentBinding &arg : named.function.signature().arguments)
        if (arg.kind == ArgumentBinding::Kind::Extern &&
            !llvm::is_contained(*declared, arg.name))
          declared->push_back(arg.name);
  llvm::sort(*declared);
  for (const auto &[name, tensor] : scene.externs)
    if (!llvm::is_contained(*declared, name))
      return llvm::createStringError(
          scene.path + ": externs." + name + ": " + programPath +
          " declares no extern tensor '" + name + "' (it declares " +
          (declared->empty() ? std::string("none")
                             : "'" + llvm::join(*declared, "', '") + "'") +
          ")");
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

/// Binds the sets and extern tensors `function` needs from the registry.
llvm::Error bindFromScene(const SceneDescription &scene, SetRegistry &registry,
                          const std::string &name, Function &function) {
  for (const std::string &setName : function.requiredSets()) {
    Set *set = registry.find(setName);
    if (!set)
      return llvm::createStringError(
          scene.path + ": sets: the program's function '" + name +
          "' uses set '" + setName + "', which the scene does not define");
    if (llvm::Error err = function.bind(setName, *set))
      return llvm::createStringError(scene.path + ": sets." + setName + ": " +
                                     llvm::toString(std::move(err)));
  }
  for (const ArgumentBinding &arg : function.signature().arguments) {
    if (arg.kind == ArgumentBinding::Kind::Parameter)
      return llvm::createStringError(
          scene.path + ": " +
          (llvm::is_contained(scene.init, name) ? "init" : "step") +
          ": function '" + name +
          "' takes parameters; a scene can only run functions without "
          "parameters");
    if (arg.kind != ArgumentBinding::Kind::Extern)
      continue;
    ExternTensor *tensor = registry.findExtern(arg.name);
    if (!tensor)
      return llvm::createStringError(
          scene.path + ": externs: the program's function '" + name +
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


double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}
} // namespace

SceneTimeSummary SceneTimes::summarize() const {
  SceneTimeSummary summary;
  summary.compileMs = compileMs;
  summary.bindMs = bindMs;
  summary.setsMs = setsMs;
  summary.initMs = initMs;
  summary.frames = static_cast<int>(frameMs.size());
  if (frameMs.empty())
    return summary;
  // Frame 1 includes first-touch costs; the median leaves it out.
  auto steady = [](const std::vector<double> &perFrame) {
    return median(perFrame.size() > 1
                      ? std::vector<double>(perFrame.begin() + 1,
                                            perFrame.end())
                      : perFrame);
  };
  summary.frameMs = steady(frameMs);
  summary.assemblyMs = steady(assemblyMs);
  summary.solveMs = steady(solveMs);
  if (!checkMs.empty())
    summary.checkMs = steady(checkMs);
  summary.firstFrameMs = frameMs.front();
  return summary;
}

/// What the scene promises the compiler, as far as `options` let it use it.
static ProgramSpecialisation specialisationOf(const SceneRunOptions &options,
                                              const SceneDescription &scene) {
  ProgramSpecialisation specialisation;
  if (options.skipUncalledFunctions)
    for (const std::vector<std::string> *names : {&scene.init, &scene.step})
      for (const std::string &name : *names)
        if (!llvm::is_contained(specialisation.entryFunctions, name))
          specialisation.entryFunctions.push_back(name);
  // Larger values would only bloat the code (and the cache key).
  constexpr int64_t kMaxFoldedComponents = 64;
  if (options.foldConstantExterns)
    for (const auto &[name, tensor] : scene.externs)
      if (tensor.constant &&
          static_cast<int64_t>(tensor.values.size()) <= kMaxFoldedComponents)
        specialisation.constantExterns[name] = tensor.values;
  if (options.foldUniformFields)
    for (const SetSpec &set : scene.sets)
      for (const FieldSpec &field : set.fields) {
        int64_t blockSize = 1;
        for (int dim : field.shape)
          blockSize = std::min<int64_t>(blockSize * dim,
                                        kMaxFoldedComponents + 1);
        if (blockSize > kMaxFoldedComponents)
          continue;
        if (field.init.kind == FieldInit::Constant)
          specialisation.uniformFields[set.name][field.name] =
              field.init.values;
        else if (field.init.kind == FieldInit::Zero)
          specialisation.uniformFields[set.name][field.name] =
              std::vector<double>(blockSize, 0.0);
      }
  return specialisation;
}

/// The scene with only the fields that `functions` bind or an output
/// names: the others are never built.
using FunctionGroup = std::vector<SceneRunner::NamedFunction>;

static SceneDescription
withUsedFields(const SceneDescription &scene,
               std::initializer_list<const FunctionGroup *> groups) {
  std::set<std::pair<std::string, std::string>> used;
  for (const auto *group : groups)
    for (const SceneRunner::NamedFunction &named : *group)
      for (const ArgumentBinding &arg : named.function.signature().arguments)
        if (arg.kind == ArgumentBinding::Kind::Field)
          used.insert({arg.set, arg.field});
  used.merge(outputFields(scene));
  SceneDescription kept = scene;
  for (SetSpec &set : kept.sets)
    llvm::erase_if(set.fields, [&](const FieldSpec &field) {
      return !used.count({set.name, field.name});
    });
  return kept;
}

static ProgramOptions programOptionsOf(const SceneRunOptions &options,
                                       const SceneDescription &scene) {
  ProgramOptions program;
  program.precision = options.precision;
  program.timePhases = options.timePhases;
  program.checkNumerics = options.checkNumerics;
  program.threads = options.threads;
  program.cacheDirectory = options.cacheDirectory;
  program.solver = options.solver.appliedTo(scene.solver);
  program.shermanMorrison = options.shermanMorrison;
  program.hostLibraries = options.hostLibraries;
  program.target = options.target;
  program.eliminateDeadAssemblies = options.eliminateDeadAssemblies;
  program.vectorizeElements = options.vectorizeElements;
  program.specialisation = specialisationOf(options, scene);
  llvm::append_range(program.hostLibraries, scene.libraries);
  return program;
}

SceneRunner::SceneRunner(SceneDescription scene,
                         const SceneRunOptions &options)
    : description(std::move(scene)), options(options),
      program(programOptionsOf(options, description)) {}

SceneRunner::~SceneRunner() = default;

llvm::Expected<std::unique_ptr<SceneRunner>>
SceneRunner::create(SceneDescription scene, const SceneRunOptions &options) {
  std::unique_ptr<SceneRunner> runner(
      new SceneRunner(std::move(scene), options));
  const SceneDescription &desc = runner->description;
  std::string programPath =
      options.programPath.empty() ? desc.program : options.programPath;
  if (programPath.empty())
    return llvm::createStringError(
        desc.path + ": no program: give one on the command line or as "
                    "\"program\" in the scene");
  if (options.frames && *options.frames < 0)
    return llvm::createStringError("frames: expected a frame count of at "
                                   "least 0, not " +
                                   llvm::Twine(*options.frames));
  runner->frameCount = options.frames.value_or(desc.frames);
  if (runner->frameCount > 0 && desc.step.empty())
    return llvm::createStringError(desc.path + ": " +
                                   llvm::Twine(runner->frameCount) +
                                   " frames need a \"step\" function");

  Clock::time_point compileStart = Clock::now();
  Program &program = runner->program;
  if (llvm::Error err = program.loadFile(programPath))
    return std::move(err);
  if (llvm::Error err = checkSceneFields(desc, program, programPath))
    return std::move(err);
  for (auto [names, group] :
       {std::pair(&desc.init, &runner->initFunctions),
        std::pair(&desc.step, &runner->stepFunctions)}) {
    for (const std::string &name : *names) {
      llvm::Expected<Function> function = program.compile(name);
      if (!function)
        return llvm::createStringError(programPath + ": " +
                                       llvm::toString(function.takeError()));
      group->push_back({name, std::move(*function)});
    }
  }
  SceneTimes &times = runner->timings;
  times.compileMs = millisecondsSince(compileStart);

  Clock::time_point bindStart = Clock::now();
  if (llvm::Error err = checkSceneExterns(
          desc, {&runner->initFunctions, &runner->stepFunctions}, program,
          programPath))
    return std::move(err);
  SetRegistry &registry = runner->registry;
  if (llvm::Error err =
          options.skipUnusedFields
              ? buildSets(withUsedFields(desc, {&runner->initFunctions,
                                                &runner->stepFunctions}),
                          registry)
              : buildSets(desc, registry))
    return std::move(err);
  if (llvm::Error err =
          checkSceneEndpoints(desc, registry, program, programPath))
    return std::move(err);
  times.setsMs = millisecondsSince(bindStart);
  for (auto *group : {&runner->initFunctions, &runner->stepFunctions})
    for (NamedFunction &named : *group)
      if (llvm::Error err =
              provideFields(desc, registry, named.name, named.function))
        return std::move(err);
  for (auto *group : {&runner->initFunctions, &runner->stepFunctions})
    for (NamedFunction &named : *group)
      if (llvm::Error err =
              bindFromScene(desc, registry, named.name, named.function))
        return std::move(err);
  if (llvm::Error err = provideOutputFields(desc, registry, program))
    return std::move(err);
  times.bindMs = millisecondsSince(bindStart);

  if (options.outputDirectory) {
    auto writer =
        SceneOutputWriter::create(desc, registry, *options.outputDirectory,
                                  runner->frameCount);
    if (!writer)
      return writer.takeError();
    runner->writer = std::move(*writer);
  }
  return std::move(runner);
}

/// Runs every function of `group` in order.
llvm::Error SceneRunner::runAll(std::vector<NamedFunction> &group,
                                int frame) {
  for (NamedFunction &named : group) {
    std::string where =
        "function '" + named.name + "' (frame " + std::to_string(frame) + ")";
    if (llvm::Error err = named.function.run()) {
      std::string message = llvm::toString(std::move(err));
      // An assembly's NaN that a later statement tripped over (a solve of
      // a NaN right-hand side) is the cause: it is named first.
      if (options.checkNumerics)
        if (std::optional<std::string> problem = takeNumericsProblem())
          return llvm::createStringError("check-numerics: " + where + ": " +
                                         *problem + "; then " + message);
      return llvm::createStringError(where + ": " + message);
    }
    if (!options.checkNumerics)
      continue;
    // First the assembly or solve that produced a NaN or infinity, then
    // what the function left in the fields and externs (from work that is
    // neither, e.g. a solver written in Simit).
    if (std::optional<std::string> problem = takeNumericsProblem())
      return llvm::createStringError("check-numerics: " + where + ": " +
                                     *problem);
    Clock::time_point scanStart = Clock::now();
    std::string problem = named.function.findNonFinite();
    stateScanMs += millisecondsSince(scanStart);
    if (!problem.empty())
      return llvm::createStringError("check-numerics: after " + where + ": " +
                                     problem);
  }
  return llvm::Error::success();
}

llvm::Error SceneRunner::init() {
  if (initDone)
    return llvm::Error::success();
  Clock::time_point start = Clock::now();
  if (llvm::Error err = runAll(initFunctions, 0))
    return err;
  if (checksFrames())
    if (llvm::Error err = checkFrame(initFunctions, 0))
      return err;
  timings.initMs = millisecondsSince(start);
  initDone = true;
  return writeFrame(0);
}

llvm::Error SceneRunner::step(int count) {
  if (count < 0)
    return llvm::createStringError("step: expected a frame count of at "
                                   "least 0, not " +
                                   llvm::Twine(count));
  if (llvm::Error err = init())
    return err;
  if (count > 0 && stepFunctions.empty())
    return llvm::createStringError(description.path +
                                   ": frames need a \"step\" function");
  Clock::time_point runStart = Clock::now();
  Clock::time_point lastProgress = runStart;
  for (int i = 0; i < count; ++i) {
    int frame = ++currentFrame;
    resetPhaseTimes();
    Clock::time_point frameStart = Clock::now();
    stateScanMs = 0;
    if (llvm::Error err = runAll(stepFunctions, frame))
      return err;
    if (options.checkNumerics)
      timings.checkMs.push_back(stateScanMs);
    if (checksFrames()) {
      Clock::time_point checkStart = Clock::now();
      if (llvm::Error err = checkFrame(stepFunctions, frame))
        return err;
      timings.checkMs.push_back(millisecondsSince(checkStart));
    }
    timings.frameMs.push_back(millisecondsSince(frameStart));
    PhaseTimes phases = readPhaseTimes();
    timings.assemblyMs.push_back(phases.assemblyMs);
    timings.solveMs.push_back(phases.solveMs);
    if (llvm::Error err = writeFrame(frame))
      return err;
    if (options.progress && millisecondsSince(runStart) > 2000 &&
        millisecondsSince(lastProgress) > 1000) {
      llvm::errs() << "frame " << frame << " of " << frameCount << " ("
                   << llvm::format("%.2f", timings.frameMs.back()) << " ms)\n";
      lastProgress = Clock::now();
    }
  }
  return llvm::Error::success();
}

llvm::Error SceneRunner::checkFrame(const std::vector<NamedFunction> &group,
                                    int frame) {
  for (const NamedFunction &named : group) {
    std::string problem = named.function.findNonFinite();
    if (!problem.empty())
      return llvm::createStringError(
          description.path + ": frame " + llvm::Twine(frame) + ": after function '" +
          named.name + "': " + problem +
          " (rerun with --check-numerics to find the statement that "
          "produced it, or --no-check to run on)");
  }
  return llvm::Error::success();
}

llvm::Error SceneRunner::writeFrame(int frame) {
  if (!writer)
    return llvm::Error::success();
  if (llvm::Error err = writer->writeFrame(frame, frame == frameCount))
    return err;
  // The files that collect frames are complete after the last one.
  return frame == frameCount ? writer->finish() : llvm::Error::success();
}

llvm::Error SceneRunner::run() {
  if (llvm::Error err = init())
    return err;
  return step(std::max(0, frameCount - currentFrame));
}

const std::vector<std::string> &SceneRunner::writtenFiles() const {
  static const std::vector<std::string> none;
  return writer ? writer->writtenFiles() : none;
}
