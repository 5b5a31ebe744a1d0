//===- Lexer.cpp - Simit lexer --------------------------------------------===//

#include "simit/Frontend/Lexer.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSwitch.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

using namespace simit::frontend;
using llvm::SMLoc;
using llvm::StringRef;

StringRef simit::frontend::tokenKindName(TokenKind kind) {
  switch (kind) {
  case TokenKind::Eof: return "end of file";
  case TokenKind::Error: return "an invalid token";
  case TokenKind::Ident: return "an identifier";
  case TokenKind::IntLit: return "an integer literal";
  case TokenKind::FloatLit: return "a float literal";
  case TokenKind::StringLit: return "a string literal";
  case TokenKind::TestStart: return "'%!'";
  case TokenKind::TestEnd: return "the end of the test line";
  case TokenKind::KwAnd: return "'and'";
  case TokenKind::KwApply: return "'apply'";
  case TokenKind::KwBool: return "'bool'";
  case TokenKind::KwComplex: return "'complex'";
  case TokenKind::KwConst: return "'const'";
  case TokenKind::KwDelete: return "'delete'";
  case TokenKind::KwDo: return "'do'";
  case TokenKind::KwElement: return "'element'";
  case TokenKind::KwElif: return "'elif'";
  case TokenKind::KwElse: return "'else'";
  case TokenKind::KwEnd: return "'end'";
  case TokenKind::KwExport: return "'export'";
  case TokenKind::KwExtern: return "'extern'";
  case TokenKind::KwFalse: return "'false'";
  case TokenKind::KwFloat: return "'float'";
  case TokenKind::KwFor: return "'for'";
  case TokenKind::KwFunc: return "'func'";
  case TokenKind::KwGrid: return "'grid'";
  case TokenKind::KwIf: return "'if'";
  case TokenKind::KwIn: return "'in'";
  case TokenKind::KwInout: return "'inout'";
  case TokenKind::KwInt: return "'int'";
  case TokenKind::KwIvar: return "'ivar'";
  case TokenKind::KwMap: return "'map'";
  case TokenKind::KwMatrix: return "'matrix'";
  case TokenKind::KwNew: return "'new'";
  case TokenKind::KwNot: return "'not'";
  case TokenKind::KwOpaque: return "'opaque'";
  case TokenKind::KwOr: return "'or'";
  case TokenKind::KwPrint: return "'print'";
  case TokenKind::KwPrintln: return "'println'";
  case TokenKind::KwReduce: return "'reduce'";
  case TokenKind::KwReturn: return "'return'";
  case TokenKind::KwSet: return "'set'";
  case TokenKind::KwString: return "'string'";
  case TokenKind::KwTensor: return "'tensor'";
  case TokenKind::KwThrough: return "'through'";
  case TokenKind::KwTo: return "'to'";
  case TokenKind::KwTrue: return "'true'";
  case TokenKind::KwVar: return "'var'";
  case TokenKind::KwVector: return "'vector'";
  case TokenKind::KwWhile: return "'while'";
  case TokenKind::KwWith: return "'with'";
  case TokenKind::KwXor: return "'xor'";
  case TokenKind::LParen: return "'('";
  case TokenKind::RParen: return "')'";
  case TokenKind::LBracket: return "'['";
  case TokenKind::RBracket: return "']'";
  case TokenKind::LBrace: return "'{'";
  case TokenKind::RBrace: return "'}'";
  case TokenKind::Comma: return "','";
  case TokenKind::Semi: return "';'";
  case TokenKind::Colon: return "':'";
  case TokenKind::Dot: return "'.'";
  case TokenKind::Arrow: return "'->'";
  case TokenKind::Assign: return "'='";
  case TokenKind::Eq: return "'=='";
  case TokenKind::Ne: return "'!='";
  case TokenKind::Lt: return "'<'";
  case TokenKind::Gt: return "'>'";
  case TokenKind::Le: return "'<='";
  case TokenKind::Ge: return "'>='";
  case TokenKind::Plus: return "'+'";
  case TokenKind::Minus: return "'-'";
  case TokenKind::Star: return "'*'";
  case TokenKind::Slash: return "'/'";
  case TokenKind::Backslash: return "'\\'";
  case TokenKind::DotStar: return "'.*'";
  case TokenKind::DotSlash: return "'./'";
  case TokenKind::Caret: return "'^'";
  case TokenKind::Quote: return "'''";
  }
  return "a token";
}

