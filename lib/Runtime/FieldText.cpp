//===--- FieldText.cpp - Writing field components as text -----------------===//

#include "FieldText.h"

#include "llvm/Support/Format.h"

using namespace simit;

void detail::writeComponent(llvm::raw_ostream &os, const void *data,
                            ComponentType type, size_t i) {
  switch (type) {
  case ComponentType::Float64:
    os << llvm::format("%.17g", static_cast<const double *>(data)[i]);
    return;
  case ComponentType::Float32:
    os << llvm::format("%.9g", static_cast<const float *>(data)[i]);
    return;
  case ComponentType::Int32:
    os << static_cast<const int32_t *>(data)[i];
    return;
  case ComponentType::Bool:
    os << (static_cast<const bool *>(data)[i] ? 1 : 0);
    return;
  }
}
