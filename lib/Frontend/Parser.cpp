//===- Parser.cpp - Simit parser ------------------------------------------===//
//
// Syntax errors unwind to the nearest recovery point (statement, top-level
// declaration or test line) through a private exception, which keeps the
// grammar code free of error plumbing; nothing escapes this file.
//
//===----------------------------------------------------------------------===//

#include "simit/Frontend/Parser.h"
#include "simit/Frontend/Lexer.h"

using namespace simit::frontend;
using llvm::SMLoc;
using llvm::StringRef;
using TK = TokenKind;

const std::set<std::string> &simit::frontend::intrinsicNames() {
  static const std::set<std::string> names = {
      "mod", "sin", "cos", "tan", "asin", "acos", "sqrt", "cbrt", "log",
      "exp", "abs", "atan2", "pow", "max", "min", "det", "det2", "det4",
      "inv", "inv2", "inv4", "cross", "norm", "dot", "lu", "chol", "lusolve",
      "lltsolve", "lumatsolve", "lltmatsolve", "lufree", "cholfree",
      "triangularSolve", "createComplex", "complexNorm", "complexGetReal",
      "complexGetImag", "complexConj", "clock", "storeTime"};
  return names;
}

namespace {

/// Thrown after a syntax error has been reported.
struct SyntaxError {};

/// Deep nesting is reported rather than allowed to exhaust the stack.
constexpr unsigned kMaxNesting = 200;
/// Chains of operators (`a + a + ...`, `v''...`) build tall trees without
/// nesting in the parser; the walks over them recurse on the height.
constexpr unsigned kMaxHeight = 1000;

/// Calls `f` on each operand of `e` (its direct subexpressions).
void forEachOperand(const Expr &e, llvm::function_ref<void(const Expr &)> f) {
  auto each = [&](const std::vector<ExprPtr> &list) {
    for (const ExprPtr &operand : list)
      if (operand)
        f(*operand);
  };
  if (auto *call = llvm::dyn_cast<CallExpr>(&e)) {
    each(call->args);
  } else if (auto *read = llvm::dyn_cast<ReadExpr>(&e)) {
    f(*read->base);
    each(read->indices);
  } else if (auto *field = llvm::dyn_cast<FieldExpr>(&e)) {
    f(*field->base);
  } else if (auto *setRead = llvm::dyn_cast<SetReadExpr>(&e)) {
    f(*setRead->base);
    each(setRead->offsets);
    each(setRead->directions);
  } else if (auto *unary = llvm::dyn_cast<UnaryExpr>(&e)) {
    f(*unary->operand);
  } else if (auto *binary = llvm::dyn_cast<BinaryExpr>(&e)) {
    f(*binary->lhs);
    f(*binary->rhs);
  } else if (auto *compare = llvm::dyn_cast<CompareExpr>(&e)) {
    each(compare->operands);
  } else if (auto *transpose = llvm::dyn_cast<TransposeExpr>(&e)) {
    f(*transpose->operand);
  } else if (auto *map = llvm::dyn_cast<MapExpr>(&e)) {
    each(map->args);
  }
}

class Parser {
public:
  Parser(StringRef source, DiagnosticEngine &diags,
         std::set<std::string> knownFunctions)
      : source(source), diags(diags), tokens(lex(source, diags)),
        knownFunctions(std::move(knownFunctions)) {}

  std::unique_ptr<Program> parseProgram();
  std::unique_ptr<FuncDecl> parseSingleFunction();

private:
  // Token access.
  const Token &tok(size_t ahead = 0) const {
    size_t i = pos + ahead;
    return i < tokens.size() ? tokens[i] : tokens.back();
  }
  bool is(TK kind, size_t ahead = 0) const { return tok(ahead).kind == kind; }
  const Token &take() {
    const Token &t = tok();
    if (pos < tokens.size() - 1)
      ++pos;
    return t;
  }
  bool accept(TK kind) {
    if (!is(kind))
      return false;
    take();
    return true;
  }
  [[noreturn]] void fail(SMLoc loc, const llvm::Twine &message) {
    diags.error(loc, message);
    throw SyntaxError();
  }
  [[noreturn]] void expected(const llvm::Twine &what) {
    // Error tokens were diagnosed by the lexer; do not pile on.
    if (is(TK::Error)) {
      throw SyntaxError();
    }
    fail(tok().loc(), "expected " + what + ", found " + describe(tok()));
  }
  std::string describe(const Token &t) const {
    if (t.is(TK::Ident))
      return "'" + t.text.str() + "'";
    if (t.is(TK::IntLit) || t.is(TK::FloatLit))
      return "'" + t.text.str() + "'";
    return tokenKindName(t.kind).str();
  }
  const Token &expect(TK kind) {
    if (!is(kind))
      expected(tokenKindName(kind));
    return take();
  }
  std::string expectIdent(const char *what = "an identifier") {
    if (!is(TK::Ident))
      expected(what);
    return take().text.str();
  }

  /// Sets the height of a new node from its operands'; a tree taller than
  /// kMaxHeight is an error at the node's operator.
  template <typename T> std::unique_ptr<T> measured(std::unique_ptr<T> expr,
                                                    SMLoc at) {
    forEachOperand(*expr, [&](const Expr &operand) {
      expr->height = std::max(expr->height, operand.height + 1);
    });
    if (expr->height > kMaxHeight)
      fail(at, "expression nested too deeply (more than " +
                   llvm::Twine(kMaxHeight) + " operators on one path)");
    return expr;
  }

