//===- LowerPrint.cpp - Printing and strings ------------------------------===//
//
// simit.print and strings through runtime functions.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "StringConstant.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;
using ::simit::abi::RuntimeFunction;

Value FunctionLowering::callRuntime(Location loc, StringRef name,
                                    TypeRange results, ValueRange args) {
  auto type = FunctionType::get(b.getContext(), args.getTypes(), results);
  if (!module.lookupSymbol<func::FuncOp>(name)) {
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(module.getBody());
    auto decl = func::FuncOp::create(b, loc, name, type);
    decl.setPrivate();
  }
  auto call = func::CallOp::create(b, loc, name, results, args);
  return call.getNumResults() ? call.getResult(0) : Value();
}

Value FunctionLowering::stringConstant(Location loc, StringRef text) {
  return createStringConstant(b, module, loc, text);
}

LogicalResult FunctionLowering::printMatrix(
    Location loc, Value matrix,
    function_ref<LogicalResult(Value)> printScalar) {
  // Dense, as language.md section 6 prints every tensor: one line per
  // scalar row, its components separated by spaces, zeros where the
  // storage has no block.
  Storage storage = storageOf(matrix);
  if (!storage.isMatrix())
    return matrix.getDefiningOp()
               ? matrix.getDefiningOp()->emitError(
                     "printing a system matrix of unknown sparsity")
               : failure();
  auto type = cast<SystemTensorType>(matrix.getType());
  SmallVector<int64_t> shape = getLocalShape(type.getBlockType());
  int64_t blockRows = shape.empty() ? 1 : shape[0];
  int64_t blockCols = shape.size() < 2 ? 1 : shape[1];
  Value array = lookup(matrix);
  auto printText = [&](StringRef text) {
    callRuntime(loc, runtimeName(RuntimeFunction::PrintStr), {},
                {stringConstant(loc, text)});
  };
  auto printIf = [&](Value condition, StringRef text) {
    auto branch = scf::IfOp::create(b, loc, TypeRange{}, condition,
                                    /*withElseRegion=*/false);
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(branch.thenBlock());
    printText(text);
  };
  auto notFirst = [&](Value index) {
    return arith::CmpIOp::create(b, loc, arith::CmpIPredicate::ne, index,
                                 indexConstant(0));
  };
  LogicalResult result = success();
  forLoop(loc, getSetSize(storage.rows), [&](Value row) {
    for (int64_t i = 0; i < blockRows; ++i) {
      if (i == 0)
        printIf(notFirst(row), "\n");
      else
        printText("\n");
      forLoop(loc, getSetSize(storage.cols), [&](Value col) {
        SmallVector<Value> block = readMatrixBlock(
            loc, storage, array, row, col, blockRows * blockCols);
        for (int64_t j = 0; j < blockCols; ++j) {
          if (j == 0)
            printIf(notFirst(col), " ");
          else
            printText(" ");
          if (failed(printScalar(block[i * blockCols + j])))
            result = failure();
        }
      });
    }
  });
  return result;
}

