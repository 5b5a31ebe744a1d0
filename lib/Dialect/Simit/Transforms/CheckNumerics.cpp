//===- CheckNumerics.cpp - Mark the assemblies and solves to scan ---------===//
//
// A NaN or infinity is easiest to fix where it first appears: in the
// assembly or solve that produced it, not in the field it reaches at the
// end of a time step. This pass only describes, in source terms, the ops
// whose results are scanned; convert-simit-to-loops emits the scans
// (LowerCheckNumerics.cpp), since only there do the result arrays exist.
//
//===----------------------------------------------------------------------===//

#include "SourcePosition.h"

#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITCHECKNUMERICS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// Whether the loop lowering scans values of `type`: system tensors of
/// floats, whose arrays it holds.
bool isScanned(Type type) {
  auto system = dyn_cast<SystemTensorType>(type);
  return system && system.isSystem() &&
         isa<FloatType>(system.getComponentType());
}

/// The name of result `index` of element function `callee`: the name its
/// final load carries (IRGen), else its position.
std::string resultName(func::FuncOp callee, unsigned index) {
  if (callee && !callee.isExternal()) {
    auto ret = cast<func::ReturnOp>(callee.getBody().back().getTerminator());
    Value value = ret.getOperand(index);
    if (Operation *def = value.getDefiningOp())
      if (auto name = def->getLoc()->findInstanceOf<NameLoc>())
        return name.getName().str();
  }
  return ("result " + Twine(index)).str();
}

/// What `op` is in the source and the names of its results, if its results
/// are scanned.
std::optional<std::pair<std::string, SmallVector<std::string>>>
describe(Operation *op, ModuleOp module) {
  if (!llvm::any_of(op->getResultTypes(), isScanned))
    return std::nullopt;
  SmallVector<std::string> names;
  if (isa<MapOp, AssembleOp>(op)) {
    auto calleeName = op->getAttrOfType<FlatSymbolRefAttr>("callee");
    auto callee = module.lookupSymbol<func::FuncOp>(calleeName);
    Value set = isa<MapOp>(op) ? cast<MapOp>(op).getSet()
                               : cast<AssembleOp>(op).getSet();
    for (unsigned i = 0; i < op->getNumResults(); ++i)
      names.push_back(resultName(callee, i));
    return std::make_pair(("map " + calleeName.getValue() + " to " +
                           cast<SetType>(set.getType()).getName().getValue() +
                           sourcePositionSuffix(op))
                              .str(),
                          names);
  }
  if (isa<SolveOp>(op))
    return std::make_pair("solve" + sourcePositionSuffix(op),
                          SmallVector<std::string>{"solution"});
  auto call = dyn_cast<func::CallOp>(op);
  if (!call)
    return std::nullopt;
  auto callee = module.lookupSymbol<func::FuncOp>(call.getCalleeAttr());
  auto simitName =
      callee ? callee->getAttrOfType<StringAttr>("simit.runtime_function")
             : StringAttr();
  if (!simitName || !simitName.getValue().contains_insensitive("solve"))
    return std::nullopt;
  names.assign(call.getNumResults(), "solution");
  return std::make_pair((simitName.getValue() + sourcePositionSuffix(op)).str(), names);
}

struct CheckNumerics
    : public simit::impl::SimitCheckNumericsBase<CheckNumerics> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    MLIRContext *ctx = module.getContext();
    for (auto function : module.getOps<func::FuncOp>()) {
      if (!isExportedFunction(function) || function.isExternal())
        continue;
      function.walk([&](Operation *op) {
        auto description = describe(op, module);
        if (!description)
          return;
        SmallVector<Attribute> names;
        for (const std::string &name : description->second)
          names.push_back(StringAttr::get(ctx, name));
        op->setAttr(kCheckNumericsAttr,
                    DictionaryAttr::get(
                        ctx, {NamedAttribute(StringAttr::get(ctx, "op"),
                                             StringAttr::get(
                                                 ctx, description->first)),
                              NamedAttribute(StringAttr::get(ctx, "results"),
                                             ArrayAttr::get(ctx, names))}));
      });
    }
  }
};
} // namespace
