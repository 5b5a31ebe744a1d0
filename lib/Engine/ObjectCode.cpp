//===--- ObjectCode.cpp - Loading compiled code into a JIT ----------------===//

#include "ObjectCode.h"

#include "PerfMap.h"
#include "RuntimeSymbols.h"
#include "Threads.h"

#include "simit/ABI/RuntimeFunctions.h"

#include "llvm/ADT/StringSet.h"
#include "llvm/ExecutionEngine/Orc/ExecutionUtils.h"
#include "llvm/ExecutionEngine/Orc/LLJIT.h"
#include "llvm/IR/DataLayout.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/DynamicLibrary.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/TargetSelect.h"

#include <mutex>

using namespace simit;

llvm::Expected<llvm::orc::JITTargetMachineBuilder> simit::hostTarget() {
  static std::once_flag initialized;
  std::call_once(initialized, [] {
    llvm::InitializeNativeTarget();
    llvm::InitializeNativeTargetAsmPrinter();
    // The second instruction scheduling, after register allocation, took
    // a quarter of codegen (about 100 of the Neo-Hookean program's 390 ms)
    // and bought no run time on an out-of-order core (fem-dragon frames
    // 28.0 ms without it, 28.9 with it, medians of 5 alternated runs). It
    // is LLVM's process-wide option, which the pass obeys when it has a
    // position on a command line: one given on the real one stays.
    if (llvm::cl::Option *postRA =
            llvm::cl::getRegisteredOptions().lookup("post-RA-scheduler"))
      if (postRA->getNumOccurrences() == 0)
        postRA->addOccurrence(1, "post-RA-scheduler", "false");
  });
  auto target = llvm::orc::JITTargetMachineBuilder::detectHost();
  if (!target)
    return target.takeError();
  target->setCodeGenOptLevel(llvm::CodeGenOptLevel::Aggressive);
  target->setCodeModel(llvm::CodeModel::Small);
  target->setRelocationModel(llvm::Reloc::PIC_);
  return target;
}

unsigned simit::hostVectorBits() {
  auto target = hostTarget();
  if (!target) {
    llvm::consumeError(target.takeError());
    return 128;
  }
  const llvm::SubtargetFeatures &features = target->getFeatures();
  auto has = [&](llvm::StringRef feature) {
    return llvm::is_contained(features.getFeatures(), "+" + feature.str());
  };
  if (has("avx512f"))
    return 512;
  if (has("avx"))
    return 256;
  return 128;
}

/// Names the symbols the objects need that none of them, the runtime, the
/// OpenMP runtime nor the process (its libraries, and the host libraries
/// loaded for `extern func`s) defines, before the JIT would fail on them
/// less clearly. A host function without floats is called by its name;
/// the original Simit runtime's later versions prefix every host symbol
/// with the precision ('d' or 's', both the same function then): such a
/// definition serves too, added to `runtime` under the name.
static llvm::Error checkExternalSymbols(llvm::ArrayRef<std::string> objects,
                                        llvm::orc::SymbolMap &runtime,
                                        llvm::sys::DynamicLibrary &openMP,
                                        llvm::orc::MangleAndInterner &mangle) {
  std::vector<std::unique_ptr<llvm::object::ObjectFile>> files;
  llvm::StringSet<> defined;
  for (const std::string &object : objects) {
    auto file = llvm::object::ObjectFile::createObjectFile(
        llvm::MemoryBufferRef(object, "simit-module.o"));
    if (!file)
      return file.takeError();
    for (const llvm::object::SymbolRef &symbol : (*file)->symbols()) {
      auto flags = symbol.getFlags();
      auto name = symbol.getName();
      if (flags && !(*flags & llvm::object::SymbolRef::SF_Undefined) && name)
        defined.insert(*name);
    }
    files.push_back(std::move(*file));
  }
  std::string missing;
  for (const auto &file : files)
    for (const llvm::object::SymbolRef &symbol : file->symbols()) {
      auto flags = symbol.getFlags();
      if (!flags || !(*flags & llvm::object::SymbolRef::SF_Undefined))
        continue;
      auto name = symbol.getName();
      if (!name || name->empty() || defined.contains(*name) ||
          runtime.count(mangle(*name)) ||
          openMP.getAddressOfSymbol(name->str().c_str()) ||
          llvm::sys::DynamicLibrary::SearchForAddressOfSymbol(name->str()))
        continue;
      void *prefixed = nullptr;
      for (const char *precision : {"d", "s"})
        if (!prefixed)
          prefixed = llvm::sys::DynamicLibrary::SearchForAddressOfSymbol(
              precision + name->str());
      if (prefixed) {
        runtime[mangle(*name)] = {llvm::orc::ExecutorAddr::fromPtr(prefixed),
                                  llvm::JITSymbolFlags::Exported};
        continue;
      }
      missing += (missing.empty() ? "" : ", ") + name->str();
    }
  if (missing.empty())
    return llvm::Error::success();
  return llvm::createStringError(
      "host functions not found: " + missing +
      " (the C functions of the program's extern funcs; give the shared "
      "library that defines them: simit-run --extern-lib, the scene's "
      "\"libraries\", ProgramOptions::hostLibraries)");
}

