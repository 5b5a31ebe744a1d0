//===--- PatternUnionTest.cpp - Union patterns and gather maps ------------===//

#include "simit/Runtime/PatternUnion.h"

#include "gmock/gmock.h"

#include <random>
#include <set>

using namespace simit;

namespace {

/// A random edge set of `count` edges over `verts` (cardinality `c`).
void addRandomEdges(Set &edges, int count, int numVerts, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, numVerts - 1);
  for (int e = 0; e < count; ++e) {
    std::vector<int> ends(edges.cardinality());
    for (int &end : ends)
      end = pick(rng);
    edges.add(ends);
  }
}

std::set<std::pair<int, int>> blocksOf(const SparsityPattern &p) {
  std::set<std::pair<int, int>> blocks;
  for (int r = 0; r < p.numRows(); ++r)
    for (int k = p.rowPointers()[r]; k < p.rowPointers()[r + 1]; ++k)
      blocks.insert({r, p.columnIndices()[k]});
  return blocks;
}

// The union of a spring pattern, a triangle pattern and a tet pattern over
// one vertex set holds exactly the blocks of the three, sorted per row, and
// each gather map names the member's own position of the same block.
TEST(PatternUnion, MergesThreeEdgeSetsWithGatherMaps) {
  Set verts("verts");
  for (int i = 0; i < 30; ++i)
    verts.add();
  Set springs("springs", {&verts, &verts});
  Set triangles("triangles", {&verts, &verts, &verts});
  Set tets("tets", {&verts, &verts, &verts, &verts});
  addRandomEdges(springs, 25, 30, 1);
  addRandomEdges(triangles, 10, 30, 2);
  addRandomEdges(tets, 6, 30, 3);
  std::vector<const Set *> members = {&springs, &triangles, &tets};
  auto u = unionPattern(members, verts, verts);
  ASSERT_TRUE(bool(u)) << llvm::toString(u.takeError());
  const SparsityPattern &merged = **u;

  std::set<std::pair<int, int>> expected;
  std::vector<std::shared_ptr<const SparsityPattern>> patterns;
  for (const Set *edges : members) {
    patterns.push_back(*SparsityPattern::get(*edges, verts, verts));
    std::set<std::pair<int, int>> own = blocksOf(*patterns.back());
    expected.insert(own.begin(), own.end());
  }
  EXPECT_EQ(blocksOf(merged), expected);
  EXPECT_EQ(merged.numBlocks(), static_cast<int>(expected.size()));
  // A part may be a member or a smaller union.
  auto pair = unionPattern({&springs, &tets}, verts, verts);
  ASSERT_TRUE(bool(pair));
  patterns.push_back(*pair);
  for (unsigned m = 0; m < patterns.size(); ++m) {
    std::vector<int32_t> gather = gatherPositions(merged, *patterns[m]);
    ASSERT_EQ(gather.size(), expected.size());
    for (int r = 0; r < merged.numRows(); ++r)
      for (int k = merged.rowPointers()[r]; k < merged.rowPointers()[r + 1];
           ++k)
        EXPECT_EQ(gather[k],
                  patterns[m]->findBlock(r, merged.columnIndices()[k]))
            << "member " << m << " block (" << r << ", "
            << merged.columnIndices()[k] << ")";
  }
}

TEST(PatternUnion, RectangularMembers) {
  Set points("points"), nodes("nodes");
  for (int i = 0; i < 5; ++i)
    points.add();
  for (int i = 0; i < 4; ++i)
    nodes.add();
  Set a("a", {&points, &nodes}), b("b", {&points, &nodes});
  a.add(0, 1);
  a.add(3, 2);
  b.add(0, 1);
  b.add(4, 0);
  auto u = unionPattern({&a, &b}, points, nodes);
  ASSERT_TRUE(bool(u)) << llvm::toString(u.takeError());
  std::set<std::pair<int, int>> expected = {{0, 1}, {3, 2}, {4, 0}};
  EXPECT_EQ(blocksOf(**u), expected);
  EXPECT_THAT(gatherPositions(**u, **SparsityPattern::get(a, points, nodes)),
              ::testing::ElementsAre(0, 1, -1));
  EXPECT_THAT(gatherPositions(**u, **SparsityPattern::get(b, points, nodes)),
              ::testing::ElementsAre(0, -1, 1));
}

// A part read transposed: block (r, c) of the whole is block (c, r) of the
// part, which is over (cols, rows).
TEST(PatternUnion, TransposedGather) {
  Set points("points"), nodes("nodes");
  for (int i = 0; i < 3; ++i)
    points.add();
  for (int i = 0; i < 2; ++i)
    nodes.add();
  Set links("links", {&points, &nodes});
  links.add(0, 1);
  links.add(2, 0);
  links.add(2, 1);
  auto forward = SparsityPattern::get(links, points, nodes); // 3 x 2
  auto backward = SparsityPattern::get(links, nodes, points); // 2 x 3
  ASSERT_TRUE(forward && backward);
  // Backward: (0, 2), (1, 0), (1, 2); forward: (0, 1), (2, 0), (2, 1).
  EXPECT_THAT(gatherTransposedPositions(**backward, **forward),
              ::testing::ElementsAre(1, 0, 2));
}

TEST(PatternUnion, MemberOverOtherSetsIsAnError) {
  Set points("points"), nodes("nodes");
  points.add();
  nodes.add();
  Set a("a", {&points, &points}), b("b", {&nodes, &nodes});
  auto u = unionPattern({&a, &b}, points, points);
  ASSERT_FALSE(bool(u));
  EXPECT_THAT(llvm::toString(u.takeError()),
              ::testing::HasSubstr("expected endpoint sets of 'b'"));
}

} // namespace
