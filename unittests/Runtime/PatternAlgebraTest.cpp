//===--- PatternAlgebraTest.cpp - Unions, gather maps and products --------===//

#include "simit/Runtime/PatternAlgebra.h"
#include "simit/Runtime/SparseProduct.h"

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

// The product pattern of two random patterns holds exactly the blocks
// (r, c) with a path r -> m -> c, plus the diagonal when asked; the numeric
// product on it matches a dense product.
TEST(PatternProduct, MatchesDenseProduct) {
  Set verts("verts");
  for (int i = 0; i < 12; ++i)
    verts.add();
  Set springs("springs", {&verts, &verts});
  Set tets("tets", {&verts, &verts, &verts, &verts});
  addRandomEdges(springs, 10, 12, 4);
  addRandomEdges(tets, 3, 12, 5);
  auto a = *SparsityPattern::get(springs, verts, verts);
  auto b = *SparsityPattern::get(tets, verts, verts);
  for (bool withDiagonal : {false, true}) {
    auto c = productPattern(*a, *b, withDiagonal);
    std::set<std::pair<int, int>> expected;
    for (auto [r, m] : blocksOf(*a))
      for (auto [m2, col] : blocksOf(*b))
        if (m == m2)
          expected.insert({r, col});
    if (withDiagonal)
      for (int r = 0; r < 12; ++r)
        expected.insert({r, r});
    EXPECT_EQ(blocksOf(*c), expected);
  }

  // Values: 2x2 blocks, random; C = A B against dense.
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> value(-1, 1);
  auto c = productPattern(*a, *b, true);
  std::vector<double> av(a->numBlocks() * 4), bv(b->numBlocks() * 4),
      cv(c->numBlocks() * 4, 99.0);
  for (double &v : av)
    v = value(rng);
  for (double &v : bv)
    v = value(rng);
  auto view = [](const SparsityPattern &p, std::vector<double> &values) {
    BlockMatrixView<double> m;
    m.rows = p.numRows();
    m.cols = p.numCols();
    m.blockRows = m.blockCols = 2;
    m.rowptr = p.rowPointers().data();
    m.colidx = p.columnIndices().data();
    m.values = values.data();
    return m;
  };
  ASSERT_FALSE(bool(multiplyInto(view(*a, av), view(*b, bv), view(*c, cv))));
  auto dense = [](const SparsityPattern &p, const std::vector<double> &v) {
    std::vector<std::vector<double>> d(24, std::vector<double>(24, 0.0));
    for (int r = 0; r < p.numRows(); ++r)
      for (int k = p.rowPointers()[r]; k < p.rowPointers()[r + 1]; ++k)
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j)
            d[2 * r + i][2 * p.columnIndices()[k] + j] = v[k * 4 + i * 2 + j];
    return d;
  };
  auto da = dense(*a, av), db = dense(*b, bv), dc = dense(*c, cv);
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j) {
      double sum = 0;
      for (int k = 0; k < 24; ++k)
        sum += da[i][k] * db[k][j];
      EXPECT_NEAR(dc[i][j], sum, 1e-12) << i << ", " << j;
    }
}

// A chain's pattern holds the product however it is associated: A (B C)
// stores B C over (V, V) with its diagonal, so A's own block (0, 1) is in
// it, although (A B) C, with A B over (V, S) and no diagonal, has none
// there. Vertex 1 is in no edge of the incidence B = C'.
TEST(PatternProduct, ChainHoldsEveryAssociation) {
  auto a = SparsityPattern::fromArrays(2, 2, {0, 1, 1}, {1});
  auto b = SparsityPattern::fromArrays(2, 1, {0, 1, 1}, {0});
  auto c = SparsityPattern::fromArrays(1, 2, {0, 1}, {0});
  auto chain = chainProductPattern({a.get(), b.get(), c.get()},
                                   {"V", "V", "S", "V"});
  std::set<std::pair<int, int>> expected{{0, 0}, {0, 1}, {1, 1}};
  EXPECT_EQ(blocksOf(*chain), expected);
  // Two factors: productPattern's, with the diagonal when square.
  EXPECT_EQ(blocksOf(*chainProductPattern({a.get(), a.get()}, {"V", "V", "V"})),
            blocksOf(*productPattern(*a, *a, true)));
  EXPECT_EQ(blocksOf(*chainProductPattern({b.get(), c.get()}, {"V", "S", "V"})),
            blocksOf(*productPattern(*b, *c, true)));
  EXPECT_EQ(blocksOf(*chainProductPattern({c.get(), b.get()}, {"S", "V", "S"})),
            blocksOf(*productPattern(*c, *b, true)));
}

// A result pattern that misses a block of the product is an error, not a
// dropped contribution.
TEST(PatternProduct, MissingBlockIsAnError) {
  auto a = SparsityPattern::fromArrays(2, 2, {0, 1, 2}, {1, 0});
  auto c = SparsityPattern::fromArrays(2, 2, {0, 1, 2}, {0, 1});
  std::vector<double> av{1.0, 2.0}, cv(2);
  BlockMatrixView<double> left, right, result;
  for (auto *m : {&left, &right, &result}) {
    m->rows = m->cols = 2;
    m->colidx = m == &result ? c->columnIndices().data()
                             : a->columnIndices().data();
    m->rowptr = m == &result ? c->rowPointers().data()
                             : a->rowPointers().data();
  }
  left.values = right.values = av.data();
  result.values = cv.data();
  // (a a) is diagonal, which c holds; (a) alone as the result does not.
  EXPECT_FALSE(bool(multiplyInto(left, right, result)));
  result.rowptr = a->rowPointers().data();
  result.colidx = a->columnIndices().data();
  llvm::Error err = multiplyInto(left, right, result);
  ASSERT_TRUE(bool(err));
  EXPECT_THAT(llvm::toString(std::move(err)),
              ::testing::HasSubstr("block (0, 0) of the product is not in "
                                   "the result's pattern"));
}

} // namespace
