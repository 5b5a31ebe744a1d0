//===--- TestRun.h - Running %! assertions and --eval calls ---------------===//

#ifndef SIMIT_TOOLS_SIMIT_RUN_TESTRUN_H
#define SIMIT_TOOLS_SIMIT_RUN_TESTRUN_H

#include "simit/Engine/Program.h"

#include "llvm/Support/raw_ostream.h"

#include <string>
#include <vector>

namespace simit {

struct TestRunOptions {
  std::string path;
  FloatPrecision precision = FloatPrecision::Double;
  /// ProgramOptions::cacheDirectory of every section's Program.
  std::string cacheDirectory;
  /// ProgramOptions::threads of every section's Program.
  int threads = 0;
  /// ProgramOptions::hostLibraries (--extern-lib).
  std::vector<std::string> hostLibraries;
  /// ProgramOptions::target (--target).
  Target target = Target::CPU;
};

/// Runs the assertions of every enabled section of a .sim file, printing
/// each failure with its file line and then "N passed, N failed". Returns
/// the exit status: 0 when nothing failed.
int runTests(const TestRunOptions &options, llvm::raw_ostream &os);

struct EvalOptions {
  std::string path;
  /// `name(literal, ...)`.
  std::string call;
  FloatPrecision precision = FloatPrecision::Double;
  std::string cacheDirectory;
  int threads = 0;
  std::vector<std::string> hostLibraries;
  Target target = Target::CPU;
};

/// Calls one function with literal arguments and prints each result as a
/// Simit literal on its own line. Returns the exit status.
int runEval(const EvalOptions &options, llvm::raw_ostream &os);

} // namespace simit

#endif // SIMIT_TOOLS_SIMIT_RUN_TESTRUN_H
