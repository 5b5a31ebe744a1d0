//===--- RunState.h - The run lowered code is in --------------------------===//
//
// The runtime's functions end the run of the exported function in progress
// (simit::runGuarded) when they fail, and serve its solves from the run's
// SolveSession. Failures.cpp keeps this state per thread.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_ABI_RUNSTATE_H
#define SIMIT_LIB_ABI_RUNSTATE_H

#include "llvm/ADT/Twine.h"

namespace simit {
class SolveSession;

namespace abi {

/// Ends the run in progress with the message recorded by fail() (or
/// simit_rt_fail). The frames it unwinds are lowered code and the runtime
/// function that failed, which holds no object with a destructor when it
/// calls this.
[[noreturn]] void abandonRun();

/// Records the failure of the statement `where` and returns false.
bool fail(const char *where, const llvm::Twine &message);

/// Ends the run with the failure fail() recorded, as simit_rt_fail does:
/// inside a parallel region of the run's code the failure is kept for the
/// region's end, and this returns.
void failRun();

/// The solver of the run in progress on this thread (its Program's), else
/// one of the process for lowered code run outside a Program.
SolveSession &solver();

} // namespace abi
} // namespace simit

#endif // SIMIT_LIB_ABI_RUNSTATE_H
