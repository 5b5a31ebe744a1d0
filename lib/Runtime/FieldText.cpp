//===--- FieldText.cpp - Writing field components as text -----------------===//

#include "FieldText.h"

#include "llvm/Support/Format.h"

#include <cmath>

using namespace simit;

void detail::writeComponent(llvm::raw_ostream &os, const void *data,
                            ComponentType type, size_t i) {
  switch (type) {
  case ComponentType::Float64:
  case ComponentType::Float32: {
    double value = type == ComponentType::Float64
                       ? static_cast<const double *>(data)[i]
                       : static_cast<const float *>(data)[i];
    // A NaN's sign bit (0/0 sets it) is no value: "nan", never "-nan".
    if (std::isnan(value))
      os << "nan";
    else
      os << llvm::format(type == ComponentType::Float64 ? "%.17g" : "%.9g",
                         value);
    return;
  }
  case ComponentType::Int32:
    os << static_cast<const int32_t *>(data)[i];
    return;
  case ComponentType::Bool:
    os << (static_cast<const bool *>(data)[i] ? 1 : 0);
    return;
  }
}
