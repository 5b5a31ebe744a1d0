//===--- AtomicFile.h - Files that appear only when complete ---*- C++ -*-===//
//
// Outputs are written to a temporary file beside their final name and
// renamed over it when complete, so that a run that fails or is killed
// never leaves a truncated file under the final name, nor truncates the
// file an earlier run wrote there. Every error names the final file.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_ATOMICFILE_H
#define SIMIT_LIB_RUNTIME_ATOMICFILE_H

#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/raw_ostream.h"

#include <memory>
#include <optional>
#include <string>

namespace simit {
namespace detail {

/// An output file being written: a temporary file in the folder of `path`
/// that commit() renames to `path`. Destroyed uncommitted, it removes the
/// temporary file (as a signal that ends the process does).
class AtomicFile {
public:
  /// Creates the temporary file; "-" writes to standard output instead.
  static llvm::Expected<std::unique_ptr<AtomicFile>>
  create(llvm::StringRef path);
  ~AtomicFile();

  llvm::raw_ostream &stream() { return *os; }
  /// Flushes what was written so far; the error names the file.
  llvm::Error flush();
  /// Flushes, closes and renames the file to its final name.
  llvm::Error commit();

private:
  AtomicFile(std::string path, std::optional<llvm::sys::fs::TempFile> temp);
  llvm::Error failure(const llvm::Twine &reason) const;

  std::string path;
  std::optional<llvm::sys::fs::TempFile> temp; // none for standard output
  std::unique_ptr<llvm::raw_fd_ostream> ownedStream;
  llvm::raw_ostream *os;
};

/// Writes `path` through `write` as one AtomicFile.
llvm::Error
writeFileAtomically(llvm::StringRef path,
                    llvm::function_ref<llvm::Error(llvm::raw_ostream &)> write);

} // namespace detail
} // namespace simit

#endif // SIMIT_LIB_RUNTIME_ATOMICFILE_H