LogicalResult FunctionLowering::lowerPrintOrString(Operation *op) {
  Location loc = op->getLoc();
  MLIRContext *ctx = op->getContext();
  auto ptrType = LLVM::LLVMPointerType::get(ctx);
  auto stringConstant = [&](StringRef text) {
    return this->stringConstant(loc, text);
  };

  if (auto constant = dyn_cast<StringConstantOp>(op)) {
    map(constant, stringConstant(constant.getValue()));
    return success();
  }
  if (auto concat = dyn_cast<StringConcatOp>(op)) {
    map(concat, callRuntime(loc, runtimeName(RuntimeFunction::StringConcat), {ptrType},
                            {lookup(concat.getLhs()), lookup(concat.getRhs())}));
    return success();
  }
  if (auto cmp = dyn_cast<StringCmpOp>(op)) {
    Value order =
        callRuntime(loc, runtimeName(RuntimeFunction::StringCompare), {b.getI32Type()},
                    {lookup(cmp.getLhs()), lookup(cmp.getRhs())});
    arith::CmpIPredicate predicate;
    switch (cmp.getPredicate()) {
    case StringPredicate::eq: predicate = arith::CmpIPredicate::eq; break;
    case StringPredicate::ne: predicate = arith::CmpIPredicate::ne; break;
    case StringPredicate::lt: predicate = arith::CmpIPredicate::slt; break;
    case StringPredicate::le: predicate = arith::CmpIPredicate::sle; break;
    case StringPredicate::gt: predicate = arith::CmpIPredicate::sgt; break;
    case StringPredicate::ge: predicate = arith::CmpIPredicate::sge; break;
    }
    Value zero = arith::ConstantIntOp::create(b, loc, b.getI32Type(), 0);
    map(cmp, arith::CmpIOp::create(b, loc, predicate, order, zero));
    return success();
  }

  auto print = cast<PrintOp>(op);
  auto printText = [&](StringRef text) {
    callRuntime(loc, runtimeName(RuntimeFunction::PrintStr), {}, {stringConstant(text)});
  };
  auto printFloat = [&](Value scalar) -> LogicalResult {
    auto floatType = cast<FloatType>(scalar.getType());
    if (floatType.getWidth() < 64)
      scalar = arith::ExtFOp::create(b, loc, b.getF64Type(), scalar);
    else if (floatType.getWidth() > 64)
      return op->emitError("cannot print floats wider than 64 bits");
    callRuntime(loc, runtimeName(RuntimeFunction::PrintF64), {}, {scalar});
    return success();
  };
  auto printScalar = [&](Value scalar) -> LogicalResult {
    Type type = scalar.getType();
    if (isa<LLVM::LLVMPointerType>(type)) {
      callRuntime(loc, runtimeName(RuntimeFunction::PrintStr), {}, {scalar});
      return success();
    }
    if (isa<FloatType>(type))
      return printFloat(scalar);
    // A complex prints as <re,im> (language.md section 6).
    if (isa<ComplexType>(type)) {
      printText("<");
      if (failed(printFloat(complex::ReOp::create(b, loc, scalar))))
        return failure();
      printText(",");
      if (failed(printFloat(complex::ImOp::create(b, loc, scalar))))
        return failure();
      printText(">");
      return success();
    }
    if (isa<IndexType>(type)) {
      scalar = arith::IndexCastOp::create(b, loc, b.getI64Type(), scalar);
      type = scalar.getType();
    }
    if (auto intType = dyn_cast<IntegerType>(type)) {
      if (intType.getWidth() == 1)
        scalar = arith::ExtUIOp::create(b, loc, b.getI64Type(), scalar);
      else if (intType.getWidth() < 64)
        scalar = arith::ExtSIOp::create(b, loc, b.getI64Type(), scalar);
      else if (intType.getWidth() > 64)
        return op->emitError("cannot print integers wider than 64 bits");
      callRuntime(loc, runtimeName(RuntimeFunction::PrintI64), {}, {scalar});
      return success();
    }
    return op->emitError("printing values of type ")
           << type << " is not supported by the loop lowering";
  };
  for (Value value : print.getValues()) {
    Type type = value.getType();
    if (auto tensor = dyn_cast<RankedTensorType>(type)) {
      Value lowered = lookup(value);
      if (!lowered)
        return op->emitError("print operand was not lowered");
      // Components separated by spaces; the rows of a matrix by newlines.
      int64_t n = tensor.getNumElements();
      int64_t columns = tensor.getRank() >= 2 ? tensor.getShape().back() : n;
      for (int64_t i = 0; i < n; ++i) {
        if (i > 0)
          printText(i % columns == 0 ? "\n" : " ");
        if (failed(printScalar(component(type, lowered, i))))
          return failure();
      }
      continue;
    }
    if (auto local = dyn_cast<SystemTensorType>(type);
        local && !local.isSystem()) {
      // A blocked local tensor: as a blocked system vector, one line per
      // element of a vector; a matrix as the grid of its scalar rows.
      Value lowered = lookup(value);
      if (!lowered)
        return op->emitError("print operand was not lowered");
      SmallVector<int64_t> shape;
      std::optional<SmallVector<int64_t>> order = unblockedOrder(type, shape);
      if (!order)
        return op->emitError("printing local tensors whose blocks are of "
                             "another rank is not supported by the loop "
                             "lowering");
      int64_t columns =
          shape.size() == 2
              ? shape[1]
              : shape[0] / cast<IntegerAttr>(local.getDims()[0]).getInt();
      for (auto [i, position] : llvm::enumerate(*order)) {
        if (i > 0)
          printText(i % columns == 0 ? "\n" : " ");
        if (failed(
                printScalar(component(type, lowered, indexConstant(position)))))
          return failure();
      }
      continue;
    }
    if (auto system = dyn_cast<SystemTensorType>(type);
        system && system.isSystem()) {
      if (!hasBlockPerElement(system)) {
        if (system.getOrder() != 2)
          return op->emitError("printing system tensors of order ")
                 << system.getOrder() << " is not supported";
        if (failed(printMatrix(loc, value, printScalar)))
          return failure();
        continue;
      }
      // A system vector: its elements in set order, separated by spaces
      // when they are scalars, one element's block per line otherwise
      // (the block's components separated by spaces).
      Value array = lookup(value);
      auto memref = cast<MemRefType>(array.getType());
      int64_t blockSize = 1;
      for (int64_t d : memref.getShape().drop_front())
        blockSize *= d;
      Value size = memref::DimOp::create(b, loc, array, 0);
      LogicalResult inner = success();
      scf::ForOp::create(
          b, loc, indexConstant(0), size, indexConstant(1), ValueRange{},
          [&](OpBuilder &nb, Location, Value i, ValueRange) {
            OpBuilder::InsertionGuard guard(b);
            b.setInsertionPoint(nb.getInsertionBlock(),
                                nb.getInsertionPoint());
            Value notFirst = arith::CmpIOp::create(
                b, loc, arith::CmpIPredicate::ne, i, indexConstant(0));
            scf::IfOp::create(b, loc, notFirst, [&](OpBuilder &tb, Location) {
              OpBuilder::InsertionGuard guard(b);
              b.setInsertionPoint(tb.getInsertionBlock(),
                                  tb.getInsertionPoint());
              callRuntime(loc, runtimeName(RuntimeFunction::PrintStr), {},
                          {stringConstant(blockSize == 1 ? " " : "\n")});
              scf::YieldOp::create(b, loc);
            });
            for (int64_t c = 0; c < blockSize; ++c) {
              if (c > 0)
                callRuntime(loc, runtimeName(RuntimeFunction::PrintStr), {},
                            {stringConstant(" ")});
              Value scalar = memref::LoadOp::create(
                  b, loc, array, blockIndices(memref, {i}, c));
              if (failed(printScalar(scalar)))
                inner = failure();
            }
            scf::YieldOp::create(b, loc);
          });
      if (failed(inner))
        return failure();
      continue;
    }
    if (isa<SystemTensorType>(type))
      return op->emitError("printing system tensors is not supported by the "
                           "loop lowering yet");
    Value lowered = lookup(value);
    if (!lowered)
      return op->emitError("print operand was not lowered");
    if (failed(printScalar(lowered)))
      return failure();
  }
  if (print.getNewline())
    printText("\n");
  return success();
}
