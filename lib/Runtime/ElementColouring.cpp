//===--- ElementColouring.cpp - Race-free order of scatter assembly --------===//

#include "simit/Runtime/ElementColouring.h"

#include <algorithm>
#include <cassert>

using namespace simit;

std::shared_ptr<const ElementColouring>
ElementColouring::get(const Set &edges, int chunk) {
  auto &cached = edges.colouringCache[chunk];
  if (!cached || !cached->isCurrent(edges)) {
    auto colouring = std::const_pointer_cast<ElementColouring>(
        build(llvm::ArrayRef<int32_t>(edges.endpointData(),
                                      static_cast<size_t>(edges.size()) *
                                          edges.cardinality()),
              edges.size(), edges.cardinality(), chunk));
    colouring->versions.push_back(edges.version());
    for (const Set *set : edges.endpointSetList())
      colouring->versions.push_back(set->version());
    cached = std::move(colouring);
  }
  return cached;
}

bool ElementColouring::isCurrent(const Set &edges) const {
  if (versions.size() != 1 + edges.endpointSetList().size() ||
      versions[0] != edges.version())
    return false;
  for (auto [i, set] : llvm::enumerate(edges.endpointSetList()))
    if (versions[1 + i] != set->version())
      return false;
  return true;
}

std::shared_ptr<const ElementColouring>
ElementColouring::build(llvm::ArrayRef<int32_t> endpoints, int numElements,
                        int cardinality, int chunk) {
  assert(chunk > 0 && "chunks hold at least one element");
  auto colouring = std::make_shared<ElementColouring>();
  colouring->chunk = chunk;
  int numChunks = numElements == 0 ? 0 : (numElements - 1) / chunk + 1;
  int32_t largest = -1;
  for (int32_t v : endpoints)
    largest = std::max(largest, v);

  // First fit: a chunk takes the smallest colour that no chunk before it
  // sharing one of its endpoints took. coloursAt[v] lists the colours of
  // the chunks touching v; `seenBy[c] == q` marks colour c taken for chunk q.
  std::vector<std::vector<int32_t>> coloursAt(largest + 1);
  std::vector<int32_t> chunkColour(numChunks), seenBy;
  for (int q = 0; q < numChunks; ++q) {
    size_t begin = static_cast<size_t>(q) * chunk * cardinality;
    size_t end = std::min(static_cast<size_t>(q + 1) * chunk,
                          static_cast<size_t>(numElements)) *
                 cardinality;
    for (size_t i = begin; i < end; ++i)
      for (int32_t c : coloursAt[endpoints[i]])
        seenBy[c] = q;
    int32_t colour = 0;
    while (colour < static_cast<int32_t>(seenBy.size()) && seenBy[colour] == q)
      ++colour;
    if (colour == static_cast<int32_t>(seenBy.size()))
      seenBy.push_back(-1);
    chunkColour[q] = colour;
    for (size_t i = begin; i < end; ++i) {
      std::vector<int32_t> &colours = coloursAt[endpoints[i]];
      if (colours.empty() || colours.back() != colour)
        colours.push_back(colour);
    }
  }

  // Counting sort of the chunks by colour keeps each colour's chunks in
  // increasing order.
  int numColours = static_cast<int>(seenBy.size());
  std::vector<int32_t> &layout = colouring->layout;
  layout.assign(2 + numColours + numChunks, 0);
  layout[0] = numColours;
  std::vector<int32_t> next(numColours + 1, 0);
  for (int32_t colour : chunkColour)
    ++next[colour + 1];
  for (int c = 0; c < numColours; ++c)
    next[c + 1] += next[c];
  int32_t first = 2 + numColours;
  for (int c = 0; c <= numColours; ++c)
    layout[1 + c] = first + next[c];
  for (int q = 0; q < numChunks; ++q)
    layout[first + next[chunkColour[q]]++] = q;
  return colouring;
}
