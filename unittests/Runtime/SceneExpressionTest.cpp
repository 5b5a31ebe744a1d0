//===--- SceneExpressionTest.cpp - The scene expression language ----------===//

#include "simit/Runtime/SceneExpression.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

CoordinateFrame frame(double x, double y, double z) {
  CoordinateFrame f;
  f.position = {x, y, z};
  f.min = {-1, -2, -3};
  f.max = {1, 2, 3};
  return f;
}

double eval(llvm::StringRef text, const CoordinateFrame &f) {
  auto e = SceneExpression::parse(text);
  if (!e) {
    ADD_FAILURE() << text.str() << ": " << llvm::toString(e.takeError());
    return NAN;
  }
  return e->evaluate(f);
}

TEST(SceneExpression, ArithmeticPrecedenceAndAssociativity) {
  CoordinateFrame f = frame(2, 3, 5);
  EXPECT_EQ(eval("1 + 2 * 3", f), 7);
  EXPECT_EQ(eval("(1 + 2) * 3", f), 9);
  EXPECT_EQ(eval("10 - 4 - 3", f), 3);
  EXPECT_EQ(eval("12 / 3 / 2", f), 2);
  EXPECT_EQ(eval("-x * 2 + -(-y)", f), -1);
  EXPECT_EQ(eval("x * y - z", f), 1);
  EXPECT_DOUBLE_EQ(eval("1.5e-1 + .25 + 2E1", f), 20.4);
}

TEST(SceneExpression, BoundingBoxNames) {
  CoordinateFrame f = frame(0, -1.85, 0);
  EXPECT_EQ(eval("min_x + max_y * min_z", f), -1 + 2 * -3);
  auto fixed = SceneExpression::parse("y < min_y + 0.05 * (max_y - min_y)");
  ASSERT_TRUE(bool(fixed));
  EXPECT_TRUE(fixed->isBoolean());
  EXPECT_EQ(fixed->evaluate(frame(0, -1.85, 0)), 1.0); // -2 + 0.2 = -1.8
  EXPECT_EQ(fixed->evaluate(frame(0, -1.75, 0)), 0.0);
}

TEST(SceneExpression, ComparisonsAndLogic) {
  CoordinateFrame f = frame(0.05, 0.5, 1);
  EXPECT_EQ(eval("x < 0.1", f), 1);
  EXPECT_EQ(eval("x <= 0.05 and y >= 0.5", f), 1);
  EXPECT_EQ(eval("x > 0.1 or z == 1", f), 1);
  EXPECT_EQ(eval("not x < 0.1", f), 0);
  EXPECT_EQ(eval("not (x < 0.1 and y != 0.5)", f), 1);
  // `and` binds tighter than `or`.
  EXPECT_EQ(eval("true or false and false", f), 1);
  EXPECT_EQ(eval("(true or false) and false", f), 0);
}

TEST(SceneExpression, ConditionalValue) {
  EXPECT_EQ(eval("0.1 if y > 1e-4 else 0", frame(0, 1, 0)), 0.1);
  EXPECT_EQ(eval("0.1 if y > 1e-4 else 0", frame(0, 0, 0)), 0.0);
  // Right associative: a if c else b if d else e.
  EXPECT_EQ(eval("1 if x < 0 else 2 if x < 1 else 3", frame(0.5, 0, 0)), 2);
  EXPECT_EQ(eval("1 if x < 0 else 2 if x < 1 else 3", frame(5, 0, 0)), 3);
}

std::string parseError(llvm::StringRef text) {
  return errorOf(SceneExpression::parse(text));
}

TEST(SceneExpression, SyntaxErrorsNameTheColumn) {
  EXPECT_THAT(parseError("x <"), HasSubstr("column 4: expected a number, a "
                                           "name or '(', found the end"));
  EXPECT_THAT(parseError("(x + 1"), HasSubstr("column 7: expected ')'"));
  EXPECT_THAT(parseError("x + w"), HasSubstr("column 5: unknown name 'w'"));
  EXPECT_THAT(parseError("x ^ 2"), HasSubstr("column 3: expected an operator "
                                             "or the end"));
  EXPECT_THAT(parseError("1.2.3"), HasSubstr("column 1: expected a number, "
                                             "found '1.2.3'"));
  EXPECT_THAT(parseError("1 if x < 0"), HasSubstr("expected 'else'"));
  EXPECT_THAT(parseError("#"), HasSubstr("column 1: expected a number, a "
                                         "name or '(', found '#'"));
}

TEST(SceneExpression, TypeErrors) {
  EXPECT_THAT(parseError("x and y"),
              HasSubstr("column 1: expected a boolean operand of 'and', "
                        "found a number"));
  EXPECT_THAT(parseError("(x < 1) + 2"),
              HasSubstr("column 1: expected a number arithmetic operand"));
  EXPECT_THAT(parseError("not x"),
              HasSubstr("column 5: expected a boolean operand of 'not'"));
  EXPECT_THAT(parseError("1 if x else 2"),
              HasSubstr("column 6: expected a boolean condition after 'if'"));
  EXPECT_THAT(parseError("1 if x < 0 else true"),
              HasSubstr("expected both branches of 'if' to have one type"));
  EXPECT_THAT(parseError("(x < 1) < 2"),
              HasSubstr("expected a number operand of a comparison"));
}

std::string repeated(llvm::StringRef text, size_t times) {
  std::string result;
  result.reserve(text.size() * times);
  for (size_t i = 0; i < times; ++i)
    result += text;
  return result;
}

TEST(SceneExpression, DeepNestingIsAnErrorNotAStackOverflow) {
  const size_t n = 200000;
  EXPECT_THAT(parseError(repeated("(", n) + "x" + repeated(")", n)),
              HasSubstr("expression nested too deeply (more than 200 "
                        "levels)"));
  EXPECT_THAT(parseError(repeated("-", n) + "x"),
              HasSubstr("nested too deeply"));
  EXPECT_THAT(parseError(repeated("not ", n) + "x < 1"),
              HasSubstr("nested too deeply"));
  EXPECT_THAT(parseError(repeated("1 if x < 0 else ", n) + "2"),
              HasSubstr("nested too deeply"));
  // A long sum nests only in its tree: each '+' holds the sum before it.
  // The 1000th '+' passes the limit, at column 3 + 4 * 999.
  EXPECT_THAT(parseError(repeated("x + ", n) + "x"),
              HasSubstr("column 3999: expression nested too deeply (more "
                        "than 1000 operators on one path)"));
  EXPECT_THAT(parseError(repeated("x * ", n) + "x"),
              HasSubstr("nested too deeply"));
  EXPECT_THAT(parseError(repeated("x < 1 and ", n) + "true"),
              HasSubstr("nested too deeply"));
}

TEST(SceneExpression, NestingBelowTheLimitsEvaluates) {
  // 100 parentheses and a sum of 900 terms: 900 * x.
  std::string text = repeated("(", 100) + repeated("x + ", 899) + "x" +
                     repeated(")", 100);
  EXPECT_DOUBLE_EQ(eval(text, frame(0.5, 0, 0)), 450.0);
  EXPECT_DOUBLE_EQ(eval(repeated("-", 100) + "x", frame(0.5, 0, 0)), 0.5);
}

TEST(SceneExpression, NumbersMustBeFinite) {
  EXPECT_THAT(parseError("x + 1e999"),
              HasSubstr("column 5: expected a finite number, found '1e999'"));
}

} // namespace
