//===--- SetTest.cpp - Sets, fields, endpoints and grids ------------------===//

#include "simit/Runtime/Set.h"

#include "TestFiles.h"

#include "gmock/gmock.h"

#include <set>
#include <tuple>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

TEST(Set, ThePapersPyramid) {
  Set verts;
  Set tets(verts, verts, verts, verts);
  FieldRef<double, 3> x = verts.addField<double, 3>("x");
  FieldRef<double> w = tets.addField<double>("W");
  FieldRef<double, 3, 3> b = tets.addField<double, 3, 3>("B");
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(verts.add(), i);
  int t0 = tets.add(0, 1, 2, 4);
  int t1 = tets.add(1, 2, 3, 4);
  x.set(4, {0.0, 1.0, 0.0});
  w.set(t1, 2.5);
  b.set(t0, {1, 2, 3, 4, 5, 6, 7, 8, 9});
  EXPECT_EQ(verts.size(), 5);
  EXPECT_EQ(tets.size(), 2);
  EXPECT_EQ(tets.cardinality(), 4);
  EXPECT_EQ(x.get(4), (std::array<double, 3>{0, 1, 0}));
  EXPECT_EQ(x.get(3), (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(w.get(t1), 2.5);
  EXPECT_EQ(w.get(t0), 0.0);
  // Row-major block: B(1, 2) of t0 is component 1 * 3 + 2.
  const double *raw = static_cast<const double *>(tets.fieldData("B"));
  EXPECT_EQ(raw[5], 6.0);
  EXPECT_EQ(raw[9], 0.0);
  EXPECT_EQ(tets.endpoint(t1, 3), 4);
  EXPECT_EQ(std::vector<int32_t>(tets.endpointData(), tets.endpointData() + 8),
            (std::vector<int32_t>{0, 1, 2, 4, 1, 2, 3, 4}));
}

TEST(Set, FieldArraysAreContiguousAlignedAndTyped) {
  Set points("points");
  auto f32 = points.addField<float, 2>("f");
  auto i32 = points.addField<int32_t>("i");
  auto flag = points.addField<bool>("fixed");
  for (int e = 0; e < 100; ++e) {
    points.add();
    f32.set(e, {float(e), float(-e)});
    i32.set(e, 3 * e);
    flag.set(e, e % 3 == 0);
  }
  for (const char *name : {"f", "i", "fixed"})
    EXPECT_EQ(reinterpret_cast<uintptr_t>(points.fieldData(name)) % 64, 0u)
        << name;
  const float *f = static_cast<const float *>(points.fieldData("f"));
  const int32_t *i = static_cast<const int32_t *>(points.fieldData("i"));
  const uint8_t *fixed =
      static_cast<const uint8_t *>(points.fieldData("fixed"));
  EXPECT_EQ(f[2 * 57 + 1], -57.0f);
  EXPECT_EQ(i[99], 297);
  EXPECT_EQ(fixed[99], 1);
  EXPECT_EQ(fixed[98], 0);
  EXPECT_EQ(points.fieldDescriptor("f")->blockBytes(), 8u);
  EXPECT_EQ(points.fieldDescriptor("fixed")->type, ComponentType::Bool);
  EXPECT_EQ(points.fieldData("missing"), nullptr);
}

TEST(Set, FieldAddedLaterIsZeroAndKeepsOthers) {
  Set points;
  auto a = points.addField<double>("a");
  for (int e = 0; e < 40; ++e)
    a.set(points.add(), e + 0.5);
  auto late = points.addField<double>("late", {2, 2});
  EXPECT_EQ(late.blockSize(), 4u);
  for (int e = 0; e < 40; ++e) {
    EXPECT_EQ(a.get(e), e + 0.5);
    for (double v : late.get(e))
      EXPECT_EQ(v, 0.0);
  }
  late.set(7, std::vector<double>{1, 2, 3, 4});
  EXPECT_EQ(late.get(7)[3], 4.0);
  EXPECT_EQ(static_cast<double *>(points.fieldData("late"))[7 * 4 + 2], 3.0);
}

TEST(Set, UntypedFieldErrors) {
  Set points("points");
  EXPECT_FALSE(bool(points.addField("x", ComponentType::Float64, {3})));
  EXPECT_THAT(errorOf(points.addField("x", ComponentType::Float32, {})),
              HasSubstr("set 'points': field 'x' already exists"));
  EXPECT_THAT(errorOf(points.addField("y", ComponentType::Float64, {3, 0})),
              HasSubstr("field 'y': expected positive dimensions, found 0"));
  EXPECT_THAT(errorOf(points.addField("", ComponentType::Float64, {})),
              HasSubstr("a field needs a name"));
}

TEST(Set, TypedAccessToAnExistingField) {
  Set points;
  ASSERT_FALSE(bool(points.addField("x", ComponentType::Float64, {3})));
  points.add();
  points.field<double, 3>("x").set(0, {1, 2, 3});
  EXPECT_EQ(points.dynamicField<double>("x").get(0)[1], 2.0);
  EXPECT_EQ(points.fields().size(), 1u);
  points.removeField("x");
  EXPECT_FALSE(points.hasField("x"));
}

TEST(SetDeathTest, WrongTypedAccessIsAFatalError) {
  Set points("points");
  ASSERT_FALSE(bool(points.addField("x", ComponentType::Float64, {3})));
  EXPECT_DEATH((points.field<float, 3>("x")),
               "another component type or shape");
  EXPECT_DEATH((points.field<double, 2>("x")),
               "another component type or shape");
  EXPECT_DEATH(points.field<double>("nope"), "no field 'nope'");
}

TEST(Set, EndpointChecks) {
  Set verts("verts");
  Set springs("springs", {&verts, &verts});
  verts.add();
  verts.add();
  EXPECT_FALSE(bool(springs.checkEndpoints({0, 1})));
  EXPECT_THAT(errorOf(springs.checkEndpoints({0})),
              HasSubstr("set 'springs': expected 2 endpoints, found 1"));
  EXPECT_THAT(errorOf(springs.checkEndpoints({0, 2})),
              HasSubstr("endpoint 1 is 2, out of range for set 'verts' of "
                        "size 2"));
  EXPECT_THAT(errorOf(springs.checkEndpoints({-1, 0})),
              HasSubstr("endpoint 0 is -1"));
}

TEST(SetDeathTest, AddingABadEdgeIsAFatalError) {
  Set verts("verts");
  Set springs("springs", {&verts, &verts});
  verts.add();
  EXPECT_DEATH(springs.add(0, 3), "out of range");
  EXPECT_DEATH(springs.add(), "add\\(\\) without endpoints");
}

TEST(Set, HeterogeneousEndpoints) {
  Set particles("particles"), nodes("nodes");
  Set links("links", {&particles, &nodes});
  for (int i = 0; i < 3; ++i)
    particles.add();
  nodes.add();
  EXPECT_EQ(links.add(2, 0), 0);
  EXPECT_EQ(&links.endpointSet(0), &particles);
  EXPECT_EQ(&links.endpointSet(1), &nodes);
  EXPECT_FALSE(bool(links.checkEndpoints({2, 0})));
  EXPECT_TRUE(bool(links.checkEndpoints({0, 1}))) << "nodes has one element";
  llvm::consumeError(links.checkEndpoints({0, 1}));
}

TEST(Set, VersionBumpsOnStructuralChange) {
  Set verts;
  uint64_t v0 = verts.version();
  verts.add();
  uint64_t v1 = verts.version();
  EXPECT_GT(v1, v0);
  auto x = verts.addField<double>("x");
  uint64_t v2 = verts.version();
  EXPECT_GT(v2, v1);
  x.set(0, 1.0); // writing values is not structural
  EXPECT_EQ(verts.version(), v2);
  verts.remove(0);
  EXPECT_GT(verts.version(), v2);
}

TEST(Set, PointersStayValidWithinTheCapacity) {
  Set verts;
  verts.addField<double>("x");
  verts.reserve(1000);
  void *before = verts.fieldData("x");
  for (int i = 0; i < 1000; ++i)
    verts.add();
  EXPECT_EQ(verts.fieldData("x"), before);
  verts.add();
  EXPECT_EQ(verts.size(), 1001);
}

TEST(Set, RemoveMovesTheLastElementAndZeroesReusedSlots) {
  Set verts;
  auto x = verts.addField<double>("x");
  for (int i = 0; i < 4; ++i)
    x.set(verts.add(), 10.0 + i);
  verts.remove(1);
  ASSERT_EQ(verts.size(), 3);
  EXPECT_EQ(x.get(0), 10.0);
  EXPECT_EQ(x.get(1), 13.0);
  EXPECT_EQ(x.get(2), 12.0);
  int e = verts.add();
  EXPECT_EQ(e, 3);
  EXPECT_EQ(x.get(3), 0.0);
}

TEST(Set, RemovingAVertexRemovesAndRenumbersItsEdges) {
  Set verts;
  Set springs(verts, verts);
  auto k = springs.addField<double>("k");
  for (int i = 0; i < 5; ++i)
    verts.add();
  // Edges: (0,1) (1,2) (2,3) (3,4) (4,0)
  for (int i = 0; i < 5; ++i)
    k.set(springs.add(i, (i + 1) % 5), i);
  verts.remove(2); // vertex 4 becomes 2
  ASSERT_EQ(verts.size(), 4);
  // (1,2) and (2,3) go; the rest keep their stiffness, 4 renamed to 2.
  std::multiset<std::tuple<int, int, double>> remaining;
  for (int e = 0; e < springs.size(); ++e)
    remaining.insert({springs.endpoint(e, 0), springs.endpoint(e, 1),
                      k.get(e)});
  EXPECT_EQ(remaining, (std::multiset<std::tuple<int, int, double>>{
                           {0, 1, 0.0}, {3, 2, 3.0}, {2, 0, 4.0}}));
}

TEST(Set, GridConnectsNeighboursPeriodically) {
  Set points("points");
  auto grid = Set::makeGrid(points, {2, 3}, "g");
  ASSERT_TRUE(bool(grid)) << llvm::toString(grid.takeError());
  Set &g = **grid;
  EXPECT_TRUE(g.isGrid());
  EXPECT_EQ(points.size(), 6);
  ASSERT_EQ(g.size(), 12);
  // Point (k0, k1) is k0 * 3 + k1; edge p * 2 + a goes one step along a.
  for (int k0 = 0; k0 < 2; ++k0)
    for (int k1 = 0; k1 < 3; ++k1) {
      int p = k0 * 3 + k1;
      EXPECT_EQ(g.endpoint(2 * p, 0), p);
      EXPECT_EQ(g.endpoint(2 * p, 1), ((k0 + 1) % 2) * 3 + k1);
      EXPECT_EQ(g.endpoint(2 * p + 1, 1), k0 * 3 + (k1 + 1) % 3);
    }
}

TEST(Set, GridErrors) {
  Set points("points");
  points.add();
  EXPECT_THAT(errorOf(Set::makeGrid(points, {2, 2}, "g")),
              HasSubstr("grid 'g': the point set 'points' has 1 points, "
                        "expected 4"));
  Set fresh("fresh");
  EXPECT_THAT(errorOf(Set::makeGrid(fresh, {2, 0}, "g")),
              HasSubstr("expected positive dimensions, found 0"));
  EXPECT_THAT(errorOf(Set::makeGrid(fresh, {}, "g")),
              HasSubstr("expected at least one dimension"));
  Set edges("edges", {&points});
  EXPECT_THAT(errorOf(Set::makeGrid(edges, {1}, "g")),
              HasSubstr("the point set 'edges' is an edge set"));
}

} // namespace
