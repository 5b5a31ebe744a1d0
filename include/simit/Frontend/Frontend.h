//===- Frontend.h - Simit frontend entry points -----------------*- C++ -*-===//
//
// parseProgram + checkProgram turn a .sim buffer into a checked AST;
// splitSections implements the `%%%` test-file convention (language.md 11).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_FRONTEND_H
#define SIMIT_FRONTEND_FRONTEND_H

#include "simit/Frontend/AST.h"
#include "simit/Frontend/Diagnostics.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SourceMgr.h"

#include <memory>
#include <string>
#include <vector>

namespace simit::frontend {

/// Parses buffer `bufferId` of `sourceMgr`. Never returns null; syntax errors
/// are reported to `diags` and the program holds what could be parsed.
std::unique_ptr<Program> parseProgram(llvm::SourceMgr &sourceMgr,
                                      unsigned bufferId,
                                      DiagnosticEngine &diags);

/// Type-checks and resolves `program`; true when it is legal.
bool checkProgram(Program &program, DiagnosticEngine &diags);

/// One `%%%` section of a test file (or the whole file when unsectioned).
struct Section {
  llvm::StringRef text;  // from the `%%%` line to the next one
  std::string name;      // trimmed header text
  bool disabled = false; // header starts with `%%%-`
  unsigned index = 0;    // 0-based position in the file
  unsigned firstLine = 1; // line of the header in the file
};

/// Splits `source` at lines starting with `%%%` when the text begins with
/// `%%%`; otherwise returns one enabled section holding everything.
std::vector<Section> splitSections(llvm::StringRef source);

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_FRONTEND_H
