//===--- CudaDriver.h - The CUDA driver API, loaded at run time -*- C++ -*-===//
//
// The few CUDA driver functions the GPU path calls, resolved with dlopen and
// dlsym from libcuda.so.1 when first needed, so that the project builds,
// links and runs its CPU code on machines without CUDA. No CUDA header is
// used: the handful of types and constants are declared here.
//
//   llvm::Expected<cuda::Device &> device = cuda::defaultDevice();
//   if (!device) -> "no CUDA device: " + the one-line reason
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_CUDADRIVER_H
#define SIMIT_RUNTIME_CUDADRIVER_H

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace simit::cuda {

using CUresult = int;
using CUdevice = int;
using CUdeviceptr = uint64_t;
using CUcontext = struct CUctx_st *;
using CUmodule = struct CUmod_st *;
using CUfunction = struct CUfunc_st *;
using CUstream = struct CUstream_st *;
using CUevent = struct CUevent_st *;

constexpr CUresult CUDA_SUCCESS = 0;
/// CUdevice_attribute values.
constexpr int CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR = 75;
constexpr int CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR = 76;
/// CUjit_option values.
constexpr int CU_JIT_INFO_LOG_BUFFER = 3;
constexpr int CU_JIT_INFO_LOG_BUFFER_SIZE_BYTES = 4;
constexpr int CU_JIT_ERROR_LOG_BUFFER = 5;
constexpr int CU_JIT_ERROR_LOG_BUFFER_SIZE_BYTES = 6;
constexpr int CU_JIT_OPTIMIZATION_LEVEL = 7;
constexpr unsigned CU_STREAM_NON_BLOCKING = 1;
constexpr unsigned CU_MEM_ATTACH_GLOBAL = 1;

/// The driver library name the process loads by default.
constexpr llvm::StringLiteral kDriverLibrary = "libcuda.so.1";

/// The driver functions, under their ABI names (cuMemAlloc is
/// cuMemAlloc_v2 in the library, as cuda.h maps it).
struct DriverAPI {
  CUresult (*cuInit)(unsigned flags);
  CUresult (*cuDriverGetVersion)(int *version);
  CUresult (*cuGetErrorName)(CUresult error, const char **name);
  CUresult (*cuGetErrorString)(CUresult error, const char **text);
  CUresult (*cuDeviceGetCount)(int *count);
  CUresult (*cuDeviceGet)(CUdevice *device, int ordinal);
  CUresult (*cuDeviceGetName)(char *name, int length, CUdevice device);
  CUresult (*cuDeviceGetAttribute)(int *value, int attribute, CUdevice device);
  CUresult (*cuDevicePrimaryCtxRetain)(CUcontext *context, CUdevice device);
  CUresult (*cuDevicePrimaryCtxRelease)(CUdevice device);
  CUresult (*cuCtxSetCurrent)(CUcontext context);
  CUresult (*cuModuleLoadDataEx)(CUmodule *module, const void *image,
                                 unsigned numOptions, int *options,
                                 void **optionValues);
  CUresult (*cuModuleUnload)(CUmodule module);
  CUresult (*cuModuleGetFunction)(CUfunction *function, CUmodule module,
                                  const char *name);
  CUresult (*cuLaunchKernel)(CUfunction function, unsigned gridX,
                             unsigned gridY, unsigned gridZ, unsigned blockX,
                             unsigned blockY, unsigned blockZ,
                             unsigned sharedBytes, CUstream stream,
                             void **params, void **extra);
  CUresult (*cuStreamCreate)(CUstream *stream, unsigned flags);
  CUresult (*cuStreamDestroy)(CUstream stream);
  CUresult (*cuStreamSynchronize)(CUstream stream);
  CUresult (*cuMemAlloc)(CUdeviceptr *pointer, size_t bytes);
  CUresult (*cuMemAllocManaged)(CUdeviceptr *pointer, size_t bytes,
                                unsigned flags);
  CUresult (*cuMemFree)(CUdeviceptr pointer);
  CUresult (*cuMemcpyAsync)(CUdeviceptr dst, CUdeviceptr src, size_t bytes,
                            CUstream stream);
};

/// A loaded driver library.
class Driver : public DriverAPI {
public:
  /// dlopens `library` and resolves every function of DriverAPI. The error
  /// is one line: the library is missing, or lacks a function (named).
  static llvm::Expected<std::unique_ptr<Driver>>
  load(llvm::StringRef library = kDriverLibrary);
  ~Driver();
  Driver(const Driver &) = delete;
  Driver &operator=(const Driver &) = delete;

  /// "CUDA_ERROR_NAME (the driver's description)" of `result`.
  std::string describe(CUresult result) const;
  /// Success for CUDA_SUCCESS, else "`call` failed: describe(result)".
  llvm::Error check(CUresult result, llvm::StringRef call) const;

private:
  Driver() = default;
  void *handle = nullptr;
};

/// A driver with cuInit done and device 0's primary context retained.
class Device {
public:
  /// Loads `library`, initialises the driver and opens device 0. The error
  /// is the one-line reason there is no device ("libcuda.so.1 not found:
  /// ...", "cuInit failed: ...", "0 devices").
  static llvm::Expected<std::unique_ptr<Device>>
  open(llvm::StringRef library = kDriverLibrary);
  ~Device();

  const Driver &driver() const { return *api; }
  CUdevice handle() const { return device; }
  CUcontext context() const { return primaryContext; }
  /// The device's name, e.g. "NVIDIA H200".
  const std::string &name() const { return deviceName; }
  /// Compute capability major * 10 + minor (90 for sm_90).
  int computeCapability() const { return capability; }
  /// The driver's CUDA version, e.g. 12040 for 12.4.
  int driverVersion() const { return version; }
  /// Makes the device's context current on the calling thread.
  llvm::Error makeCurrent() const;

private:
  Device() = default;
  std::unique_ptr<Driver> api;
  CUdevice device = 0;
  CUcontext primaryContext = nullptr;
  std::string deviceName;
  int capability = 0;
  int version = 0;
};

/// The process's device, opened on first call from $SIMIT_CUDA_LIBRARY
/// when set (tests give stand-in drivers), else libcuda.so.1; every later
/// call gives the same answer, device or reason.
llvm::Expected<Device &> defaultDevice();

/// "NVIDIA H200 (sm_90, driver CUDA 12.4)".
std::string describeDevice(const Device &device);

} // namespace simit::cuda

#endif // SIMIT_RUNTIME_CUDADRIVER_H
