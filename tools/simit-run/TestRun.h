//===--- TestRun.h - Running %! assertions and --eval calls ---------------===//

#ifndef SIMIT_TOOLS_SIMIT_RUN_TESTRUN_H
#define SIMIT_TOOLS_SIMIT_RUN_TESTRUN_H

#include "simit/Engine/Program.h"

#include "llvm/Support/raw_ostream.h"

#include <string>

namespace simit {

struct TestRunOptions {
  std::string path;
  /// The options of every section's Program; the functions the assertions
  /// call are added to its hostFunctions.
  ProgramOptions program;
};

/// Runs the assertions of every enabled section of a .sim file, printing
/// each failure with its file line and then "N passed, N failed". Returns
/// the exit status: 0 when nothing failed.
int runTests(const TestRunOptions &options, llvm::raw_ostream &os);

struct EvalOptions {
  std::string path;
  /// `name(literal, ...)`.
  std::string call;
  /// The Program's options; the called function is its host function.
  ProgramOptions program;
};

/// Calls one function with literal arguments and prints each result as a
/// Simit literal on its own line. Returns the exit status.
int runEval(const EvalOptions &options, llvm::raw_ostream &os);

} // namespace simit

#endif // SIMIT_TOOLS_SIMIT_RUN_TESTRUN_H
