//===- SourcePosition.cpp - Source positions in run-time messages ---------===//

#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include "mlir/IR/Location.h"
#include "llvm/Support/Path.h"

using namespace mlir;

std::string simit::sourcePositionSuffix(Operation *op) {
  return sourcePositionSuffix(op->getLoc());
}

std::string simit::sourcePositionSuffix(Location loc) {
  auto file = loc->findInstanceOf<FileLineColLoc>();
  if (!file)
    return "";
  return (" (" + llvm::sys::path::filename(file.getFilename().getValue()) +
          ":" + Twine(file.getLine()) + ":" + Twine(file.getColumn()) + ")")
      .str();
}
