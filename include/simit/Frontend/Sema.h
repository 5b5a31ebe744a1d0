//===- Sema.h - Simit semantic analysis -------------------------*- C++ -*-===//
//
// Checks a parsed program against language.md sections 4-10 and resolves it
// in place (see AST.h). Errors go to the DiagnosticEngine; the result says
// whether the program is legal.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_SEMA_H
#define SIMIT_FRONTEND_SEMA_H

#include "simit/Frontend/AST.h"
#include "simit/Frontend/Diagnostics.h"

namespace simit::frontend {

/// Type-checks `program`; returns true when no error was found.
bool check(Program &program, DiagnosticEngine &diags);

/// Is `e` a literal (after folding unary `-`/`+` and `'`)?
bool isLiteral(const Expr &e);

/// Which intrinsic a function declaration is (None for user functions).
Intrinsic intrinsicOf(const FuncDecl &func);

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_SEMA_H
