//===- Diagnostics.h - Positioned frontend diagnostics ----------*- C++ -*-===//
//
// Collects errors and warnings with their source positions and prints them
// sorted by position as `file:line:col: error: msg`, the source line and a
// caret (llvm::SourceMgr does the formatting).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_DIAGNOSTICS_H
#define SIMIT_FRONTEND_DIAGNOSTICS_H

#include "llvm/Support/SMLoc.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

#include <string>
#include <vector>

namespace simit::frontend {

struct Diagnostic {
  llvm::SMLoc loc;
  llvm::SourceMgr::DiagKind kind;
  std::string message;
};

class DiagnosticEngine {
public:
  explicit DiagnosticEngine(llvm::SourceMgr &sourceMgr) : sourceMgr(sourceMgr) {}

  void error(llvm::SMLoc loc, const llvm::Twine &message);
  void warning(llvm::SMLoc loc, const llvm::Twine &message);

  unsigned errorCount() const { return numErrors; }
  bool hasErrors() const { return numErrors != 0; }

  /// The diagnostics sorted by position (errors at one position keep their
  /// order); an identical diagnostic reported twice (e.g. by a generic body
  /// and one of its instances) appears once.
  std::vector<Diagnostic> sorted() const;

  /// Prints sorted() through the source manager.
  void print(llvm::raw_ostream &os) const;

  /// Line and column of a location, 1-based.
  std::pair<unsigned, unsigned> lineAndColumn(llvm::SMLoc loc) const;

  llvm::SourceMgr &getSourceMgr() const { return sourceMgr; }

private:
  llvm::SourceMgr &sourceMgr;
  std::vector<Diagnostic> diagnostics;
  unsigned numErrors = 0;
};

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_DIAGNOSTICS_H
