//===- Lexer.h - Simit tokens and lexer -------------------------*- C++ -*-===//
//
// Turns a buffer into tokens (language.md section 2). Comments vanish; a `%!`
// test line becomes TestStart ... TestEnd around its tokens.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_LEXER_H
#define SIMIT_FRONTEND_LEXER_H

#include "simit/Frontend/Diagnostics.h"

#include "llvm/ADT/StringRef.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace simit::frontend {

enum class TokenKind {
  Eof,
  Error, // an unlexable piece, already diagnosed
  Ident,
  IntLit,
  FloatLit,
  StringLit,
  TestStart, // "%!"
  TestEnd,   // the line break ending a test line
  // Keywords.
  KwAnd, KwApply, KwBool, KwComplex, KwConst, KwDelete, KwDo, KwElement,
  KwElif, KwElse, KwEnd, KwExport, KwExtern, KwFalse, KwFloat, KwFor, KwFunc,
  KwGrid, KwIf, KwIn, KwInout, KwInt, KwIvar, KwMap, KwMatrix, KwNew, KwNot,
  KwOpaque, KwOr, KwPrint, KwPrintln, KwReduce, KwReturn, KwSet, KwString,
  KwTensor, KwThrough, KwTo, KwTrue, KwVar, KwVector, KwWhile, KwWith, KwXor,
  // Punctuation and operators.
  LParen, RParen, LBracket, RBracket, LBrace, RBrace, Comma, Semi, Colon, Dot,
  Arrow, Assign, Eq, Ne, Lt, Gt, Le, Ge, Plus, Minus, Star, Slash, Backslash,
  DotStar, DotSlash, Caret, Quote,
};

/// The spelling used in diagnostics, e.g. "';'" or "an identifier".
llvm::StringRef tokenKindName(TokenKind kind);

struct Token {
  TokenKind kind = TokenKind::Eof;
  llvm::StringRef text; // the source spelling
  int64_t intValue = 0;
  double floatValue = 0.0;
  std::string stringValue; // decoded string literal

  llvm::SMLoc loc() const { return llvm::SMLoc::getFromPointer(text.data()); }
  bool is(TokenKind k) const { return kind == k; }
  bool isKeyword() const {
    return kind >= TokenKind::KwAnd && kind <= TokenKind::KwXor;
  }
};

/// The character the escape sequence `\\e` of a string literal stands for
/// (C's simple escapes), or none when `e` does not start one.
std::optional<char> decodeEscape(char e);

/// Lexes the whole buffer; the last token is Eof. Errors go to `diags`.
std::vector<Token> lex(llvm::StringRef buffer, DiagnosticEngine &diags);

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_LEXER_H
