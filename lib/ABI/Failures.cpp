//===--- Failures.cpp - Runs of lowered code and their failures -----------===//
//
// simit::runGuarded calls an entry point of lowered code so that a failure
// of the runtime inside it (simit_rt_fail) returns there as an error.
//
//===----------------------------------------------------------------------===//

#include "RunState.h"

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/SolveSession.h"

#include "llvm/Support/ErrorHandling.h"

#include <csetjmp>
#include <mutex>
#include <optional>
#include <string>

// libomp's (omp.h is not among the installed headers of every system).
extern "C" int omp_get_level(void);

namespace {
/// The run in progress on this thread, where simit_rt_fail returns to, and
/// the message of its failure.
thread_local std::jmp_buf *activeRun = nullptr;
/// The OpenMP nesting level at which that run began: deeper, its code is
/// inside one of its own parallel regions (a caller may run Simit functions
/// inside parallel regions of its own).
thread_local int activeRunLevel = 0;
thread_local std::string runFailure;

/// The solver of the run in progress on this thread (its Program's), else
/// one of the process for lowered code run outside a Program.
thread_local simit::SolveSession *activeSolver = nullptr;

/// A failure inside an OpenMP parallel region, raised when the region ends.
/// Of several, the least message is kept, so that which one is reported
/// does not depend on the threads' timing.
std::mutex parallelFailureMutex;
std::optional<std::string> parallelFailure;
} // namespace

void simit::abi::abandonRun() {
  if (!activeRun)
    llvm::report_fatal_error(llvm::StringRef(runFailure));
  std::longjmp(*activeRun, 1);
}

bool simit::abi::fail(const char *where, const llvm::Twine &message) {
  runFailure = (llvm::Twine(where ? where : "runtime") + ": " + message).str();
  return false;
}

simit::SolveSession &simit::abi::solver() {
  if (activeSolver)
    return *activeSolver;
  static simit::SolveSession processSolver;
  return processSolver;
}

extern "C" void simit_rt_fail(const char *message) {
  std::string text = message ? message : "the program failed";
  // Inside a parallel region of the run's code, on any of its threads (the
  // pool's threads run no run of their own).
  int level = omp_get_level();
  if (level > 0 && (!activeRun || level > activeRunLevel)) {
    std::lock_guard<std::mutex> lock(parallelFailureMutex);
    if (!parallelFailure || text < *parallelFailure)
      parallelFailure = std::move(text);
    return;
  }
  runFailure = std::move(text);
  simit::abi::abandonRun();
}

void simit::abi::failRun() { simit_rt_fail(runFailure.c_str()); }

extern "C" void simit_rt_raise_parallel_failure() {
  std::optional<std::string> failure;
  {
    std::lock_guard<std::mutex> lock(parallelFailureMutex);
    failure.swap(parallelFailure);
  }
  if (failure) {
    runFailure = std::move(*failure);
    simit::abi::abandonRun();
  }
}

llvm::Error simit::runGuarded(void (*entry)(void **), void **args,
                              SolveSession *session) {
  std::jmp_buf buffer;
  std::jmp_buf *outer = activeRun;
  int outerLevel = activeRunLevel;
  SolveSession *outerSolver = activeSolver;
  activeRun = &buffer;
  activeRunLevel = omp_get_level();
  activeSolver = session;
  if (setjmp(buffer)) {
    activeRun = outer;
    activeRunLevel = outerLevel;
    activeSolver = outerSolver;
    return llvm::createStringError(runFailure);
  }
  entry(args);
  activeRun = outer;
  activeRunLevel = outerLevel;
  activeSolver = outerSolver;
  return llvm::Error::success();
}
