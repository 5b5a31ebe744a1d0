//===--- SystemProgramsTest.cpp - test/Programs/System end to end ---------===//
//
// The programs of test/Programs/System that need assembled system matrices,
// compiled from their files and run on the scenes of their header comments,
// built here with the C++ API. Every expected number is the one the file's
// header comment derives by hand.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "llvm/Support/raw_ostream.h"

#include "gtest/gtest.h"

#include <cstdio>
#include <unistd.h>

using namespace simit;
using namespace simit::test;

namespace {
/// Binds the sets in order and runs the function once.
std::string bindAndRun(Function &function,
                       std::initializer_list<std::pair<const char *, Set *>>
                           sets) {
  for (auto [name, set] : sets)
    if (llvm::Error err = function.bind(name, *set))
      return message(std::move(err));
  return message(function.run());
}
} // namespace

// A = [1 2; 0 1]: A x = (21, 10), A' x = (1, 12) for x = (1, 10).
TEST(SystemProgramsTest, Transpose) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, "system_transpose");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  Set links("links", {&points, &points});
  auto x = points.addField<double>("x");
  auto y = points.addField<double>("y");
  auto z = points.addField<double>("z");
  auto w = links.addField<double>("w");
  x.set(points.add(), 1.0);
  x.set(points.add(), 10.0);
  w.set(links.add(0, 1), 2.0);
  ASSERT_EQ(bindAndRun(*compiled, {{"points", &points}, {"links", &links}}),
            "success");
  EXPECT_DOUBLE_EQ(y.get(0), 21.0);
  EXPECT_DOUBLE_EQ(y.get(1), 10.0);
  EXPECT_DOUBLE_EQ(z.get(0), 1.0);
  EXPECT_DOUBLE_EQ(z.get(1), 12.0);
}

// A = [1 0 2; 0 3 0]: A x = (201, 30) for x = (1, 10, 100) and
// A' q = (1, 6, 2) for q = (1, 2).
TEST(SystemProgramsTest, HeterogeneousEdges) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, "heterogeneous_edges");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set particles("particles"), nodes("nodes");
  Set links("links", {&particles, &nodes});
  auto q = particles.addField<double>("q");
  auto y = particles.addField<double>("y");
  auto x = nodes.addField<double>("x");
  auto z = nodes.addField<double>("z");
  auto w = links.addField<double>("w");
  q.set(particles.add(), 1.0);
  q.set(particles.add(), 2.0);
  for (double xi : {1.0, 10.0, 100.0})
    x.set(nodes.add(), xi);
  w.set(links.add(0, 0), 1.0);
  w.set(links.add(0, 2), 2.0);
  w.set(links.add(1, 1), 3.0);
  ASSERT_EQ(bindAndRun(*compiled, {{"particles", &particles},
                               {"nodes", &nodes},
                               {"links", &links}}),
            "success");
  EXPECT_DOUBLE_EQ(y.get(0), 201.0);
  EXPECT_DOUBLE_EQ(y.get(1), 30.0);
  EXPECT_DOUBLE_EQ(z.get(0), 1.0);
  EXPECT_DOUBLE_EQ(z.get(1), 6.0);
  EXPECT_DOUBLE_EQ(z.get(2), 2.0);
}

// D = [-1 1 0; 0 -1 1]: D x = (3, 5) for x = (1, 4, 9) and
// D' (3, 5) = (-3, -2, 5).
TEST(SystemProgramsTest, EdgeVertexIncidence) {
  Program program;
  llvm::Expected<Function> compiled =
      compileSystemMain(program, "edge_vertex_incidence");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  Set springs("springs", {&points, &points});
  auto x = points.addField<double>("x");
  auto div = points.addField<double>("div");
  auto grad = springs.addField<double>("grad");
  for (double xi : {1.0, 4.0, 9.0})
    x.set(points.add(), xi);
  springs.add(0, 1);
  springs.add(1, 2);
  ASSERT_EQ(bindAndRun(*compiled, {{"points", &points}, {"springs", &springs}}),
            "success");
  EXPECT_DOUBLE_EQ(grad.get(0), 3.0);
  EXPECT_DOUBLE_EQ(grad.get(1), 5.0);
  EXPECT_DOUBLE_EQ(div.get(0), -3.0);
  EXPECT_DOUBLE_EQ(div.get(1), -2.0);
  EXPECT_DOUBLE_EQ(div.get(2), 5.0);
}