std::optional<char> simit::frontend::decodeEscape(char e) {
  switch (e) {
  case 'a':
    return '\a';
  case 'b':
    return '\b';
  case 'f':
    return '\f';
  case 'n':
    return '\n';
  case 'r':
    return '\r';
  case 't':
    return '\t';
  case 'v':
    return '\v';
  case '\\':
  case '\'':
  case '"':
  case '?':
    return e;
  default:
    return std::nullopt;
  }
}

namespace {

TokenKind keywordKind(StringRef word) {
  return llvm::StringSwitch<TokenKind>(word)
      .Case("and", TokenKind::KwAnd)
      .Case("apply", TokenKind::KwApply)
      .Case("bool", TokenKind::KwBool)
      .Case("complex", TokenKind::KwComplex)
      .Case("const", TokenKind::KwConst)
      .Case("delete", TokenKind::KwDelete)
      .Case("do", TokenKind::KwDo)
      .Case("element", TokenKind::KwElement)
      .Case("elif", TokenKind::KwElif)
      .Case("else", TokenKind::KwElse)
      .Case("end", TokenKind::KwEnd)
      .Case("export", TokenKind::KwExport)
      .Case("extern", TokenKind::KwExtern)
      .Case("false", TokenKind::KwFalse)
      .Case("float", TokenKind::KwFloat)
      .Case("for", TokenKind::KwFor)
      .Case("func", TokenKind::KwFunc)
      .Case("grid", TokenKind::KwGrid)
      .Case("if", TokenKind::KwIf)
      .Case("in", TokenKind::KwIn)
      .Case("inout", TokenKind::KwInout)
      .Case("int", TokenKind::KwInt)
      .Case("ivar", TokenKind::KwIvar)
      .Case("map", TokenKind::KwMap)
      .Case("matrix", TokenKind::KwMatrix)
      .Case("new", TokenKind::KwNew)
      .Case("not", TokenKind::KwNot)
      .Case("opaque", TokenKind::KwOpaque)
      .Case("or", TokenKind::KwOr)
      .Case("print", TokenKind::KwPrint)
      .Case("println", TokenKind::KwPrintln)
      .Case("reduce", TokenKind::KwReduce)
      .Case("return", TokenKind::KwReturn)
      .Case("set", TokenKind::KwSet)
      .Case("string", TokenKind::KwString)
      .Case("tensor", TokenKind::KwTensor)
      .Case("through", TokenKind::KwThrough)
      .Case("to", TokenKind::KwTo)
      .Case("true", TokenKind::KwTrue)
      .Case("var", TokenKind::KwVar)
      .Case("vector", TokenKind::KwVector)
      .Case("while", TokenKind::KwWhile)
      .Case("with", TokenKind::KwWith)
      .Case("xor", TokenKind::KwXor)
      .Default(TokenKind::Ident);
}

class Lexer {
public:
  Lexer(StringRef buffer, DiagnosticEngine &diags)
      : buffer(buffer), diags(diags) {}

  std::vector<Token> run();

private:
  char peek(size_t ahead = 0) const {
    return pos + ahead < buffer.size() ? buffer[pos + ahead] : '\0';
  }
  bool atEnd() const { return pos >= buffer.size(); }
  SMLoc locAt(size_t offset) const {
    return SMLoc::getFromPointer(buffer.data() + offset);
  }
  void push(TokenKind kind, size_t start) {
    Token token;
    token.kind = kind;
    token.text = buffer.slice(start, pos);
    tokens.push_back(std::move(token));
  }
  void skipLineComment() {
    while (!atEnd() && peek() != '\n' && peek() != '\r')
      ++pos;
  }
  void lexPercent();
  void lexNumber();
  void lexString();
  void lexOperator();
  void endLine();

