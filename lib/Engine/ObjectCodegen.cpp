//===--- ObjectCodegen.cpp - LLVM IR to objects, on several cores ---------===//

#include "ObjectCodegen.h"

#include "Stopwatch.h"

#include "mlir/ExecutionEngine/OptUtils.h"

#include "llvm/Bitcode/BitcodeReader.h"
#include "llvm/Bitcode/BitcodeWriter.h"
#include "llvm/IR/LegacyPassManager.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Threading.h"
#include "llvm/Target/TargetMachine.h"
#include "llvm/Transforms/Utils/Cloning.h"

#include <algorithm>
#include <thread>

using namespace simit;

namespace {
/// A partition smaller than this costs more in threads and the bitcode
/// round trip than it saves (springs.sim's module holds about 6,000
/// instructions, neo-hookean.sim's about 16,000).
constexpr size_t kInstructionsPerPartition = 2000;
constexpr unsigned kMaxPartitions = 4;

/// One partition's module, in a context of its own once it is on its
/// thread.
struct Partition {
  std::string bitcode;
  std::unique_ptr<llvm::LLVMContext> context;
  std::unique_ptr<llvm::Module> module;
  std::unique_ptr<llvm::TargetMachine> machine;
  std::string object;
  std::string error;
};

/// Runs `work(i)` for every i < n, each on a thread of its own (the
/// calling thread takes i = 0).
void runEach(size_t n, llvm::function_ref<void(size_t)> work) {
  std::vector<std::thread> threads;
  for (size_t i = 1; i < n; ++i)
    threads.emplace_back([&work, i] { work(i); });
  work(0);
  for (std::thread &thread : threads)
    thread.join();
}

std::string optimize(llvm::Module &module, llvm::TargetMachine &machine) {
  auto transform = mlir::makeOptimizingTransformer(
      /*optLevel=*/3, /*sizeLevel=*/0, &machine);
  if (llvm::Error err = transform(&module))
    return llvm::toString(std::move(err));
  return {};
}

std::string emitObject(llvm::Module &module, llvm::TargetMachine &machine,
                       std::string &object) {
  llvm::SmallVector<char, 0> bytes;
  llvm::raw_svector_ostream os(bytes);
  llvm::legacy::PassManager codegen;
  if (machine.addPassesToEmitFile(codegen, os, nullptr,
                                  llvm::CodeGenFileType::ObjectFile))
    return "the host target cannot emit objects";
  codegen.run(module);
  object.assign(bytes.begin(), bytes.end());
  return {};
}

/// Whether every partition gets its own copy of `global`: local constants
/// (strings, tables), which then stay visible to the optimiser.
bool copiedIntoEachPartition(const llvm::GlobalValue &global) {
  auto *variable = llvm::dyn_cast<llvm::GlobalVariable>(&global);
  return variable && variable->hasLocalLinkage() && variable->isConstant();
}

/// Makes the module's other local symbols external and hidden (named, if
/// they were not), so that a partition can refer to one another defines.
void externalizeLocals(llvm::Module &module) {
  for (llvm::GlobalValue &global : module.global_values()) {
    if (!global.hasLocalLinkage() || copiedIntoEachPartition(global))
      continue;
    global.setLinkage(llvm::GlobalValue::ExternalLinkage);
    global.setVisibility(llvm::GlobalValue::HiddenVisibility);
    if (!global.hasName())
      global.setName("simit.local");
  }
}

/// The partition of every function definition: the largest first, each to
/// the partition with the fewest instructions so far.
llvm::DenseMap<const llvm::Function *, unsigned>
assignFunctions(llvm::Module &module, unsigned partitions) {
  std::vector<std::pair<size_t, const llvm::Function *>> bySize;
  for (const llvm::Function &function : module)
    if (!function.isDeclaration())
      bySize.push_back({function.getInstructionCount(), &function});
  llvm::stable_sort(
      bySize, [](const auto &a, const auto &b) { return a.first > b.first; });
  std::vector<size_t> load(partitions, 0);
  llvm::DenseMap<const llvm::Function *, unsigned> assigned;
  for (const auto &[size, function] : bySize) {
    unsigned lightest = static_cast<unsigned>(
        std::min_element(load.begin(), load.end()) - load.begin());
    assigned[function] = lightest;
    load[lightest] += size;
  }
  return assigned;
}
} // namespace

