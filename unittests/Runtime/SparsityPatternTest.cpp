//===--- SparsityPatternTest.cpp - BCSR index, location tables, SpMV ------===//

#include "simit/Runtime/Mesh.h"
#include "simit/Runtime/SparsityPattern.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include <random>
#include <set>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// Every (row, col) block an assembly from `edges` over (rows, cols) can
/// write, found by brute force over all edges and endpoint pairs.
std::set<std::pair<int, int>> bruteForceBlocks(const Set &edges,
                                               const Set &rows,
                                               const Set &cols) {
  std::set<std::pair<int, int>> blocks;
  if (&rows == &cols)
    for (int r = 0; r < rows.size(); ++r)
      blocks.insert({r, r});
  for (int e = 0; e < edges.size(); ++e)
    for (int i = 0; i < edges.cardinality(); ++i)
      for (int j = 0; j < edges.cardinality(); ++j)
        if (&edges.endpointSet(i) == &rows && &edges.endpointSet(j) == &cols)
          blocks.insert({edges.endpoint(e, i), edges.endpoint(e, j)});
  return blocks;
}

/// Checks the pattern's arrays and location table against brute force.
void checkPattern(const SparsityPattern &p, const Set &edges, const Set &rows,
                  const Set &cols) {
  std::set<std::pair<int, int>> expected = bruteForceBlocks(edges, rows, cols);
  ASSERT_EQ(p.numRows(), rows.size());
  ASSERT_EQ(p.numCols(), cols.size());
  ASSERT_EQ(p.numBlocks(), static_cast<int>(expected.size()));
  // Walking rowPtr/colIdx in order lists the sorted block set.
  std::vector<std::pair<int, int>> listed;
  for (int r = 0; r < p.numRows(); ++r)
    for (int k = p.rowPointers()[r]; k < p.rowPointers()[r + 1]; ++k)
      listed.push_back({r, p.columnIndices()[k]});
  std::vector<std::pair<int, int>> sorted(expected.begin(), expected.end());
  EXPECT_EQ(listed, sorted);
  int c = edges.cardinality();
  ASSERT_EQ(p.locations().size(), static_cast<size_t>(edges.size()) * c * c);
  for (int e = 0; e < edges.size(); ++e)
    for (int i = 0; i < c; ++i)
      for (int j = 0; j < c; ++j) {
        int k = p.location(e, i, j);
        if (&edges.endpointSet(i) != &rows || &edges.endpointSet(j) != &cols) {
          EXPECT_EQ(k, -1);
          continue;
        }
        ASSERT_GE(k, 0);
        EXPECT_EQ(listed[k], std::make_pair(edges.endpoint(e, i),
                                            edges.endpoint(e, j)))
            << "edge " << e << " pair " << i << "," << j;
      }
}

TEST(SparsityPattern, SpringsWithAnIsolatedVertex) {
  Set verts("verts");
  Set springs("springs", {&verts, &verts});
  for (int i = 0; i < 5; ++i)
    verts.add();
  springs.add(0, 1);
  springs.add(1, 2);
  springs.add(3, 1);
  // Vertex 4 has no spring but keeps its diagonal block.
  auto p = SparsityPattern::get(springs, verts, verts);
  ASSERT_TRUE(bool(p)) << llvm::toString(p.takeError());
  EXPECT_EQ((*p)->rowPointers().vec(), (std::vector<int32_t>{0, 2, 6, 8, 10, 11}));
  EXPECT_EQ((*p)->columnIndices().vec(),
            (std::vector<int32_t>{0, 1, 0, 1, 2, 3, 1, 2, 1, 3, 4}));
  // Spring 2 = (3, 1): block (3, 1) is index 8, (1, 3) is index 5.
  EXPECT_EQ((*p)->location(2, 0, 1), 8);
  EXPECT_EQ((*p)->location(2, 1, 0), 5);
  EXPECT_EQ((*p)->location(2, 0, 0), 9);
  checkPattern(**p, springs, verts, verts);
}

TEST(SparsityPattern, RandomTetsMatchBruteForce) {
  std::mt19937 rng(7);
  Set verts("verts");
  Set tets("tets", {&verts, &verts, &verts, &verts});
  for (int i = 0; i < 60; ++i)
    verts.add();
  std::uniform_int_distribution<int> pick(0, 59);
  for (int t = 0; t < 150; ++t)
    tets.add(pick(rng), pick(rng), pick(rng), pick(rng));
  auto p = SparsityPattern::get(tets, verts, verts);
  ASSERT_TRUE(bool(p)) << llvm::toString(p.takeError());
  checkPattern(**p, tets, verts, verts);
}

