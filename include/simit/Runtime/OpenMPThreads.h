//===- OpenMPThreads.h - The process's OpenMP thread limit -------*- C++ -*-===//
//
// Compiled set loops and CHOLMOD's supernodal loops share one OpenMP
// runtime (libomp; CHOLMOD's GOMP_* calls bind to it). CHOLMOD asks for 4
// threads in its loops whatever the machine has, which on 2 cores, or with
// --threads 1, oversubscribes them: so the process caps every parallel
// region's threads before the runtime starts.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_OPENMPTHREADS_H
#define SIMIT_RUNTIME_OPENMPTHREADS_H

namespace simit {

/// The cores this process may run on (its affinity mask), at least 1.
int availableCores();

/// Caps the threads of every OpenMP parallel region of the process at
/// `threads` (libomp's KMP_DEVICE_THREAD_LIMIT; libomp's warnings are
/// turned off, as it would warn at each region the cap narrows). Only the
/// first call counts; a limit in the environment (OMP_THREAD_LIMIT,
/// KMP_DEVICE_THREAD_LIMIT) wins. Returns the cap set, 0 when none was
/// (a limit in the environment, no libomp).
int capOpenMPThreads(int threads);

} // namespace simit

#endif // SIMIT_RUNTIME_OPENMPTHREADS_H
