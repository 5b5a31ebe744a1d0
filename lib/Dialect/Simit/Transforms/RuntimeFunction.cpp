//===- RuntimeFunction.cpp - Declarations of runtime functions ------------===//

#include "RuntimeFunction.h"

using namespace mlir;

func::FuncOp mlir::simit::declareRuntimeFunction(ModuleOp module,
                                                 StringRef name,
                                                 FunctionType type) {
  if (auto existing = module.lookupSymbol<func::FuncOp>(name)) {
    if (existing.getFunctionType() == type)
      return existing;
    existing.emitError("@") << name << " is declared with another type";
    return {};
  }
  OpBuilder b = OpBuilder::atBlockEnd(module.getBody());
  auto declaration = func::FuncOp::create(b, module.getLoc(), name, type);
  declaration.setPrivate();
  return declaration;
}
