//===--- Program.cpp - Loading and compiling Simit programs ---------------===//

#include "simit/Engine/Program.h"

#include "CompileCache.h"
#include "CompiledModule.h"
#include "Lowering.h"
#include "ObjectCode.h"
#include "SimImport.h"
#include "Specialise.h"
#include "Stopwatch.h"

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Frontend/IRGen.h"
#include "simit/Runtime/CudaDriver.h"

#include "mlir/IR/BuiltinOps.h"
#include "mlir/IR/Diagnostics.h"
#include "mlir/IR/MLIRContext.h"
#include "mlir/IR/OwningOpRef.h"
#include "mlir/Parser/Parser.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/DynamicLibrary.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/SourceMgr.h"

#include <optional>

using namespace simit;

namespace {
/// What was loaded, as given: it is imported when first needed, which a
/// program found in the compile cache may never be.
struct Source {
  enum class Kind { Sim, MLIR };
  Kind kind = Kind::Sim;
  std::string name, text;
};

/// The fields of a set's elements, each with the type of its array over the
/// set: memref<? x local shape x component>, complex components as pairs of
/// their parts (ValueType::isComplex).
std::vector<DeclaredField> fieldDeclarations(mlir::simit::SetType set) {
  std::vector<DeclaredField> fields;
  mlir::simit::ElementType element = set.getElement();
  for (auto [name, type] :
       llvm::zip(element.getFieldNames(), element.getFieldTypes())) {
    llvm::SmallVector<int64_t> shape{mlir::ShapedType::kDynamic};
    llvm::append_range(shape, mlir::simit::getLocalShape(type));
    mlir::Type component = mlir::simit::getComponentType(type);
    auto complex = llvm::dyn_cast<mlir::ComplexType>(component);
    llvm::Expected<ValueType> array = toValueType(mlir::MemRefType::get(
        shape, complex ? complex.getElementType() : component));
    if (!array) {
      // A component the runtime has no arrays of (e.g. i16 in hand-written
      // IR): declared, but not a memref.
      llvm::consumeError(array.takeError());
      array = ValueType();
    }
    array->isComplex = static_cast<bool>(complex);
    fields.push_back({name.str(), std::move(*array)});
  }
  return fields;
}

/// The set of each endpoint position of a set (a grid's point set at both);
/// none for a vertex set.
std::vector<std::string> endpointNames(mlir::simit::SetType set) {
  std::vector<std::string> names;
  for (unsigned i = 0; i < set.getCardinality(); ++i)
    names.push_back(set.getEndpoint(i).str());
  return names;
}
} // namespace

struct Program::Impl {
  ProgramOptions options;
  /// Made on first use: a program loaded from the cache needs none.
  std::unique_ptr<mlir::MLIRContext> context;
  std::optional<Source> source;
  /// The program in the simit dialect (or loops), once imported.
  mlir::OwningOpRef<mlir::ModuleOp> module;
  /// The lowered module and what lowering recorded, once lowered.
  mlir::OwningOpRef<mlir::ModuleOp> llvmModule;
  LoweringResult lowering;
  /// The compile cache's entry for the source, when it has one.
  std::optional<ObjectCode> cachedCode;
  std::shared_ptr<CompiledModule> compiled;
  CompileTimes times;
  std::shared_ptr<SolveSession> solver;

  /// options.threads resolved (resolveThreadCount()); a malformed request
  /// is reported by the first lowering or compile.
  int threads = 1;
  std::string threadsError;

  explicit Impl(ProgramOptions options)
      : options(std::move(options)),
        solver(std::make_shared<SolveSession>(this->options.solver)) {
    llvm::Expected<int> resolved = resolveThreadCount(this->options.threads);
    if (resolved)
      threads = *resolved;
    else
      threadsError = llvm::toString(resolved.takeError());
  }

  /// One thread compiles code without parallel regions.
  bool openmp() const { return threads > 1; }

  /// The vector width element kernels are compiled for; 0 when they run one
  /// element at a time.
  unsigned elementVectorBits() const {
    return options.vectorizeElements && options.target == Target::CPU
               ? hostVectorBits()
               : 0;
  }

  mlir::MLIRContext &getContext() {
    if (!context) {
      context = std::make_unique<mlir::MLIRContext>(
          mlir::MLIRContext::Threading::DISABLED);
      mlir::DialectRegistry registry;
      registerEngineDialects(registry);
      context->appendDialectRegistry(registry);
      context->loadAllAvailableDialects();
      // Diagnostics name the .sim position; the op dump would bury it.
      context->printOpOnDiagnostic(false);
      frontend::loadIRGenDialects(*context);
    }
    return *context;
  }