llvm::Expected<std::shared_ptr<CompiledModule>>
simit::loadObjectCode(const ObjectCode &code) {
  auto target = hostTarget();
  if (!target)
    return target.takeError();
  auto dataLayout = llvm::DataLayout::parse(code.dataLayout);
  if (!dataLayout)
    return dataLayout.takeError();
  // No platform: the object has no initializers to run (Lowering.cpp
  // rejects modules with global constructors), and setting one up costs
  // more than the rest of the load.
  auto jit = llvm::orc::LLJITBuilder()
                 .setJITTargetMachineBuilder(std::move(*target))
                 .setDataLayout(std::move(*dataLayout))
                 .setPlatformSetUp(llvm::orc::setUpInactivePlatform)
                 .create();
  if (!jit)
    return jit.takeError();
  addPerfMapWhenAsked(**jit);
  llvm::orc::MangleAndInterner mangle((*jit)->getExecutionSession(),
                                      (*jit)->getDataLayout());
  // OpenMP calls (__kmpc_*) go to the runtime the engine is linked with,
  // looked up in its own file: a process that loaded the engine locally
  // (Python's extension modules) does not export its symbols.
  std::string openMP = openMPLibraryPath();
  std::string why;
  llvm::sys::DynamicLibrary openMPLibrary =
      openMP.empty() ? llvm::sys::DynamicLibrary()
                     : llvm::sys::DynamicLibrary::getLibrary(openMP.c_str(),
                                                             &why);
  if (!openMPLibrary.isValid())
    return llvm::createStringError("the OpenMP runtime cannot be found" +
                                   (why.empty() ? "" : ": " + why));
  llvm::orc::SymbolMap runtime = runtimeSymbolMap(mangle);
  if (llvm::Error err =
          checkExternalSymbols(code.objects, runtime, openMPLibrary, mangle))
    return err;
  if (llvm::Error err = (*jit)->getMainJITDylib().define(
          llvm::orc::absoluteSymbols(std::move(runtime))))
    return std::move(err);
  auto openMPSymbols = llvm::orc::DynamicLibrarySearchGenerator::Load(
      openMP.c_str(), (*jit)->getDataLayout().getGlobalPrefix());
  if (!openMPSymbols)
    return openMPSymbols.takeError();
  (*jit)->getMainJITDylib().addGenerator(std::move(*openMPSymbols));
  for (const std::string &object : code.objects)
    if (llvm::Error err = (*jit)->addObjectFile(
            llvm::MemoryBuffer::getMemBufferCopy(object, "simit-module.o")))
      return std::move(err);

  auto compiled = std::make_shared<CompiledModule>();
  compiled->functions = code.functions;
  for (auto &entry : compiled->functions) {
    auto address = (*jit)->lookup(("_mlir_" + entry.getKey()).str());
    if (!address)
      return address.takeError();
    entry.getValue().entry = address->toPtr<void (*)(void **)>();
  }
  auto init = (*jit)->lookup("_simit_module_init");
  if (!init)
    return init.takeError();
  auto fini = (*jit)->lookup("_simit_module_fini");
  if (!fini)
    return fini.takeError();
  compiled->jit = std::move(*jit);
  // GPU code loads its kernels here; a failure (no device, PTX the driver
  // cannot compile) ends the load, not the process.
  if (llvm::Error err =
          runGuarded(init->toPtr<void (*)(void **)>(), nullptr, nullptr))
    return llvm::createStringError("loading the compiled module failed: " +
                                   llvm::toString(std::move(err)));
  compiled->finalize = fini->toPtr<void (*)(void **)>();
  return compiled;
}

CompiledModule::~CompiledModule() {
  // What fails here (a device already torn down) has no one to tell.
  if (finalize)
    llvm::consumeError(runGuarded(finalize, nullptr, nullptr));
}
