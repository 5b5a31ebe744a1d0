//===--- MeshRefineTest.cpp - Shared meshes and 1-to-8 refinement ---------===//

#include "simit/Runtime/Mesh.h"

#include "TestFiles.h"

#include <cmath>
#include <map>
#include <set>

using namespace simit;
using namespace simit::test;

namespace {

using Point = std::array<double, 3>;
using Tet = std::array<int, 4>;

double totalVolume(const Mesh &mesh) {
  double sum = 0;
  for (const Tet &t : mesh.tets)
    sum += std::abs(signedTetVolume(mesh, t));
  return sum;
}

Mesh loadShared(llvm::StringRef base) {
  auto mesh = loadTetGen(sharedPath(("data/meshes/" + base).str()));
  if (!mesh) {
    ADD_FAILURE() << llvm::toString(mesh.takeError());
    return Mesh();
  }
  return std::move(*mesh);
}

TEST(SharedMeshes, Bunny) {
  Mesh mesh = loadShared("bunny.1");
  EXPECT_EQ(mesh.points.size(), 3607u);
  EXPECT_EQ(mesh.tets.size(), 12687u);
  EXPECT_EQ(mesh.edges.size(), 19233u);
  ASSERT_FALSE(mesh.points.empty());
  // First and last records of bunny.1.node and .ele, as written.
  EXPECT_EQ(mesh.points[0], (Point{-0.89565700000000004, -0.13128500000000001,
                                   1.40157}));
  EXPECT_EQ(mesh.tets.back(), (Tet{2605, 1471, 3382, 3502}));
  EXPECT_EQ(mesh.edges.front(), (std::array<int, 2>{3169, 2323}));
}

TEST(SharedMeshes, Dragon40k) {
  Mesh mesh = loadShared("dragon40k");
  EXPECT_EQ(mesh.points.size(), 11083u);
  EXPECT_EQ(mesh.tets.size(), 40715u);
  EXPECT_TRUE(mesh.edges.empty());
}

TEST(SharedMeshes, Bar2kIsNegativelyOrientedInTheDmConvention) {
  Mesh mesh = loadShared("bar2k");
  EXPECT_EQ(mesh.points.size(), 439u);
  EXPECT_EQ(mesh.tets.size(), 1151u);
  // scenes.md: every tet has det(Dm) < 0 with Dm columns x_i - x_3, which
  // is det[x1-x0, x2-x0, x3-x0] > 0.
  for (const Tet &t : mesh.tets) {
    const auto &p = mesh.points;
    double dm[3][3];
    for (int i = 0; i < 3; ++i)
      for (int d = 0; d < 3; ++d)
        dm[d][i] = p[t[i]][d] - p[t[3]][d];
    double det = dm[0][0] * (dm[1][1] * dm[2][2] - dm[1][2] * dm[2][1]) -
                 dm[0][1] * (dm[1][0] * dm[2][2] - dm[1][2] * dm[2][0]) +
                 dm[0][2] * (dm[1][0] * dm[2][1] - dm[1][1] * dm[2][0]);
    ASSERT_LT(det, 0);
    ASSERT_NEAR(signedTetVolume(mesh, t), -det / 6, 1e-12);
  }
}

TEST(SignedTetVolume, UnitTetIsOneSixth) {
  Mesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_DOUBLE_EQ(signedTetVolume(mesh, {0, 1, 2, 3}), 1.0 / 6);
  EXPECT_DOUBLE_EQ(signedTetVolume(mesh, {0, 1, 3, 2}), -1.0 / 6);
}

/// The midpoint of (a, b) in `refined`, found by position, independently of
/// the refinement's numbering.
int findPoint(const Mesh &refined, const Point &p) {
  for (size_t i = 0; i < refined.points.size(); ++i)
    if (refined.points[i] == p)
      return static_cast<int>(i);
  return -1;
}

Point mid(const Point &a, const Point &b) {
  return {(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2};
}

TEST(RefineTets, SingleTetCornersAndNumbering) {
  Mesh mesh;
  mesh.points = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  mesh.tets = {{0, 1, 2, 3}};
  Mesh refined = refineTets(mesh);
  ASSERT_EQ(refined.points.size(), 10u);
  ASSERT_EQ(refined.tets.size(), 8u);
  // Midpoints in order 01, 02, 03, 12, 13, 23 get ids 4..9.
  const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int k = 0; k < 6; ++k)
    EXPECT_EQ(refined.points[4 + k],
              mid(mesh.points[pairs[k][0]], mesh.points[pairs[k][1]]))
        << "midpoint " << k;
  EXPECT_EQ(refined.tets[0], (Tet{0, 4, 5, 6}));
  EXPECT_EQ(refined.tets[1], (Tet{4, 1, 7, 8}));
  EXPECT_EQ(refined.tets[2], (Tet{5, 7, 2, 9}));
  EXPECT_EQ(refined.tets[3], (Tet{6, 8, 9, 3}));
  EXPECT_NEAR(totalVolume(refined), totalVolume(mesh), 1e-12);
}

/// The inner children of one refined tet share exactly one pair of
/// vertices (the chosen diagonal); returns it sorted.
std::pair<int, int> innerDiagonal(const Mesh &refined) {
  std::map<int, int> uses;
  for (int c = 4; c < 8; ++c)
    for (int v : refined.tets[c])
      ++uses[v];
  std::vector<int> shared;
  for (auto [v, n] : uses)
    if (n == 4)
      shared.push_back(v);
  EXPECT_EQ(shared.size(), 2u);
  return shared.size() == 2 ? std::make_pair(shared[0], shared[1])
                            : std::make_pair(-1, -1);
}

TEST(RefineTets, RegularTetBreaksTheTieWithM01M23) {
  Mesh mesh;
  mesh.points = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  mesh.tets = {{0, 1, 2, 3}};
  Mesh refined = refineTets(mesh);
  int m01 = findPoint(refined, mid(mesh.points[0], mesh.points[1]));
  int m23 = findPoint(refined, mid(mesh.points[2], mesh.points[3]));
  EXPECT_EQ(innerDiagonal(refined), std::make_pair(std::min(m01, m23),
                                                   std::max(m01, m23)));
  // A regular tet splits into eight children of equal volume.
  double parent = signedTetVolume(mesh, mesh.tets[0]);
  for (const Tet &child : refined.tets)
    EXPECT_NEAR(signedTetVolume(refined, child), parent / 8, 1e-12);
}

TEST(RefineTets, PicksTheShortestDiagonal) {
  // m02-m13 is (x1 + x3 - x0 - x2) / 2, short when x2 is near x1 + x3.
  Mesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.5}, {0, 1, 0}};
  mesh.tets = {{0, 1, 2, 3}};
  Mesh refined = refineTets(mesh);
  const auto &p = mesh.points;
  double d0 = 0, d1 = 0, d2 = 0;
  for (int d = 0; d < 3; ++d) {
    d0 += std::pow(mid(p[0], p[1])[d] - mid(p[2], p[3])[d], 2);
    d1 += std::pow(mid(p[0], p[2])[d] - mid(p[1], p[3])[d], 2);
    d2 += std::pow(mid(p[0], p[3])[d] - mid(p[1], p[2])[d], 2);
  }
  ASSERT_LT(d1, d0);
  ASSERT_LT(d1, d2);
  int m02 = findPoint(refined, mid(p[0], p[2]));
  int m13 = findPoint(refined, mid(p[1], p[3]));
  EXPECT_EQ(innerDiagonal(refined),
            std::make_pair(std::min(m02, m13), std::max(m02, m13)));
  EXPECT_NEAR(totalVolume(refined), totalVolume(mesh), 1e-12);
}

