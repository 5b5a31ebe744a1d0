//===- RecordHostABI.cpp - Host signatures as attributes -----------------===//
//
// The conversion to LLVM replaces a function's memref arguments by their
// descriptors' parts (or bare pointers), after which the engine could only
// guess the host signature from the number of LLVM arguments. This pass
// writes it down while the types are still memrefs.
//
//===----------------------------------------------------------------------===//

#include "simit/ABI/BindingKind.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITRECORDHOSTABI
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
struct RecordHostABI
    : public mlir::simit::impl::SimitRecordHostABIBase<RecordHostABI> {
  using Base::Base;

  void runOnOperation() override {
    namespace abi = ::simit::abi;
    StringAttr convention = StringAttr::get(
        &getContext(), barePointers ? abi::kBarePointerConvention
                                    : abi::kDescriptorConvention);
    WalkResult result = getOperation().walk([&](func::FuncOp function) {
      auto bindings =
          function->getAttrOfType<ArrayAttr>(StringRef(abi::kBindingsAttr));
      if (!bindings)
        return WalkResult::advance();
      FunctionType type = function.getFunctionType();
      if (bindings.size() != type.getNumInputs()) {
        function.emitOpError("has ")
            << bindings.size() << " simit.bindings entries for "
            << type.getNumInputs() << " arguments";
        return WalkResult::interrupt();
      }
      function->setAttr(StringRef(abi::kHostTypeAttr), TypeAttr::get(type));
      function->setAttr(StringRef(abi::kMemRefConventionAttr), convention);
      return WalkResult::advance();
    });
    if (result.wasInterrupted())
      signalPassFailure();
  }
};
} // namespace
