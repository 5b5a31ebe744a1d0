//===- SetChecks.cpp - Checks of values against named sets -------------===//

#include "SetChecks.h"

#include "mlir/Interfaces/FunctionInterfaces.h"

using namespace mlir;
using namespace mlir::simit;

SetType mlir::simit::lookupSetByName(Operation *from, StringAttr name) {
  for (Operation *scope = from->getParentOp(); scope;
       scope = scope->getParentOp()) {
    if (auto function = dyn_cast<FunctionOpInterface>(scope))
      for (Type type : function.getArgumentTypes())
        if (auto set = dyn_cast<SetType>(type); set && set.getName() == name)
          return set;
    if (!scope->hasTrait<OpTrait::SymbolTable>())
      continue;
    for (Block &block : scope->getRegion(0))
      for (auto global : block.getOps<ExternOp>())
        if (auto set = dyn_cast<SetType>(global.getType());
            set && set.getName() == name)
          return set;
  }
  return {};
}

LogicalResult mlir::simit::verifyElementOfSet(Operation *op, Type elementType,
                                              StringAttr name,
                                              const Twine &what) {
  SetType set = lookupSetByName(op, name);
  if (!set || set.getElementType() == elementType)
    return success();
  return op->emitOpError() << what << " must be an element of set '"
                           << name.getValue() << "' ("
                           << set.getElementType() << "), got " << elementType;
}

LogicalResult mlir::simit::verifyEndpointTuple(Operation *op, SetType set,
                                              simit::TupleType tuple) {
  if (set.getCardinality() == 0)
    return op->emitOpError() << "set '" << set.getName().getValue()
                             << "' is a vertex set and has no endpoints";
  if (tuple.size() != set.getCardinality())
    return op->emitOpError() << "endpoint tuple has " << tuple.size()
                             << " components but elements of set '"
                             << set.getName().getValue() << "' have "
                             << set.getCardinality() << " endpoints";
  if (!tuple.isNamed() && !set.isHomogeneous())
    return op->emitOpError() << "set '" << set.getName().getValue()
                             << "' is heterogeneous; its endpoint tuple "
                                "must be named";
  for (unsigned i = 0, e = tuple.size(); i < e; ++i)
    if (failed(verifyElementOfSet(op, tuple.getElementTypes()[i],
                                  set.getEndpoint(i),
                                  "endpoint " + Twine(i))))
      return failure();
  return success();
}
