//===--- SpecialisationTest.cpp - Programs made for the runs promised -----===//
//
// ProgramOptions::specialisation (docs/scene-specialisation.md): entry
// functions, constant externs and uniform fields, and their place in the
// compile cache's key. Results are checked against K x worked out by hand.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "gtest/gtest.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"

using namespace simit;
using namespace simit::test;

namespace {
/// y = scale K x, K assembled from springs between points; t counts calls.
constexpr llvm::StringLiteral kChain = R"sim(
element Point
  x : float;
  y : float;
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);
extern scale   : float;
extern t       : float;

func stiffness(s : Spring, p : (Point*2)) -> (K : tensor[points,points](float))
  K(p(0), p(0)) = s.k;
  K(p(0), p(1)) = -s.k;
  K(p(1), p(0)) = -s.k;
  K(p(1), p(1)) = s.k;
end

export func multiply()
  K = map stiffness to springs reduce +;
  points.y = scale * (K * points.x);
end

export func tick()
  t = t + 1.0;
end
)sim";

/// Runs multiply on points at x = 0, 1, 3 joined by springs of stiffness 2
/// and 3, binding scale = 0.5 only when the function still needs it.
std::vector<double> runMultiply(Program &program) {
  llvm::Expected<Function> multiply = program.compile("multiply");
  if (!multiply) {
    ADD_FAILURE() << llvm::toString(multiply.takeError());
    return {};
  }
  Set points("points");
  Set springs("springs", {&points, &points});
  auto x = points.addField<double>("x");
  auto y = points.addField<double>("y");
  auto k = springs.addField<double>("k");
  for (double xi : {0.0, 1.0, 3.0})
    x.set(points.add(), xi);
  k.set(springs.add(0, 1), 2.0);
  k.set(springs.add(1, 2), 3.0);
  double scale = 0.5;
  EXPECT_EQ(message(multiply->bind("points", points)), "success");
  EXPECT_EQ(message(multiply->bind("springs", springs)), "success");
  if (llvm::is_contained(multiply->requiredTensors(), "scale"))
    EXPECT_EQ(message(multiply->bind("scale", &scale)), "success");
  EXPECT_EQ(message(multiply->run()), "success");
  return {y.get(0), y.get(1), y.get(2)};
}

bool bindsField(const Function &function, llvm::StringRef field) {
  return llvm::any_of(function.signature().arguments,
                      [&](const ArgumentBinding &arg) {
                        return arg.kind == ArgumentBinding::Kind::Field &&
                               arg.field == field;
                      });
}

Program load(const ProgramOptions &options) {
  Program program(options);
  EXPECT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
  return program;
}
} // namespace

TEST(SpecialisationTest, WithoutPromisesEverythingIsBound) {
  Program program = load({});
  EXPECT_EQ(runMultiply(program), (std::vector<double>{-1.0, -2.0, 3.0}));
  llvm::Expected<Function> multiply = program.compile("multiply");
  ASSERT_TRUE(static_cast<bool>(multiply));
  EXPECT_TRUE(llvm::is_contained(multiply->requiredTensors(), "scale"));
  EXPECT_TRUE(bindsField(*multiply, "k"));
}

TEST(SpecialisationTest, OnlyEntryFunctionsAreCompiled) {
  ProgramOptions options;
  options.specialisation.entryFunctions = {"multiply"};
  Program program = load(options);
  auto names = program.exportedFunctions();
  ASSERT_TRUE(static_cast<bool>(names));
  EXPECT_EQ(*names, std::vector<std::string>{"multiply"});
  llvm::Expected<Function> tick = program.compile("tick");
  EXPECT_EQ(message(tick.takeError()),
            "unknown function 'tick' (exported functions: multiply)");
}

TEST(SpecialisationTest, AConstantExternIsFoldedAndNotBound) {
  ProgramOptions options;
  options.specialisation.constantExterns["scale"] = {2.0};
  Program program = load(options);
  // 2 K x = (-4, -8, 12): the folded 2, not a bound 0.5.
  EXPECT_EQ(runMultiply(program), (std::vector<double>{-4.0, -8.0, 12.0}));
  llvm::Expected<Function> multiply = program.compile("multiply");
  ASSERT_TRUE(static_cast<bool>(multiply));
  EXPECT_FALSE(llvm::is_contained(multiply->requiredTensors(), "scale"));
}

TEST(SpecialisationTest, AWrittenExternIsNotFolded) {
  ProgramOptions options;
  options.specialisation.constantExterns["t"] = {1.0};
  Program program = load(options);
  llvm::Expected<Function> tick = program.compile("tick");
  ASSERT_TRUE(static_cast<bool>(tick));
  EXPECT_TRUE(llvm::is_contained(tick->requiredTensors(), "t"));
  double t = 5.0;
  EXPECT_EQ(message(tick->bind("t", &t)), "success");
  EXPECT_EQ(message(tick->run()), "success");
  EXPECT_EQ(t, 6.0);
}

TEST(SpecialisationTest, AUniformFieldIsFoldedAndNotBound) {
  ProgramOptions options;
  options.specialisation.uniformFields["springs"]["k"] = {2.0};
  Program program = load(options);
  // Both springs of stiffness 2: 0.5 K x = (-1, -1, 2).
  EXPECT_EQ(runMultiply(program), (std::vector<double>{-1.0, -1.0, 2.0}));
  llvm::Expected<Function> multiply = program.compile("multiply");
  ASSERT_TRUE(static_cast<bool>(multiply));
  EXPECT_FALSE(bindsField(*multiply, "k"));
}

TEST(SpecialisationTest, FoldedValuesAreInTheCacheKey) {
  llvm::SmallString<128> directory;
  ASSERT_FALSE(llvm::sys::fs::createUniqueDirectory("simit-specialise-test",
                                                    directory));
  auto run = [&](double scale, bool &cached) {
    ProgramOptions options;
    options.cacheDirectory = std::string(directory);
    options.specialisation.constantExterns["scale"] = {scale};
    Program program = load(options);
    std::vector<double> y = runMultiply(program);
    cached = program.compileTimes().cached;
    return y;
  };
  bool cached = true;
  EXPECT_EQ(run(1.0, cached), (std::vector<double>{-2.0, -4.0, 6.0}));
  EXPECT_FALSE(cached);
  EXPECT_EQ(run(3.0, cached), (std::vector<double>{-6.0, -12.0, 18.0}));
  EXPECT_FALSE(cached);
  EXPECT_EQ(run(1.0, cached), (std::vector<double>{-2.0, -4.0, 6.0}));
  EXPECT_TRUE(cached);
  llvm::sys::fs::remove_directories(directory);
}
