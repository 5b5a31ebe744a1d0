//===- LowerControlFlow.cpp - Structured control flow ---------------------===//
//
// scf.for, scf.if and scf.while of simit values, rebuilt around their
// lowered bodies, and ops lowered generically (operands and results
// converted).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

LogicalResult FunctionLowering::lowerOps(Block &block) {
  for (Operation &op : block) {
    if (isa<scf::YieldOp, scf::ConditionOp, YieldOp>(op))
      continue;
    if (failed(lowerOp(&op)))
      return failure();
    if (op.hasAttr(kCheckNumericsAttr) && failed(scanForNonFinite(&op)))
      return failure();
  }
  return success();
}

/// The lowered values of the operands that are not result slots.
static SmallVector<Value> keptOperands(FunctionLowering &lowering,
                                       ValueRange operands) {
  SmallVector<Value> kept;
  for (Value operand : operands)
    if (!lowering.isSink(operand))
      kept.push_back(lowering.lookup(operand));
  return kept;
}

LogicalResult FunctionLowering::lowerFor(scf::ForOp op) {
  SmallVector<Value> inits = keptOperands(*this, op.getInitArgs());
  if (llvm::is_contained(inits, Value()))
    return op.emitError("cannot lower a loop-carried value");
  for (auto [init, result, arg] :
       llvm::zip(op.getInitArgs(), op.getResults(), op.getRegionIterArgs())) {
    carryStorage(arg, init);
    carryStorage(result, init);
  }
  // The body is lowered into the finished loop: index checks look at the
  // bounds of the loop that defines their index.
  auto loop = scf::ForOp::create(b, op.getLoc(), lookup(op.getLowerBound()),
                                 lookup(op.getUpperBound()),
                                 lookup(op.getStep()), inits);
  Block *body = loop.getBody();
  if (body->mightHaveTerminator())
    body->getTerminator()->erase();
  bool failedBody = false;
  {
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToEnd(body);
    map(op.getInductionVar(), loop.getInductionVar());
    unsigned next = 0;
    for (Value arg : op.getRegionIterArgs())
      if (!isSink(arg))
        map(arg, loop.getRegionIterArgs()[next++]);
    failedBody = failed(lowerOps(*op.getBody()));
    if (!failedBody)
      scf::YieldOp::create(b, op.getLoc(),
                           keptOperands(*this, op.getYieldedValues()));
  }
  if (failedBody)
    return failure();
  unsigned next = 0;
  for (Value result : op.getResults())
    if (!isSink(result))
      map(result, loop.getResult(next++));
  return success();
}

LogicalResult FunctionLowering::lowerIf(scf::IfOp op) {
  SmallVector<Type> types;
  for (Value result : op.getResults())
    if (!isSink(result)) {
      Type type = convertType(result.getType());
      if (!type)
        return op.emitError("cannot lower a result of type ")
               << result.getType();
      types.push_back(type);
    }
  auto lowered = scf::IfOp::create(b, op.getLoc(), types,
                                   lookup(op.getCondition()),
                                   /*withElseRegion=*/true);
  for (auto [from, to] : llvm::zip(op->getRegions(), lowered->getRegions())) {
    Block *dest = &to.front();
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToEnd(dest);
    if (!dest->empty() && dest->back().hasTrait<OpTrait::IsTerminator>())
      dest->back().erase();
    if (from.empty()) {
      scf::YieldOp::create(b, op.getLoc());
      continue;
    }
    if (failed(lowerOps(from.front())))
      return failure();
    auto yield = cast<scf::YieldOp>(from.front().getTerminator());
    scf::YieldOp::create(b, yield.getLoc(),
                         keptOperands(*this, yield.getOperands()));
  }
  unsigned next = 0;
  for (Value result : op.getResults())
    if (!isSink(result))
      map(result, lowered.getResult(next++));
  if (op.getNumResults())
    for (auto [result, x] :
         llvm::zip(op.getResults(), op.thenYield().getOperands()))
      carryStorage(result, x);
  return success();
}

