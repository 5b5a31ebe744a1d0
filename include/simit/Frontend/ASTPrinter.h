//===- ASTPrinter.h - Readable dump of a checked AST ------------*- C++ -*-===//
//
// One line per declaration and statement; expressions as s-expressions that
// show how sema resolved them, each ending with its type (`: T`).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_ASTPRINTER_H
#define SIMIT_FRONTEND_ASTPRINTER_H

#include "simit/Frontend/AST.h"

#include "llvm/Support/raw_ostream.h"

namespace simit::frontend {

void printProgram(const Program &program, llvm::raw_ostream &os);
void printExpr(const Expr &expr, llvm::raw_ostream &os);

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_ASTPRINTER_H