// K(p,p) = (sum of k at p) I with k = 1, 2: K(p,p)(0,0) = (1, 3, 2) lands
// in component 1 of g; the other components stay 0.
TEST(SystemProgramsTest, BlockedComponentAccess) {
  Program program;
  llvm::Expected<Function> compiled =
      compileSystemMain(program, "blocked_component_access");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  Set springs("springs", {&points, &points});
  auto g = points.addField<double, 3>("g");
  auto k = springs.addField<double>("k");
  for (int i = 0; i < 3; ++i)
    points.add();
  k.set(springs.add(0, 1), 1.0);
  k.set(springs.add(1, 2), 2.0);
  ASSERT_EQ(bindAndRun(*compiled, {{"points", &points}, {"springs", &springs}}),
            "success");
  const double expected[] = {1.0, 3.0, 2.0};
  for (int p = 0; p < 3; ++p) {
    std::array<double, 3> block = g.get(p);
    EXPECT_DOUBLE_EQ(block[0], 0.0) << "point " << p;
    EXPECT_DOUBLE_EQ(block[1], expected[p]) << "point " << p;
    EXPECT_DOUBLE_EQ(block[2], 0.0) << "point " << p;
  }
}

// A = L + I = [2 -1 0; -1 3 -1; 0 -1 2]: A x = (0, 2, 4) for x = (1, 2, 3).
TEST(SystemProgramsTest, ForOverSet) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, "for_over_set");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  Set springs("springs", {&points, &points});
  auto x = points.addField<double>("x");
  auto y = points.addField<double>("y");
  auto k = springs.addField<double>("k");
  for (double xi : {1.0, 2.0, 3.0})
    x.set(points.add(), xi);
  k.set(springs.add(0, 1), 1.0);
  k.set(springs.add(1, 2), 1.0);
  ASSERT_EQ(bindAndRun(*compiled, {{"points", &points}, {"springs", &springs}}),
            "success");
  EXPECT_DOUBLE_EQ(y.get(0), 0.0);
  EXPECT_DOUBLE_EQ(y.get(1), 2.0);
  EXPECT_DOUBLE_EQ(y.get(2), 4.0);
}

// "x: " then 1 2 3, then "sum: " and 1 + 2 + 3 = 6.
TEST(SystemProgramsTest, PrintSystemVector) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, "print_system_vector");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  auto x = points.addField<double>("x");
  for (double xi : {1.0, 2.0, 3.0})
    x.set(points.add(), xi);
  llvm::outs().flush();
  testing::internal::CaptureStdout();
  std::string result = bindAndRun(*compiled, {{"points", &points}});
  llvm::outs().flush();
  std::string printed = testing::internal::GetCapturedStdout();
  ASSERT_EQ(result, "success");
  EXPECT_EQ(printed, "x: 1 2 3\nsum: 6\n");
  EXPECT_DOUBLE_EQ(x.get(2), 3.0);
}

/// The scene of system_backslash.sim and system_cholesky.sim: points with
/// m = (2, 0, 0), b = (2, 0, 3); springs (0,1) k = 2, (1,2) k = 3.
struct SpdScene {
  Set points{"points"};
  Set springs{"springs", {&points, &points}};
  FieldRef<double> m = points.addField<double>("m");
  FieldRef<double> b = points.addField<double>("b");
  FieldRef<double> x = points.addField<double>("x");
  FieldRef<double> k = springs.addField<double>("k");
  SpdScene() {
    const double ms[] = {2, 0, 0}, bs[] = {2, 0, 3};
    for (int p = 0; p < 3; ++p) {
      points.add();
      m.set(p, ms[p]);
      b.set(p, bs[p]);
    }
    k.set(springs.add(0, 1), 2.0);
    k.set(springs.add(1, 2), 3.0);
  }
};