  struct NestingGuard {
    explicit NestingGuard(Parser &p) : p(p) {
      if (++p.nesting > kMaxNesting)
        p.fail(p.tok().loc(), "expression or block nested too deeply");
    }
    ~NestingGuard() { --p.nesting; }
    Parser &p;
  };

  // Recovery.
  static bool isTopLevelStart(TK kind) {
    return kind == TK::KwElement || kind == TK::KwExtern ||
           kind == TK::KwFunc || kind == TK::KwExport ||
           kind == TK::TestStart || kind == TK::Eof;
  }
  void recoverTopLevel();
  void recoverStatement();

  // Declarations.
  void parseTopLevel(Program &program);
  std::unique_ptr<ElementDecl> parseElement();
  std::unique_ptr<VarDecl> parseExtern();
  std::unique_ptr<VarDecl> parseConst(VarDecl::Role role);
  std::unique_ptr<FuncDecl> parseFunc(const char *begin, bool isExport,
                                      bool isExtern);
  void parseGenerics(FuncDecl &func);
  void parseParams(FuncDecl &func);
  void parseResults(FuncDecl &func);
  void parseTestLine(Program &program);

  // Types.
  std::unique_ptr<TypeExpr> parseType();
  std::unique_ptr<TypeExpr> parseTensorType();
  std::unique_ptr<TypeExpr> parseTensorForm(TK keyword);
  DimExpr parseDim();
  std::vector<DimExpr> parseGenericArgs();

  // Statements.
  std::unique_ptr<Block> parseBlock();
  StmtPtr parseStmt();
  StmtPtr parseVarDecl();
  StmtPtr parseIf();
  StmtPtr parseFor();
  StmtPtr parsePrint();
  StmtPtr parseApply();
  StmtPtr parseExprStmt();

  // Expressions.
  ExprPtr parseExpr();
  std::unique_ptr<MapExpr> parseMapBody(SMLoc loc, bool allowReduce);
  ExprPtr parseOr();
  ExprPtr parseAnd();
  ExprPtr parseXor();
  ExprPtr parseCompare();
  ExprPtr parseTerm();
  ExprPtr parseAdd();
  ExprPtr parseMul();
  ExprPtr parseUnary();
  ExprPtr parsePow();
  ExprPtr parsePostfix();
  ExprPtr parsePrimary();
  ExprPtr parseReadArgs(ExprPtr base);
  ExprPtr parseComplexLiteral();
  ExprPtr parseDenseLiteral();
  void parseDense(DenseLiteral &lit, std::vector<int64_t> &shape,
                  bool &kindKnown);
  void appendSignedLiteral(DenseLiteral &lit, bool &kindKnown);
  std::vector<ExprPtr> parseExprList(TK close);
  bool looksLikeGenericCall() const;

