//===--- MemRef.h - Memref descriptors of the C interface -------*- C++ -*-===//
//
// How lowered code passes a memref to a runtime function declared with
// `llvm.emit_c_interface`: a pointer to a descriptor laid out as MLIR's
// memref-to-LLVM lowering lays it out (docs/lowering.md). The runtime, its
// tests and other hosts read these without MLIR's headers. This header
// depends on nothing but the C++ standard library.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ABI_MEMREF_H
#define SIMIT_ABI_MEMREF_H

#include <cstdint>

namespace simit {
namespace abi {

/// A memref of rank N > 0 with elements of type T.
template <typename T, int N> struct MemRefDescriptor {
  /// What the allocation returned (freed with it), and the first element
  /// the memref may address (aligned).
  T *allocated;
  T *data;
  /// Element (i_0, ..., i_N-1) is data[offset + sum_d i_d * strides[d]].
  int64_t offset;
  int64_t sizes[N];
  int64_t strides[N];
};

/// A memref of unknown rank (memref<*xT>): its rank and a pointer to the
/// descriptor of that rank.
template <typename T> struct UnrankedMemRefDescriptor {
  int64_t rank;
  void *descriptor;
};

/// The fields of the ranked descriptor an unranked one points to.
template <typename T> struct DynamicMemRefView {
  int64_t rank;
  T *data;
  int64_t offset;
  const int64_t *sizes;
  const int64_t *strides;

  explicit DynamicMemRefView(const UnrankedMemRefDescriptor<T> &memref)
      : rank(memref.rank) {
    // Every rank shares the layout of rank 1 up to `sizes`; the strides
    // follow the rank sizes.
    auto *ranked =
        static_cast<const MemRefDescriptor<T, 1> *>(memref.descriptor);
    data = ranked->data;
    offset = ranked->offset;
    sizes = rank == 0 ? nullptr : ranked->sizes;
    strides = rank == 0 ? nullptr : ranked->sizes + rank;
  }
};

/// Whether a memref's strides are the row-major strides of its sizes, so
/// its data can be walked as one flat array.
template <typename T, int N>
bool isContiguous(const MemRefDescriptor<T, N> &m) {
  int64_t expected = 1;
  for (int d = N - 1; d >= 0; --d) {
    if (m.sizes[d] != 1 && m.strides[d] != expected)
      return false;
    expected *= m.sizes[d];
  }
  return true;
}

} // namespace abi
} // namespace simit

#endif // SIMIT_ABI_MEMREF_H