llvm::Expected<std::vector<std::string>>
simit::compileToObjects(llvm::Module &module,
                        const llvm::orc::JITTargetMachineBuilder &target,
                        unsigned partitions, CompileTimes &times) {
  if (partitions == 0) {
    unsigned cores = llvm::hardware_concurrency().compute_thread_count();
    partitions = static_cast<unsigned>(std::clamp<size_t>(
        module.getInstructionCount() / kInstructionsPerPartition, 1,
        std::clamp(cores, 1u, kMaxPartitions)));
  }
  // Appending globals (llvm.used and the like) belong to one module each.
  if (llvm::any_of(module.globals(), [](const llvm::GlobalVariable &global) {
        return global.hasAppendingLinkage();
      }))
    partitions = 1;
  size_t definitions = llvm::count_if(
      module, [](const llvm::Function &f) { return !f.isDeclaration(); });
  partitions = static_cast<unsigned>(
      std::clamp<size_t>(partitions, 1, std::max<size_t>(definitions, 1)));

  Stopwatch stopwatch;
  std::vector<Partition> parts(partitions);
  if (partitions == 1) {
    // Whole, in the caller's context.
    auto machine =
        llvm::orc::JITTargetMachineBuilder(target).createTargetMachine();
    if (!machine)
      return machine.takeError();
    parts[0].machine = std::move(*machine);
    parts[0].error = optimize(module, *parts[0].machine);
  } else {
    externalizeLocals(module);
    llvm::DenseMap<const llvm::Function *, unsigned> assigned =
        assignFunctions(module, partitions);
    for (unsigned p = 0; p < partitions; ++p) {
      llvm::ValueToValueMapTy map;
      std::unique_ptr<llvm::Module> part =
          llvm::CloneModule(module, map, [&](const llvm::GlobalValue *global) {
            if (auto *function = llvm::dyn_cast<llvm::Function>(global))
              return assigned.lookup(function) == p;
            return p == 0 || copiedIntoEachPartition(*global);
          });
      llvm::raw_string_ostream os(parts[p].bitcode);
      llvm::WriteBitcodeToFile(*part, os);
    }
    runEach(partitions, [&](size_t p) {
      Partition &part = parts[p];
      part.context = std::make_unique<llvm::LLVMContext>();
      auto parsed = llvm::parseBitcodeFile(
          llvm::MemoryBufferRef(part.bitcode, "partition"), *part.context);
      if (!parsed) {
        part.error = llvm::toString(parsed.takeError());
        return;
      }
      part.module = std::move(*parsed);
      auto machine =
          llvm::orc::JITTargetMachineBuilder(target).createTargetMachine();
      if (!machine) {
        part.error = llvm::toString(machine.takeError());
        return;
      }
      part.machine = std::move(*machine);
      part.error = optimize(*part.module, *part.machine);
    });
  }
  auto firstError = [&]() -> llvm::Error {
    for (const Partition &part : parts)
      if (!part.error.empty())
        return llvm::createStringError(part.error);
    return llvm::Error::success();
  };
  if (llvm::Error err = firstError())
    return std::move(err);
  times.optimizationMs += stopwatch.milliseconds();

  stopwatch.restart();
  runEach(partitions, [&](size_t p) {
    Partition &part = parts[p];
    part.error = emitObject(part.module ? *part.module : module, *part.machine,
                            part.object);
  });
  if (llvm::Error err = firstError())
    return std::move(err);
  times.codegenMs += stopwatch.milliseconds();

  std::vector<std::string> objects;
  for (Partition &part : parts)
    objects.push_back(std::move(part.object));
  return objects;
}