TEST(SparsityPattern, HeterogeneousRowsAndColumns) {
  std::mt19937 rng(11);
  Set particles("particles"), nodes("nodes");
  Set links("links", {&particles, &nodes, &particles});
  for (int i = 0; i < 20; ++i)
    particles.add();
  for (int i = 0; i < 7; ++i)
    nodes.add();
  std::uniform_int_distribution<int> pickP(0, 19), pickN(0, 6);
  for (int e = 0; e < 40; ++e)
    links.add(pickP(rng), pickN(rng), pickP(rng));
  for (auto [rows, cols] : {std::pair<Set *, Set *>{&particles, &nodes},
                           {&nodes, &particles},
                           {&particles, &particles},
                           {&nodes, &nodes}}) {
    auto p = SparsityPattern::get(links, *rows, *cols);
    ASSERT_TRUE(bool(p)) << llvm::toString(p.takeError());
    SCOPED_TRACE(rows->name().str() + " x " + cols->name().str());
    checkPattern(**p, links, *rows, *cols);
  }
}

TEST(SparsityPattern, SharedMeshBlockCounts) {
  // A vertex-vertex pattern has one diagonal block per vertex and two blocks
  // per distinct mesh edge. bunny.1.edge lists 19,233 distinct edges; the
  // tets of dragon40k have 73,964 - 11,083 distinct edges (one refinement
  // midpoint each, scenes.md).
  struct Case {
    const char *base;
    int cardinality;
    int expectedBlocks;
  } cases[] = {{"bunny.1", 2, 3607 + 2 * 19233},
               {"dragon40k", 4, 11083 + 2 * (73964 - 11083)}};
  for (const Case &c : cases) {
    auto mesh = loadTetGen(sharedPath(std::string("data/meshes/") + c.base));
    ASSERT_TRUE(bool(mesh)) << llvm::toString(mesh.takeError());
    Set verts("verts");
    std::vector<Set *> ends(c.cardinality, &verts);
    Set elements("elements", ends);
    verts.reserve(mesh->points.size());
    for (size_t i = 0; i < mesh->points.size(); ++i)
      verts.add();
    if (c.cardinality == 2)
      for (auto e : mesh->edges)
        elements.add(e[0], e[1]);
    else
      for (auto t : mesh->tets)
        elements.add(t[0], t[1], t[2], t[3]);
    auto p = SparsityPattern::get(elements, verts, verts);
    ASSERT_TRUE(bool(p));
    EXPECT_EQ((*p)->numBlocks(), c.expectedBlocks) << c.base;
    // Symmetric: (r, c) present iff (c, r) is.
    for (int r = 0; r < (*p)->numRows(); ++r)
      for (int k = (*p)->rowPointers()[r]; k < (*p)->rowPointers()[r + 1]; ++k)
        ASSERT_GE((*p)->findBlock((*p)->columnIndices()[k], r), 0);
  }
}

TEST(SparsityPattern, RowsAndColumnsMustBeEndpointSets) {
  Set verts("verts"), other("other");
  Set springs("springs", {&verts, &verts});
  EXPECT_THAT(errorOf(SparsityPattern::get(springs, verts, other)),
              HasSubstr("sparsity pattern over (verts, other) from set "
                        "'springs': expected endpoint sets of 'springs'"));
}

TEST(SparsityPattern, CachedAndRebuiltOnChange) {
  Set verts("verts");
  Set springs("springs", {&verts, &verts});
  for (int i = 0; i < 3; ++i)
    verts.add();
  springs.add(0, 1);
  auto first = SparsityPattern::get(springs, verts, verts);
  auto again = SparsityPattern::get(springs, verts, verts);
  ASSERT_TRUE(first && again);
  EXPECT_EQ(first->get(), again->get()) << "shared, not rebuilt";
  springs.add(1, 2);
  auto rebuilt = SparsityPattern::get(springs, verts, verts);
  ASSERT_TRUE(bool(rebuilt));
  EXPECT_NE(rebuilt->get(), first->get());
  EXPECT_EQ((*rebuilt)->numBlocks(), 7);
  EXPECT_EQ((*first)->numBlocks(), 5) << "old holders keep the old pattern";
  verts.add(); // a new row needs a new diagonal block
  auto grown = SparsityPattern::get(springs, verts, verts);
  ASSERT_TRUE(bool(grown));
  EXPECT_EQ((*grown)->numBlocks(), 8);
  checkPattern(**grown, springs, verts, verts);
}

