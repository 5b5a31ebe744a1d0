//===--- GPUFunctions.cpp - The mgpu* functions of GPU code ---------------===//
//
// What the host code of simit-gpu-pipeline calls: MLIR's gpu-to-llvm
// lowering and gpu.binary's translation emit calls of mgpu* functions
// (module load, kernel launch, streams, allocation, copies). They are
// implemented here over the CUDA driver, loaded at run time
// (simit/Runtime/CudaDriver.h). A failing driver call ends the run of the
// exported function through simit_rt_fail, with a message that names the
// call, the CUDA error, the kernel and the Simit statement that launched it.
//
//===----------------------------------------------------------------------===//

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/CudaDriver.h"

#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/Support/xxhash.h"

#include <cstring>
#include <map>
#include <mutex>

using namespace simit;
using namespace simit::cuda;

namespace {
/// The message of the failure in progress: built here, not in a local of
/// the failing function, because simit_rt_fail does not return to destroy
/// it.
thread_local std::string gpuFailure;
/// The Simit statement of the next launch (simit_rt_gpu_statement).
thread_local const char *currentStatement = nullptr;

[[noreturn]] void failWith(const llvm::Twine &message) {
  gpuFailure = message.str();
  simit_rt_fail(gpuFailure.c_str());
}

/// The process's device with its context current on this thread.
Device &device() {
  thread_local Device *current = nullptr;
  if (current)
    return *current;
  llvm::Expected<Device &> opened = defaultDevice();
  if (!opened) {
    gpuFailure = "no CUDA device: " + llvm::toString(opened.takeError());
    simit_rt_fail(gpuFailure.c_str());
  }
  if (llvm::Error err = opened->makeCurrent()) {
    gpuFailure = llvm::toString(std::move(err));
    simit_rt_fail(gpuFailure.c_str());
  }
  current = &*opened;
  return *current;
}

/// What the process knows of its kernels and streams, for messages.
struct Registry {
  std::mutex mutex;
  /// Kernel names and modules by function handle (mgpuModuleGetFunction).
  llvm::DenseMap<CUfunction, std::pair<CUmodule, std::string>> kernels;
  /// The kernel and statement of the last launch on each stream: an error
  /// of a kernel shows at the next synchronisation.
  llvm::DenseMap<CUstream, std::pair<CUfunction, const char *>> lastLaunch;
  /// Loaded modules by the hash of their PTX and JIT level, and how many
  /// loads share each: every Program compiled from one source runs the
  /// same kernels, which the driver then JIT-compiles once.
  struct LoadedModule {
    CUmodule module;
    int users;
  };
  std::map<std::pair<uint64_t, int>, LoadedModule> modules;
};

Registry &registry() {
  static Registry *instance = new Registry();
  return *instance;
}

/// " in kernel K (launched by S)", for the kernel `function` and the
/// statement `where`. (The strings of a failing call's message are not
/// freed: simit_rt_fail leaves their frames without unwinding; a failure
/// ends the run, so this costs bytes once per run, not per call.)
std::string launchContext(CUfunction function, const char *where) {
  std::string context;
  {
    std::lock_guard<std::mutex> lock(registry().mutex);
    auto it = registry().kernels.find(function);
    if (it != registry().kernels.end())
      context = " in kernel " + it->second.second;
  }
  if (where && *where)
    context += std::string(" (launched by ") + where + ")";
  return context;
}

/// Ends the run when `result` is an error of `call`.
void check(CUresult result, const char *call, const llvm::Twine &context = "") {
  if (result == CUDA_SUCCESS)
    return;
  Device &gpu = device();
  failWith(llvm::Twine("CUDA error: ") + call + " failed" + context + ": " +
           gpu.driver().describe(result));
}

/// Ends the run when `result` is an error of a stream operation: a kernel's
/// failure (an assertion, an illegal address) is reported by whatever
/// waits on its stream next, so the message names the stream's last launch.
void checkStream(CUresult result, const char *call, CUstream stream) {
  if (result == CUDA_SUCCESS)
    return;
  std::pair<CUfunction, const char *> last{nullptr, nullptr};
  {
    std::lock_guard<std::mutex> lock(registry().mutex);
    auto it = registry().lastLaunch.find(stream);
    if (it != registry().lastLaunch.end())
      last = it->second;
  }
  std::string context =
      last.first ? " after the launch" + launchContext(last.first, last.second)
                 : "";
  check(result, call, context);
}
} // namespace

