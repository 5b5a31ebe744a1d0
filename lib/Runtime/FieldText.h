//===--- FieldText.h - Writing field components as text ---------*- C++ -*-===//

#ifndef SIMIT_LIB_RUNTIME_FIELDTEXT_H
#define SIMIT_LIB_RUNTIME_FIELDTEXT_H

#include "simit/Runtime/Set.h"

#include "llvm/Support/raw_ostream.h"

namespace simit {
namespace detail {

/// Writes component `i` of a field array of `type` (doubles and floats with
/// enough digits to read back exactly, bools as 0/1).
void writeComponent(llvm::raw_ostream &os, const void *data,
                    ComponentType type, size_t i);

} // namespace detail
} // namespace simit

#endif // SIMIT_LIB_RUNTIME_FIELDTEXT_H
