//===--- OpenMPThreads.cpp - The process's OpenMP thread limit ------------===//

#include "simit/Runtime/OpenMPThreads.h"

#include <sched.h>

#include <cstdlib>
#include <string>

// libomp's API, weak: the runtime library does not need an OpenMP runtime,
// and libgomp has no kmp_set_defaults.
extern "C" void kmp_set_defaults(const char *settings) __attribute__((weak));

int simit::availableCores() {
  cpu_set_t mask;
  if (sched_getaffinity(0, sizeof(mask), &mask) != 0)
    return 1;
  int cores = CPU_COUNT(&mask);
  return cores > 0 ? cores : 1;
}

int simit::capOpenMPThreads(int threads) {
  static int cap = [threads] {
    for (const char *chosen :
         {"OMP_THREAD_LIMIT", "KMP_DEVICE_THREAD_LIMIT", "KMP_ALL_THREADS"})
      if (std::getenv(chosen))
        return 0;
    if (!kmp_set_defaults || threads < 1)
      return 0;
    // kmp_set_defaults reads one setting as the environment would. libomp
    // warns on every region whose num_threads clause the cap lowers
    // (CHOLMOD's): its warnings go first.
    kmp_set_defaults("KMP_WARNINGS=0");
    kmp_set_defaults(
        ("KMP_DEVICE_THREAD_LIMIT=" + std::to_string(threads)).c_str());
    return threads;
  }();
  return cap;
}
