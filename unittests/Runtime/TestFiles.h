//===--- TestFiles.h - Temporary input files for runtime tests --*- C++ -*-===//

#ifndef SIMIT_UNITTESTS_RUNTIME_TESTFILES_H
#define SIMIT_UNITTESTS_RUNTIME_TESTFILES_H

#include "llvm/ADT/SmallString.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

#include "gtest/gtest.h"

#include <fstream>
#include <string>

namespace simit::test {

/// A fresh directory removed with its files when the test ends.
class TempDir {
public:
  TempDir() {
    std::error_code ec =
        llvm::sys::fs::createUniqueDirectory("simit-runtime-test", dir);
    EXPECT_FALSE(ec) << ec.message();
  }
  ~TempDir() { llvm::sys::fs::remove_directories(dir); }

  std::string path(llvm::StringRef name) const {
    llvm::SmallString<128> p(dir);
    llvm::sys::path::append(p, name);
    return std::string(p);
  }

  /// Writes `contents` to `name` inside the directory; returns its path.
  std::string write(llvm::StringRef name, llvm::StringRef contents) const {
    std::string p = path(name);
    std::ofstream(p, std::ios::binary) << contents.str();
    return p;
  }

private:
  llvm::SmallString<128> dir;
};

/// The message of an expected error ("" and a test failure when none).
template <typename T> std::string errorOf(llvm::Expected<T> value) {
  if (value) {
    ADD_FAILURE() << "expected an error";
    return "";
  }
  return llvm::toString(value.takeError());
}

inline std::string errorOf(llvm::Error error) {
  if (!error) {
    ADD_FAILURE() << "expected an error";
    return "";
  }
  return llvm::toString(std::move(error));
}

inline std::string sharedPath(llvm::StringRef relative) {
  return (llvm::Twine(SIMIT_SHARED_DIR) + "/" + relative).str();
}

} // namespace simit::test

#endif // SIMIT_UNITTESTS_RUNTIME_TESTFILES_H
