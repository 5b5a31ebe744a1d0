//===--- Allocator.cpp - Heap memory of JIT-compiled code -----------------===//
//
// Lowered code allocates the same temporaries every frame: assembled
// matrices, right-hand sides, CG vectors. glibc hands blocks that large back
// to the kernel on free, so each frame would page-fault and zero them again
// (more than the assembly itself on springs-bunny). The engine lowers
// memref.alloc/dealloc to these functions (finalize-memref-to-llvm's generic
// allocation functions, without aligned alloc: lowered code aligns within
// the block), which keep freed large blocks for reuse by size.
//
//===----------------------------------------------------------------------===//

#include "simit/ABI/RuntimeFunctions.h"

#include <cstdlib>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace {
/// Each block starts with a header holding its payload size; 16 bytes keep
/// the payload as aligned as malloc's.
constexpr size_t kHeader = 16;
/// Smaller blocks come from malloc's arenas, which reuse them already.
constexpr size_t kCachedMinimum = 64 * 1024;
/// Freed blocks kept per size, and in all: the cache never holds more than
/// a program's own peak of temporaries, bounded in case sizes keep changing.
constexpr size_t kBlocksPerSize = 16;
constexpr size_t kCachedBytesLimit = size_t(4) << 30;

struct BlockCache {
  std::mutex mutex;
  std::unordered_map<size_t, std::vector<void *>> freeBlocks;
  size_t cachedBytes = 0;
};

BlockCache &cache() {
  static BlockCache *instance = new BlockCache; // outlives static JIT code
  return *instance;
}

void *payloadOf(void *block) { return static_cast<char *>(block) + kHeader; }
void *blockOf(void *payload) { return static_cast<char *>(payload) - kHeader; }
size_t sizeOf(void *payload) {
  return *static_cast<size_t *>(blockOf(payload));
}
} // namespace

extern "C" void *_mlir_memref_to_llvm_alloc(size_t size) {
  if (size >= kCachedMinimum) {
    BlockCache &c = cache();
    std::lock_guard<std::mutex> lock(c.mutex);
    auto it = c.freeBlocks.find(size);
    if (it != c.freeBlocks.end() && !it->second.empty()) {
      void *block = it->second.back();
      it->second.pop_back();
      c.cachedBytes -= size;
      return payloadOf(block);
    }
  }
  void *block = std::malloc(size + kHeader);
  if (!block)
    return nullptr;
  *static_cast<size_t *>(block) = size;
  return payloadOf(block);
}

extern "C" void _mlir_memref_to_llvm_free(void *payload) {
  if (!payload)
    return;
  size_t size = sizeOf(payload);
  if (size >= kCachedMinimum) {
    BlockCache &c = cache();
    std::lock_guard<std::mutex> lock(c.mutex);
    std::vector<void *> &blocks = c.freeBlocks[size];
    if (blocks.size() < kBlocksPerSize &&
        c.cachedBytes + size <= kCachedBytesLimit) {
      blocks.push_back(blockOf(payload));
      c.cachedBytes += size;
      return;
    }
  }
  std::free(blockOf(payload));
}
