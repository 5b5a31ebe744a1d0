//===--- ThreadsOption.h - The tools' --threads option ----------*- C++ -*-===//
//
// --threads N of simit-run and of bench/'s drivers. Debian's libLLVM
// registers an undocumented integer option of that name (nothing here reads
// it), so it is renamed `llvm-threads` first and this option is made
// afterwards: call threadsOption() in main(), before parsing the command
// line (a global cl::opt would be registered before the renaming).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ENGINE_THREADSOPTION_H
#define SIMIT_ENGINE_THREADSOPTION_H

#include "llvm/Support/CommandLine.h"

namespace simit {

/// The --threads option in `category`, 0 when not given; made once.
inline llvm::cl::opt<int> &threadsOption(llvm::cl::OptionCategory &category,
                                         llvm::StringRef description) {
  static bool renamed = [] {
    llvm::cl::Option *taken =
        llvm::cl::getRegisteredOptions().lookup("threads");
    if (taken)
      taken->setArgStr("llvm-threads");
    return taken != nullptr;
  }();
  (void)renamed;
  static llvm::cl::opt<int> threads(llvm::cl::cat(category), "threads",
                                    llvm::cl::desc(description),
                                    llvm::cl::value_desc("N"),
                                    llvm::cl::init(0));
  return threads;
}

} // namespace simit

#endif // SIMIT_ENGINE_THREADSOPTION_H
