//===--- ElementColouring.h - Race-free order of scatter assembly -*- C++ -*-===//
//
// An assembly over an edge set adds each element's contributions into its
// endpoints' blocks, which other elements share. To run it on several
// threads without races and with a result that does not depend on their
// number, the elements are cut into chunks of `chunk` consecutive elements
// (consecutive elements are usually near each other in the mesh, so a chunk
// keeps its locality) and the chunks are coloured so that no two chunks of
// one colour share an endpoint. The chunks of a colour then run in parallel
// and the colours one after another: every block receives its contributions
// in the same order on any number of threads.
//
// Layout (the `element_colours` binding of JIT-compiled code, docs/threads.md):
// int32 words [K, start_0, ..., start_K, chunk numbers...]: the chunks of
// colour c are words[start_c] .. words[start_(c+1) - 1], in increasing order;
// chunk q holds elements q * chunk .. min((q + 1) * chunk, size) - 1.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_ELEMENTCOLOURING_H
#define SIMIT_RUNTIME_ELEMENTCOLOURING_H

#include "simit/Runtime/Set.h"

#include "llvm/ADT/ArrayRef.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace simit {

class ElementColouring {
public:
  /// The colouring of `edges` in chunks of `chunk` (> 0) elements: greedy,
  /// first fit, chunk by chunk in order, so it depends on the endpoints and
  /// the chunk size only. Endpoints are compared by index whatever their
  /// set (chunks whose endpoints in different sets have the same index get
  /// different colours too: fewer chunks per colour, never a race). Built
  /// once and cached on the edge set; rebuilt when it or an endpoint set
  /// changed structure since.
  static std::shared_ptr<const ElementColouring> get(const Set &edges,
                                                     int chunk);

  /// The colouring of `numElements` elements of `cardinality` endpoints
  /// each, `endpoints[e * cardinality + i]` (the layout of Set).
  static std::shared_ptr<const ElementColouring>
  build(llvm::ArrayRef<int32_t> endpoints, int numElements, int cardinality,
        int chunk);

  llvm::ArrayRef<int32_t> words() const { return layout; }
  int numColours() const { return layout.empty() ? 0 : layout[0]; }
  /// The chunk numbers of colour `c`, in increasing order.
  llvm::ArrayRef<int32_t> chunksOfColour(int c) const {
    return llvm::ArrayRef<int32_t>(layout).slice(
        layout[1 + c], layout[2 + c] - layout[1 + c]);
  }
  int chunkSize() const { return chunk; }

private:
  bool isCurrent(const Set &edges) const;

  std::vector<int32_t> layout;
  int chunk = 1;
  /// Versions of the edge set and of each endpoint set at build time.
  std::vector<uint64_t> versions;
};

} // namespace simit

#endif // SIMIT_RUNTIME_ELEMENTCOLOURING_H
