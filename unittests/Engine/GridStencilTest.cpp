//===--- GridStencilTest.cpp - Maps through grids, end to end -------------===//
//
// The grid programs of test/Programs/System compiled and run on grids built
// with Set::makeGrid. Expected numbers come from the programs' header
// comments (computed by hand), or are computed by hand here.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {
/// A vertex set `points` (fields `in` and `out`) with values `in`, and a
/// grid `grid` of the given extents over it.
struct Grid {
  Set points;
  FieldRef<double> in, out;
  std::unique_ptr<Set> grid;
  Grid(llvm::StringRef pointsName, llvm::StringRef inName,
       llvm::StringRef outName, llvm::StringRef gridName,
       llvm::ArrayRef<int> dims, llvm::ArrayRef<double> values)
      : points(pointsName.str()), in(points.addField<double>(inName)),
        out(points.addField<double>(outName)) {
    auto made = Set::makeGrid(points, dims, gridName);
    EXPECT_TRUE(!!made) << llvm::toString(made.takeError());
    grid = std::move(*made);
    for (auto [i, value] : llvm::enumerate(values))
      in.set(static_cast<int>(i), value);
  }
};

/// Runs `main` of a program with nodes.x / links (the 1-D programs).
std::vector<double> run1D(llvm::StringRef program,
                          llvm::ArrayRef<double> x,
                          llvm::ArrayRef<double> k = {}) {
  Program p;
  llvm::Expected<Function> main = compileSystemMain(p, program);
  EXPECT_TRUE(!!main) << llvm::toString(main.takeError());
  if (!main)
    return {};
  Grid g("nodes", "x", "y", "links", {static_cast<int>(x.size())}, x);
  if (!k.empty()) {
    FieldRef<double> kField = g.grid->addField<double>("k");
    for (auto [i, value] : llvm::enumerate(k))
      kField.set(static_cast<int>(i), value);
  }
  EXPECT_EQ(message(main->bind("nodes", g.points)), "success");
  EXPECT_EQ(message(main->bind("links", *g.grid)), "success");
  EXPECT_EQ(message(main->run()), "success");
  std::vector<double> y;
  for (int i = 0; i < g.points.size(); ++i)
    y.push_back(g.out.get(i));
  return y;
}
} // namespace

TEST(GridStencilTest, PeriodicSecondDifference) {
  EXPECT_THAT(run1D("grid_stencil_1d", {1, 2, 4, 8}),
              ::testing::ElementsAre(-8, -1, -2, 11));
}

TEST(GridStencilTest, TwoDimensionalLaplacian) {
  Program p;
  llvm::Expected<Function> main = compileSystemMain(p, "grid_stencil_2d");
  ASSERT_TRUE(!!main) << llvm::toString(main.takeError());
  Grid g("points", "a", "c", "links", {3, 3}, {0, 0, 0, 0, 1, 0, 0, 0, 0});
  ASSERT_EQ(message(main->bind("points", g.points)), "success");
  ASSERT_EQ(message(main->bind("links", *g.grid)), "success");
  ASSERT_EQ(message(main->run()), "success");
  std::vector<double> c;
  for (int i = 0; i < 9; ++i)
    c.push_back(g.out.get(i));
  EXPECT_THAT(c, ::testing::ElementsAre(0, -1, 0, -1, 4, -1, 0, -1, 0));
}

TEST(GridStencilTest, ReadsEdgeFields) {
  EXPECT_THAT(run1D("grid_stencil_edge_fields", {1, 2, 4, 8}, {1, 2, 3, 4}),
              ::testing::ElementsAre(-29, -3, -8, 40));
}

TEST(GridStencilTest, OffsetsNamingOnePointShareALocation) {
  // On two points nodes[1] and nodes[-1] are the same point: A(p, q) is
  // written twice with -1 and holds -1 (the last write), so
  // y = (2 x0 - x1, 2 x1 - x0) = (0, 3) for x = (1, 2).
  EXPECT_THAT(run1D("grid_stencil_1d", {1, 2}),
              ::testing::ElementsAre(0, 3));
  // On one point all three offsets are p: the last write leaves A(p, p) = -1.
  EXPECT_THAT(run1D("grid_stencil_1d", {5}), ::testing::ElementsAre(-5));
}

TEST(GridStencilTest, ABoundSetThatIsNotAGridIsAnError) {
  Program p;
  llvm::Expected<Function> main = compileSystemMain(p, "grid_stencil_1d");
  ASSERT_TRUE(!!main) << llvm::toString(main.takeError());
  Set nodes("nodes");
  nodes.addField<double>("x");
  nodes.addField<double>("y");
  nodes.add();
  nodes.add();
  Set links("links", {&nodes, &nodes});
  links.add(0, 1);
  ASSERT_EQ(message(main->bind("nodes", nodes)), "success");
  ASSERT_EQ(message(main->bind("links", links)), "success");
  EXPECT_THAT(message(main->init()),
              HasSubstr("set 'links' is not a grid, but the program expects "
                        "a grid of rank 1"));
}