  StringRef buffer;
  DiagnosticEngine &diags;
  size_t pos = 0;
  bool inTestLine = false;
  size_t testLineStart = 0;
  std::vector<Token> tokens;
};

std::vector<Token> Lexer::run() {
  while (!atEnd()) {
    char c = peek();
    if (c == '\n' || c == '\r') {
      endLine();
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\v' || c == '\f') {
      ++pos;
      continue;
    }
    if (c == '%') {
      lexPercent();
      continue;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      size_t start = pos;
      while (std::isalnum(static_cast<unsigned char>(peek())) || peek() == '_')
        ++pos;
      push(keywordKind(buffer.slice(start, pos)), start);
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c))) {
      lexNumber();
      continue;
    }
    if (c == '"') {
      lexString();
      continue;
    }
    lexOperator();
  }
  if (inTestLine) {
    diags.error(locAt(testLineStart), "unclosed test: a test line must end "
                                      "with a line break");
    inTestLine = false;
  }
  Token eof;
  eof.kind = TokenKind::Eof;
  eof.text = buffer.substr(buffer.size());
  tokens.push_back(eof);
  return std::move(tokens);
}

void Lexer::endLine() {
  size_t start = pos;
  if (peek() == '\r' && peek(1) == '\n')
    pos += 2;
  else
    ++pos;
  if (inTestLine) {
    inTestLine = false;
    push(TokenKind::TestEnd, start);
  }
}

void Lexer::lexPercent() {
  size_t start = pos;
  char next = peek(1);
  if (next == '!') {
    pos += 2;
    if (inTestLine) {
      diags.error(locAt(start), "unexpected '%!' inside a test line");
      push(TokenKind::Error, start);
      return;
    }
    push(TokenKind::TestStart, start);
    inTestLine = true;
    testLineStart = start;
    return;
  }
  if (next == '{') {
    pos += 2;
    while (!atEnd() && !(peek() == '%' && peek(1) == '}'))
      ++pos;
    if (atEnd()) {
      diags.error(locAt(start), "unclosed comment");
      return;
    }
    pos += 2;
    return;
  }
  if (next == '}') {
    pos += 2;
    diags.error(locAt(start), "unexpected '%}' outside a block comment");
    push(TokenKind::Error, start);
    return;
  }
  skipLineComment();
}

void Lexer::lexNumber() {
  size_t start = pos;
  auto digits = [&] {
    while (std::isdigit(static_cast<unsigned char>(peek())))
      ++pos;
  };
  digits();
  bool isFloat = false;
  if (peek() == '.' && peek(1) != '*' && peek(1) != '/') {
    if (!std::isdigit(static_cast<unsigned char>(peek(1)))) {
      ++pos;
      diags.error(locAt(start), "expected digits after '.' in a float "
                                "literal");
      push(TokenKind::Error, start);
      return;
    }
    ++pos;
    digits();
    isFloat = true;
  }
  if (peek() == 'e' || peek() == 'E') {
    size_t expStart = pos;
    ++pos;
    if (peek() == '+' || peek() == '-')
      ++pos;
    if (!std::isdigit(static_cast<unsigned char>(peek()))) {
      diags.error(locAt(expStart), "expected digits in the exponent of a "
                                   "float literal");
      push(TokenKind::Error, start);
      return;
    }
    digits();
    isFloat = true;
  }
  if (std::isalpha(static_cast<unsigned char>(peek())) || peek() == '_') {
    while (std::isalnum(static_cast<unsigned char>(peek())) || peek() == '_')
      ++pos;
    diags.error(locAt(start), "invalid numeric literal '" +
                                  buffer.slice(start, pos) + "'");
    push(TokenKind::Error, start);
    return;
  }
  std::string spelling = buffer.slice(start, pos).str();
  if (isFloat) {
    push(TokenKind::FloatLit, start);
    double value = std::strtod(spelling.c_str(), nullptr);
    if (std::isinf(value)) {
      diags.error(locAt(start), "float literal '" + spelling +
                                    "' is too large for a 64-bit float");
      value = 0;
    }
    tokens.back().floatValue = value;
    return;
  }
  push(TokenKind::IntLit, start);
  errno = 0;
  unsigned long long value = std::strtoull(spelling.c_str(), nullptr, 10);
  // The magnitude 2^31 is allowed so that `-2147483648` folds; anything
  // larger cannot be a 32-bit int.
  if (errno == ERANGE || value > 2147483648ULL) {
    diags.error(locAt(start), "integer literal '" + spelling +
                                  "' does not fit in 32 bits");
    value = 0;
  }
  if (spelling.size() > 1 && spelling[0] == '0')
    diags.warning(locAt(start), "integer literal with a leading zero is "
                                "read as decimal");
  tokens.back().intValue = static_cast<int64_t>(value);
}

