//===--- IncidenceViewTest.cpp - Incidence matrices row by row ------------===//

#include "simit/Runtime/IncidenceView.h"
#include "simit/Runtime/PatternAlgebra.h"
#include "simit/Runtime/SparseProduct.h"

#include "gmock/gmock.h"

#include <Eigen/Dense>

using namespace simit;
using testing::ElementsAre;

namespace {

/// Four vertices and three springs; spring 2 names vertex 3 twice.
struct Springs {
  Set verts{"verts"};
  Set springs{"springs", {&verts, &verts}};
  Springs() {
    for (int i = 0; i < 4; ++i)
      verts.add();
    springs.add(0, 2);
    springs.add(2, 1);
    springs.add(3, 3);
  }
};

TEST(IncidenceView, RowsAreEdgesInEndpointOrder) {
  Springs s;
  auto view = IncidenceView::get(s.springs, s.verts, /*transposed=*/false);
  ASSERT_TRUE(bool(view)) << llvm::toString(view.takeError());
  EXPECT_EQ((*view)->rows, 3);
  EXPECT_EQ((*view)->cols, 4);
  EXPECT_THAT((*view)->rowPtr, ElementsAre(0, 2, 4, 6));
  EXPECT_THAT((*view)->colIdx, ElementsAre(0, 2, 2, 1, 3, 3));
  EXPECT_THAT((*view)->positions, ElementsAre(0, 1, 2, 3, 4, 5));
}

TEST(IncidenceView, TransposedRowsAreVerticesByEdge) {
  Springs s;
  auto view = IncidenceView::get(s.springs, s.verts, /*transposed=*/true);
  ASSERT_TRUE(bool(view)) << llvm::toString(view.takeError());
  EXPECT_EQ((*view)->rows, 4);
  EXPECT_EQ((*view)->cols, 3);
  // Vertex 0: spring 0 (block 0); 1: spring 1 (block 3); 2: springs 0 and
  // 1 (blocks 1, 2); 3: spring 2 twice (blocks 4, 5).
  EXPECT_THAT((*view)->rowPtr, ElementsAre(0, 1, 2, 4, 6));
  EXPECT_THAT((*view)->colIdx, ElementsAre(0, 1, 0, 1, 2, 2));
  EXPECT_THAT((*view)->positions, ElementsAre(0, 3, 1, 2, 4, 5));
}

TEST(IncidenceView, PatternMergesRepeatedColumns) {
  Springs s;
  auto pattern = unionPattern({&s.springs}, s.verts, s.springs);
  ASSERT_TRUE(bool(pattern)) << llvm::toString(pattern.takeError());
  EXPECT_THAT((*pattern)->rowPointers(), ElementsAre(0, 1, 2, 4, 5));
  EXPECT_THAT((*pattern)->columnIndices(), ElementsAre(0, 1, 0, 1, 2));
}

/// Links (verts, nodes, nodes): the incidence over nodes holds positions 1
/// and 2, over verts position 0.
struct Links {
  Set verts{"verts"}, nodes{"nodes"};
  Set links{"links", {&verts, &nodes, &nodes}};
  Links() {
    for (int i = 0; i < 2; ++i)
      verts.add();
    for (int i = 0; i < 3; ++i)
      nodes.add();
    links.add(1, 2, 0);
    links.add(0, 1, 1);
  }
};

TEST(IncidenceView, HoldsTheEndpointPositionsInItsColumnSet) {
  Links l;
  auto nodes = IncidenceView::get(l.links, l.nodes, /*transposed=*/false);
  ASSERT_TRUE(bool(nodes)) << llvm::toString(nodes.takeError());
  EXPECT_EQ((*nodes)->cols, 3);
  EXPECT_THAT((*nodes)->rowPtr, ElementsAre(0, 2, 4));
  EXPECT_THAT((*nodes)->colIdx, ElementsAre(2, 0, 1, 1));
  EXPECT_THAT((*nodes)->positions, ElementsAre(0, 1, 2, 3));
  auto verts = IncidenceView::get(l.links, l.verts, /*transposed=*/false);
  ASSERT_TRUE(bool(verts)) << llvm::toString(verts.takeError());
  EXPECT_THAT((*verts)->rowPtr, ElementsAre(0, 1, 2));
  EXPECT_THAT((*verts)->colIdx, ElementsAre(1, 0));
}

TEST(IncidenceView, TransposedHoldsTheSamePositions) {
  Links l;
  auto view = IncidenceView::get(l.links, l.nodes, /*transposed=*/true);
  ASSERT_TRUE(bool(view)) << llvm::toString(view.takeError());
  // Node 0: link 0 (block 1); 1: link 1 twice (blocks 2, 3); 2: link 0
  // (block 0).
  EXPECT_THAT((*view)->rowPtr, ElementsAre(0, 1, 3, 4));
  EXPECT_THAT((*view)->colIdx, ElementsAre(0, 1, 1, 0));
  EXPECT_THAT((*view)->positions, ElementsAre(1, 2, 3, 0));
}

TEST(IncidenceView, RejectsASetOfNoEndpoint) {
  Links l;
  Set other("other");
  other.add();
  auto view = IncidenceView::get(l.links, other, /*transposed=*/false);
  ASSERT_FALSE(bool(view));
  EXPECT_THAT(llvm::toString(view.takeError()),
              testing::HasSubstr("no endpoint of 'links' is in 'other'"));
}

// D' D of the incidence D over (springs, verts), through the view of D'
// and of D, equals the dense product; spring 2's two blocks at vertex 3
// both count.
TEST(IncidenceView, ProductOfViewsMatchesDense) {
  Springs s;
  auto rows = IncidenceView::get(s.springs, s.verts, false);
  auto cols = IncidenceView::get(s.springs, s.verts, true);
  ASSERT_TRUE(rows && cols);
  std::vector<double> d = {1.5, -2.0, 0.5, 3.0, 4.0, -1.0};
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(3, 4);
  for (int e = 0; e < 3; ++e)
    for (int k = 0; k < 2; ++k)
      dense(e, s.springs.endpoint(e, k)) += d[e * 2 + k];
  Eigen::MatrixXd expected = dense.transpose() * dense;

  auto pattern = productPattern(*(*cols)->pattern(), *(*rows)->pattern(),
                                /*withDiagonal=*/true);
  std::vector<double> values(pattern->numBlocks());
  auto view = [](const IncidenceView &v, double *data) {
    BlockMatrixView<double> m;
    m.rows = v.rows;
    m.cols = v.cols;
    m.rowptr = v.rowPtr.data();
    m.colidx = v.colIdx.data();
    m.positions = v.positions.data();
    m.values = data;
    return m;
  };
  BlockMatrixView<double> result;
  result.rows = result.cols = 4;
  result.rowptr = pattern->rowPointers().data();
  result.colidx = pattern->columnIndices().data();
  result.values = values.data();
  ASSERT_FALSE(bool(multiplyInto(view(**cols, d.data()),
                                 view(**rows, d.data()), result)));
  Eigen::MatrixXd actual = Eigen::MatrixXd::Zero(4, 4);
  for (int r = 0; r < 4; ++r)
    for (int k = pattern->rowPointers()[r]; k < pattern->rowPointers()[r + 1];
         ++k)
      actual(r, pattern->columnIndices()[k]) = values[k];
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), 1e-14)
      << "actual\n" << actual << "\nexpected\n" << expected;
}

} // namespace
