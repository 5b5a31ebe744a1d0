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