TEST(RefineTets, SharedEdgesGetOneMidpoint) {
  Mesh mesh;
  mesh.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  mesh.tets = {{0, 1, 2, 3}, {1, 2, 3, 4}};
  Mesh refined = refineTets(mesh);
  // 6 + 6 edges, 3 of them (12, 13, 23) shared.
  EXPECT_EQ(refined.points.size(), 5u + 9u);
  EXPECT_EQ(refined.tets.size(), 16u);
}

TEST(RefineTets, Dragon40kCountsOrientationAndVolume) {
  Mesh mesh = loadShared("dragon40k");
  ASSERT_EQ(mesh.tets.size(), 40715u);
  Mesh refined = refineTets(mesh);
  EXPECT_EQ(refined.points.size(), 73964u);
  ASSERT_EQ(refined.tets.size(), 325720u);
  std::set<std::pair<int, int>> edges;
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    double parent = signedTetVolume(mesh, mesh.tets[t]);
    double children = 0;
    for (int c = 0; c < 8; ++c) {
      double child = signedTetVolume(refined, refined.tets[8 * t + c]);
      ASSERT_EQ(child > 0, parent > 0) << "tet " << t << " child " << c;
      children += child;
    }
    ASSERT_NEAR(children, parent, 1e-12 * std::max(1.0, std::abs(parent)))
        << "tet " << t;
  }
  EXPECT_NEAR(totalVolume(refined), totalVolume(mesh),
              1e-12 * totalVolume(mesh));
}

} // namespace