LogicalResult FunctionLowering::lowerWhile(scf::WhileOp op) {
  for (Value v : llvm::concat<Value>(op.getInits(), op.getResults()))
    if (isSink(v))
      return op.emitError("a map result cannot be carried by a while loop");
  SmallVector<Value> inits = keptOperands(*this, op.getInits());
  SmallVector<Type> afterTypes;
  for (Value result : op.getResults())
    afterTypes.push_back(convertType(result.getType()));
  if (llvm::is_contained(inits, Value()) ||
      llvm::is_contained(afterTypes, Type()))
    return op.emitError("cannot lower a loop-carried value");
  for (auto [init, arg] : llvm::zip(op.getInits(), op.getBeforeArguments()))
    carryStorage(arg, init);

  auto loop = scf::WhileOp::create(b, op.getLoc(), afterTypes, inits);
  OpBuilder::InsertionGuard guard(b);
  SmallVector<Type> beforeTypes = llvm::to_vector(ValueRange(inits).getTypes());
  SmallVector<Location> beforeLocs(beforeTypes.size(), op.getLoc());
  SmallVector<Location> afterLocs(afterTypes.size(), op.getLoc());
  Block *before = b.createBlock(&loop.getBefore(), {}, beforeTypes, beforeLocs);
  Block *after = b.createBlock(&loop.getAfter(), {}, afterTypes, afterLocs);

  for (auto [from, to] :
       llvm::zip(op.getBeforeArguments(), before->getArguments()))
    map(from, to);
  b.setInsertionPointToEnd(before);
  if (failed(lowerOps(op.getBefore().front())))
    return failure();
  scf::ConditionOp condition = op.getConditionOp();
  for (auto [arg, result] : llvm::zip(condition.getArgs(), op.getResults()))
    carryStorage(result, arg);
  scf::ConditionOp::create(b, condition.getLoc(),
                           lookup(condition.getCondition()),
                           keptOperands(*this, condition.getArgs()));

  for (auto [from, to] :
       llvm::zip(op.getAfterArguments(), after->getArguments())) {
    map(from, to);
    carryStorage(from, condition.getArgs()[to.getArgNumber()]);
  }
  b.setInsertionPointToEnd(after);
  if (failed(lowerOps(op.getAfter().front())))
    return failure();
  scf::YieldOp::create(b, op.getLoc(),
                       keptOperands(*this, op.getYieldOp().getOperands()));
  for (auto [from, to] : llvm::zip(op.getResults(), loop.getResults()))
    map(from, to);
  return success();
}

Value FunctionLowering::allocaSlot(Location loc, MemRefType type) {
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPointToStart(allocaBlock);
  return memref::AllocaOp::create(b, loc, type);
}

LogicalResult FunctionLowering::lowerGeneric(Operation *op) {
  if (op->getNumRegions() != 0)
    return op->emitError("the loop lowering does not support '")
           << op->getName() << "' with regions";
  IRMapping mapping;
  for (Value operand : op->getOperands()) {
    Value lowered = lookup(operand);
    if (!lowered)
      return op->emitError("operand of type ")
             << operand.getType() << " has no lowered value";
    mapping.map(operand, lowered);
  }
  // Constants of local tensors become constants of flat vectors.
  if (auto constant = dyn_cast<arith::ConstantOp>(op)) {
    if (auto dense = dyn_cast<DenseElementsAttr>(constant.getValue())) {
      Type type = convertType(constant.getType());
      // Complex components become (re, im) pairs of floats.
      if (auto complex = dyn_cast<ComplexType>(dense.getElementType())) {
        SmallVector<Attribute> parts;
        for (std::complex<APFloat> c :
             dense.getValues<std::complex<APFloat>>()) {
          parts.push_back(FloatAttr::get(complex.getElementType(), c.real()));
          parts.push_back(FloatAttr::get(complex.getElementType(), c.imag()));
        }
        Value lowered =
            isa<VectorType>(type)
                ? arith::ConstantOp::create(
                      b, op->getLoc(),
                      DenseElementsAttr::get(cast<ShapedType>(type), parts))
                      .getResult()
                : complex::ConstantOp::create(b, op->getLoc(), complex,
                                              b.getArrayAttr(parts))
                      .getResult();
        map(constant, lowered);
        return success();
      }
      Attribute value = isa<VectorType>(type)
                            ? Attribute(dense.reshape(cast<ShapedType>(type)))
                            : dense.getSplatValue<Attribute>();
      map(constant, arith::ConstantOp::create(b, op->getLoc(),
                                              cast<TypedAttr>(value)));
      return success();
    }
  }
  Operation *clone = b.clone(*op, mapping);
  for (auto [from, to] : llvm::zip(op->getResults(), clone->getResults())) {
    Type type = convertType(from.getType());
    if (!type)
      return op->emitError("cannot lower a result of type ") << from.getType();
    to.setType(type);
    map(from, to);
  }
  return success();
}
