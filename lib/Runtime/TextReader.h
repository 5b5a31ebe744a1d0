//===--- TextReader.h - Line-oriented reading of text inputs ----*- C++ -*-===//
//
// Shared by the mesh and array loaders: splits a file into whitespace
// separated tokens line by line, strips `#` comments, and builds errors that
// name the file and line ("file:line: what was expected").
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_TEXTREADER_H
#define SIMIT_LIB_RUNTIME_TEXTREADER_H

#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/MemoryBuffer.h"

#include <memory>
#include <string>

namespace simit {
namespace detail {

class TextReader {
public:
  /// Opens `path`; the error names the file and the system's reason.
  static llvm::Expected<TextReader> open(llvm::StringRef path,
                                         bool hashComments = true);

  /// Advances to the next line holding at least one token and splits it.
  /// Returns false at the end of the file.
  bool nextTokens(llvm::SmallVectorImpl<llvm::StringRef> &tokens);

  /// Advances to the next line holding a token; at the end of the file
  /// returns an error saying that `expected` was expected.
  llvm::Error requireTokens(llvm::SmallVectorImpl<llvm::StringRef> &tokens,
                            const llvm::Twine &expected);

  /// The line number of the last line read (1-based; 0 before the first).
  unsigned lineNumber() const { return line; }
  llvm::StringRef fileName() const { return name; }

  /// "file:line: message" for the last line read.
  llvm::Error error(const llvm::Twine &message) const;
  /// "file: message" for problems that belong to the whole file.
  llvm::Error fileError(const llvm::Twine &message) const;

  /// Parses `token` as an integer / a number; errors name `what`.
  llvm::Expected<long long> parseInt(llvm::StringRef token,
                                     const llvm::Twine &what) const;
  llvm::Expected<double> parseDouble(llvm::StringRef token,
                                     const llvm::Twine &what) const;
  /// parseDouble for values that must be finite (coordinates): NaN and
  /// infinities are errors.
  llvm::Expected<double> parseFiniteDouble(llvm::StringRef token,
                                           const llvm::Twine &what) const;

  /// The most records of `tokens` tokens each that the rest of the file
  /// can hold (a token and a separator take two bytes at least): what a
  /// count read from a header may reserve room for before the records are
  /// read, so that a header promising 2e9 points on a short file cannot
  /// allocate gigabytes.
  size_t recordCapacity(unsigned tokens) const {
    return (rest.size() + 1) / (2 * static_cast<size_t>(tokens));
  }

private:
  TextReader(std::string name, std::unique_ptr<llvm::MemoryBuffer> buffer,
             bool hashComments)
      : name(std::move(name)), buffer(std::move(buffer)),
        rest(this->buffer->getBuffer()), hashComments(hashComments) {}

  std::string name;
  std::unique_ptr<llvm::MemoryBuffer> buffer;
  llvm::StringRef rest;
  unsigned line = 0;
  bool hashComments;
};

/// Parses a complete token as a finite or infinite double in decimal
/// notation (strtod syntax without hexadecimal).
bool parseDoubleToken(llvm::StringRef token, double &value);

} // namespace detail
} // namespace simit

#endif // SIMIT_LIB_RUNTIME_TEXTREADER_H