  llvm::Expected<mlir::OwningOpRef<mlir::ModuleOp>> import(const Source &from) {
    if (from.kind == Source::Kind::Sim)
      return importSimit(from.text, from.name, getContext(), options);
    llvm::SourceMgr sourceMgr;
    sourceMgr.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBuffer(from.text, from.name), llvm::SMLoc());
    std::string diagnostics;
    llvm::raw_string_ostream os(diagnostics);
    mlir::SourceMgrDiagnosticHandler handler(sourceMgr, &getContext(), os);
    mlir::OwningOpRef<mlir::ModuleOp> parsed =
        mlir::parseSourceFile<mlir::ModuleOp>(sourceMgr, &getContext());
    if (!parsed)
      return llvm::createStringError(diagnostics);
    return parsed;
  }

  /// Makes `from` the program: from the cache when it holds it, else
  /// imported now, so that its errors are reported by the load.
  llvm::Error load(Source from) {
    Stopwatch cacheRead;
    std::optional<ObjectCode> code = readCached(from);
    double cacheMs = cacheRead.milliseconds();
    mlir::OwningOpRef<mlir::ModuleOp> imported;
    if (!code) {
      auto result = import(from);
      if (!result)
        return result.takeError();
      imported = std::move(*result);
    }
    source = std::move(from);
    module = std::move(imported);
    llvmModule = nullptr;
    lowering = LoweringResult();
    cachedCode = std::move(code);
    compiled = nullptr;
    times = CompileTimes();
    times.loadMs = cacheMs;
    return llvm::Error::success();
  }

  llvm::Error requireModule() {
    if (module)
      return llvm::Error::success();
    if (!source)
      return llvm::createStringError("no program is loaded");
    auto result = import(*source);
    if (!result)
      return result.takeError();
    module = std::move(*result);
    return llvm::Error::success();
  }

  /// What Target::GPU compiles kernels for: the device's chip, or sm_90
  /// where there is none (emit() needs no device); nullopt for the CPU.
  std::optional<GPUKernelTarget> kernelTarget() const {
    if (options.target != Target::GPU)
      return std::nullopt;
    llvm::Expected<cuda::Device &> device = cuda::defaultDevice();
    if (!device) {
      llvm::consumeError(device.takeError());
      return GPUKernelTarget();
    }
    return gpuKernelTargetFor(device->computeCapability());
  }

  llvm::Error lower() {
    if (llvmModule)
      return llvm::Error::success();
    return lowerClone(llvmModule, lowering, /*keepLoopsStage=*/false);
  }

  /// Lowers a specialised copy of the module into `lowered` and `result`.
  llvm::Error lowerClone(mlir::OwningOpRef<mlir::ModuleOp> &lowered,
                         LoweringResult &result, bool keepLoopsStage) {
    if (!threadsError.empty())
      return llvm::createStringError(threadsError);
    if (llvm::Error err = requireModule())
      return err;
    mlir::OwningOpRef<mlir::ModuleOp> clone = module->clone();
    specialiseModule(*clone, options.specialisation);
    mlir::simit::SimitCpuPipelineOptions pipelineOptions;
    pipelineOptions.timePhases = options.timePhases;
    pipelineOptions.checkNumerics = options.checkNumerics;
    pipelineOptions.openmp = openmp();
    pipelineOptions.shermanMorrison = options.shermanMorrison;
    pipelineOptions.eliminateDeadAssemblies = options.eliminateDeadAssemblies;
    pipelineOptions.elementVectorBits = elementVectorBits();
    if (llvm::Error err = lowerToLLVM(*clone, result, pipelineOptions,
                                      kernelTarget(), keepLoopsStage))
      return err;
    lowered = std::move(clone);
    return llvm::Error::success();
  }

  /// Everything the code compiled from `from` depends on; empty when the
  /// cache is off or cannot tell this compiler from others
  /// (CompileCache.h).
  std::string cacheKey(const Source &from) const {
    if (options.cacheDirectory.empty() || compilerIdentity().empty())
      return "";
    auto target = hostTarget();
    if (!target) {
      llvm::consumeError(target.takeError());
      return "";
    }
    std::vector<std::string> features = target->getFeatures().getFeatures();
    llvm::sort(features);
    std::string key;
    llvm::raw_string_ostream os(key);
    os << compilerIdentity() << "\ncpu " << target->getCPU() << " "
       << llvm::join(features, ",") << "\nprecision "
       << (options.precision == FloatPrecision::Single ? "single" : "double")
       << "\nhost functions " << llvm::join(options.hostFunctions, ",")
       << "\ntime phases " << options.timePhases << "\ncheck numerics "
       << options.checkNumerics << "\nsherman-morrison "
       << options.shermanMorrison << "\nopenmp " << openmp() << "\ntarget "
       << targetName(options.target);
    if (std::optional<GPUKernelTarget> gpu = kernelTarget())
      os << " " << gpu->chip << " " << gpu->features;
    os << "\ndead assemblies " << options.eliminateDeadAssemblies
       << "\nelement vector bits " << elementVectorBits();
    writeSpecialisationKey(os, options.specialisation);
    os << "\n"
       << (from.kind == Source::Kind::Sim ? "sim " : "mlir ") << from.name
       << "\n"
       << from.text;
    return key;
  }

  /// The cache's entry for `from`, if it has a sound one.
  std::optional<ObjectCode> readCached(const Source &from) const {
    std::string key = cacheKey(from);
    if (key.empty())
      return std::nullopt;
    std::optional<std::string> payload =
        readCacheEntry(options.cacheDirectory, key);
    if (!payload)
      return std::nullopt;
    llvm::Expected<ObjectCode> code = deserializeObjectCode(*payload);
    if (!code) {
      llvm::consumeError(code.takeError());
      return std::nullopt;
    }
    return std::move(*code);
  }

  /// For each extern set of the imported module, by name, what `of` gives
  /// its type.
  template <typename PerSet>
  std::map<std::string, PerSet>
  externSetsOfModule(llvm::function_ref<PerSet(mlir::simit::SetType)> of) {
    std::map<std::string, PerSet> sets;
    for (auto global : module->getOps<mlir::simit::ExternOp>())
      if (auto set = llvm::dyn_cast<mlir::simit::SetType>(global.getType()))
        sets[set.getName().str()] = of(set);
    return sets;
  }

  std::vector<std::string> externTensorsOfModule() {
    std::vector<std::string> names;
    for (auto global : module->getOps<mlir::simit::ExternOp>())
      if (!llvm::isa<mlir::simit::SetType>(global.getType()))
        names.push_back(global.getSymName().str());
    llvm::sort(names);
    return names;
  }

  /// What a program declares for each extern set: kept with the compiled
  /// code, so that a program loaded from the cache need not be imported.
  template <typename PerSet>
  llvm::Expected<std::map<std::string, PerSet>>
  externSets(std::map<std::string, PerSet> ObjectCode::*kept,
             llvm::function_ref<PerSet(mlir::simit::SetType)> of) {
    if (cachedCode)
      return (*cachedCode).*kept;
    if (llvm::Error err = requireModule())
      return std::move(err);
    return externSetsOfModule(of);
  }

  llvm::Error compile() {
    if (compiled)
      return llvm::Error::success();
    if (!threadsError.empty())
      return llvm::createStringError(threadsError);
    // Before anything heavy: without a device nothing can run.
    if (options.target == Target::GPU) {
      llvm::Expected<cuda::Device &> device = cuda::defaultDevice();
      if (!device)
        return llvm::createStringError("no CUDA device: " +
                                       llvm::toString(device.takeError()));
    }
    // Their symbols join the process's, where the JIT looks for what the
    // runtime does not define.
    for (const std::string &library : options.hostLibraries) {
      std::string why;
      if (llvm::sys::DynamicLibrary::LoadLibraryPermanently(library.c_str(),
                                                            &why))
        return llvm::createStringError("cannot load the host library '" +
                                       library + "': " + why);
    }
    if (cachedCode) {
      Stopwatch link;
      auto loaded = loadObjectCode(*cachedCode);
      if (loaded) {
        compiled = std::move(*loaded);
        compiled->threads = threads;
        compiled->solver = solver;
        times.cached = true;
        times.loadMs += link.milliseconds();
        return llvm::Error::success();
      }
      // Sound bytes that do not link (e.g. a runtime function this build
      // lacks): compile as if there were no entry.
      llvm::consumeError(loaded.takeError());
      cachedCode.reset();
    }

    Stopwatch loweringTime;
    if (llvm::Error err = lower())
      return err;
    CompileTimes newTimes;
    newTimes.loweringMs = loweringTime.milliseconds();
    auto code = compileToObject(*llvmModule, lowering.signatures, newTimes);
    if (!code)
      return code.takeError();
    code->externSetFields =
        externSetsOfModule<std::vector<DeclaredField>>(fieldDeclarations);
    code->externSetEndpoints =
        externSetsOfModule<std::vector<std::string>>(endpointNames);
    code->externTensors = externTensorsOfModule();
    Stopwatch link;
    auto loaded = loadObjectCode(*code);
    if (!loaded)
      return loaded.takeError();
    newTimes.loadMs = link.milliseconds();
    compiled = std::move(*loaded);
    compiled->threads = threads;
    compiled->solver = solver;
    times = newTimes;
    // A cache that cannot be written costs the next run its compile time,
    // nothing else.
    if (std::string key = cacheKey(*source); !key.empty())
      llvm::consumeError(writeCacheEntry(options.cacheDirectory, key,
                                         serializeObjectCode(*code)));
    return llvm::Error::success();
  }
};

