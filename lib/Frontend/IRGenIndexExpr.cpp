//===- IRGenIndexExpr.cpp - Index expressions (ivar assignments) ----------===//

#include "IRGenImpl.h"

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

void IRGenerator::genIndexAssign(const AssignStmt &stmt) {
  unsupported(stmt.loc, "index expressions");
}
