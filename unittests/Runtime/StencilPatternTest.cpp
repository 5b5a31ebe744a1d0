//===- StencilPatternTest.cpp - Grid stencils as BCSR patterns ------------===//

#include "simit/Runtime/StencilPattern.h"

#include "gmock/gmock.h"

using namespace simit;
using ::testing::ElementsAre;

namespace {

// On a periodic grid 2 wide, offsets -1 and +1 name the same point: the row
// holds it once and both stencil blocks add there.
TEST(StencilPattern, OffsetsNamingOnePointShareAPosition) {
  auto pattern = StencilPattern::get({2}, {{-1}, {0}, {1}});
  ASSERT_TRUE(bool(pattern)) << llvm::toString(pattern.takeError());
  const StencilPattern &p = **pattern;
  EXPECT_THAT(p.rowPtr, ElementsAre(0, 2, 4));
  EXPECT_THAT(p.colIdx, ElementsAre(0, 1, 0, 1));
  // Block k * 2 + r: row 0 offsets -1, 0, +1 at columns 1, 0, 1; row 1 at
  // columns 0, 1, 0.
  EXPECT_THAT(p.positions, ElementsAre(1, 2, 0, 3, 1, 2));
}

// A 3 x 4 grid (the last axis fastest): point (1, 3) = 7 with offsets
// (0, 1) and (-1, 0) reaches (1, 0) = 4 and (0, 3) = 3, sorted.
TEST(StencilPattern, TwoDimensionalRowsAreSorted) {
  auto pattern = StencilPattern::get({3, 4}, {{-1, 0}, {0, 0}, {0, 1}});
  ASSERT_TRUE(bool(pattern)) << llvm::toString(pattern.takeError());
  const StencilPattern &p = **pattern;
  ASSERT_EQ(p.rowPtr.size(), 13u);
  std::vector<int32_t> row7(p.colIdx.begin() + p.rowPtr[7],
                            p.colIdx.begin() + p.rowPtr[8]);
  EXPECT_THAT(row7, ElementsAre(3, 4, 7));
  EXPECT_EQ(p.colIdx[p.positions[0 * 12 + 7]], 3);
  EXPECT_EQ(p.colIdx[p.positions[1 * 12 + 7]], 7);
  EXPECT_EQ(p.colIdx[p.positions[2 * 12 + 7]], 4);
}

TEST(StencilPattern, OffsetOfAnotherRankIsAnError) {
  auto pattern = StencilPattern::get({3, 4}, {{0}});
  ASSERT_FALSE(bool(pattern));
  EXPECT_THAT(llvm::toString(pattern.takeError()),
              ::testing::HasSubstr("rank"));
}

} // namespace
