//===--- Program.cpp - Loading and compiling Simit programs ---------------===//

#include "simit/Engine/Program.h"

#include "CompiledModule.h"
#include "Lowering.h"
#include "SimImport.h"

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Frontend/IRGen.h"

#include "mlir/IR/BuiltinOps.h"
#include "mlir/IR/Diagnostics.h"
#include "mlir/IR/MLIRContext.h"
#include "mlir/IR/OwningOpRef.h"
#include "mlir/Parser/Parser.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/SourceMgr.h"

using namespace simit;

struct Program::Impl {
  ProgramOptions options;
  mlir::MLIRContext context;
  /// The program in the simit dialect (or loops), as loaded.
  mlir::OwningOpRef<mlir::ModuleOp> module;
  /// The lowered module and what lowering recorded, once lowered.
  mlir::OwningOpRef<mlir::ModuleOp> llvmModule;
  LoweringResult lowering;
  std::shared_ptr<CompiledModule> compiled;

  explicit Impl(ProgramOptions options)
      : options(options), context(mlir::MLIRContext::Threading::DISABLED) {
    mlir::DialectRegistry registry;
    registerEngineDialects(registry);
    context.appendDialectRegistry(registry);
    context.loadAllAvailableDialects();
    // Diagnostics name the .sim position; the op dump would bury it.
    context.printOpOnDiagnostic(false);
    frontend::loadIRGenDialects(context);
  }

  void reset(mlir::OwningOpRef<mlir::ModuleOp> newModule) {
    module = std::move(newModule);
    llvmModule = nullptr;
    lowering = LoweringResult();
    compiled = nullptr;
  }

  llvm::Error requireModule() const {
    if (!module)
      return llvm::createStringError("no program is loaded");
    return llvm::Error::success();
  }

  llvm::Error lower() {
    if (llvmModule)
      return llvm::Error::success();
    if (llvm::Error err = requireModule())
      return err;
    mlir::OwningOpRef<mlir::ModuleOp> clone = module->clone();
    LoweringResult result;
    mlir::simit::SimitCpuPipelineOptions pipelineOptions;
    pipelineOptions.timePhases = options.timePhases;
    pipelineOptions.checkNumerics = options.checkNumerics;
    if (llvm::Error err = lowerToLLVM(*clone, result, pipelineOptions))
      return err;
    llvmModule = std::move(clone);
    lowering = std::move(result);
    return llvm::Error::success();
  }

  llvm::Error compile() {
    if (compiled)
      return llvm::Error::success();
    if (llvm::Error err = lower())
      return err;
    auto result = compileModule(*llvmModule, lowering.signatures);
    if (!result)
      return result.takeError();
    compiled = std::move(*result);
    return llvm::Error::success();
  }
};

Program::Program(ProgramOptions options)
    : impl(std::make_unique<Impl>(options)) {}
Program::Program(Program &&) = default;
Program &Program::operator=(Program &&) = default;
Program::~Program() = default;

llvm::Error Program::loadFile(llvm::StringRef path) {
  auto buffer = llvm::MemoryBuffer::getFile(path, /*IsText=*/true);
  if (!buffer)
    return llvm::createStringError(path + ": cannot read the file: " +
                                   buffer.getError().message());
  if (llvm::sys::path::extension(path) == ".mlir")
    return loadMLIR((*buffer)->getBuffer(), path);
  return loadString((*buffer)->getBuffer(), path);
}

llvm::Error Program::loadString(llvm::StringRef source,
                                llvm::StringRef bufferName) {
  auto module = importSimit(source, bufferName, impl->context, impl->options);
  if (!module)
    return module.takeError();
  impl->reset(std::move(*module));
  return llvm::Error::success();
}

llvm::Error Program::loadMLIR(llvm::StringRef text,
                              llvm::StringRef bufferName) {
  llvm::SourceMgr sourceMgr;
  sourceMgr.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, bufferName), llvm::SMLoc());
  std::string diagnostics;
  llvm::raw_string_ostream os(diagnostics);
  mlir::SourceMgrDiagnosticHandler handler(sourceMgr, &impl->context, os);
  mlir::OwningOpRef<mlir::ModuleOp> module =
      mlir::parseSourceFile<mlir::ModuleOp>(sourceMgr, &impl->context);
  if (!module)
    return llvm::createStringError(diagnostics);
  impl->reset(std::move(module));
  return llvm::Error::success();
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
  case Stage::Loops:
    if (llvm::Error err = impl->lower())
      return std::move(err);
    if (impl->lowering.loopsText.empty())
      return llvm::createStringError(
          "the program has no loops stage: it was not lowered by "
          "convert-simit-to-loops");
    return impl->lowering.loopsText;
  case Stage::LLVM:
    if (llvm::Error err = impl->lower())
      return std::move(err);
    impl->llvmModule->print(os);
    return text;
  }
  llvm_unreachable("unknown stage");
}

llvm::Expected<std::vector<std::string>> Program::exportedFunctions() {
  if (llvm::Error err = impl->lower())
    return std::move(err);
  std::vector<std::string> names;
  for (const auto &entry : impl->lowering.signatures)
    names.push_back(entry.getKey().str());
  llvm::sort(names);
  return names;
}

llvm::Expected<std::map<std::string, std::vector<std::string>>>
Program::externSetFields() {
  if (llvm::Error err = impl->requireModule())
    return std::move(err);
  std::map<std::string, std::vector<std::string>> fields;
  for (auto global : impl->module->getOps<mlir::simit::ExternOp>()) {
    auto set = llvm::dyn_cast<mlir::simit::SetType>(global.getType());
    if (!set)
      continue;
    std::vector<std::string> &names = fields[set.getName().str()];
    for (mlir::StringAttr name : set.getElement().getFieldNames())
      names.push_back(name.str());
  }
  return fields;
}

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
        (names.empty() ? std::string("none") : llvm::join(names, ", ")) +
        ")");
  }
  return Function(impl->compiled, it->second.signature);
}
