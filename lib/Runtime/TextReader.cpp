//===--- TextReader.cpp - Line-oriented reading of text inputs ------------===//

#include "TextReader.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

using namespace simit;
using namespace simit::detail;

llvm::Expected<TextReader> TextReader::open(llvm::StringRef path,
                                            bool hashComments) {
  auto buffer = llvm::MemoryBuffer::getFile(path, /*IsText=*/true);
  if (!buffer)
    return llvm::createStringError(buffer.getError(), "%s: cannot open: %s",
                                   path.str().c_str(),
                                   buffer.getError().message().c_str());
  return TextReader(path.str(), std::move(*buffer), hashComments);
}

bool TextReader::nextTokens(llvm::SmallVectorImpl<llvm::StringRef> &tokens) {
  while (!rest.empty()) {
    auto [lineText, remainder] = rest.split('\n');
    rest = remainder;
    ++line;
    if (hashComments)
      lineText = lineText.split('#').first;
    tokens.clear();
    lineText.split(tokens, ' ', -1, /*KeepEmpty=*/false);
    // Tabs and carriage returns separate tokens too.
    llvm::SmallVector<llvm::StringRef, 16> split;
    for (llvm::StringRef token : tokens) {
      llvm::SmallVector<llvm::StringRef, 4> parts;
      token.split(parts, '\t', -1, false);
      for (llvm::StringRef part : parts) {
        part = part.trim("\r\v\f");
        if (!part.empty())
          split.push_back(part);
      }
    }
    if (split.empty())
      continue;
    tokens.assign(split.begin(), split.end());
    return true;
  }
  return false;
}

llvm::Error
TextReader::requireTokens(llvm::SmallVectorImpl<llvm::StringRef> &tokens,
                          const llvm::Twine &expected) {
  if (nextTokens(tokens))
    return llvm::Error::success();
  return llvm::createStringError(
                                 name + ":" + llvm::Twine(line + 1) +
                                     ": expected " + expected +
                                     ", found the end of the file");
}

llvm::Error TextReader::error(const llvm::Twine &message) const {
  return llvm::createStringError(
                                 name + ":" + llvm::Twine(line) + ": " +
                                     message);
}

llvm::Error TextReader::fileError(const llvm::Twine &message) const {
  return llvm::createStringError(
                                 name + ": " + message);
}

llvm::Expected<long long> TextReader::parseInt(llvm::StringRef token,
                                               const llvm::Twine &what) const {
  long long value;
  if (token.getAsInteger(10, value))
    return error("expected an integer for " + what + ", found '" + token +
                 "'");
  return value;
}

bool simit::detail::parseDoubleToken(llvm::StringRef token, double &value) {
  // Decimal notation only: strtod would also read hexadecimal ("0x10").
  if (token.empty() || token.find_first_of("xX") != llvm::StringRef::npos)
    return false;
  std::string text = token.str();
  char *end = nullptr;
  errno = 0;
  value = std::strtod(text.c_str(), &end);
  // Underflow to a denormal or zero is fine; anything unparsed is not.
  return end == text.c_str() + text.size();
}

llvm::Expected<double> TextReader::parseDouble(llvm::StringRef token,
                                               const llvm::Twine &what) const {
  double value;
  if (!parseDoubleToken(token, value))
    return error("expected a number for " + what + ", found '" + token + "'");
  return value;
}

llvm::Expected<double>
TextReader::parseFiniteDouble(llvm::StringRef token,
                              const llvm::Twine &what) const {
  auto value = parseDouble(token, what);
  if (value && !std::isfinite(*value))
    return error("expected a finite number for " + what + ", found '" +
                 token + "'");
  return value;
}
