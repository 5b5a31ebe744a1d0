//===--- Threads.h - The OpenMP threads of compiled set loops --------------===//

#ifndef SIMIT_LIB_ENGINE_THREADS_H
#define SIMIT_LIB_ENGINE_THREADS_H

#include <string>

namespace simit {

/// Makes the parallel regions that the calling thread starts use `threads`
/// threads (OpenMP's nthreads-var of the calling thread).
void useThreads(int threads);

/// The file of the OpenMP runtime the engine is linked with, whose
/// `__kmpc_*` entry points compiled code calls; empty if unknown.
std::string openMPLibraryPath();

} // namespace simit

#endif // SIMIT_LIB_ENGINE_THREADS_H