llvm::StringRef simit::targetName(Target target) {
  return target == Target::GPU ? "gpu" : "cpu";
}

Program::Program(ProgramOptions options)
    : impl(std::make_unique<Impl>(std::move(options))) {}
Program::Program(Program &&) = default;
Program &Program::operator=(Program &&) = default;
Program::~Program() = default;

llvm::Error Program::loadFile(llvm::StringRef path) {
  auto buffer = llvm::MemoryBuffer::getFile(path, /*IsText=*/true);
  if (!buffer)
    return llvm::createStringError(
        path + ": cannot read the file: " + buffer.getError().message());
  if (llvm::sys::path::extension(path) == ".mlir")
    return loadMLIR((*buffer)->getBuffer(), path);
  return loadString((*buffer)->getBuffer(), path);
}

llvm::Error Program::loadString(llvm::StringRef source,
                                llvm::StringRef bufferName) {
  return impl->load({Source::Kind::Sim, bufferName.str(), source.str()});
}

llvm::Error Program::loadMLIR(llvm::StringRef text,
                              llvm::StringRef bufferName) {
  return impl->load({Source::Kind::MLIR, bufferName.str(), text.str()});
}

llvm::Expected<std::string> Program::emit(Stage stage) {
  std::string text;
  llvm::raw_string_ostream os(text);
  switch (stage) {
  case Stage::Simit:
    if (llvm::Error err = impl->requireModule())
      return std::move(err);
    impl->module->print(os);
    return text;
  case Stage::Loops: {
    // Printed only here: every compile would otherwise pay for it.
    mlir::OwningOpRef<mlir::ModuleOp> lowered;
    LoweringResult result;
    if (llvm::Error err =
            impl->lowerClone(lowered, result, /*keepLoopsStage=*/true))
      return std::move(err);
    if (result.loopsText.empty())
      return llvm::createStringError(
          "the program has no loops stage: it was not lowered by "
          "convert-simit-to-loops");
    return result.loopsText;
  }
  case Stage::LLVM:
    if (llvm::Error err = impl->lower())
      return std::move(err);
    impl->llvmModule->print(os);
    return text;
  }
  llvm_unreachable("unknown stage");
}

