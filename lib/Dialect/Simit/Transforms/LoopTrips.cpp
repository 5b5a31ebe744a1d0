//===- LoopTrips.cpp - Trip counts of loop dimensions ---------------------===//

#include "LoopTrips.h"

#include "mlir/Dialect/Arith/IR/Arith.h"

using namespace mlir;

Value simit::tripCount(OpBuilder &b, Location loc, Value lb, Value ub,
                       Value step) {
  Value zero = arith::ConstantIndexOp::create(b, loc, 0);
  Value extent = b.createOrFold<arith::SubIOp>(loc, ub, lb);
  extent = b.createOrFold<arith::MaxSIOp>(loc, extent, zero);
  return b.createOrFold<arith::CeilDivUIOp>(loc, extent, step);
}
