//===--- ElementColouringTest.cpp - Race-free order of scatter assembly ----===//

#include "simit/Runtime/ElementColouring.h"
#include "simit/Runtime/Mesh.h"

#include "gtest/gtest.h"

#include <random>
#include <set>

using namespace simit;

namespace {
/// Checks the layout, that every chunk has exactly one colour, that each
/// colour lists its chunks in increasing order, and that no two chunks of
/// one colour share an endpoint index.
void checkColouring(const ElementColouring &colouring,
                    llvm::ArrayRef<int32_t> endpoints, int numElements,
                    int cardinality) {
  int chunk = colouring.chunkSize();
  int numChunks = (numElements + chunk - 1) / chunk;
  llvm::ArrayRef<int32_t> words = colouring.words();
  int k = colouring.numColours();
  ASSERT_EQ(words.size(), static_cast<size_t>(2 + k + numChunks));
  EXPECT_EQ(words[1], 2 + k);
  EXPECT_EQ(words[1 + k], static_cast<int32_t>(words.size()));
  std::vector<int> seen(numChunks, 0);
  for (int c = 0; c < k; ++c) {
    llvm::ArrayRef<int32_t> chunks = colouring.chunksOfColour(c);
    EXPECT_FALSE(chunks.empty()) << "colour " << c;
    EXPECT_TRUE(std::is_sorted(chunks.begin(), chunks.end()));
    std::set<int32_t> used;
    for (int32_t q : chunks) {
      ASSERT_GE(q, 0);
      ASSERT_LT(q, numChunks);
      ++seen[q];
      std::set<int32_t> ends;
      for (int e = q * chunk; e < std::min((q + 1) * chunk, numElements); ++e)
        for (int i = 0; i < cardinality; ++i)
          ends.insert(endpoints[e * cardinality + i]);
      for (int32_t v : ends)
        EXPECT_TRUE(used.insert(v).second)
            << "colour " << c << " shares endpoint " << v;
    }
  }
  for (int q = 0; q < numChunks; ++q)
    EXPECT_EQ(seen[q], 1) << "chunk " << q;
}
} // namespace

TEST(ElementColouring, FirstFitByChunk) {
  // A path 0-1-2-3-4-5 of five springs in chunks of two: chunks {01,12},
  // {23,34}, {45} share 2 and 4 in a row, so 0 and 2 get colour 0, 1 gets 1.
  std::vector<int32_t> path = {0, 1, 1, 2, 2, 3, 3, 4, 4, 5};
  auto colouring = ElementColouring::build(path, 5, 2, 2);
  EXPECT_EQ(colouring->words().vec(),
            (std::vector<int32_t>{2, 4, 6, 7, 0, 2, 1}));
  checkColouring(*colouring, path, 5, 2);
}

TEST(ElementColouring, EmptySetAndOneChunk) {
  auto none = ElementColouring::build({}, 0, 2, 64);
  EXPECT_EQ(none->words().vec(), (std::vector<int32_t>{0, 2}));
  std::vector<int32_t> star = {0, 1, 0, 2, 0, 3};
  auto one = ElementColouring::build(star, 3, 2, 64);
  EXPECT_EQ(one->words().vec(), (std::vector<int32_t>{1, 3, 4, 0}));
}

TEST(ElementColouring, AHubNeedsAColourPerChunk) {
  // Every spring touches vertex 0: no two chunks can share a colour.
  std::vector<int32_t> star;
  for (int i = 1; i <= 40; ++i)
    star.insert(star.end(), {0, i});
  auto colouring = ElementColouring::build(star, 40, 2, 4);
  EXPECT_EQ(colouring->numColours(), 10);
  checkColouring(*colouring, star, 40, 2);
}

TEST(ElementColouring, RandomTetrahedraInAnyOrder) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int32_t> vertex(0, 999);
  std::vector<int32_t> tets;
  for (int e = 0; e < 3000; ++e)
    for (int i = 0; i < 4; ++i)
      tets.push_back(vertex(random));
  for (int chunk : {1, 3, 64}) {
    auto colouring = ElementColouring::build(tets, 3000, 4, chunk);
    checkColouring(*colouring, tets, 3000, 4);
  }
}

TEST(ElementColouring, CachedOnTheSetUntilItChanges) {
  Set verts("verts");
  Set springs("springs", {&verts, &verts});
  for (int i = 0; i < 4; ++i)
    verts.add();
  springs.add(0, 1);
  springs.add(2, 3);
  auto first = ElementColouring::get(springs, 1);
  EXPECT_EQ(first, ElementColouring::get(springs, 1));
  EXPECT_EQ(first->numColours(), 1);
  EXPECT_NE(first, ElementColouring::get(springs, 2));
  springs.add(1, 2);
  auto changed = ElementColouring::get(springs, 1);
  EXPECT_NE(first, changed);
  EXPECT_EQ(changed->numColours(), 2);
}
