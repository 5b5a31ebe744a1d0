//===--- MemoryBudget.cpp - Refusing allocations the machine cannot hold ---===//

#include "MemoryBudget.h"

#include "llvm/Support/Format.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <cstdio>
#include <sys/resource.h>
#include <unistd.h>

using namespace simit;
using namespace simit::detail;

uint64_t detail::availableMemory() {
  uint64_t bytes = UINT64_MAX;
  long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  if (pages > 0 && pageSize > 0)
    bytes = static_cast<uint64_t>(pages) * static_cast<uint64_t>(pageSize);
  // Under an address-space limit, what the process already maps (the
  // libraries, the JIT) is not available.
  struct rlimit limit;
  if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    uint64_t mapped = 0;
    if (FILE *statm = std::fopen("/proc/self/statm", "r")) {
      unsigned long pagesMapped;
      if (std::fscanf(statm, "%lu", &pagesMapped) == 1 && pageSize > 0)
        mapped = static_cast<uint64_t>(pagesMapped) * pageSize;
      std::fclose(statm);
    }
    uint64_t limitBytes = limit.rlim_cur;
    bytes = std::min(bytes, limitBytes > mapped ? limitBytes - mapped : 0);
  }
  return bytes;
}

std::optional<uint64_t> detail::checkedProduct(uint64_t a, uint64_t b) {
  uint64_t product;
  if (__builtin_mul_overflow(a, b, &product))
    return std::nullopt;
  return product;
}

std::optional<uint64_t>
detail::checkedProduct(llvm::ArrayRef<uint64_t> factors) {
  std::optional<uint64_t> product = 1;
  for (uint64_t factor : factors)
    if (!(product = checkedProduct(*product, factor)))
      return std::nullopt;
  return product;
}

static std::string gibibytes(uint64_t bytes) {
  std::string text;
  llvm::raw_string_ostream os(text);
  os << llvm::format("%.3g", static_cast<double>(bytes) / (1ull << 30));
  return text;
}

llvm::Error detail::checkMemoryRequest(std::optional<uint64_t> bytes,
                                       const llvm::Twine &what) {
  uint64_t available = availableMemory();
  if (bytes && *bytes <= available)
    return llvm::Error::success();
  std::string needed = bytes ? gibibytes(*bytes) + " GiB"
                             : std::string("more than 2^64 bytes");
  return llvm::createStringError("scene needs " + needed + " for " + what +
                                 ", more than the " + gibibytes(available) +
                                 " GiB available");
}
