//===--- PerfMap.h - Naming JIT-compiled code for perf ---------------------===//
//
// Linux perf names samples in JIT-compiled code from /tmp/perf-<pid>.map,
// one "start size name" line per function. With SIMIT_PERF_MAP=DIR, every
// function the JIT links is appended to DIR/perf-<pid>.map (DIR=/tmp for
// perf), so that `perf report` attributes time to the functions of a Simit
// program (its entry points and outlined parallel loops) instead of to
// anonymous memory.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ENGINE_PERFMAP_H
#define SIMIT_LIB_ENGINE_PERFMAP_H

#include "llvm/ExecutionEngine/Orc/LLJIT.h"

namespace simit {

/// Makes `jit` append its functions to $SIMIT_PERF_MAP/perf-<pid>.map when
/// that environment variable is set.
void addPerfMapWhenAsked(llvm::orc::LLJIT &jit);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_PERFMAP_H
