// A stand-in for libcuda.so.1 that defines every driver function the
// runtime resolves, for the tests of the reasons there is no device:
// built with -DFAIL_INIT, cuInit fails with CUDA_ERROR_NO_DEVICE (100);
// otherwise the driver starts and reports 0 devices. No other function is
// ever reached.
#include <cstddef>

namespace {
int notReached() { return 999; }
} // namespace

extern "C" {
int cuInit(unsigned) {
#ifdef FAIL_INIT
  return 100;
#else
  return 0;
#endif
}
int cuDeviceGetCount(int *count) {
  *count = 0;
  return 0;
}
int cuGetErrorName(int error, const char **name) {
  *name = error == 100 ? "CUDA_ERROR_NO_DEVICE" : "CUDA_ERROR_UNKNOWN";
  return 0;
}
int cuGetErrorString(int error, const char **text) {
  *text = error == 100 ? "no CUDA-capable device is detected"
                       : "unknown error";
  return 0;
}
#define NOT_REACHED(name)                                                      \
  int name() { return notReached(); }
NOT_REACHED(cuDriverGetVersion)
NOT_REACHED(cuDeviceGet)
NOT_REACHED(cuDeviceGetName)
NOT_REACHED(cuDeviceGetAttribute)
NOT_REACHED(cuDevicePrimaryCtxRetain)
NOT_REACHED(cuDevicePrimaryCtxRelease_v2)
NOT_REACHED(cuCtxSetCurrent)
NOT_REACHED(cuModuleLoadDataEx)
NOT_REACHED(cuModuleUnload)
NOT_REACHED(cuModuleGetFunction)
NOT_REACHED(cuLaunchKernel)
NOT_REACHED(cuStreamCreate)
NOT_REACHED(cuStreamDestroy_v2)
NOT_REACHED(cuStreamSynchronize)
NOT_REACHED(cuMemAlloc_v2)
NOT_REACHED(cuMemAllocManaged)
NOT_REACHED(cuMemFree_v2)
NOT_REACHED(cuMemcpyAsync)
}
