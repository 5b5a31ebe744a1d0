//===--- MemoryBudget.h - Refusing what the machine cannot hold -*- C++ -*-===//
//
// A scene can ask for more memory than the machine has (a huge set, a field
// shape, a refinement level). Such requests are checked before allocating,
// so that they fail with "scene needs N GiB for ..." rather than an abort.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_RUNTIME_MEMORYBUDGET_H
#define SIMIT_LIB_RUNTIME_MEMORYBUDGET_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/Error.h"

#include <cstdint>
#include <optional>

namespace simit {
namespace detail {

/// The bytes this process may allocate: the machine's physical memory, or
/// what the address-space limit (`ulimit -v`) leaves when that is lower.
uint64_t availableMemory();

/// `a * b`, or nothing when the product does not fit in 64 bits.
std::optional<uint64_t> checkedProduct(uint64_t a, uint64_t b);

/// The product of `factors`, or nothing when it does not fit in 64 bits.
std::optional<uint64_t> checkedProduct(llvm::ArrayRef<uint64_t> factors);

/// Succeeds when `bytes` (nothing: more than 64 bits can count) fit in
/// availableMemory(); else "scene needs N GiB for <what>, more than the
/// M GiB available".
llvm::Error checkMemoryRequest(std::optional<uint64_t> bytes,
                               const llvm::Twine &what);

} // namespace detail
} // namespace simit

#endif // SIMIT_LIB_RUNTIME_MEMORYBUDGET_H
