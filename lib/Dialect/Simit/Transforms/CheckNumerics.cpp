//===- CheckNumerics.cpp - Mark the assemblies and solves to scan ---------===//
//
// A NaN or infinity is easiest to fix where it first appears: in the
// assembly or solve that produced it, not in the field it reaches at the
// end of a time step. This pass only describes, in source terms, the ops
// whose results are scanned; convert-simit-to-loops emits the scans
// (LowerCheckNumerics.cpp), since only there do the result arrays exist.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/SourcePosition.h"

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

/// The float fields of its element that element function `callee` writes
/// (an `inout` element: `t.B = inv(Dm)`), each once, in order.
SmallVector<std::string> writtenFloatFields(func::FuncOp callee) {
  SmallVector<std::string> fields;
  if (!callee || callee.isExternal() || callee.getNumArguments() == 0)
    return fields;
  Value element = callee.getArgument(0);
  callee.walk([&](ElemWriteOp write) {
    auto type = dyn_cast<ElementType>(element.getType());
    if (write.getElement() != element || !type)
      return;
    Type field = type.getFieldType(write.getField());
    if (field && isa<FloatType>(getComponentType(field)) &&
        !llvm::is_contained(fields, write.getField()))
      fields.push_back(write.getField().str());
  });
  return fields;
}

/// What `op` is in the source, the names of its results, and the fields of
/// the mapped set its element function writes, if any of them is scanned.
struct Description {
  std::string op;
  SmallVector<std::string> results, fields;
};

std::optional<Description> describe(Operation *op, ModuleOp module) {
  bool scansResults = llvm::any_of(op->getResultTypes(), isScanned);
  Description description;
  if (isa<MapOp, AssembleOp>(op)) {
    auto calleeName = op->getAttrOfType<FlatSymbolRefAttr>("callee");
    auto callee = module.lookupSymbol<func::FuncOp>(calleeName);
    Value set = isa<MapOp>(op) ? cast<MapOp>(op).getSet()
                               : cast<AssembleOp>(op).getSet();
    description.fields = writtenFloatFields(callee);
    if (!scansResults && description.fields.empty())
      return std::nullopt;
    for (unsigned i = 0; i < op->getNumResults(); ++i)
      description.results.push_back(resultName(callee, i));
    description.op = ((op->getNumResults() ? "map " : "apply ") +
                      calleeName.getValue() + " to " +
                      cast<SetType>(set.getType()).getName().getValue() +
                      sourcePositionSuffix(op))
                         .str();
    return description;
  }
  if (!scansResults)
    return std::nullopt;
  // A Woodbury step stands for the `\` it rewrote.
  if (isa<SolveOp, WoodburyOp>(op)) {
    description.op = "solve" + sourcePositionSuffix(op);
    description.results = {"solution"};
    return description;
  }
  if (auto solve = dyn_cast<FactorSolveOp>(op)) {
    description.op =
        (solve.getIntrinsicName() + sourcePositionSuffix(op)).str();
    description.results = {"solution"};
    return description;
  }
  if (isa<TriangularSolveOp>(op)) {
    description.op = "triangularSolve" + sourcePositionSuffix(op);
    description.results = {"solution"};
    return description;
  }
  return std::nullopt;
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
        auto strings = [&](ArrayRef<std::string> texts) {
          SmallVector<Attribute> attrs;
          for (const std::string &text : texts)
            attrs.push_back(StringAttr::get(ctx, text));
          return ArrayAttr::get(ctx, attrs);
        };
        SmallVector<NamedAttribute> marks = {
            NamedAttribute(StringAttr::get(ctx, "op"),
                           StringAttr::get(ctx, description->op)),
            NamedAttribute(StringAttr::get(ctx, "results"),
                           strings(description->results))};
        if (!description->fields.empty())
          marks.push_back(NamedAttribute(StringAttr::get(ctx, "fields"),
                                         strings(description->fields)));
        op->setAttr(kCheckNumericsAttr, DictionaryAttr::get(ctx, marks));
      });
    }
  }
};
} // namespace
