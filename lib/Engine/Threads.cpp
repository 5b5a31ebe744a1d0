//===--- Threads.cpp - The OpenMP threads of compiled set loops ------------===//

#include "Threads.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/OpenMPThreads.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Process.h"

#include <dlfcn.h>

// libomp's API (omp.h is not among the installed headers of every system).
extern "C" {
void omp_set_num_threads(int threads);
}

using namespace simit;

void simit::useThreads(int threads) { omp_set_num_threads(threads); }

std::string simit::openMPLibraryPath() {
  Dl_info info;
  if (!dladdr(reinterpret_cast<void *>(&omp_set_num_threads), &info) ||
      !info.dli_fname)
    return "";
  return info.dli_fname;
}

llvm::Expected<int> simit::resolveThreadCount(int requested) {
  if (requested < 0)
    return llvm::createStringError("the number of threads must be positive, "
                                   "not " +
                                   llvm::Twine(requested));
  if (requested > 0)
    return requested;
  if (std::optional<std::string> text =
          llvm::sys::Process::GetEnv("SIMIT_NUM_THREADS")) {
    int threads = 0;
    if (llvm::StringRef(*text).trim().getAsInteger(10, threads) ||
        threads < 1)
      return llvm::createStringError(
          "SIMIT_NUM_THREADS must be a positive integer, not '" + *text + "'");
    return threads;
  }
  // The cores this process may run on (its affinity mask), found without
  // starting the OpenMP runtime: its thread cap must come first.
  return availableCores();
}
