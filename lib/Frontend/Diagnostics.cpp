//===- Diagnostics.cpp - Positioned frontend diagnostics ------------------===//

#include "simit/Frontend/Diagnostics.h"

#include <algorithm>

using namespace simit::frontend;

void DiagnosticEngine::error(llvm::SMLoc loc, const llvm::Twine &message) {
  diagnostics.push_back({loc, llvm::SourceMgr::DK_Error, message.str()});
  ++numErrors;
}

void DiagnosticEngine::warning(llvm::SMLoc loc, const llvm::Twine &message) {
  diagnostics.push_back({loc, llvm::SourceMgr::DK_Warning, message.str()});
}

std::vector<Diagnostic> DiagnosticEngine::sorted() const {
  std::vector<Diagnostic> result = diagnostics;
  std::stable_sort(result.begin(), result.end(),
                   [](const Diagnostic &a, const Diagnostic &b) {
                     return a.loc.getPointer() < b.loc.getPointer();
                   });
  auto same = [](const Diagnostic &a, const Diagnostic &b) {
    return a.loc == b.loc && a.kind == b.kind && a.message == b.message;
  };
  std::vector<Diagnostic> unique;
  for (const Diagnostic &d : result) {
    bool seen = false;
    for (auto it = unique.rbegin(); it != unique.rend() && it->loc == d.loc;
         ++it)
      seen |= same(*it, d);
    if (!seen)
      unique.push_back(d);
  }
  return unique;
}

void DiagnosticEngine::print(llvm::raw_ostream &os) const {
  for (const Diagnostic &d : sorted())
    sourceMgr.PrintMessage(os, d.loc, d.kind, d.message);
}

std::pair<unsigned, unsigned>
DiagnosticEngine::lineAndColumn(llvm::SMLoc loc) const {
  return sourceMgr.getLineAndColumn(loc);
}