llvm::Expected<std::vector<std::string>> Program::exportedFunctions() {
  std::vector<std::string> names;
  auto addNames = [&](const auto &map) {
    for (const auto &entry : map)
      names.push_back(entry.getKey().str());
  };
  if (impl->compiled) {
    addNames(impl->compiled->functions);
  } else if (impl->cachedCode) {
    addNames(impl->cachedCode->functions);
  } else {
    if (llvm::Error err = impl->lower())
      return std::move(err);
    addNames(impl->lowering.signatures);
  }
  llvm::sort(names);
  return names;
}

const CompileTimes &Program::compileTimes() const { return impl->times; }

llvm::Expected<DeclaredFields> Program::externSetFields() {
  return impl->externSets<std::vector<DeclaredField>>(
      &ObjectCode::externSetFields, fieldDeclarations);
}

llvm::Expected<ObjectCode::SetNames> Program::externSetEndpoints() {
  return impl->externSets<std::vector<std::string>>(
      &ObjectCode::externSetEndpoints, endpointNames);
}

llvm::Expected<std::vector<std::string>> Program::externTensorNames() {
  if (impl->cachedCode)
    return impl->cachedCode->externTensors;
  if (llvm::Error err = impl->requireModule())
    return std::move(err);
  return impl->externTensorsOfModule();
}

SolveSession &Program::solver() { return *impl->solver; }

llvm::Expected<Function> Program::compile(llvm::StringRef name) {
  if (llvm::Error err = impl->compile())
    return std::move(err);
  auto it = impl->compiled->functions.find(name);
  if (it == impl->compiled->functions.end()) {
    std::vector<std::string> names;
    for (const auto &entry : impl->compiled->functions)
      names.push_back(entry.getKey().str());
    llvm::sort(names);
    return llvm::createStringError(
        "unknown function '" + name + "' (exported functions: " +
        (names.empty() ? std::string("none") : llvm::join(names, ", ")) + ")");
  }
  return Function(impl->compiled, it->second.signature);
}
