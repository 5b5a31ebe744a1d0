//===- LexerTest.cpp - Lexer unit tests -----------------------------------===//

#include "simit/Frontend/Lexer.h"

#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

using namespace simit::frontend;
using TK = TokenKind;

namespace {

struct Lexed {
  explicit Lexed(llvm::StringRef text) : diags(mgr) {
    mgr.AddNewSourceBuffer(llvm::MemoryBuffer::getMemBufferCopy(text, "t"),
                           llvm::SMLoc());
    tokens = lex(mgr.getMemoryBuffer(1)->getBuffer(), diags);
  }
  std::vector<TK> kinds() const {
    std::vector<TK> k;
    for (const Token &t : tokens)
      k.push_back(t.kind);
    return k;
  }
  std::string firstError() const {
    for (const Diagnostic &d : diags.sorted())
      if (d.kind == llvm::SourceMgr::DK_Error)
        return d.message;
    return "";
  }
  llvm::SourceMgr mgr;
  DiagnosticEngine diags;
  std::vector<Token> tokens;
};

TEST(Lexer, EmptyInputIsJustEof) {
  Lexed l("");
  EXPECT_EQ(l.kinds(), std::vector<TK>{TK::Eof});
}

TEST(Lexer, IdentifiersAndKeywords) {
  Lexed l("element Foo_1 end proc test");
  EXPECT_EQ(l.kinds(), (std::vector<TK>{TK::KwElement, TK::Ident, TK::KwEnd,
                                        TK::Ident, TK::Ident, TK::Eof}));
  EXPECT_EQ(l.tokens[1].text, "Foo_1");
}

TEST(Lexer, EveryKeyword) {
  Lexed l("and apply bool complex const delete do elif element else end "
          "export extern false float for func grid if in inout int ivar map "
          "matrix new not opaque or print println reduce return set string "
          "tensor through to true var vector while with xor");
  for (size_t i = 0; i + 1 < l.tokens.size(); ++i)
    EXPECT_TRUE(l.tokens[i].isKeyword()) << l.tokens[i].text.str();
  EXPECT_EQ(l.tokens.size(), 45u); // 44 keywords and Eof
  EXPECT_FALSE(l.diags.hasErrors());
}

TEST(Lexer, KeywordsAreCaseSensitive) {
  Lexed l("End FUNC");
  EXPECT_EQ(l.kinds(), (std::vector<TK>{TK::Ident, TK::Ident, TK::Eof}));
}

TEST(Lexer, IntegerLiteral) {
  Lexed l("42 0 2147483647");
  ASSERT_EQ(l.tokens[0].kind, TK::IntLit);
  EXPECT_EQ(l.tokens[0].intValue, 42);
  EXPECT_EQ(l.tokens[2].intValue, 2147483647);
  EXPECT_FALSE(l.diags.hasErrors());
}

TEST(Lexer, IntegerTooLarge) {
  Lexed l("99999999999");
  EXPECT_NE(l.firstError().find("does not fit in 32 bits"), std::string::npos);
}

TEST(Lexer, LeadingZeroWarnsAndReadsDecimal) {
  Lexed l("010");
  EXPECT_EQ(l.tokens[0].intValue, 10);
  EXPECT_FALSE(l.diags.hasErrors());
  EXPECT_EQ(l.diags.sorted().size(), 1u);
}

TEST(Lexer, FloatForms) {
  Lexed l("0.5 2.0e-3 1e3 1E+2");
  ASSERT_EQ(l.kinds(), (std::vector<TK>{TK::FloatLit, TK::FloatLit,
                                        TK::FloatLit, TK::FloatLit, TK::Eof}));
  EXPECT_DOUBLE_EQ(l.tokens[0].floatValue, 0.5);
  EXPECT_DOUBLE_EQ(l.tokens[1].floatValue, 0.002);
  EXPECT_DOUBLE_EQ(l.tokens[2].floatValue, 1000.0);
  EXPECT_DOUBLE_EQ(l.tokens[3].floatValue, 100.0);
}

TEST(Lexer, TrailingDotIsAnError) {
  Lexed l("z = 2.;");
  EXPECT_NE(l.firstError().find("expected digits after '.'"),
            std::string::npos);
}

TEST(Lexer, LeadingDotIsAnError) {
  Lexed l(".5");
  EXPECT_NE(l.firstError().find("expected digits before '.'"),
            std::string::npos);
}

TEST(Lexer, MissingExponentDigits) {
  Lexed l("1e+");
  EXPECT_NE(l.firstError().find("exponent"), std::string::npos);
}

TEST(Lexer, StringEscapes) {
  Lexed l(R"("a\n\t\\\"\'\?b")");
  ASSERT_EQ(l.tokens[0].kind, TK::StringLit);
  EXPECT_EQ(l.tokens[0].stringValue, "a\n\t\\\"'?b");
}

TEST(Lexer, StringMaySpanLines) {
  Lexed l("\"a\nb\"");
  ASSERT_EQ(l.tokens[0].kind, TK::StringLit);
  EXPECT_EQ(l.tokens[0].stringValue, "a\nb");
}

TEST(Lexer, UnrecognizedEscape) {
  Lexed l(R"("a\q")");
  EXPECT_NE(l.firstError().find("unrecognized escape"), std::string::npos);
}

TEST(Lexer, UnclosedString) {
  Lexed l("\"abc");
  EXPECT_NE(l.firstError().find("unclosed string"), std::string::npos);
}

TEST(Lexer, LineCommentsVanish) {
  Lexed l("a % comment\n%% also\n%%% section\n%- off\nb");
  EXPECT_EQ(l.kinds(), (std::vector<TK>{TK::Ident, TK::Ident, TK::Eof}));
}

TEST(Lexer, BlockComment) {
  Lexed l("a %{ x\n y %} b");
  EXPECT_EQ(l.kinds(), (std::vector<TK>{TK::Ident, TK::Ident, TK::Eof}));
}

TEST(Lexer, BlockCommentDoesNotNest) {
  Lexed l("%{ %{ %} b %}");
  EXPECT_EQ(l.tokens[0].kind, TK::Ident);
  EXPECT_NE(l.firstError().find("'%}'"), std::string::npos);
}

TEST(Lexer, UnclosedBlockComment) {
  Lexed l("a %{ never");
  EXPECT_NE(l.firstError().find("unclosed comment"), std::string::npos);
}

TEST(Lexer, StrayBlockCommentEnd) {
  Lexed l("%}");
  EXPECT_NE(l.firstError().find("outside a block comment"), std::string::npos);
}

TEST(Lexer, TestLineTokens) {
  Lexed l("%! f(1) == 2;\nx");
  EXPECT_EQ(l.kinds(),
            (std::vector<TK>{TK::TestStart, TK::Ident, TK::LParen, TK::IntLit,
                             TK::RParen, TK::Eq, TK::IntLit, TK::Semi,
                             TK::TestEnd, TK::Ident, TK::Eof}));
}

TEST(Lexer, TestLineNeedsLineBreak) {
  Lexed l("%! f(1) == 2;");
  EXPECT_NE(l.firstError().find("unclosed test"), std::string::npos);
}

TEST(Lexer, DoublePercentBangIsComment) {
  Lexed l("%%! f(1) == 2;\n");
  EXPECT_EQ(l.kinds(), std::vector<TK>{TK::Eof});
}

TEST(Lexer, Operators) {
  Lexed l("( ) [ ] { } , ; : . -> = == != < > <= >= + - * / \\ .* ./ ^ '");
  EXPECT_EQ(l.kinds(),
            (std::vector<TK>{TK::LParen, TK::RParen, TK::LBracket,
                             TK::RBracket, TK::LBrace, TK::RBrace, TK::Comma,
                             TK::Semi, TK::Colon, TK::Dot, TK::Arrow,
                             TK::Assign, TK::Eq, TK::Ne, TK::Lt, TK::Gt,
                             TK::Le, TK::Ge, TK::Plus, TK::Minus, TK::Star,
                             TK::Slash, TK::Backslash, TK::DotStar,
                             TK::DotSlash, TK::Caret, TK::Quote, TK::Eof}));
}

TEST(Lexer, DotStarAfterInteger) {
  Lexed l("2.*x");
  EXPECT_EQ(l.kinds(), (std::vector<TK>{TK::IntLit, TK::DotStar, TK::Ident,
                                        TK::Eof}));
}

TEST(Lexer, UnexpectedSymbols) {
  for (const char *s : {"#", "@", "$", "&", "|", "?", "~", "!"}) {
    Lexed l(s);
    EXPECT_NE(l.firstError().find("unexpected symbol"), std::string::npos)
        << s;
  }
}

TEST(Lexer, CRLFIsOneLineBreak) {
  Lexed l("%! f() == 1;\r\nx");
  EXPECT_EQ(l.tokens[7].kind, TK::TestEnd);
  EXPECT_EQ(l.tokens[7].text, "\r\n");
}

TEST(Lexer, NonAsciiOutsideCommentsIsAnError) {
  Lexed l("a \xc3\xa9");
  EXPECT_NE(l.firstError().find("unexpected symbol"), std::string::npos);
}

TEST(Lexer, ErrorsCarryPositions) {
  Lexed l("ab\n  #");
  auto diags = l.diags.sorted();
  ASSERT_EQ(diags.size(), 1u);
  auto [line, col] = l.diags.lineAndColumn(diags[0].loc);
  EXPECT_EQ(line, 2u);
  EXPECT_EQ(col, 3u);
}

} // namespace