  StringRef source;
  DiagnosticEngine &diags;
  std::vector<Token> tokens;
  size_t pos = 0;
  unsigned nesting = 0;
  std::set<std::string> knownFunctions;
};

//===----------------------------------------------------------------------===//
// Recovery
//===----------------------------------------------------------------------===//

void Parser::recoverTopLevel() {
  // Always make progress, then skip to something that starts a declaration.
  take();
  while (!isTopLevelStart(tok().kind) && !is(TK::KwConst))
    take();
}

void Parser::recoverStatement() {
  while (true) {
    TK k = tok().kind;
    if (k == TK::Semi) {
      take();
      return;
    }
    if (k == TK::KwEnd || k == TK::KwElif || k == TK::KwElse ||
        k == TK::KwElement || k == TK::KwExtern || k == TK::KwFunc ||
        k == TK::KwExport || k == TK::Eof || k == TK::TestEnd)
      return;
    take();
  }
}

//===----------------------------------------------------------------------===//
// Declarations
//===----------------------------------------------------------------------===//

std::unique_ptr<Program> Parser::parseProgram() {
  auto program = std::make_unique<Program>();
  while (!is(TK::Eof)) {
    size_t start = pos;
    try {
      parseTopLevel(*program);
    } catch (SyntaxError &) {
      if (pos == start || !isTopLevelStart(tok().kind))
        recoverTopLevel();
    }
  }
  return program;
}

std::unique_ptr<FuncDecl> Parser::parseSingleFunction() {
  try {
    const char *begin = tok().text.data();
    bool isExport = accept(TK::KwExport);
    return parseFunc(begin, isExport, /*isExtern=*/false);
  } catch (SyntaxError &) {
    return nullptr;
  }
}

void Parser::parseTopLevel(Program &program) {
  switch (tok().kind) {
  case TK::KwElement: {
    auto element = parseElement();
    program.order.push_back(element.get());
    program.elements.push_back(std::move(element));
    return;
  }
  case TK::KwExtern:
    if (is(TK::KwFunc, 1)) {
      const char *begin = take().text.data();
      auto func = parseFunc(begin, false, true);
      program.order.push_back(func.get());
      program.funcs.push_back(std::move(func));
      return;
    } else {
      auto var = parseExtern();
      program.order.push_back(var.get());
      program.globals.push_back(std::move(var));
      return;
    }
  case TK::KwConst: {
    auto var = parseConst(VarDecl::Role::GlobalConst);
    program.order.push_back(var.get());
    program.globals.push_back(std::move(var));
    return;
  }
  case TK::KwExport:
  case TK::KwFunc: {
    const char *begin = tok().text.data();
    bool isExport = accept(TK::KwExport);
    if (!is(TK::KwFunc))
      expected("'func'");
    auto func = parseFunc(begin, isExport, false);
    program.order.push_back(func.get());
    program.funcs.push_back(std::move(func));
    return;
  }
  case TK::TestStart:
    parseTestLine(program);
    return;
  default:
    expected("a program element (element, extern, const, func or a test)");
  }
}

std::unique_ptr<ElementDecl> Parser::parseElement() {
  take();
  SMLoc nameLoc = tok().loc();
  auto element = std::make_unique<ElementDecl>(expectIdent(), nameLoc);
  while (!is(TK::KwEnd)) {
    ElementDecl::Field field;
    field.loc = tok().loc();
    field.name = expectIdent("a field name or 'end'");
    expect(TK::Colon);
    field.typeExpr = parseTensorType();
    expect(TK::Semi);
    element->fields.push_back(std::move(field));
  }
  take();
  return element;
}

std::unique_ptr<VarDecl> Parser::parseExtern() {
  take();
  if (is(TK::KwInout))
    fail(tok().loc(), "'inout' is not allowed on an extern");
  SMLoc nameLoc = tok().loc();
  auto var = std::make_unique<VarDecl>(VarDecl::Role::Extern,
                                       expectIdent(), nameLoc);
  expect(TK::Colon);
  var->typeExpr = parseType();
  expect(TK::Semi);
  return var;
}

std::unique_ptr<VarDecl> Parser::parseConst(VarDecl::Role role) {
  take();
  SMLoc nameLoc = tok().loc();
  auto var = std::make_unique<VarDecl>(role, expectIdent(), nameLoc);
  if (accept(TK::Colon))
    var->typeExpr = parseTensorType();
  expect(TK::Assign);
  var->init = parseExpr();
  expect(TK::Semi);
  return var;
}

std::unique_ptr<FuncDecl> Parser::parseFunc(const char *begin, bool isExport,
                                            bool isExtern) {
  expect(TK::KwFunc);
  SMLoc nameLoc = tok().loc();
  auto func = std::make_unique<FuncDecl>(expectIdent("a function name"),
                                         nameLoc);
  func->isExport = isExport;
  func->isExtern = isExtern;
  // The function is known (for generic-call lookahead) from here on, which
  // lets a recursive call be reported by sema rather than as a syntax error.
  knownFunctions.insert(func->name);
  if (is(TK::Lt))
    parseGenerics(*func);
  parseParams(*func);
  if (is(TK::Arrow))
    parseResults(*func);
  if (isExtern) {
    expect(TK::Semi);
    return func;
  }
  func->body = parseBlock();
  const Token &end = expect(TK::KwEnd);
  const char *stop = end.text.data() + end.text.size();
  func->source = StringRef(begin, stop - begin);
  return func;
}

void Parser::parseGenerics(FuncDecl &func) {
  take();
  do {
    bool isRange = false;
    if (is(TK::IntLit)) {
      if (tok().intValue != 0 || !is(TK::Colon, 1))
        expected("an identifier or '0:'");
      take();
      take();
      isRange = true;
    }
    SMLoc loc = tok().loc();
    std::string name = expectIdent("an identifier or '0:'");
    func.generics.push_back(std::make_unique<GenericParamDecl>(
        name, loc, isRange, func.generics.size()));
  } while (accept(TK::Comma));
  expect(TK::Gt);
}

void Parser::parseParams(FuncDecl &func) {
  expect(TK::LParen);
  if (accept(TK::RParen))
    return;
  do {
    bool inout = accept(TK::KwInout);
    SMLoc loc = tok().loc();
    auto param = std::make_unique<VarDecl>(VarDecl::Role::Param,
                                           expectIdent("a parameter name"), loc);
    param->inout = inout;
    expect(TK::Colon);
    param->typeExpr = parseType();
    func.params.push_back(std::move(param));
  } while (accept(TK::Comma));
  expect(TK::RParen);
}

void Parser::parseResults(FuncDecl &func) {
  take();
  auto parseResult = [&] {
    if (is(TK::KwInout))
      fail(tok().loc(), "'inout' is not allowed on a result");
    SMLoc loc = tok().loc();
    auto result = std::make_unique<VarDecl>(VarDecl::Role::Result,
                                            expectIdent("a result name"), loc);
    expect(TK::Colon);
    result->typeExpr = parseType();
    func.results.push_back(std::move(result));
  };
  if (accept(TK::LParen)) {
    do
      parseResult();
    while (accept(TK::Comma));
    expect(TK::RParen);
  } else {
    parseResult();
  }
}

void Parser::parseTestLine(Program &program) {
  TestLine test;
  test.loc = take().loc();
  test.line = diags.lineAndColumn(test.loc).first;
  try {
    test.funcLoc = tok().loc();
    test.funcName = expectIdent("a function name");
    expect(TK::LParen);
    test.args = parseExprList(TK::RParen);
    expect(TK::RParen);
    expect(TK::Eq);
    test.expected = parseExpr();
    expect(TK::Semi);
    if (!is(TK::TestEnd) && !is(TK::Eof))
      expected("the end of the test line");
    accept(TK::TestEnd);
  } catch (SyntaxError &) {
    while (!is(TK::TestEnd) && !is(TK::Eof))
      take();
    accept(TK::TestEnd);
    return;
  }
  program.tests.push_back(std::move(test));
}

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

DimExpr Parser::parseDim() {
  DimExpr dim;
  dim.loc = tok().loc();
  if (is(TK::IntLit)) {
    dim.isInt = true;
    dim.value = take().intValue;
    return dim;
  }
  dim.name = expectIdent("an integer literal or an identifier");
  return dim;
}

std::vector<DimExpr> Parser::parseGenericArgs() {
  expect(TK::Lt);
  std::vector<DimExpr> args;
  do
    args.push_back(parseDim());
  while (accept(TK::Comma));
  expect(TK::Gt);
  return args;
}

static bool isScalarKeyword(TK kind) {
  return kind == TK::KwInt || kind == TK::KwFloat || kind == TK::KwBool ||
         kind == TK::KwComplex || kind == TK::KwString;
}

static ScalarKind scalarOf(TK kind) {
  switch (kind) {
  case TK::KwInt: return ScalarKind::Int;
  case TK::KwBool: return ScalarKind::Bool;
  case TK::KwComplex: return ScalarKind::Complex;
  case TK::KwString: return ScalarKind::String;
  default: return ScalarKind::Float;
  }
}

std::unique_ptr<TypeExpr> Parser::parseTensorType() {
  auto type = std::make_unique<TypeExpr>();
  type->loc = tok().loc();
  if (isScalarKeyword(tok().kind)) {
    type->kind = TypeExpr::Kind::Scalar;
    type->scalar = scalarOf(take().kind);
    return type;
  }
  if (is(TK::KwTensor) || is(TK::KwVector) || is(TK::KwMatrix)) {
    TK keyword = tok().kind;
    auto tensor = parseTensorForm(keyword);
    if (is(TK::Quote)) {
      if (keyword == TK::KwMatrix)
        fail(tok().loc(), "a matrix type cannot be transposed");
      take();
      tensor->transposed = true;
    }
    return tensor;
  }
  expected("a tensor type");
}

std::unique_ptr<TypeExpr> Parser::parseTensorForm(TK keyword) {
  NestingGuard guard(*this);
  auto type = std::make_unique<TypeExpr>();
  type->kind = TypeExpr::Kind::Tensor;
  type->loc = take().loc();
  type->keyword = keyword == TK::KwVector   ? TypeExpr::Keyword::Vector
                  : keyword == TK::KwMatrix ? TypeExpr::Keyword::Matrix
                                            : TypeExpr::Keyword::Tensor;
  if (accept(TK::LBracket)) {
    type->dims.push_back(parseDim());
    if (keyword == TK::KwMatrix) {
      expect(TK::Comma);
      type->dims.push_back(parseDim());
    } else if (keyword == TK::KwTensor) {
      while (accept(TK::Comma))
        type->dims.push_back(parseDim());
    }
    expect(TK::RBracket);
  }
  expect(TK::LParen);
  auto inner = std::make_unique<TypeExpr>();
  inner->loc = tok().loc();
  if (isScalarKeyword(tok().kind)) {
    inner->kind = TypeExpr::Kind::Scalar;
    inner->scalar = scalarOf(take().kind);
  } else if (is(keyword)) {
    inner = parseTensorForm(keyword);
  } else {
    expected(llvm::Twine("a component type or ") + tokenKindName(keyword));
  }
  type->block = std::move(inner);
  expect(TK::RParen);
  return type;
}

std::unique_ptr<TypeExpr> Parser::parseType() {
  auto type = std::make_unique<TypeExpr>();
  type->loc = tok().loc();
  switch (tok().kind) {
  case TK::Ident:
    type->kind = TypeExpr::Kind::Element;
    type->nameLoc = tok().loc();
    type->name = take().text.str();
    return type;
  case TK::KwOpaque:
    take();
    type->kind = TypeExpr::Kind::Opaque;
    return type;
  case TK::KwSet: {
    take();
    type->kind = TypeExpr::Kind::Set;
    expect(TK::LBrace);
    type->nameLoc = tok().loc();
    type->name = expectIdent("an element type name");
    expect(TK::RBrace);
    if (accept(TK::LParen)) {
      type->hasEndpoints = true;
      do {
        DimExpr endpoint;
        endpoint.loc = tok().loc();
        endpoint.name = expectIdent("a set name");
        type->endpoints.push_back(endpoint);
        if (type->endpoints.size() == 1 && is(TK::Star)) {
          take();
          type->repeatLoc = tok().loc();
          type->repeat = expect(TK::IntLit).intValue;
          break;
        }
      } while (accept(TK::Comma));
      expect(TK::RParen);
    }
    return type;
  }
  case TK::KwGrid: {
    take();
    type->kind = TypeExpr::Kind::Grid;
    expect(TK::LBracket);
    type->repeatLoc = tok().loc();
    type->repeat = expect(TK::IntLit).intValue;
    expect(TK::RBracket);
    expect(TK::LBrace);
    type->nameLoc = tok().loc();
    type->name = expectIdent("an element type name");
    expect(TK::RBrace);
    expect(TK::LParen);
    DimExpr points;
    points.loc = tok().loc();
    points.name = expectIdent("a set name");
    type->endpoints.push_back(points);
    expect(TK::RParen);
    return type;
  }
  case TK::LParen: {
    take();
    type->kind = TypeExpr::Kind::Tuple;
    SMLoc firstLoc = tok().loc();
    std::string first = expectIdent();
    if (accept(TK::Star)) {
      type->name = first;
      type->nameLoc = firstLoc;
      type->repeatLoc = tok().loc();
      type->repeat = expect(TK::IntLit).intValue;
      expect(TK::RParen);
      return type;
    }
    if (!is(TK::Colon))
      expected("'*' or ':'");
    take();
    type->memberNames.push_back(first);
    type->memberLocs.push_back(firstLoc);
    type->memberTypes.push_back(expectIdent("an element type name"));
    while (accept(TK::Comma)) {
      type->memberLocs.push_back(tok().loc());
      type->memberNames.push_back(expectIdent());
      expect(TK::Colon);
      type->memberTypes.push_back(expectIdent("an element type name"));
    }
    expect(TK::RParen);
    return type;
  }
  default:
    return parseTensorType();
  }
}

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

std::unique_ptr<Block> Parser::parseBlock() {
  NestingGuard guard(*this);
  auto block = std::make_unique<Block>();
  block->loc = tok().loc();
  while (true) {
    TK k = tok().kind;
    if (k == TK::KwEnd || k == TK::KwElif || k == TK::KwElse || k == TK::Eof)
      return block;
    // A new top-level declaration means this block was never closed.
    if (k == TK::KwElement || k == TK::KwExtern || k == TK::KwFunc ||
        k == TK::KwExport)
      expected("'end'");
    size_t start = pos;
    try {
      if (StmtPtr stmt = parseStmt())
        block->stmts.push_back(std::move(stmt));
    } catch (SyntaxError &) {
      recoverStatement();
      if (pos == start)
        take();
      if (is(TK::TestEnd))
        take();
    }
  }
}

StmtPtr Parser::parseStmt() {
  switch (tok().kind) {
  case TK::Semi:
    take();
    return nullptr;
  case TK::KwVar:
    return parseVarDecl();
  case TK::KwConst: {
    SMLoc loc = tok().loc();
    return std::make_unique<VarDeclStmt>(loc, parseConst(VarDecl::Role::Const));
  }
  case TK::KwIvar: {
    SMLoc loc = take().loc();
    SMLoc nameLoc = tok().loc();
    auto var = std::make_unique<VarDecl>(VarDecl::Role::IndexVar,
                                         expectIdent(), nameLoc);
    return std::make_unique<IVarDeclStmt>(loc, std::move(var));
  }
  case TK::KwIf:
    return parseIf();
  case TK::KwWhile: {
    auto stmt = std::make_unique<WhileStmt>(take().loc());
    stmt->condition = parseExpr();
    stmt->body = parseBlock();
    expect(TK::KwEnd);
    return stmt;
  }
  case TK::KwDo: {
    auto stmt = std::make_unique<DoWhileStmt>(take().loc());
    stmt->body = parseBlock();
    expect(TK::KwEnd);
    expect(TK::KwWhile);
    stmt->condition = parseExpr();
    return stmt;
  }
  case TK::KwFor:
    return parseFor();
  case TK::KwPrint:
  case TK::KwPrintln:
    return parsePrint();
  case TK::KwApply:
    return parseApply();
  default:
    return parseExprStmt();
  }
}

StmtPtr Parser::parseVarDecl() {
  SMLoc loc = take().loc();
  SMLoc nameLoc = tok().loc();
  auto var = std::make_unique<VarDecl>(VarDecl::Role::Var, expectIdent(),
                                       nameLoc);
  if (accept(TK::Colon)) {
    var->typeExpr = parseTensorType();
    if (accept(TK::Assign))
      var->init = parseExpr();
  } else if (accept(TK::Assign)) {
    var->init = parseExpr();
  } else {
    expected("':' or '='");
  }
  expect(TK::Semi);
  return std::make_unique<VarDeclStmt>(loc, std::move(var));
}

StmtPtr Parser::parseIf() {
  auto stmt = std::make_unique<IfStmt>(take().loc());
  stmt->conditions.push_back(parseExpr());
  stmt->blocks.push_back(parseBlock());
  while (accept(TK::KwElif)) {
    stmt->conditions.push_back(parseExpr());
    stmt->blocks.push_back(parseBlock());
  }
  if (accept(TK::KwElse))
    stmt->elseBlock = parseBlock();
  expect(TK::KwEnd);
  return stmt;
}

StmtPtr Parser::parseFor() {
  auto stmt = std::make_unique<ForStmt>(take().loc());
  SMLoc nameLoc = tok().loc();
  stmt->var = std::make_unique<VarDecl>(VarDecl::Role::LoopVar,
                                        expectIdent(), nameLoc);
  expect(TK::KwIn);
  if (is(TK::Ident) && !is(TK::Colon, 1)) {
    stmt->domainLoc = tok().loc();
    stmt->domain = take().text.str();
  } else {
    stmt->lower = parseExpr();
    expect(TK::Colon);
    stmt->upper = parseExpr();
  }
  stmt->body = parseBlock();
  expect(TK::KwEnd);
  return stmt;
}

StmtPtr Parser::parsePrint() {
  bool newline = is(TK::KwPrintln);
  auto stmt = std::make_unique<PrintStmt>(take().loc(), newline);
  do
    stmt->args.push_back(parseExpr());
  while (accept(TK::Comma));
  expect(TK::Semi);
  return stmt;
}

StmtPtr Parser::parseApply() {
  SMLoc loc = take().loc();
  auto map = parseMapBody(loc, /*allowReduce=*/false);
  expect(TK::Semi);
  return std::make_unique<ApplyStmt>(loc, std::move(map));
}

StmtPtr Parser::parseExprStmt() {
  SMLoc loc = tok().loc();
  std::vector<ExprPtr> exprs;
  exprs.push_back(parseExpr());
  while (accept(TK::Comma))
    exprs.push_back(parseExpr());
  if (accept(TK::Assign)) {
    auto stmt = std::make_unique<AssignStmt>(loc);
    stmt->targets = std::move(exprs);
    stmt->value = parseExpr();
    expect(TK::Semi);
    return stmt;
  }
  if (exprs.size() > 1)
    expected("'='");
  expect(TK::Semi);
  return std::make_unique<ExprStmt>(loc, std::move(exprs.front()));
}

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

ExprPtr Parser::parseExpr() {
  NestingGuard guard(*this);
  if (is(TK::KwMap)) {
    SMLoc loc = take().loc();
    return parseMapBody(loc, /*allowReduce=*/true);
  }
  return parseOr();
}

std::unique_ptr<MapExpr> Parser::parseMapBody(SMLoc loc, bool allowReduce) {
  auto map = std::make_unique<MapExpr>(loc);
  map->funcLoc = tok().loc();
  map->funcName = expectIdent("a function name");
  if (is(TK::Lt)) {
    map->hasGenericArgs = true;
    map->genericArgs = parseGenericArgs();
  }
  if (accept(TK::LParen)) {
    map->args = parseExprList(TK::RParen);
    expect(TK::RParen);
    map = measured(std::move(map), loc);
  }
  expect(TK::KwTo);
  map->targetLoc = tok().loc();
  map->target = expectIdent("a set name");
  if (allowReduce) {
    if (accept(TK::KwThrough)) {
      map->throughLoc = tok().loc();
      map->through = expectIdent("a grid name");
    }
    if (accept(TK::KwReduce)) {
      expect(TK::Plus);
      map->reduce = true;
    }
  } else if (is(TK::KwThrough)) {
    take();
    map->throughLoc = tok().loc();
    map->through = expectIdent("a grid name");
  }
  return map;
}

std::vector<ExprPtr> Parser::parseExprList(TK close) {
  std::vector<ExprPtr> list;
  if (is(close))
    return list;
  do
    list.push_back(parseExpr());
  while (accept(TK::Comma));
  return list;
}

ExprPtr Parser::parseOr() {
  ExprPtr lhs = parseAnd();
  while (is(TK::KwOr)) {
    SMLoc loc = take().loc();
    lhs = measured(std::make_unique<BinaryExpr>(loc, BinaryExpr::Op::Or,
                                                std::move(lhs), parseAnd()),
                   loc);
  }
  return lhs;
}

ExprPtr Parser::parseAnd() {
  ExprPtr lhs = parseXor();
  while (is(TK::KwAnd)) {
    SMLoc loc = take().loc();
    lhs = measured(std::make_unique<BinaryExpr>(loc, BinaryExpr::Op::And,
                                                std::move(lhs), parseXor()),
                   loc);
  }
  return lhs;
}

ExprPtr Parser::parseXor() {
  ExprPtr lhs = parseCompare();
  while (is(TK::KwXor)) {
    SMLoc loc = take().loc();
    lhs = measured(std::make_unique<BinaryExpr>(loc, BinaryExpr::Op::Xor,
                                                std::move(lhs),
                                                parseCompare()),
                   loc);
  }
  return lhs;
}

static bool compareOp(TK kind, CompareExpr::Op &op) {
  switch (kind) {
  case TK::Eq: op = CompareExpr::Op::Eq; return true;
  case TK::Ne: op = CompareExpr::Op::Ne; return true;
  case TK::Lt: op = CompareExpr::Op::Lt; return true;
  case TK::Gt: op = CompareExpr::Op::Gt; return true;
  case TK::Le: op = CompareExpr::Op::Le; return true;
  case TK::Ge: op = CompareExpr::Op::Ge; return true;
  default: return false;
  }
}

ExprPtr Parser::parseCompare() {
  ExprPtr first = parseTerm();
  CompareExpr::Op op;
  if (!compareOp(tok().kind, op))
    return first;
  auto cmp = std::make_unique<CompareExpr>(first->loc);
  cmp->operands.push_back(std::move(first));
  while (compareOp(tok().kind, op)) {
    cmp->opLocs.push_back(take().loc());
    cmp->ops.push_back(op);
    cmp->operands.push_back(parseTerm());
  }
  SMLoc opLoc = cmp->opLocs.front();
  return measured(std::move(cmp), opLoc);
}

ExprPtr Parser::parseTerm() {
  if (is(TK::KwNot)) {
    NestingGuard guard(*this);
    SMLoc loc = take().loc();
    return measured(
        std::make_unique<UnaryExpr>(loc, UnaryExpr::Op::Not, parseTerm()), loc);
  }
  return parseAdd();
}

ExprPtr Parser::parseAdd() {
  ExprPtr lhs = parseMul();
  while (is(TK::Plus) || is(TK::Minus)) {
    auto op = is(TK::Plus) ? BinaryExpr::Op::Add : BinaryExpr::Op::Sub;
    SMLoc loc = take().loc();
    lhs = measured(
        std::make_unique<BinaryExpr>(loc, op, std::move(lhs), parseMul()), loc);
  }
  return lhs;
}

ExprPtr Parser::parseMul() {
  ExprPtr lhs = parseUnary();
  while (true) {
    BinaryExpr::Op op;
    switch (tok().kind) {
    case TK::Star: op = BinaryExpr::Op::Mul; break;
    case TK::Slash: op = BinaryExpr::Op::Div; break;
    case TK::Backslash: op = BinaryExpr::Op::LeftDiv; break;
    case TK::DotStar: op = BinaryExpr::Op::ElemMul; break;
    case TK::DotSlash: op = BinaryExpr::Op::ElemDiv; break;
    default: return lhs;
    }
    SMLoc loc = take().loc();
    lhs = measured(
        std::make_unique<BinaryExpr>(loc, op, std::move(lhs), parseUnary()),
        loc);
  }
}

ExprPtr Parser::parseUnary() {
  if (is(TK::Minus) || is(TK::Plus)) {
    NestingGuard guard(*this);
    auto op = is(TK::Minus) ? UnaryExpr::Op::Neg : UnaryExpr::Op::Plus;
    SMLoc loc = take().loc();
    return measured(std::make_unique<UnaryExpr>(loc, op, parseUnary()), loc);
  }
  return parsePow();
}

ExprPtr Parser::parsePow() {
  ExprPtr base = parsePostfix();
  if (!is(TK::Caret))
    return base;
  NestingGuard guard(*this);
  SMLoc loc = take().loc();
  return measured(std::make_unique<BinaryExpr>(loc, BinaryExpr::Op::Pow,
                                               std::move(base), parsePow()),
                  loc);
}

bool Parser::looksLikeGenericCall() const {
  // IDENT < dim > (   or   IDENT < dim ,
  if (!is(TK::Lt, 1) || !(is(TK::Ident, 2) || is(TK::IntLit, 2)))
    return false;
  if (is(TK::Comma, 3))
    return true;
  return is(TK::Gt, 3) && is(TK::LParen, 4);
}

ExprPtr Parser::parsePostfix() {
  ExprPtr expr = parsePrimary();
  // A bare name may take one tuple-style access (`t(0)`, `t.a`) that allows
  // the ordinary postfix chain afterwards (`p(0).x(1)`, `n.left.x`); sema
  // rejects these forms when the name is not a tuple.
  bool bareName = llvm::isa<NameExpr>(expr.get()) && !expr->parenthesized;
  bool tupleLike = false;
  if (bareName && is(TK::LParen)) {
    expr = parseReadArgs(std::move(expr));
    auto *read = llvm::cast<ReadExpr>(expr.get());
    tupleLike = read->indices.size() == 1 && read->indices[0];
  } else if (bareName && is(TK::Dot) && is(TK::Ident, 1) && is(TK::Dot, 2)) {
    take();
    SMLoc fieldLoc = tok().loc();
    std::string field = take().text.str();
    SMLoc loc = expr->loc;
    expr = measured(
        std::make_unique<FieldExpr>(loc, std::move(expr), field, fieldLoc),
        fieldLoc);
  } else if (is(TK::LBracket)) {
    SMLoc loc = take().loc();
    auto read = std::make_unique<SetReadExpr>(loc, std::move(expr));
    if (!is(TK::RBracket)) {
      read->offsets = parseExprList(TK::Semi);
      if (accept(TK::Semi)) {
        read->hasDirections = true;
        read->directions = parseExprList(TK::RBracket);
      }
    }
    expect(TK::RBracket);
    expr = measured(std::move(read), loc);
  }
  if (is(TK::Dot)) {
    if (llvm::isa<ReadExpr>(expr.get()) && !expr->parenthesized && !tupleLike)
      fail(tok().loc(), "a field access cannot follow an index; write the "
                        "field first (S.f(p))");
    take();
    SMLoc fieldLoc = tok().loc();
    std::string field = expectIdent("a field name");
    SMLoc loc = expr->loc;
    expr = measured(
        std::make_unique<FieldExpr>(loc, std::move(expr), field, fieldLoc),
        fieldLoc);
  }
  while (is(TK::LParen))
    expr = parseReadArgs(std::move(expr));
  while (is(TK::Quote)) {
    SMLoc loc = take().loc();
    expr = measured(std::make_unique<TransposeExpr>(loc, std::move(expr)),
                    loc);
  }
  if (is(TK::LParen))
    fail(tok().loc(), "an index cannot follow a transpose; write (v')(i)");
  if (is(TK::Dot) || is(TK::LBracket))
    expected("an operator or ';'");
  return expr;
}

ExprPtr Parser::parseReadArgs(ExprPtr base) {
  SMLoc open = take().loc();
  SMLoc loc = base->loc;
  auto read = std::make_unique<ReadExpr>(loc, std::move(base));
  if (accept(TK::RParen))
    return measured(std::move(read), open);
  do {
    read->indexLocs.push_back(tok().loc());
    if (is(TK::Colon) && (is(TK::Comma, 1) || is(TK::RParen, 1))) {
      take();
      read->indices.push_back(nullptr);
    } else {
      read->indices.push_back(parseExpr());
    }
  } while (accept(TK::Comma));
  expect(TK::RParen);
  return measured(std::move(read), open);
}

ExprPtr Parser::parsePrimary() {
  NestingGuard guard(*this);
  const Token &t = tok();
  SMLoc loc = t.loc();
  switch (t.kind) {
  case TK::LParen: {
    take();
    ExprPtr inner = parseExpr();
    expect(TK::RParen);
    inner->parenthesized = true;
    return inner;
  }
  case TK::Ident: {
    if (is(TK::Lt, 1) &&
        (looksLikeGenericCall() || knownFunctions.count(t.text.str()))) {
      auto call = std::make_unique<CallExpr>(loc, take().text.str());
      call->hasGenericArgs = true;
      call->genericArgs = parseGenericArgs();
      expect(TK::LParen);
      call->args = parseExprList(TK::RParen);
      expect(TK::RParen);
      return measured(std::move(call), loc);
    }
    return std::make_unique<NameExpr>(loc, take().text.str());
  }
  case TK::IntLit:
    return std::make_unique<IntLiteral>(loc, take().intValue);
  case TK::FloatLit:
    return std::make_unique<FloatLiteral>(loc, take().floatValue);
  case TK::StringLit:
    return std::make_unique<StringLiteral>(loc, take().stringValue);
  case TK::KwTrue:
    take();
    return std::make_unique<BoolLiteral>(loc, true);
  case TK::KwFalse:
    take();
    return std::make_unique<BoolLiteral>(loc, false);
  case TK::Lt:
    return parseComplexLiteral();
  case TK::LBracket:
    return parseDenseLiteral();
  case TK::KwMap:
    fail(loc, "'map' cannot be an operand; use it as a whole right-hand "
              "side, initializer or argument");
  default:
    expected("an expression");
  }
}

static double signedFloat(const Token &t, bool negative) {
  return negative ? -t.floatValue : t.floatValue;
}

ExprPtr Parser::parseComplexLiteral() {
  SMLoc loc = take().loc();
  auto part = [&] {
    bool negative = false;
    if (is(TK::Minus) || is(TK::Plus))
      negative = take().is(TK::Minus);
    if (!is(TK::FloatLit))
      expected("a float literal");
    return signedFloat(take(), negative);
  };
  double re = part();
  expect(TK::Comma);
  double im = part();
  expect(TK::Gt);
  return std::make_unique<ComplexLiteral>(loc, re, im);
}

ExprPtr Parser::parseDenseLiteral() {
  auto lit = std::make_unique<DenseLiteral>(tok().loc());
  bool kindKnown = false;
  parseDense(*lit, lit->shape, kindKnown);
  return lit;
}

void Parser::appendSignedLiteral(DenseLiteral &lit, bool &kindKnown) {
  SMLoc loc = tok().loc();
  bool negative = false;
  if (is(TK::Minus) || is(TK::Plus))
    negative = take().is(TK::Minus);
  ScalarKind kind;
  if (is(TK::IntLit))
    kind = ScalarKind::Int;
  else if (is(TK::FloatLit))
    kind = ScalarKind::Float;
  else if (is(TK::Lt))
    kind = ScalarKind::Complex;
  else
    expected("a numeric literal");
  if (!kindKnown) {
    lit.component = kind;
    kindKnown = true;
  } else if (lit.component != kind) {
    fail(loc, "mismatched element types in a dense literal");
  }
  if (kind == ScalarKind::Int) {
    int64_t v = take().intValue;
    lit.intValues.push_back(negative ? -v : v);
  } else if (kind == ScalarKind::Float) {
    lit.floatValues.push_back(signedFloat(take(), negative));
  } else {
    ExprPtr c = parseComplexLiteral();
    auto *complex = llvm::cast<ComplexLiteral>(c.get());
    lit.complexValues.push_back(negative ? -complex->re : complex->re);
    lit.complexValues.push_back(negative ? -complex->im : complex->im);
  }
}

void Parser::parseDense(DenseLiteral &lit, std::vector<int64_t> &shape,
                        bool &kindKnown) {
  NestingGuard guard(*this);
  SMLoc open = expect(TK::LBracket).loc();
  if (is(TK::LBracket)) {
    // Nested literals: a new leading dimension over equal-shaped parts.
    std::vector<int64_t> partShape;
    int64_t count = 0;
    do {
      std::vector<int64_t> thisShape;
      SMLoc partLoc = tok().loc();
      parseDense(lit, thisShape, kindKnown);
      if (count == 0)
        partShape = thisShape;
      else if (thisShape != partShape)
        fail(partLoc, "mismatched dimension sizes in a dense literal");
      ++count;
      accept(TK::Comma);
    } while (is(TK::LBracket));
    expect(TK::RBracket);
    shape.clear();
    shape.push_back(count);
    shape.insert(shape.end(), partShape.begin(), partShape.end());
    return;
  }
  if (is(TK::RBracket))
    fail(open, "a dense literal cannot be empty");
  int64_t rows = 0, columns = 0;
  while (true) {
    SMLoc rowLoc = tok().loc();
    int64_t n = 0;
    do {
      appendSignedLiteral(lit, kindKnown);
      ++n;
      accept(TK::Comma);
    } while (!is(TK::Semi) && !is(TK::RBracket) &&
             (is(TK::IntLit) || is(TK::FloatLit) || is(TK::Lt) ||
              is(TK::Minus) || is(TK::Plus)));
    if (rows == 0)
      columns = n;
    else if (n != columns)
      fail(rowLoc, "mismatched dimension sizes in a dense literal");
    ++rows;
    if (!accept(TK::Semi))
      break;
  }
  expect(TK::RBracket);
  shape.clear();
  if (rows > 1)
    shape.push_back(rows);
  shape.push_back(columns);
}

} // namespace

std::unique_ptr<Program> simit::frontend::parse(StringRef source,
                                                DiagnosticEngine &diags) {
  return Parser(source, diags, intrinsicNames()).parseProgram();
}

std::unique_ptr<FuncDecl>
simit::frontend::parseFunction(StringRef source, DiagnosticEngine &diags,
                               const std::set<std::string> &knownFunctions) {
  return Parser(source, diags, knownFunctions).parseSingleFunction();
}