TEST(SparsityPattern, DiagonalPatternNeedsNoIndex) {
  Set verts;
  for (int i = 0; i < 4; ++i)
    verts.add();
  auto p = SparsityPattern::diagonal(verts);
  EXPECT_EQ(p->numBlocks(), 4);
  EXPECT_TRUE(p->locations().empty());
  for (int r = 0; r < 4; ++r)
    EXPECT_EQ(p->findBlock(r, r), r);
  EXPECT_EQ(p->findBlock(0, 1), -1);
}

/// A dense copy of a BCSR matrix.
std::vector<std::vector<double>> toDense(const BCSRMatrix &a) {
  const SparsityPattern &p = *a.pattern;
  std::vector<std::vector<double>> dense(
      p.numRows() * a.blockRows,
      std::vector<double>(p.numCols() * a.blockCols, 0.0));
  for (int r = 0; r < p.numRows(); ++r)
    for (int k = p.rowPointers()[r]; k < p.rowPointers()[r + 1]; ++k)
      for (int i = 0; i < a.blockRows; ++i)
        for (int j = 0; j < a.blockCols; ++j)
          dense[r * a.blockRows + i][p.columnIndices()[k] * a.blockCols + j] =
              a.block(k)[i * a.blockCols + j];
  return dense;
}

TEST(SpMV, MatchesDenseForSquareAndRectangularBlocks) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-1, 1);
  Set particles("particles"), nodes("nodes");
  Set links("links", {&particles, &nodes});
  for (int i = 0; i < 9; ++i)
    particles.add();
  for (int i = 0; i < 5; ++i)
    nodes.add();
  std::uniform_int_distribution<int> pickP(0, 8), pickN(0, 4);
  for (int e = 0; e < 15; ++e)
    links.add(pickP(rng), pickN(rng));
  auto pattern = SparsityPattern::get(links, particles, nodes);
  ASSERT_TRUE(bool(pattern));
  for (auto [br, bc] : {std::pair<int, int>{1, 1}, {3, 3}, {2, 3}}) {
    BCSRMatrix a(*pattern, br, bc);
    for (double &v : a.values)
      v = value(rng);
    std::vector<double> x(5 * bc), y(9 * br, 42.0);
    for (double &v : x)
      v = value(rng);
    multiply(a, x.data(), y.data());
    auto dense = toDense(a);
    for (int i = 0; i < 9 * br; ++i) {
      double expected = 0;
      for (int j = 0; j < 5 * bc; ++j)
        expected += dense[i][j] * x[j];
      EXPECT_NEAR(y[i], expected, 1e-14) << br << "x" << bc << " row " << i;
    }
  }
}

TEST(SpMV, AssemblyThroughTheLocationTable) {
  // Assemble the graph Laplacian of a path through the location table and
  // compare with the closed form: (L x)_i = 2 x_i - x_{i-1} - x_{i+1}.
  Set verts;
  Set springs(verts, verts);
  const int n = 6;
  for (int i = 0; i < n; ++i)
    verts.add();
  for (int i = 0; i + 1 < n; ++i)
    springs.add(i, i + 1);
  auto pattern = SparsityPattern::get(springs, verts, verts);
  ASSERT_TRUE(bool(pattern));
  BCSRMatrix l(*pattern, 1, 1);
  for (int e = 0; e < springs.size(); ++e)
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        l.values[(*pattern)->location(e, i, j)] += i == j ? 1.0 : -1.0;
  std::vector<double> x(n), y(n);
  for (int i = 0; i < n; ++i)
    x[i] = i * i;
  multiply(l, x.data(), y.data());
  for (int i = 0; i < n; ++i) {
    double expected = (i > 0 ? x[i] - x[i - 1] : 0.0) +
                      (i + 1 < n ? x[i] - x[i + 1] : 0.0);
    EXPECT_DOUBLE_EQ(y[i], expected) << i;
  }
}

} // namespace
