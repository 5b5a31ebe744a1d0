//===--- ffi.h - For the C functions of extern funcs ------------*- C++ -*-===//
//
// Host libraries implementing a Simit program's `extern func`s may include
// this header (docs/lowering.md, "Host functions"). A function with a
// matrix result allocates its three BCSR arrays with simit_malloc (the
// original Simit runtime's name; std::malloc serves as well): Simit frees
// them once it has copied them. Depends on nothing but the C++ library.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FFI_H
#define SIMIT_FFI_H

#include <cstddef>

namespace simit {
namespace ffi {

/// Memory Simit frees with std::free: the arrays of a matrix result.
void *simit_malloc(std::size_t bytes);
/// Frees memory of simit_malloc.
void simit_free(void *memory);

} // namespace ffi
} // namespace simit

#endif // SIMIT_FFI_H
