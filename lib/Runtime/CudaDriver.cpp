//===--- CudaDriver.cpp - The CUDA driver API, loaded at run time ---------===//

#include "simit/Runtime/CudaDriver.h"

#include "llvm/ADT/Twine.h"
#include "llvm/Support/FormatVariadic.h"

#include <cstdlib>
#include <dlfcn.h>
#include <mutex>

using namespace simit;
using namespace simit::cuda;

namespace {
/// Resolves `name` from `handle` into `function`; false names it in `missing`.
template <typename F>
bool resolve(void *handle, const char *name, F &function,
             std::string &missing) {
  function = reinterpret_cast<F>(dlsym(handle, name));
  if (!function && missing.empty())
    missing = name;
  return function != nullptr;
}
} // namespace

llvm::Expected<std::unique_ptr<Driver>> Driver::load(llvm::StringRef library) {
  std::string name = library.str();
  void *handle = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char *why = dlerror();
    return llvm::createStringError(name + " not found" +
                                   (why ? std::string(": ") + why : ""));
  }
  std::unique_ptr<Driver> driver(new Driver());
  driver->handle = handle;
  std::string missing;
  // The names cuda.h maps the API to (its #define cuMemAlloc cuMemAlloc_v2
  // and the like): the original entry points keep their old ABI.
  resolve(handle, "cuInit", driver->cuInit, missing);
  resolve(handle, "cuDriverGetVersion", driver->cuDriverGetVersion, missing);
  resolve(handle, "cuGetErrorName", driver->cuGetErrorName, missing);
  resolve(handle, "cuGetErrorString", driver->cuGetErrorString, missing);
  resolve(handle, "cuDeviceGetCount", driver->cuDeviceGetCount, missing);
  resolve(handle, "cuDeviceGet", driver->cuDeviceGet, missing);
  resolve(handle, "cuDeviceGetName", driver->cuDeviceGetName, missing);
  resolve(handle, "cuDeviceGetAttribute", driver->cuDeviceGetAttribute,
          missing);
  resolve(handle, "cuDevicePrimaryCtxRetain", driver->cuDevicePrimaryCtxRetain,
          missing);
  resolve(handle, "cuDevicePrimaryCtxRelease_v2",
          driver->cuDevicePrimaryCtxRelease, missing);
  resolve(handle, "cuCtxSetCurrent", driver->cuCtxSetCurrent, missing);
  resolve(handle, "cuModuleLoadDataEx", driver->cuModuleLoadDataEx, missing);
  resolve(handle, "cuModuleUnload", driver->cuModuleUnload, missing);
  resolve(handle, "cuModuleGetFunction", driver->cuModuleGetFunction, missing);
  resolve(handle, "cuLaunchKernel", driver->cuLaunchKernel, missing);
  resolve(handle, "cuStreamCreate", driver->cuStreamCreate, missing);
  resolve(handle, "cuStreamDestroy_v2", driver->cuStreamDestroy, missing);
  resolve(handle, "cuStreamSynchronize", driver->cuStreamSynchronize, missing);
  resolve(handle, "cuMemAlloc_v2", driver->cuMemAlloc, missing);
  resolve(handle, "cuMemAllocManaged", driver->cuMemAllocManaged, missing);
  resolve(handle, "cuMemFree_v2", driver->cuMemFree, missing);
  resolve(handle, "cuMemcpyAsync", driver->cuMemcpyAsync, missing);
  if (!missing.empty())
    return llvm::createStringError(name + " lacks the driver function " +
                                   missing);
  return driver;
}

Driver::~Driver() {
  if (handle)
    dlclose(handle);
}

std::string Driver::describe(CUresult result) const {
  const char *name = nullptr, *text = nullptr;
  if (cuGetErrorName(result, &name) != CUDA_SUCCESS || !name)
    name = nullptr;
  if (cuGetErrorString(result, &text) != CUDA_SUCCESS || !text)
    text = nullptr;
  std::string description =
      name ? std::string(name) : "CUDA error " + std::to_string(result);
  if (text)
    description += std::string(" (") + text + ")";
  return description;
}

llvm::Error Driver::check(CUresult result, llvm::StringRef call) const {
  if (result == CUDA_SUCCESS)
    return llvm::Error::success();
  return llvm::createStringError(call + " failed: " + describe(result));
}

llvm::Expected<std::unique_ptr<Device>> Device::open(llvm::StringRef library) {
  auto driver = Driver::load(library);
  if (!driver)
    return driver.takeError();
  const Driver &api = **driver;
  if (llvm::Error err = api.check(api.cuInit(0), "cuInit"))
    return std::move(err);
  int count = 0;
  if (llvm::Error err =
          api.check(api.cuDeviceGetCount(&count), "cuDeviceGetCount"))
    return std::move(err);
  if (count < 1)
    return llvm::createStringError("0 devices");
  std::unique_ptr<Device> device(new Device());
  if (llvm::Error err =
          api.check(api.cuDeviceGet(&device->device, 0), "cuDeviceGet"))
    return std::move(err);
  char name[256] = {};
  if (llvm::Error err = api.check(
          api.cuDeviceGetName(name, sizeof(name) - 1, device->device),
          "cuDeviceGetName"))
    return std::move(err);
  device->deviceName = name;
  int major = 0, minor = 0;
  if (llvm::Error err = api.check(
          api.cuDeviceGetAttribute(
              &major, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR,
              device->device),
          "cuDeviceGetAttribute"))
    return std::move(err);
  if (llvm::Error err = api.check(
          api.cuDeviceGetAttribute(
              &minor, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR,
              device->device),
          "cuDeviceGetAttribute"))
    return std::move(err);
  device->capability = major * 10 + minor;
  if (llvm::Error err = api.check(api.cuDriverGetVersion(&device->version),
                                  "cuDriverGetVersion"))
    return std::move(err);
  if (llvm::Error err =
          api.check(api.cuDevicePrimaryCtxRetain(&device->primaryContext,
                                                 device->device),
                    "cuDevicePrimaryCtxRetain"))
    return std::move(err);
  device->api = std::move(*driver);
  return device;
}

Device::~Device() {
  if (primaryContext)
    api->cuDevicePrimaryCtxRelease(device);
}

llvm::Error Device::makeCurrent() const {
  return api->check(api->cuCtxSetCurrent(primaryContext), "cuCtxSetCurrent");
}

llvm::Expected<Device &> cuda::defaultDevice() {
  // Opened once, and never closed: kernels' modules and device buffers of
  // Programs alive at exit refer to it.
  static std::once_flag opened;
  static Device *device = nullptr;
  static std::string reason;
  std::call_once(opened, [] {
    llvm::StringRef library = kDriverLibrary;
    if (const char *chosen = std::getenv("SIMIT_CUDA_LIBRARY"); chosen && *chosen)
      library = chosen;
    auto result = Device::open(library);
    if (result)
      device = result->release();
    else
      reason = llvm::toString(result.takeError());
  });
  if (!device)
    return llvm::createStringError(reason);
  return *device;
}

std::string cuda::describeDevice(const Device &device) {
  return llvm::formatv("{0} (sm_{1}, driver CUDA {2}.{3})", device.name(),
                       device.computeCapability(),
                       device.driverVersion() / 1000,
                       device.driverVersion() % 1000 / 10)
      .str();
}
