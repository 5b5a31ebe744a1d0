//===--- GPUTargetTest.cpp - What GPU code asks of the runtime ------------===//
//
// Needs no GPU. Programs compiled for Target::GPU become objects whose
// undefined symbols must all be defined by the engine's runtime (the mgpu*
// functions of lib/ABI/GPUFunctions.cpp and the simit_rt_* ones) or by the
// process (libc): a lowering that starts asking for a runtime function the
// engine lacks fails here, not on a GPU machine at link time. The kernels'
// PTX must be in the object, and the kernels loaded by its initializer.
//
//===----------------------------------------------------------------------===//

#include "Lowering.h"
#include "ObjectCode.h"
#include "RuntimeSymbols.h"
#include "SimImport.h"

#include "simit/Engine/Program.h"
#include "simit/Frontend/IRGen.h"

#include "gtest/gtest.h"

#include "mlir/IR/MLIRContext.h"

#include "llvm/ADT/StringSet.h"
#include "llvm/ExecutionEngine/Orc/LLJIT.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/Support/DynamicLibrary.h"
#include "llvm/Support/MemoryBuffer.h"

using namespace simit;

namespace {
struct CompiledForGPU {
  ObjectCode code;
  /// The symbols the objects need and none of them defines.
  std::vector<std::string> undefined;
};

CompiledForGPU compileForGPU(const std::string &relativePath,
                             FloatPrecision precision) {
  std::string path = SIMIT_SOURCE_DIR "/" + relativePath;
  auto buffer = llvm::MemoryBuffer::getFile(path);
  EXPECT_TRUE(bool(buffer)) << path;
  mlir::MLIRContext context(mlir::MLIRContext::Threading::DISABLED);
  mlir::DialectRegistry registry;
  registerEngineDialects(registry);
  context.appendDialectRegistry(registry);
  context.loadAllAvailableDialects();
  frontend::loadIRGenDialects(context);
  ProgramOptions options;
  options.precision = precision;
  options.target = Target::GPU;
  auto module = importSimit((*buffer)->getBuffer(), path, context, options);
  EXPECT_TRUE(bool(module)) << (module ? "" : toString(module.takeError()));
  CompiledForGPU result;
  if (!module)
    return result;
  LoweringResult lowering;
  if (llvm::Error err =
          lowerToLLVM(**module, lowering, {}, GPUKernelTarget()))
    ADD_FAILURE() << toString(std::move(err));
  CompileTimes times;
  auto code = compileToObject(**module, lowering.signatures, times);
  if (!code) {
    ADD_FAILURE() << toString(code.takeError());
    return result;
  }
  result.code = std::move(*code);
  llvm::StringSet<> defined;
  std::vector<std::string> needed;
  for (const std::string &object : result.code.objects) {
    auto file = llvm::object::ObjectFile::createObjectFile(
        llvm::MemoryBufferRef(object, "gpu.o"));
    if (!file) {
      ADD_FAILURE() << toString(file.takeError());
      return result;
    }
    for (const llvm::object::SymbolRef &symbol : (*file)->symbols()) {
      auto flags = symbol.getFlags();
      auto name = symbol.getName();
      if (!flags || !name || name->empty())
        continue;
      if (*flags & llvm::object::SymbolRef::SF_Undefined)
        needed.push_back(name->str());
      else
        defined.insert(*name);
    }
  }
  for (const std::string &name : needed)
    if (!defined.contains(name))
      result.undefined.push_back(name);
  return result;
}

/// The names the engine's runtime defines.
llvm::StringSet<> runtimeNames() {
  llvm::StringSet<> names;
  addGPURuntimeSymbols([&](llvm::StringRef name, void *address) {
    EXPECT_NE(address, nullptr) << name.str();
    names.insert(name);
  });
  auto jit = llvm::orc::LLJITBuilder()
                 .setPlatformSetUp(llvm::orc::setUpInactivePlatform)
                 .create();
  EXPECT_TRUE(bool(jit));
  if (!jit)
    return names;
  llvm::orc::MangleAndInterner mangle((*jit)->getExecutionSession(),
                                      (*jit)->getDataLayout());
  for (const auto &entry : runtimeSymbolMap(mangle))
    names.insert(*entry.first);
  return names;
}

void expectOnlyRuntimeSymbols(const std::string &path,
                              FloatPrecision precision) {
  SCOPED_TRACE(path);
  CompiledForGPU compiled = compileForGPU(path, precision);
  llvm::StringSet<> runtime = runtimeNames();
  llvm::StringSet<> mgpu;
  for (const std::string &name : compiled.undefined) {
    if (llvm::StringRef(name).starts_with("mgpu"))
      mgpu.insert(name);
    bool defined =
        runtime.contains(name) ||
        llvm::sys::DynamicLibrary::SearchForAddressOfSymbol(name) != nullptr;
    EXPECT_TRUE(defined) << "the GPU code needs " << name
                         << ", which neither the runtime nor the process "
                            "defines";
  }
  // The set loops became launches of kernels loaded from PTX.
  for (const char *name :
       {"mgpuModuleLoadJIT", "mgpuModuleGetFunction", "mgpuLaunchKernel",
        "mgpuMemAlloc", "mgpuMemcpy", "mgpuStreamSynchronize"})
    EXPECT_TRUE(mgpu.contains(name)) << name << " is not called";
  EXPECT_TRUE(llvm::any_of(compiled.code.objects,
                           [](const std::string &object) {
                             return object.find(".visible .entry") !=
                                    std::string::npos;
                           }))
      << "no PTX kernel in the objects";
}

TEST(GPUTarget, SpringsNeedOnlyRuntimeSymbols) {
  expectOnlyRuntimeSymbols("examples/springs/springs.sim",
                           FloatPrecision::Double);
}

TEST(GPUTarget, NeoHookeanFEMNeedsOnlyRuntimeSymbols) {
  expectOnlyRuntimeSymbols("examples/fem/neo-hookean.sim",
                           FloatPrecision::Double);
}

TEST(GPUTarget, Float32NeedsOnlyRuntimeSymbols) {
  expectOnlyRuntimeSymbols("examples/springs/springs.sim",
                           FloatPrecision::Single);
}

TEST(GPUTarget, KernelTargetFollowsTheComputeCapability) {
  EXPECT_EQ(gpuKernelTargetFor(90).chip, "sm_90");
  EXPECT_EQ(gpuKernelTargetFor(90).features, "+ptx80");
  EXPECT_EQ(gpuKernelTargetFor(80).chip, "sm_80");
  EXPECT_EQ(gpuKernelTargetFor(80).features, "+ptx80");
  EXPECT_EQ(gpuKernelTargetFor(100).features, "+ptx86");
  EXPECT_EQ(gpuKernelTargetFor(120).features, "+ptx87");
}
} // namespace
