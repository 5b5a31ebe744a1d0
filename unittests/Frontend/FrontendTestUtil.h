//===- FrontendTestUtil.h - Compile snippets in unit tests ------*- C++ -*-===//

#ifndef SIMIT_UNITTESTS_FRONTEND_FRONTENDTESTUTIL_H
#define SIMIT_UNITTESTS_FRONTEND_FRONTENDTESTUTIL_H

#include "simit/Frontend/ASTPrinter.h"
#include "simit/Frontend/Frontend.h"

#include "llvm/Support/MemoryBuffer.h"

#include <string>
#include <vector>

namespace simit::frontend::test {

/// Parses (and by default checks) one program, keeping its diagnostics as
/// "line:col: message" strings.
class Compilation {
public:
  explicit Compilation(llvm::StringRef source, bool runSema = true)
      : diags(sourceMgr) {
    unsigned id = sourceMgr.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(source, "test.sim"),
        llvm::SMLoc());
    program = parseProgram(sourceMgr, id, diags);
    parsed = !diags.hasErrors();
    if (runSema && parsed)
      checkProgram(*program, diags);
    ok = !diags.hasErrors();
    for (const Diagnostic &d : diags.sorted()) {
      if (d.kind != llvm::SourceMgr::DK_Error)
        continue;
      auto [line, col] = diags.lineAndColumn(d.loc);
      errors.push_back(std::to_string(line) + ":" + std::to_string(col) +
                       ": " + d.message);
    }
  }

  /// Is there an error at `lineCol` ("3:7") whose message contains `text`?
  bool hasError(const std::string &lineCol, const std::string &text) const {
    for (const std::string &e : errors)
      if (e.rfind(lineCol + ": ", 0) == 0 && e.find(text) != std::string::npos)
        return true;
    return false;
  }

  std::string allErrors() const {
    std::string all;
    for (const std::string &e : errors)
      all += e + "\n";
    return all;
  }

  std::string dump() const {
    std::string text;
    llvm::raw_string_ostream os(text);
    printProgram(*program, os);
    return os.str();
  }

  llvm::SourceMgr sourceMgr;
  DiagnosticEngine diags;
  std::unique_ptr<Program> program;
  std::vector<std::string> errors;
  bool parsed = false;
  bool ok = false;
};

} // namespace simit::frontend::test

#define EXPECT_ACCEPTS(src)                                                    \
  do {                                                                         \
    ::simit::frontend::test::Compilation c_(src);                              \
    EXPECT_TRUE(c_.ok) << c_.allErrors();                                      \
  } while (0)

#define EXPECT_ERROR(src, lineCol, text)                                       \
  do {                                                                         \
    ::simit::frontend::test::Compilation c_(src);                              \
    EXPECT_FALSE(c_.ok);                                                       \
    EXPECT_TRUE(c_.hasError(lineCol, text)) << c_.allErrors();                 \
  } while (0)

#endif // SIMIT_UNITTESTS_FRONTEND_FRONTENDTESTUTIL_H
