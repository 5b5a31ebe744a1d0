//===--- ConformanceTest.cpp - System tensors against dense Eigen ---------===//
//
// Every operation of language.md sections 7-9 on system tensors, on every
// tuple of matrix storages it is defined on (ConformanceCases.h), run by
// the JIT on random sets and compared with a dense Eigen evaluation of the
// same operation on the same data. docs/conformance.md describes the suite
// and the cases it once left out.
//
//===----------------------------------------------------------------------===//

#include "ConformanceCases.h"
#include "ConformanceProgram.h"
#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"

#include "gtest/gtest.h"

using namespace simit;
using namespace simit::conformance;
using namespace simit::test;

namespace simit::conformance {
/// Test names stand for cases in gtest's messages.
void PrintTo(const Case &c, std::ostream *os) { *os << c.name(); }
} // namespace simit::conformance

namespace {

/// The two scenes, made once for the suite.
struct Scenes {
  Scene scalars{1, 20261201};
  Scene blocks{3, 20261201};

  Scene &of(int blockSize) { return blockSize == 1 ? scalars : blocks; }
};

/// max |actual - expected| <= tolerance * max |expected| (or tolerance,
/// where expected is zero), naming the first component that differs.
testing::AssertionResult closeTo(const Eigen::VectorXd &actual,
                                 const Eigen::VectorXd &expected,
                                 double tolerance) {
  if (actual.size() != expected.size())
    return testing::AssertionFailure()
           << actual.size() << " components, expected " << expected.size();
  double scale = expected.size() ? expected.lpNorm<Eigen::Infinity>() : 0.0;
  if (scale == 0.0)
    scale = 1.0;
  for (Eigen::Index i = 0; i < expected.size(); ++i)
    if (!(std::abs(actual[i] - expected[i]) <= tolerance * scale))
      return testing::AssertionFailure()
             << "component " << i << " is " << actual[i] << ", expected "
             << expected[i] << " (scale " << scale
             << ")\n  actual:   " << actual.transpose()
             << "\n  expected: " << expected.transpose();
  return testing::AssertionSuccess();
}

class ConformanceTest : public testing::TestWithParam<Case> {
protected:
  static void SetUpTestSuite() { scenes = std::make_unique<Scenes>(); }
  static void TearDownTestSuite() { scenes.reset(); }
  static std::unique_ptr<Scenes> scenes;
};

std::unique_ptr<Scenes> ConformanceTest::scenes;

// One program per case: compiling several cases in one module is no
// faster (the time goes to each function's code, not to the module).
TEST_P(ConformanceTest, MatchesDenseEigen) {
  const Case &c = GetParam();
  Scene &scene = scenes->of(c.blockSize);
  Program program;
  ASSERT_EQ(
      message(program.loadString(generateProgram({c}), c.name() + ".sim")),
      "success");
  llvm::Expected<Function> function = program.compile(c.name());
  ASSERT_TRUE(!!function) << llvm::toString(function.takeError());
  for (const std::string &name : function->requiredSets()) {
    SetId id = *llvm::find_if(kAllSets,
                              [&](SetId set) { return setName(set) == name; });
    ASSERT_EQ(message(function->bind(name, scene.set(id))), "success");
  }
  scene.clearOutputs();
  ASSERT_EQ(message(function->run()), "success");

  const Operation &operation = *c.operation;
  DenseInputs in;
  in.blockSize = c.blockSize;
  for (auto [i, source] : llvm::enumerate(c.sources))
    in.operands.push_back(denseMatrix(*source, kOperandFields[i % 2], scene));
  in.xRows = scene.vectorField(c.sources[0]->rows, "x");
  in.xCols = scene.vectorField(c.sources[0]->cols, "x");
  in.wRows = scene.vectorField(c.sources[0]->rows, "w");
  if (operation.shifted)
    in.shift = denseMatrix(shiftSource(), kShiftFields, scene);
  Eigen::MatrixXd expected = operation.dense(in);
  double tolerance = operation.tolerance;

  switch (operation.observed) {
  case Observed::Matrix: {
    auto [rows, cols] = c.shape();
    Eigen::VectorXd y = expected * scene.vectorField(cols, "x");
    EXPECT_TRUE(closeTo(scene.vectorField(rows, "y"), y, tolerance)) << "M * x";
    EXPECT_TRUE(closeTo(scene.vectorField(rows, "z"),
                        expected * scene.vectorField(cols, "w"), tolerance))
        << "M * w";
    EXPECT_TRUE(closeTo(scene.vectorField(rows, "u"), y, tolerance))
        << "(expression) * x";
    break;
  }
  case Observed::Vector:
    EXPECT_TRUE(closeTo(scene.vectorField(c.shape().first, "y"),
                        expected.col(0), tolerance));
    break;
  case Observed::Scalar:
    ASSERT_EQ(function->results().size(), 1u);
    EXPECT_TRUE(closeTo(
        Eigen::VectorXd::Constant(1, function->results()[0].component(0)),
        expected.col(0), tolerance));
    break;
  }
}

INSTANTIATE_TEST_SUITE_P(Conformance, ConformanceTest,
                         testing::ValuesIn(allCases()),
                         [](const testing::TestParamInfo<Case> &info) {
                           return info.param.name();
                         });

} // namespace
