//===- ParserTest.cpp - Parser unit tests ---------------------------------===//

#include "FrontendTestUtil.h"

#include <gtest/gtest.h>

using namespace simit::frontend;
using simit::frontend::test::Compilation;

namespace {

/// The parsed (unchecked) right-hand side of `x = <text>;` in a function.
std::string parseRhs(const std::string &text) {
  Compilation c("func f()\n  x = " + text + ";\nend\n", /*runSema=*/false);
  if (!c.parsed)
    return "error: " + c.allErrors();
  auto &assign = llvm::cast<AssignStmt>(*c.program->funcs[0]->body->stmts[0]);
  std::string s;
  llvm::raw_string_ostream os(s);
  printExpr(*assign.value, os);
  std::string out = os.str();
  for (size_t p; (p = out.find(" : <unchecked>")) != std::string::npos;)
    out.erase(p, 14);
  return out;
}

bool parses(const std::string &src) { return Compilation(src, false).parsed; }

std::string parseError(const std::string &src) {
  return Compilation(src, false).allErrors();
}

TEST(Parser, EmptyProgram) { EXPECT_TRUE(parses("")); }

TEST(Parser, ElementDecl) {
  Compilation c("element E\n  a : float;\n  b : vector[3](int);\nend\n", false);
  ASSERT_TRUE(c.parsed);
  ASSERT_EQ(c.program->elements.size(), 1u);
  EXPECT_EQ(c.program->elements[0]->fields.size(), 2u);
}

TEST(Parser, ExternDecls) {
  Compilation c("element E end\nextern V : set{E};\nextern F : set{E}(V, V);\n"
                "extern G : set{E}(V*3);\nextern g : grid[2]{E}(V);\n",
                false);
  ASSERT_TRUE(c.parsed) << c.allErrors();
  EXPECT_EQ(c.program->globals.size(), 4u);
  EXPECT_EQ(c.program->globals[2]->typeExpr->repeat, 3);
}

TEST(Parser, ExternFunc) {
  Compilation c("extern func h<N>(x : vector[N](float)) -> y : float;\n",
                false);
  ASSERT_TRUE(c.parsed) << c.allErrors();
  EXPECT_TRUE(c.program->funcs[0]->isExtern);
  EXPECT_EQ(c.program->funcs[0]->generics.size(), 1u);
}

TEST(Parser, FunctionForms) {
  Compilation c("export func f(inout a : float, b : int) -> (r : float, s : "
                "int)\nend\nfunc g() -> r : float\nend\n"
                "func h<N, 0:M>()\nend\n",
                false);
  ASSERT_TRUE(c.parsed) << c.allErrors();
  EXPECT_TRUE(c.program->funcs[0]->isExport);
  EXPECT_TRUE(c.program->funcs[0]->params[0]->inout);
  EXPECT_EQ(c.program->funcs[0]->results.size(), 2u);
  EXPECT_EQ(c.program->funcs[1]->results.size(), 1u);
  EXPECT_TRUE(c.program->funcs[2]->generics[1]->isRange);
}

TEST(Parser, EmptyResultListIsAnError) {
  EXPECT_NE(parseError("func f() -> ()\nend\n").find("expected a result name"),
            std::string::npos);
}

TEST(Parser, GenericLiteralMustBeZero) {
  EXPECT_NE(parseError("func f<2:N>()\nend\n").find("'0:'"),
            std::string::npos);
}

TEST(Parser, TensorTypeForms) {
  EXPECT_TRUE(parses("func f(a : tensor[3,4](float), b : vector[3](int)', c : "
                     "matrix[2,2](matrix[3,3](float)), d : tensor(float), e : "
                     "vector(complex), g : string, h : bool, o : opaque)\nend\n"));
}

TEST(Parser, MatrixTypeCannotBeTransposed) {
  EXPECT_NE(parseError("func f(m : matrix[2,2](float)')\nend\n")
                .find("cannot be transposed"),
            std::string::npos);
}

TEST(Parser, VectorTakesOneDimension) {
  EXPECT_NE(parseError("func f(v : vector[2,2](int))\nend\n")
                .find("expected ']'"),
            std::string::npos);
}

TEST(Parser, MatrixTakesTwoDimensions) {
  EXPECT_NE(parseError("func f(v : matrix[4](int))\nend\n")
                .find("expected ','"),
            std::string::npos);
}

TEST(Parser, NestedBlockMustUseSameKeyword) {
  EXPECT_NE(parseError("func f(v : vector[2](matrix[2,2](float)))\nend\n")
                .find("a component type or 'vector'"),
            std::string::npos);
}

TEST(Parser, TupleTypes) {
  EXPECT_TRUE(parses("func f(a : (E*2), b : (x : E, y : F))\nend\n"));
  EXPECT_NE(parseError("func f(t : (E * E))\nend\n")
                .find("expected an integer literal"),
            std::string::npos);
}

TEST(Parser, Precedence) {
  EXPECT_EQ(parseRhs("a + b * c"),
            "(+ (name a) (* (name b) (name c)))");
  EXPECT_EQ(parseRhs("a - b - c"),
            "(- (- (name a) (name b)) (name c))");
  EXPECT_EQ(parseRhs("-a * b"), "(* (neg (name a)) (name b))");
  EXPECT_EQ(parseRhs("a or b and c"),
            "(or (name a) (and (name b) (name c)))");
  EXPECT_EQ(parseRhs("a and b xor c"),
            "(and (name a) (xor (name b) (name c)))");
}

TEST(Parser, NotBindsLooserThanArithmeticTighterThanComparison) {
  EXPECT_EQ(parseRhs("not a == b"),
            "(compare (not (name a)) == (name b))");
  EXPECT_EQ(parseRhs("not a + b"), "(not (+ (name a) (name b)))");
}

TEST(Parser, ChainedComparison) {
  EXPECT_EQ(parseRhs("a < b <= c"),
            "(compare (name a) < (name b) <= (name c))");
}

TEST(Parser, PowIsRightAssociativeAndTighterThanUnary) {
  EXPECT_EQ(parseRhs("-a ^ b ^ c"),
            "(neg (^ (name a) (^ (name b) (name c))))");
}

TEST(Parser, RepeatedUnary) {
  EXPECT_EQ(parseRhs("--+-x"),
            "(neg (neg (plus (neg (name x)))))");
}

TEST(Parser, TransposeIsRepeatablePostfix) {
  EXPECT_EQ(parseRhs("a''"), "(transpose (transpose (name a)))");
  EXPECT_EQ(parseRhs("a' * b"), "(* (transpose (name a)) (name b))");
}

TEST(Parser, PostfixOrder) {
  EXPECT_EQ(parseRhs("S.f(p)"), "(read (field (name S) .f) (name p))");
  EXPECT_EQ(parseRhs("K(p,q)(0,1)"),
            "(read (read (name K) (name p) (name q)) (int 0) (int 1))");
  EXPECT_EQ(parseRhs("g[0,0;0,1].f"),
            "(field (grid-edge (name g) (int 0) (int 0) ; (int 0) (int 1)) "
            ".f)");
  EXPECT_EQ(parseRhs("M(1,:)"), "(slice (name M) (int 1) :)");
}

TEST(Parser, TupleStyleAccessChains) {
  EXPECT_EQ(parseRhs("p(0).x(1)"),
            "(read (field (read (name p) (int 0)) .x) (int 1))");
  EXPECT_EQ(parseRhs("n.left.x"), "(field (field (name n) .left) .x)");
}

TEST(Parser, TransposeThenIndexIsAnError) {
  EXPECT_NE(parseRhs("v'(0)").find("cannot follow a transpose"),
            std::string::npos);
  EXPECT_EQ(parseRhs("(v')(0)"), "(read (transpose (name v)) (int 0))");
}

TEST(Parser, FieldAfterMultiIndexIsAnError) {
  EXPECT_NE(parseRhs("A(i,j).f").find("cannot follow an index"),
            std::string::npos);
}

TEST(Parser, GenericCallLookahead) {
  EXPECT_EQ(parseRhs("f<V>(x)"), "(call f (name x))");
  EXPECT_EQ(parseRhs("f<V, 3>(x)"), "(call f (name x))");
  EXPECT_EQ(parseRhs("a < b"), "(compare (name a) < (name b))");
  EXPECT_EQ(parseRhs("a < b > c"),
            "(compare (name a) < (name b) > (name c))");
  EXPECT_EQ(parseRhs("lusolve<V,V>(h, b)"),
            "(call lusolve (name h) (name b))");
}

TEST(Parser, MapIsWholeExpressionOnly) {
  EXPECT_EQ(parseRhs("map f to S reduce +"), "(map f to S reduce +)");
  EXPECT_EQ(parseRhs("(map f(1) to S)"), "(map f (int 1) to S)");
  EXPECT_NE(parseRhs("2.0 * map f to S reduce +").find("cannot be an operand"),
            std::string::npos);
}

TEST(Parser, MapForms) {
  EXPECT_EQ(parseRhs("map f<V>(a, b) to S through G reduce +"),
            "(map f (name a) (name b) to S through G reduce +)");
}

TEST(Parser, DenseLiterals) {
  EXPECT_EQ(parseRhs("[1 -2]"), "(dense [1 -2])");
  EXPECT_EQ(parseRhs("[1 - 2]"), "(dense [1 -2])");
  EXPECT_EQ(parseRhs("[1, 2; 3, 4]"), "(dense [1 2 3 4])");
  EXPECT_EQ(parseRhs("[[1.0, 2.0], [3.0, 4.0]]"), "(dense [1 2 3 4])");
  EXPECT_EQ(parseRhs("[<1.0, 2.0> <3.0, -4.0>]"), "(dense [<1,2> <3,-4>])");
}

TEST(Parser, DenseLiteralShapes) {
  Compilation c("func f()\n x = [[1.0, 2.0; 3.0, 4.0], [5.0, 6.0; 7.0, 8.0]];"
                "\n y = [2.0; 3.0];\nend\n",
                false);
  ASSERT_TRUE(c.parsed);
  auto &body = c.program->funcs[0]->body->stmts;
  auto *x = llvm::cast<DenseLiteral>(
      llvm::cast<AssignStmt>(*body[0]).value.get());
  EXPECT_EQ(x->shape, (std::vector<int64_t>{2, 2, 2}));
  auto *y = llvm::cast<DenseLiteral>(
      llvm::cast<AssignStmt>(*body[1]).value.get());
  EXPECT_EQ(y->shape, (std::vector<int64_t>{2, 1}));
}

TEST(Parser, DenseLiteralErrors) {
  EXPECT_NE(parseRhs("[1 2.0]").find("mismatched element types"),
            std::string::npos);
  EXPECT_NE(parseRhs("[1 2; 3]").find("mismatched dimension sizes"),
            std::string::npos);
  EXPECT_NE(parseRhs("[]").find("cannot be empty"), std::string::npos);
  EXPECT_NE(parseRhs("[x]").find("expected a numeric literal"),
            std::string::npos);
  EXPECT_NE(parseRhs("[1 2[").find("expected ']'"), std::string::npos);
}

TEST(Parser, ComplexLiteral) {
  EXPECT_EQ(parseRhs("<1.0, -2.0>"), "(complex <1,-2>)");
}

TEST(Parser, Statements) {
  EXPECT_TRUE(parses(R"(func f()
  var a : int = 1;
  var b = 2.0;
  var c : float;
  const d = 3;
  ivar i
  ivar j;
  if a == 1
  elif a == 2
  else
  end
  while false
  end
  do
  end while false;
  for k in 0:3
  end
  for p in S
  end
  print a, b;
  println "x";
  apply g to S;
  apply g(1, 2) to S;
  x, y = h();
  g(x);
  ;
  map g to S;
end
)"));
}

TEST(Parser, SyntaxErrorMessages) {
  EXPECT_NE(parseError("var g : int;\n").find("expected a program element"),
            std::string::npos);
  EXPECT_NE(parseError("func f()\n var q;\nend\n").find("expected ':' or '='"),
            std::string::npos);
  EXPECT_NE(parseError("func f()\n const c : int;\nend\n").find("expected '='"),
            std::string::npos);
  EXPECT_NE(parseError("func h end\n").find("expected '('"),
            std::string::npos);
  EXPECT_NE(parseError("func f()\n for i 0:3\n end\nend\n").find(
                "expected 'in'"),
            std::string::npos);
  EXPECT_NE(parseError("func f()\n print ;\nend\n").find(
                "expected an expression"),
            std::string::npos);
  EXPECT_NE(parseError("func f()\n print \"a\" \"b\";\nend\n").find(
                "expected ';'"),
            std::string::npos);
}

TEST(Parser, MultipleAssignmentForms) {
  EXPECT_NE(parseError("func f()\n a = b = c;\nend\n").find("expected ';'"),
            std::string::npos);
  EXPECT_NE(parseError("func f()\n a, b = b, a;\nend\n").find("expected ';'"),
            std::string::npos);
}

TEST(Parser, UnusedKeywordsAreSyntaxErrors) {
  for (const char *kw : {"with", "return", "new", "delete"})
    EXPECT_NE(parseError(std::string("func f()\n ") + kw + " x;\nend\n")
                  .find("expected an expression"),
              std::string::npos)
        << kw;
}

TEST(Parser, ApplyCannotReduce) {
  EXPECT_NE(parseError("func f()\n apply g to S reduce +;\nend\n")
                .find("expected ';'"),
            std::string::npos);
}

TEST(Parser, TopLevelSemicolonIsAnError) {
  EXPECT_NE(parseError(";\n").find("expected a program element"),
            std::string::npos);
}

TEST(Parser, TestLine) {
  Compilation c("%! f([1.0, 2.0]', -3) == 1.5;\nfunc f()\nend\n", false);
  ASSERT_TRUE(c.parsed) << c.allErrors();
  ASSERT_EQ(c.program->tests.size(), 1u);
  EXPECT_EQ(c.program->tests[0].funcName, "f");
  EXPECT_EQ(c.program->tests[0].args.size(), 2u);
  EXPECT_EQ(c.program->tests[0].line, 1u);
}

TEST(Parser, TestLineInsideFunction) {
  EXPECT_NE(parseError("func f()\n%! f() == 1;\nend\n")
                .find("expected an expression"),
            std::string::npos);
}

TEST(Parser, RecoveryReportsSeveralErrorsSorted) {
  Compilation c("func f()\n x = 1 +;\n y = ) ;\nend\nfunc g()\n z = *;\nend\n",
                false);
  ASSERT_EQ(c.errors.size(), 3u) << c.allErrors();
  EXPECT_EQ(c.errors[0].substr(0, 4), "2:9:");
  EXPECT_EQ(c.errors[1].substr(0, 4), "3:6:");
  EXPECT_EQ(c.errors[2].substr(0, 4), "6:6:");
}

TEST(Parser, DeepNestingIsReportedNotACrash) {
  std::string deep(5000, '(');
  EXPECT_NE(parseRhs(deep + "1" + std::string(5000, ')')).find("too deeply"),
            std::string::npos);
}

std::string repeated(const std::string &text, size_t times) {
  std::string result;
  result.reserve(text.size() * times);
  for (size_t i = 0; i < times; ++i)
    result += text;
  return result;
}

TEST(Parser, TallOperatorChainsAreReportedNotACrash) {
  // Chains nest in the tree, not in the parser: `a + a + ...` is
  // ((a + a) + a) + ..., 100000 levels deep for sema and IR generation.
  for (const char *link : {" + a", " * a", " and a", " or a", "'", "(0)"}) {
    std::string err = parseRhs("a" + repeated(link, 100000));
    EXPECT_NE(err.find("expression nested too deeply (more than 1000 "
                       "operators on one path)"),
              std::string::npos)
        << link << ": " << err.substr(0, 200);
  }
  EXPECT_NE(parseRhs(repeated("-", 100000) + "a").find("too deeply"),
            std::string::npos);
  EXPECT_NE(parseRhs(repeated("not ", 100000) + "a").find("too deeply"),
            std::string::npos);
  // The error names the operator that passed the limit: the 1000th '+',
  // at column 9 + 4 * 999.
  Compilation c("func f()\n  x = a" + repeated(" + a", 2000) + ";\nend\n",
                false);
  EXPECT_TRUE(c.hasError("2:4005", "nested too deeply"))
      << c.allErrors().substr(0, 200);
}

TEST(Parser, ChainsBelowTheLimitParseAndCheck) {
  Compilation c("func f(a : float) -> (x : float)\n  x = a" +
                repeated(" + a", 998) + ";\nend\n");
  EXPECT_TRUE(c.ok) << c.allErrors().substr(0, 200);
}

TEST(Parser, ForDomainLookahead) {
  Compilation c("func f()\n for i in n:m\n end\n for p in S\n end\nend\n",
                false);
  ASSERT_TRUE(c.parsed);
  auto &body = c.program->funcs[0]->body->stmts;
  EXPECT_TRUE(llvm::cast<ForStmt>(*body[0]).isRange());
  EXPECT_FALSE(llvm::cast<ForStmt>(*body[1]).isRange());
}

} // namespace
