//===- CheckSetNames.cpp - Every set named by a type is declared ----------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Interfaces/FunctionInterfaces.h"
#include "llvm/ADT/DenseSet.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITCHECKSETNAMES
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// Collects the set names a type refers to, through element fields, tuple
/// components, refs, tensor blocks and builtin function types.
void collectSetNames(Type type, SmallVectorImpl<StringAttr> &names) {
  if (auto set = dyn_cast<SetType>(type)) {
    names.push_back(set.getName());
    llvm::append_range(names, set.getEndpoints());
    collectSetNames(set.getElementType(), names);
  } else if (auto tensor = dyn_cast<SystemTensorType>(type)) {
    for (Attribute dim : tensor.getDims())
      if (auto setName = dyn_cast<StringAttr>(dim))
        names.push_back(setName);
    collectSetNames(tensor.getBlockType(), names);
  } else if (auto element = dyn_cast<ElementType>(type)) {
    for (Type field : element.getFieldTypes())
      collectSetNames(field, names);
  } else if (auto tuple = dyn_cast<simit::TupleType>(type)) {
    for (Type component : tuple.getElementTypes())
      collectSetNames(component, names);
  } else if (auto ref = dyn_cast<RefType>(type)) {
    collectSetNames(ref.getValueType(), names);
  } else if (auto function = dyn_cast<FunctionType>(type)) {
    for (Type t : llvm::concat<const Type>(function.getInputs(),
                                           function.getResults()))
      collectSetNames(t, names);
  }
}

struct CheckSetNames
    : public simit::impl::SimitCheckSetNamesBase<CheckSetNames> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    llvm::DenseSet<StringAttr> declared;
    module.walk([&](Operation *op) {
      if (auto global = dyn_cast<ExternOp>(op)) {
        if (auto set = dyn_cast<SetType>(global.getType()))
          declared.insert(set.getName());
      } else if (auto function = dyn_cast<FunctionOpInterface>(op)) {
        for (Type type : function.getArgumentTypes())
          if (auto set = dyn_cast<SetType>(type))
            declared.insert(set.getName());
      }
    });

    llvm::DenseSet<StringAttr> reported;
    bool failedCheck = false;
    auto checkType = [&](Operation *op, Type type) {
      SmallVector<StringAttr> names;
      collectSetNames(type, names);
      for (StringAttr name : names) {
        if (declared.contains(name) || !reported.insert(name).second)
          continue;
        op->emitError() << "type " << type << " refers to set '"
                        << name.getValue()
                        << "', which no simit.extern or set parameter declares";
        failedCheck = true;
      }
    };
    module.walk([&](Operation *op) {
      for (Type type : op->getOperandTypes())
        checkType(op, type);
      for (Type type : op->getResultTypes())
        checkType(op, type);
      for (Region &region : op->getRegions())
        for (Block &block : region)
          for (BlockArgument argument : block.getArguments())
            checkType(op, argument.getType());
      if (auto global = dyn_cast<ExternOp>(op))
        checkType(op, global.getType());
      if (auto function = dyn_cast<FunctionOpInterface>(op))
        checkType(op, function.getFunctionType());
    });
    if (failedCheck)
      signalPassFailure();
  }
};
} // namespace
