//===- Parser.h - Simit parser ----------------------------------*- C++ -*-===//
//
// Recursive-descent parser for the grammar of language.md section 3. On a
// syntax error it reports `expected ...` and skips to `;`, `end` or the next
// top-level keyword, so one run reports every independent error.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_PARSER_H
#define SIMIT_FRONTEND_PARSER_H

#include "simit/Frontend/AST.h"
#include "simit/Frontend/Diagnostics.h"

#include "llvm/ADT/StringRef.h"

#include <memory>
#include <set>
#include <string>

namespace simit::frontend {

/// Parses a whole program from `source` (a buffer of the engine's SourceMgr).
std::unique_ptr<Program> parse(llvm::StringRef source, DiagnosticEngine &diags);

/// Parses one function declaration spanning exactly `source` (used to build
/// a fresh copy of a generic function for each instance). `knownFunctions`
/// are the function names visible to it (for the generic-call lookahead).
std::unique_ptr<FuncDecl>
parseFunction(llvm::StringRef source, DiagnosticEngine &diags,
              const std::set<std::string> &knownFunctions);

/// The names of the intrinsic functions (language.md section 9).
const std::set<std::string> &intrinsicNames();

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_PARSER_H
