//===--- simit-bench-bandwidth.cpp - The machine's memory bandwidth -------===//
//
// The bandwidth bench/speed compares Simit's SpMV with, measured on the same
// machine in the same run:
//   cpu: the STREAM triad a[i] = b[i] + s c[i] over three arrays of doubles,
//        each at least four times the last-level caches together (STREAM's
//        rule), on OpenMP threads with a static schedule; the arrays are
//        first touched by the threads that use them. Counted as STREAM
//        counts it: 24 bytes per i (write-allocate traffic not counted).
//   gpu: a device-to-device copy (cuMemcpyAsync) of one buffer into another
//        on the first NVIDIA GPU, through the project's CUDA driver loader;
//        counted as 2 bytes (read and write) per byte copied.
// The figure is the best of the repetitions (and their median), after one
// untimed warm-up; the triad's result is checked.
//
//===----------------------------------------------------------------------===//

#include "simit/Engine/ThreadsOption.h"
#include "simit/Runtime/CudaDriver.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/raw_ostream.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace cl = llvm::cl;
using Clock = std::chrono::steady_clock;

namespace {

cl::OptionCategory bandwidthCategory("simit-bench-bandwidth options");

enum class Target { CPU, GPU };
cl::opt<Target> target(
    "target", cl::cat(bandwidthCategory),
    cl::desc("What to measure (default: cpu)"),
    cl::values(clEnumValN(Target::CPU, "cpu", "the STREAM triad on the host"),
               clEnumValN(Target::GPU, "gpu",
                          "a device-to-device copy on the first NVIDIA GPU")),
    cl::init(Target::CPU));
cl::opt<int> mebibytes(
    "mib", cl::init(0), cl::cat(bandwidthCategory),
    cl::desc("MiB per array (default: cpu, 4 x the last-level caches "
             "together, at least 64; gpu, 1024)"));
cl::opt<int> repetitions("reps", cl::init(20), cl::cat(bandwidthCategory),
                         cl::desc("Timed repetitions (default 20)"));

llvm::Error failure(const llvm::Twine &message) {
  return llvm::createStringError(message);
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// The first line of a (sysfs) file, "" when it cannot be read.
std::string readLine(const std::string &path) {
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  return line;
}

/// The last-level caches of the CPUs together (sysfs), 0 when unknown: each
/// cache counted once, by the CPUs that share it.
uint64_t lastLevelCacheBytes() {
  int level = 0;
  uint64_t total = 0;
  std::set<std::string> seen;
  for (int cpu = 0;; ++cpu) {
    std::string base =
        "/sys/devices/system/cpu/cpu" + std::to_string(cpu) + "/cache/";
    if (readLine(base + "index0/level").empty())
      break;
    for (int index = 0;; ++index) {
      std::string dir = base + "index" + std::to_string(index) + "/";
      std::string levelText = readLine(dir + "level");
      if (levelText.empty())
        break;
      int thisLevel = std::atoi(levelText.c_str());
      std::string size = readLine(dir + "size"); // "32768K"
      uint64_t bytes = std::strtoull(size.c_str(), nullptr, 10);
      if (!size.empty() && size.back() == 'K')
        bytes <<= 10;
      else if (!size.empty() && size.back() == 'M')
        bytes <<= 20;
      if (thisLevel > level) {
        level = thisLevel;
        total = 0;
        seen.clear();
      }
      if (thisLevel == level &&
          seen.insert(readLine(dir + "shared_cpu_list")).second)
        total += bytes;
    }
  }
  return total;
}

struct Timings {
  double best = 0, median = 0;
};

Timings summarize(std::vector<double> seconds) {
  std::sort(seconds.begin(), seconds.end());
  return {seconds.front(), seconds[seconds.size() / 2]};
}

void report(llvm::StringRef kind, int threadCount, uint64_t arrayBytes,
            uint64_t bytesPerRep, const Timings &t) {
  double best = bytesPerRep / t.best / 1e9,
         median = bytesPerRep / t.median / 1e9;
  llvm::outs() << llvm::formatv(
      "{0}: {1:F1} GB/s best, {2:F1} GB/s median of {3} repetitions "
      "({4} thread(s), {5} MiB per array)\n",
      kind, best, median, repetitions.getValue(), threadCount,
      arrayBytes >> 20);
  llvm::outs() << llvm::formatv(
      "RESULT bandwidth kind={0} threads={1} array_bytes={2} "
      "bytes_per_rep={3} reps={4} best_gbs={5:F4} median_gbs={6:F4}\n",
      kind, threadCount, arrayBytes, bytesPerRep, repetitions.getValue(), best,
      median);
}

llvm::Error triad(int threads) {
  int threadCount = threads > 0 ? threads : omp_get_num_procs();
  omp_set_num_threads(threadCount);
  uint64_t llc = lastLevelCacheBytes();
  uint64_t arrayBytes =
      mebibytes > 0 ? uint64_t(mebibytes) << 20
                    : std::max<uint64_t>(4 * llc, uint64_t(64) << 20);
  int64_t n = arrayBytes / sizeof(double);
  std::unique_ptr<double[]> a(new double[n]), b(new double[n]),
      c(new double[n]);
  const double s = 3.0;
#pragma omp parallel for schedule(static)
  for (int64_t i = 0; i < n; ++i) {
    a[i] = 0;
    b[i] = double(i % 1024);
    c[i] = 0.5 * double(i % 7);
  }
  std::vector<double> seconds;
  for (int rep = 0; rep <= repetitions; ++rep) {
    Clock::time_point start = Clock::now();
#pragma omp parallel for schedule(static)
    for (int64_t i = 0; i < n; ++i)
      a[i] = b[i] + s * c[i];
    if (rep > 0)
      seconds.push_back(secondsSince(start));
  }
  for (int64_t i = 0; i < n; ++i)
    if (a[i] != double(i % 1024) + s * 0.5 * double(i % 7))
      return failure(llvm::formatv("triad: a[{0}] = {1}, expected {2}", i,
                                   a[i],
                                   double(i % 1024) + s * 0.5 * double(i % 7))
                         .str());
  if (llc)
    llvm::outs() << llvm::formatv("last-level caches: {0} MiB together\n",
                                  llc >> 20);
  report("triad", threadCount, arrayBytes, 3 * arrayBytes, summarize(seconds));
  return llvm::Error::success();
}

llvm::Error deviceCopy() {
  namespace cuda = simit::cuda;
  llvm::Expected<cuda::Device &> device = cuda::defaultDevice();
  if (!device)
    return failure("no CUDA device: " + llvm::toString(device.takeError()));
  if (llvm::Error err = device->makeCurrent())
    return err;
  const cuda::Driver &api = device->driver();
  uint64_t bytes = (mebibytes > 0 ? uint64_t(mebibytes) : 1024) << 20;
  cuda::CUdeviceptr source = 0, destination = 0;
  cuda::CUstream stream = nullptr;
  auto release = [&] {
    if (stream)
      api.cuStreamDestroy(stream);
    if (source)
      api.cuMemFree(source);
    if (destination)
      api.cuMemFree(destination);
  };
  std::vector<double> seconds;
  llvm::Error err = [&]() -> llvm::Error {
    if (auto e = api.check(api.cuMemAlloc(&source, bytes), "cuMemAlloc"))
      return e;
    if (auto e = api.check(api.cuMemAlloc(&destination, bytes), "cuMemAlloc"))
      return e;
    if (auto e = api.check(
            api.cuStreamCreate(&stream, cuda::CU_STREAM_NON_BLOCKING),
            "cuStreamCreate"))
      return e;
    for (int rep = 0; rep <= repetitions; ++rep) {
      Clock::time_point start = Clock::now();
      if (auto e = api.check(
              api.cuMemcpyAsync(destination, source, bytes, stream),
              "cuMemcpyAsync"))
        return e;
      if (auto e = api.check(api.cuStreamSynchronize(stream),
                             "cuStreamSynchronize"))
        return e;
      if (rep > 0)
        seconds.push_back(secondsSince(start));
    }
    return llvm::Error::success();
  }();
  release();
  if (err)
    return err;
  llvm::outs() << "device: " << cuda::describeDevice(*device) << "\n";
  report("device-copy", 1, bytes, 2 * bytes, summarize(seconds));
  return llvm::Error::success();
}

} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  cl::opt<int> &threads = simit::threadsOption(
      bandwidthCategory, "OpenMP threads of the triad (default: every core "
                         "this process may run on)");
  cl::HideUnrelatedOptions(bandwidthCategory);
  cl::ParseCommandLineOptions(
      argc, argv,
      "Memory bandwidth: the STREAM triad on the CPU, or a device copy on "
      "the GPU\n");
  if (repetitions < 1 || threads < 0 || mebibytes < 0) {
    llvm::errs() << "simit-bench-bandwidth: --reps must be positive, "
                    "--threads and --mib not negative\n";
    return 1;
  }
  llvm::Error err = target == Target::CPU ? triad(threads) : deviceCopy();
  if (err) {
    llvm::errs() << "simit-bench-bandwidth: " << llvm::toString(std::move(err))
                 << "\n";
    return 1;
  }
  return 0;
}
