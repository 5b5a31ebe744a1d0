//===--- Printing.cpp - print and strings of lowered code -----------------===//

#include "simit/ABI/RuntimeFunctions.h"

#include "llvm/Support/Format.h"
#include "llvm/Support/raw_ostream.h"

#include <cstdlib>
#include <cstring>

// print/println: through llvm::outs() so the output interleaves with the
// tools' own output in order. Floats like C %g, integers and bools as
// integers, strings as they are.
extern "C" void simit_rt_print_f64(double value) {
  llvm::outs() << llvm::format("%g", value);
}

extern "C" void simit_rt_print_i64(int64_t value) { llvm::outs() << value; }

extern "C" void simit_rt_print_str(const char *text) {
  llvm::outs() << (text ? text : "");
}

// Strings are NUL-terminated C strings; a concatenation allocates a new one
// that lives as long as the process.
extern "C" char *simit_rt_string_concat(const char *lhs, const char *rhs) {
  if (!lhs)
    lhs = "";
  if (!rhs)
    rhs = "";
  size_t n = std::strlen(lhs), m = std::strlen(rhs);
  char *result = static_cast<char *>(std::malloc(n + m + 1));
  std::memcpy(result, lhs, n);
  std::memcpy(result + n, rhs, m + 1);
  return result;
}

extern "C" int32_t simit_rt_string_compare(const char *lhs, const char *rhs) {
  int order = std::strcmp(lhs ? lhs : "", rhs ? rhs : "");
  return order < 0 ? -1 : order > 0 ? 1 : 0;
}
