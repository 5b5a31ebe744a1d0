//===--- EngineTestSupport.h - Helpers of the engine tests ------*- C++ -*-===//

#ifndef SIMIT_UNITTESTS_ENGINE_ENGINETESTSUPPORT_H
#define SIMIT_UNITTESTS_ENGINE_ENGINETESTSUPPORT_H

#include "simit/Engine/Program.h"

#include "llvm/Support/Error.h"

#include <string>

namespace simit::test {

/// "success", or the error's message (for EXPECT_EQ).
inline std::string message(llvm::Error err) {
  return err ? llvm::toString(std::move(err)) : "success";
}

/// Loads test/Programs/System/<name>.sim and compiles its `main`.
inline llvm::Expected<Function> compileSystemMain(Program &program,
                                                  llvm::StringRef name) {
  std::string path =
      (SIMIT_SOURCE_DIR "/test/Programs/System/" + name + ".sim").str();
  if (llvm::Error err = program.loadFile(path))
    return std::move(err);
  return program.compile("main");
}

} // namespace simit::test

#endif // SIMIT_UNITTESTS_ENGINE_ENGINETESTSUPPORT_H
