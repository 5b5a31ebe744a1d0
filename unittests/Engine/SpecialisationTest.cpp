//===--- SpecialisationTest.cpp - Programs made for the runs promised -----===//
//
// ProgramOptions::specialisation (docs/scene-specialisation.md): entry
// functions, constant externs and uniform fields, and their place in the
// compile cache's key; SceneRunner's use of them. Results are checked
// against K x worked out by hand.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Engine/SceneRun.h"
#include "simit/Runtime/Scene.h"
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

namespace {
/// Two points joined by one spring of stiffness 2 (given once for the
/// whole set, so uniform), and a field w that no function uses.
constexpr llvm::StringLiteral kSpringScene = R"json({
  "program": "empty-sets.sim",
  "sets": {
    "points": { "size": 2, "fields": { "x": [1, 2, 3], "w": 7 } },
    "springs": { "elements": [[0, 1]], "endpoints": "points",
                 "fields": { "k": 2 } }
  },
  "externs": { "h": { "value": 0.5, "constant": true } },
  "step": "step",
  "frames": 1
})json";

/// The scene run with `options`; its points' x after the frame.
std::unique_ptr<SceneRunner> runSpringScene(const SceneRunOptions &options) {
  auto scene = parseScene(kSpringScene, "spring.json",
                          SIMIT_SOURCE_DIR "/test/Run/Inputs");
  EXPECT_TRUE(static_cast<bool>(scene)) << llvm::toString(scene.takeError());
  auto runner = SceneRunner::create(std::move(*scene), options);
  if (!runner) {
    ADD_FAILURE() << llvm::toString(runner.takeError());
    return nullptr;
  }
  EXPECT_EQ(message((*runner)->run()), "success");
  return std::move(*runner);
}

std::vector<double> positions(SceneRunner &runner) {
  Set *points = runner.sets().find("points");
  const double *x = static_cast<const double *>(points->fieldData("x"));
  return std::vector<double>(x, x + 6);
}
} // namespace

TEST(SpecialisationTest, ASceneBuildsOnlyTheFieldsItsFunctionsUse) {
  SceneRunOptions options;
  options.threads = 1;
  std::unique_ptr<SceneRunner> skipping = runSpringScene(options);
  options.skipUnusedFields = false;
  options.foldConstantExterns = false;
  options.foldUniformFields = false;
  std::unique_ptr<SceneRunner> building = runSpringScene(options);
  ASSERT_TRUE(skipping && building);
  EXPECT_EQ(skipping->sets().find("points")->fieldDescriptor("w"), nullptr);
  EXPECT_NE(building->sets().find("points")->fieldDescriptor("w"), nullptr);
  // K(p0, p1) = 2 I: v0 = 2 x1 + x0 = 3 x, v1 = x; x' = x + 0.5 v.
  std::vector<double> expected = {2.5, 5, 7.5, 1.5, 3, 4.5};
  EXPECT_EQ(positions(*skipping), expected);
  EXPECT_EQ(positions(*building), expected);
}

TEST(SpecialisationTest, AConstantMarkIsTrueOrFalse) {
  auto scene = parseScene(
      R"json({"sets": {},
               "externs": {"h": {"value": 0.5, "constant": "yes"}}})json",
      "marks.json", ".");
  ASSERT_FALSE(static_cast<bool>(scene));
  EXPECT_EQ(llvm::toString(scene.takeError()),
            "marks.json: externs.h.constant: expected true or false, found "
            "a string");
  auto marked = parseScene(
      R"json({"sets": {},
               "externs": {"h": {"value": 0.5, "constant": true},
                           "g": 9.81}})json",
      "marks.json", ".");
  ASSERT_TRUE(static_cast<bool>(marked)) << llvm::toString(marked.takeError());
  ASSERT_EQ(marked->externs.size(), 2u);
  for (const auto &[name, tensor] : marked->externs)
    EXPECT_EQ(tensor.constant, name == "h") << name;
}
