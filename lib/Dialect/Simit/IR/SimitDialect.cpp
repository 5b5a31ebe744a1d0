//===- SimitDialect.cpp - The simit dialect -------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/IR/DialectImplementation.h"
#include "llvm/ADT/TypeSwitch.h"

using namespace mlir;
using namespace mlir::simit;

#include "simit/Dialect/Simit/IR/SimitDialect.cpp.inc"
#include "simit/Dialect/Simit/IR/SimitEnums.cpp.inc"

#define GET_ATTRDEF_CLASSES
#include "simit/Dialect/Simit/IR/SimitAttrs.cpp.inc"

namespace {
/// Prints every element type as an alias named after the element
/// (`!Spring = !simit.element<"Spring", {...}>`), which keeps set, tuple and
/// tensor types that mention it short.
struct SimitOpAsmInterface : public OpAsmDialectInterface {
  using OpAsmDialectInterface::OpAsmDialectInterface;

  /// Names a storage encoding after its kind and set (`#pat_springs`,
  /// `#diag_points`, `#inc_springs_t` for a transposed incidence,
  /// `#host_f_0` for the first matrix a host function call returns).
  AliasResult getAlias(Attribute attr, raw_ostream &os) const override {
    auto encoding = dyn_cast<StorageAttr>(attr);
    if (!encoding)
      return AliasResult::NoAlias;
    bool transposed = encoding.getKind() == StorageKind::Transpose;
    if (transposed)
      encoding = encoding.getOperand();
    switch (encoding.getKind()) {
    case StorageKind::Dense:
    case StorageKind::Empty:
      return AliasResult::NoAlias;
    case StorageKind::Diag:
      os << "diag_" << encoding.getSet().getValue();
      break;
    case StorageKind::Pattern:
      os << "pat_" << encoding.getSet().getValue();
      break;
    case StorageKind::Incidence:
      os << "inc_" << encoding.getSet().getValue();
      break;
    case StorageKind::Stencil:
      os << "stencil_" << encoding.getSet().getValue();
      break;
    case StorageKind::Host:
      os << "host_" << encoding.getSet().getValue() << "_"
         << encoding.getCall();
      break;
    default:
      os << stringifyStorageKind(encoding.getKind());
    }
    if (transposed)
      os << "_t";
    return AliasResult::OverridableAlias;
  }

  AliasResult getAlias(Type type, raw_ostream &os) const override {
    if (auto element = dyn_cast<ElementType>(type)) {
      os << element.getName().getValue();
      return AliasResult::FinalAlias;
    }
    return AliasResult::NoAlias;
  }
};
} // namespace

void SimitDialect::initialize() {
  registerTypes();
  registerAttributes();
  addOperations<
#define GET_OP_LIST
#include "simit/Dialect/Simit/IR/SimitOps.cpp.inc"
      >();
  registerInterfaces();
}

void SimitDialect::registerAttributes() {
  addAttributes<
#define GET_ATTRDEF_LIST
#include "simit/Dialect/Simit/IR/SimitAttrs.cpp.inc"
      >();
}

void SimitDialect::registerInterfaces() {
  addInterfaces<SimitOpAsmInterface>();
}