extern "C" {

/// Names the Simit statement of the launches that follow, for messages.
void simit_rt_gpu_statement(const char *where) { currentStatement = where; }

/// Loads a module of PTX text (NUL-terminated), which the driver
/// JIT-compiles for the device at `optLevel`.
void *mgpuModuleLoadJIT(void *ptx, int optLevel) {
  Device &gpu = device();
  const char *text = static_cast<const char *>(ptx);
  std::pair<uint64_t, int> key{
      llvm::xxh3_64bits(llvm::StringRef(text, std::strlen(text))), optLevel};
  Registry &reg = registry();
  {
    std::lock_guard<std::mutex> lock(reg.mutex);
    auto it = reg.modules.find(key);
    if (it != reg.modules.end()) {
      ++it->second.users;
      return it->second.module;
    }
  }
  static thread_local char errorLog[8192];
  errorLog[0] = '\0';
  int options[] = {CU_JIT_ERROR_LOG_BUFFER, CU_JIT_ERROR_LOG_BUFFER_SIZE_BYTES,
                   CU_JIT_OPTIMIZATION_LEVEL};
  void *values[] = {errorLog, reinterpret_cast<void *>(sizeof(errorLog) - 1),
                    reinterpret_cast<void *>(static_cast<intptr_t>(optLevel))};
  CUmodule module = nullptr;
  CUresult result =
      gpu.driver().cuModuleLoadDataEx(&module, text, 3, options, values);
  if (result != CUDA_SUCCESS)
    failWith(llvm::Twine("CUDA error: cuModuleLoadDataEx failed to "
                         "JIT-compile the kernels' PTX: ") +
             gpu.driver().describe(result) +
             (errorLog[0] ? llvm::Twine("\n") + errorLog : llvm::Twine("")));
  std::lock_guard<std::mutex> lock(reg.mutex);
  reg.modules[key] = {module, 1};
  return module;
}

void mgpuModuleUnload(void *module) {
  Device &gpu = device();
  Registry &reg = registry();
  CUmodule unload = nullptr;
  {
    std::lock_guard<std::mutex> lock(reg.mutex);
    for (auto it = reg.modules.begin(); it != reg.modules.end(); ++it) {
      if (it->second.module != module)
        continue;
      if (--it->second.users == 0) {
        unload = it->second.module;
        reg.modules.erase(it);
      }
      break;
    }
    // Handles of the unloaded module may come back from later loads.
    if (unload) {
      llvm::SmallVector<CUfunction> stale;
      for (const auto &entry : reg.kernels)
        if (entry.second.first == unload)
          stale.push_back(entry.first);
      for (CUfunction function : stale)
        reg.kernels.erase(function);
    }
  }
  if (unload)
    check(gpu.driver().cuModuleUnload(unload), "cuModuleUnload");
}

void *mgpuModuleGetFunction(void *module, const char *name) {
  Device &gpu = device();
  CUfunction function = nullptr;
  check(gpu.driver().cuModuleGetFunction(
            &function, static_cast<CUmodule>(module), name),
        "cuModuleGetFunction", llvm::Twine(" for kernel ") + name);
  std::lock_guard<std::mutex> lock(registry().mutex);
  registry().kernels.try_emplace(
      function, std::make_pair(static_cast<CUmodule>(module), name));
  return function;
}

void mgpuLaunchKernel(void *function, intptr_t gridX, intptr_t gridY,
                      intptr_t gridZ, intptr_t blockX, intptr_t blockY,
                      intptr_t blockZ, int32_t sharedBytes, void *stream,
                      void **params, void **extra, size_t /*paramCount*/) {
  Device &gpu = device();
  auto kernel = static_cast<CUfunction>(function);
  auto cuStream = static_cast<CUstream>(stream);
  {
    std::lock_guard<std::mutex> lock(registry().mutex);
    registry().lastLaunch[cuStream] = {kernel, currentStatement};
  }
  CUresult result = gpu.driver().cuLaunchKernel(
      kernel, gridX, gridY, gridZ, blockX, blockY, blockZ, sharedBytes,
      cuStream, params, extra);
  if (result != CUDA_SUCCESS)
    check(result, "cuLaunchKernel",
          launchContext(kernel, currentStatement) + " with grid " +
              std::to_string(gridX) + " x " + std::to_string(blockX));
}

void *mgpuStreamCreate() {
  Device &gpu = device();
  CUstream stream = nullptr;
  check(gpu.driver().cuStreamCreate(&stream, CU_STREAM_NON_BLOCKING),
        "cuStreamCreate");
  return stream;
}

void mgpuStreamDestroy(void *stream) {
  Device &gpu = device();
  auto cuStream = static_cast<CUstream>(stream);
  checkStream(gpu.driver().cuStreamDestroy(cuStream), "cuStreamDestroy",
              cuStream);
  std::lock_guard<std::mutex> lock(registry().mutex);
  registry().lastLaunch.erase(cuStream);
}

void mgpuStreamSynchronize(void *stream) {
  Device &gpu = device();
  auto cuStream = static_cast<CUstream>(stream);
  checkStream(gpu.driver().cuStreamSynchronize(cuStream),
              "cuStreamSynchronize", cuStream);
}

/// A device buffer of `bytes` (managed memory when `hostShared`); none for
/// zero bytes, which the driver rejects and empty sets ask for.
void *mgpuMemAlloc(uint64_t bytes, void *stream, bool hostShared) {
  Device &gpu = device();
  if (bytes == 0)
    return nullptr;
  CUdeviceptr pointer = 0;
  if (hostShared)
    checkStream(gpu.driver().cuMemAllocManaged(&pointer, bytes,
                                               CU_MEM_ATTACH_GLOBAL),
                "cuMemAllocManaged", static_cast<CUstream>(stream));
  else
    checkStream(gpu.driver().cuMemAlloc(&pointer, bytes), "cuMemAlloc",
                static_cast<CUstream>(stream));
  return reinterpret_cast<void *>(pointer);
}

void mgpuMemFree(void *pointer, void *stream) {
  Device &gpu = device();
  if (!pointer)
    return;
  checkStream(gpu.driver().cuMemFree(reinterpret_cast<CUdeviceptr>(pointer)),
              "cuMemFree", static_cast<CUstream>(stream));
}

/// Copies `bytes` on `stream`, in either direction (unified addressing).
void mgpuMemcpy(void *dst, void *src, size_t bytes, void *stream) {
  Device &gpu = device();
  if (bytes == 0)
    return;
  checkStream(gpu.driver().cuMemcpyAsync(reinterpret_cast<CUdeviceptr>(dst),
                                         reinterpret_cast<CUdeviceptr>(src),
                                         bytes, static_cast<CUstream>(stream)),
              "cuMemcpyAsync", static_cast<CUstream>(stream));
}

} // extern "C"