void Lexer::lexString() {
  size_t start = pos;
  ++pos;
  std::string value;
  bool ok = true;
  while (true) {
    if (atEnd()) {
      diags.error(locAt(start), "unclosed string literal");
      push(TokenKind::Error, start);
      return;
    }
    char c = peek();
    if (c == '"') {
      ++pos;
      break;
    }
    // CR LF is one line break (language.md §2), in strings too.
    if (c == '\r' && peek(1) == '\n') {
      value += '\n';
      pos += 2;
      continue;
    }
    if (c != '\\') {
      value += c;
      ++pos;
      continue;
    }
    char e = peek(1);
    std::optional<char> decoded = decodeEscape(e);
    if (!decoded) {
      diags.error(locAt(pos), "unrecognized escape sequence '\\" +
                                  (e ? std::string(1, e) : std::string()) +
                                  "' in a string literal");
      ok = false;
    }
    value += decoded.value_or(e);
    pos += e ? 2 : 1;
  }
  push(ok ? TokenKind::StringLit : TokenKind::Error, start);
  tokens.back().stringValue = std::move(value);
}

void Lexer::lexOperator() {
  size_t start = pos;
  char c = peek();
  char n = peek(1);
  auto one = [&](TokenKind kind) {
    ++pos;
    push(kind, start);
  };
  auto two = [&](TokenKind kind) {
    pos += 2;
    push(kind, start);
  };
  switch (c) {
  case '(': return one(TokenKind::LParen);
  case ')': return one(TokenKind::RParen);
  case '[': return one(TokenKind::LBracket);
  case ']': return one(TokenKind::RBracket);
  case '{': return one(TokenKind::LBrace);
  case '}': return one(TokenKind::RBrace);
  case ',': return one(TokenKind::Comma);
  case ';': return one(TokenKind::Semi);
  case ':': return one(TokenKind::Colon);
  case '+': return one(TokenKind::Plus);
  case '*': return one(TokenKind::Star);
  case '/': return one(TokenKind::Slash);
  case '\\': return one(TokenKind::Backslash);
  case '^': return one(TokenKind::Caret);
  case '\'': return one(TokenKind::Quote);
  case '-': return n == '>' ? two(TokenKind::Arrow) : one(TokenKind::Minus);
  case '=': return n == '=' ? two(TokenKind::Eq) : one(TokenKind::Assign);
  case '<': return n == '=' ? two(TokenKind::Le) : one(TokenKind::Lt);
  case '>': return n == '=' ? two(TokenKind::Ge) : one(TokenKind::Gt);
  case '.':
    if (n == '*')
      return two(TokenKind::DotStar);
    if (n == '/')
      return two(TokenKind::DotSlash);
    if (std::isdigit(static_cast<unsigned char>(n))) {
      ++pos;
      while (std::isdigit(static_cast<unsigned char>(peek())))
        ++pos;
      diags.error(locAt(start), "expected digits before '.' in a float "
                                "literal");
      push(TokenKind::Error, start);
      return;
    }
    return one(TokenKind::Dot);
  case '!':
    if (n == '=')
      return two(TokenKind::Ne);
    break;
  default:
    break;
  }
  ++pos;
  std::string shown = std::isprint(static_cast<unsigned char>(c))
                          ? std::string(1, c)
                          : "\\x" + llvm::utohexstr(
                                        static_cast<unsigned char>(c));
  diags.error(locAt(start), "unexpected symbol '" + shown + "'");
  push(TokenKind::Error, start);
}

} // namespace

std::vector<Token> simit::frontend::lex(StringRef buffer,
                                        DiagnosticEngine &diags) {
  return Lexer(buffer, diags).run();
}