/// Runs `main` of the System program `name` on the SPD scene, where
/// A = [4 -2 0; -2 5 -3; 0 -3 3] and A x = (2, 0, 3) gives x = (2.5, 4, 5).
static void expectSpdSolution(llvm::StringRef name) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, name);
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  SpdScene scene;
  ASSERT_EQ(bindAndRun(*compiled, {{"points", &scene.points},
                                   {"springs", &scene.springs}}),
            "success");
  EXPECT_NEAR(scene.x.get(0), 2.5, 1e-12);
  EXPECT_NEAR(scene.x.get(1), 4.0, 1e-12);
  EXPECT_NEAR(scene.x.get(2), 5.0, 1e-12);
}

TEST(SystemProgramsTest, Backslash) { expectSpdSolution("system_backslash"); }

TEST(SystemProgramsTest, Cholesky) { expectSpdSolution("system_cholesky"); }

// m = 0 and k = -1 make A = [-1 1 0; 1 -2 1; 0 1 -1], not positive
// definite (A(0,0) = -1 < 0): chol stops the run with a located error.
TEST(SystemProgramsTest, CholeskyRejectsAnIndefiniteMatrix) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, "system_cholesky");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  SpdScene scene;
  scene.m.set(0, 0.0);
  scene.k.set(0, -1.0);
  scene.k.set(1, -1.0);
  std::string error = bindAndRun(*compiled, {{"points", &scene.points},
                                             {"springs", &scene.springs}});
  EXPECT_NE(error.find("chol (system_cholesky.sim:38:"), std::string::npos)
      << error;
  EXPECT_NE(error.find("the matrix is not positive definite"),
            std::string::npos)
      << error;
}

// A = [4 1; 3 2], b = (5, 5): x = (1, 1).
TEST(SystemProgramsTest, LU) {
  Program program;
  llvm::Expected<Function> compiled = compileSystemMain(program, "system_lu");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  Set links("links", {&points, &points});
  auto b = points.addField<double>("b");
  auto x = points.addField<double>("x");
  auto a = links.addField<double>("a");
  auto c = links.addField<double>("c");
  b.set(points.add(), 5.0);
  b.set(points.add(), 5.0);
  int link = links.add(0, 1);
  a.set(link, 3.0);
  c.set(link, 1.0);
  ASSERT_EQ(bindAndRun(*compiled, {{"points", &points}, {"links", &links}}),
            "success");
  EXPECT_NEAR(x.get(0), 1.0, 1e-12);
  EXPECT_NEAR(x.get(1), 1.0, 1e-12);
}

// Block (0, 2) of a chain's matrix is not in its pattern (no edge joins
// points 0 and 2): writing it ends the run with the lowering's assertion
// instead of writing elsewhere.
TEST(SystemProgramsTest, WritingABlockOutsideThePatternFails) {
  constexpr const char *kSource = R"sim(
element Point
  x : float;
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);
func laplace(s : Spring, p : (Point*2)) -> (L : matrix[points,points](float))
  L(p(0),p(1)) = -s.k;
end
export func main()
  var A = map laplace to springs reduce +;
  for q in points
    for r in points
      A(q,r) = 1.0;
    end
  end
end
)sim";
  Program program;
  ASSERT_EQ(message(program.loadString(kSource, "outside.sim")), "success");
  llvm::Expected<Function> compiled = program.compile("main");
  ASSERT_TRUE(!!compiled) << llvm::toString(compiled.takeError());
  Set points("points");
  Set springs("springs", {&points, &points});
  points.addField<double>("x");
  auto k = springs.addField<double>("k");
  for (int i = 0; i < 3; ++i)
    points.add();
  k.set(springs.add(0, 1), 1.0);
  k.set(springs.add(1, 2), 1.0);
  // The run ends with the message; the process goes on.
  EXPECT_EQ(bindAndRun(*compiled, {{"points", &points}, {"springs", &springs}}),
            "writing a block outside the storage of the matrix, pattern of "
            "'springs' over ('points', 'points') (outside.sim:17:7)");
}
