//===- LowerSystemOps.cpp - Host-level system vector ops ------------------===//
//
// Host-level operations on system tensors: field reads and writes, set
// sizes, loads and stores of system tensor variables (with the aliasing
// rules of docs/lowering.md), and the dispatch of linear algebra, solves,
// products and slices to their parts.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "mlir/IR/IRMapping.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// Whether `op` writes field `field` of set `set`: a field write, or a map
/// whose element function writes a field of that name.
static bool writesField(Operation *op, StringAttr set, StringAttr field,
                        ModuleOp module) {
  if (auto write = dyn_cast<FieldWriteOp>(op))
    return write.getFieldAttr() == field &&
           cast<SetType>(write.getSet().getType()).getName() == set;
  if (isa<MapOp, AssembleOp>(op)) {
    auto callee = module.lookupSymbol<func::FuncOp>(
        op->getAttrOfType<FlatSymbolRefAttr>("callee"));
    if (!callee)
      return true;
    bool writes = false;
    callee.walk([&](ElemWriteOp w) {
      if (w.getFieldAttr() == field)
        writes = true;
    });
    return writes;
  }
  return isa<func::CallOp>(op);
}

/// Whether the first use of variable `alloc` in its block (the use itself
/// or the operation holding it) is a store to it.
static bool isFirstUseAStore(AllocOp alloc) {
  Block *block = alloc->getBlock();
  Operation *first = nullptr;
  for (Operation *user : alloc->getUsers()) {
    Operation *inBlock = block->findAncestorOpInBlock(*user);
    if (inBlock && (!first || inBlock->isBeforeInBlock(first)))
      first = inBlock;
  }
  auto store = dyn_cast_or_null<StoreOp>(first);
  return store && store.getRef() == alloc.getResult();
}

LogicalResult FunctionLowering::lowerSystemOp(Operation *op, bool &handled) {
  handled = true;
  Location loc = op->getLoc();
  if (auto read = dyn_cast<FieldReadOp>(op)) {
    auto set = cast<SetType>(read.getSet().getType());
    Type fieldType = set.getElement().getFieldType(read.getField());
    Value array = getField(set.getName(), read.getFieldAttr(), fieldType);
    if (canAlias(op, [&](Operation *w) {
          return writesField(w, set.getName(), read.getFieldAttr(), module);
        })) {
      map(read, array);
      return success();
    }
    Value copy = memref::AllocOp::create(
        b, loc, cast<MemRefType>(array.getType()),
        ValueRange{getSetSize(set.getName())});
    memref::CopyOp::create(b, loc, array, copy);
    map(read, copy);
    return success();
  }
  if (auto write = dyn_cast<FieldWriteOp>(op)) {
    auto set = cast<SetType>(write.getSet().getType());
    Type fieldType = set.getElement().getFieldType(write.getField());
    Value array = getField(set.getName(), write.getFieldAttr(), fieldType);
    Value value = lookup(write.getValue());
    if (isSystem(write.getValue().getType())) {
      // An index expression may have been computed into the field itself.
      if (value != array)
        memref::CopyOp::create(b, loc, value, array);
    } else
      fill(loc, array, value);
    return success();
  }

  // The remaining operations matter here only on system tensors.
  bool system = llvm::any_of(op->getOperandTypes(), isSystem) ||
                llvm::any_of(op->getResultTypes(), isSystem);
  auto refOf = [](Type type) {
    auto ref = dyn_cast<RefType>(type);
    return ref && isSystem(ref.getValueType());
  };
  bool systemRef = llvm::any_of(op->getOperandTypes(), refOf) ||
                   llvm::any_of(op->getResultTypes(), refOf);
  if (!system && !systemRef) {
    handled = false;
    return success();
  }

  if (isa<ZerosOp, BroadcastOp>(op)) {
    Type type = op->getResult(0).getType();
    bool matrix = cast<SystemTensorType>(type).getOrder() != 1;
    // A zero matrix is stored as its encoding says (simit-assign-storage:
    // `empty`, a zero-filled diagonal or dense array); a matrix of one
    // value everywhere has no sparsity to be stored in.
    if (matrix && !isa<ZerosOp>(op))
      return op->emitError("a system matrix of unknown sparsity cannot be "
                           "created here; assemble it with a map");
    Storage storage = matrix ? storageOf(op->getResult(0)) : Storage::dense();
    if (!storage.isMatrix() && matrix)
      return op->emitError("the storage of this zero matrix is not known");
    Value array = allocSystem(loc, type, storage,
                              /*zeroFill=*/isa<ZerosOp>(op));
    if (auto broadcast = dyn_cast<BroadcastOp>(op))
      fill(loc, array, lookup(broadcast.getValue()));
    map(op->getResult(0), array);
    return success();
  }
  if (auto alloc = dyn_cast<AllocOp>(op)) {
    Type type = cast<RefType>(alloc.getType()).getValueType();
    // A matrix variable's array is made by the first store when that is
    // the variable's first use in its block (it then dominates every use);
    // otherwise (first assigned in a branch or loop) here, zero filled,
    // in the storage of its type.
    if (cast<SystemTensorType>(type).getOrder() != 1) {
      if (isFirstUseAStore(alloc))
        return success();
      Storage storage = storageOf(alloc);
      if (!storage.isMatrix())
        return op->emitError("the storage of this matrix variable is not "
                             "known");
      map(alloc, allocSystem(loc, type, storage));
      return success();
    }
    map(alloc, allocSystem(loc, type, Storage::dense()));
    return success();
  }
  if (auto load = dyn_cast<LoadOp>(op)) {
    Value buffer = lookup(load.getRef());
    if (!buffer)
      return op->emitError("a variable holding a system matrix is read "
                           "before a matrix is stored to it");
    if (canAlias(op, [&](Operation *w) {
          auto store = dyn_cast<StoreOp>(w);
          return (store && store.getRef() == load.getRef()) ||
                 isa<func::CallOp>(w);
        })) {
      map(load, buffer);
      return success();
    }
    auto type = cast<MemRefType>(buffer.getType());
    Value copy = memref::AllocOp::create(
        b, loc, type,
        ValueRange{memref::DimOp::create(b, loc, buffer, 0).getResult()});
    memref::CopyOp::create(b, loc, buffer, copy);
    map(load, copy);
    return success();
  }
  if (auto store = dyn_cast<StoreOp>(op)) {
    Value value = lookup(store.getValue()), buffer = lookup(store.getRef());
    Storage storage = storageOf(store.getValue());
    if (!buffer) {
      // The first store to a matrix variable, where it is declared
      // (isFirstUseAStore), so that its array dominates every use.
      if (!storage.isMatrix())
        return op->emitError("a variable holding a system matrix must be "
                             "first assigned an assembled matrix");
      // A fresh matrix used only here becomes the variable's array.
      if (store.getValue().hasOneUse() &&
          isa_and_present<MapOp, AssembleOp, IndexExprOp, ConvertOp>(
              store.getValue().getDefiningOp())) {
        map(store.getRef(), value);
        return success();
      }
      buffer = allocSystem(loc, store.getValue().getType(), storage,
                           /*zeroFill=*/false);
      map(store.getRef(), buffer);
    } else if (storage != storageOf(store.getRef())) {
      return op->emitError("a variable stored as ")
             << storageOf(store.getRef()).describe()
             << " cannot be assigned a value stored as "
             << storage.describe();
    }
    if (value != buffer)
      memref::CopyOp::create(b, loc, value, buffer);
    return success();
  }
  if (auto insert = dyn_cast<InsertOp>(op)) {
    auto type = cast<SystemTensorType>(insert.getTensor().getType());
    if (type.getOrder() != 1)
      return lowerMatrixBlockAccess(op);
    // `v(p) = b` on a variable (load, insert, store back) writes the
    // variable's array in place; otherwise the vector is copied first.
    Value tensor = lookup(insert.getTensor());
    auto load = insert.getTensor().getDefiningOp<LoadOp>();
    auto store = insert->hasOneUse()
                     ? dyn_cast<StoreOp>(*insert->getUsers().begin())
                     : StoreOp();
    bool inPlace = load && store && store.getRef() == load.getRef() &&
                   tensor == lookup(load.getRef());
    auto memref = cast<MemRefType>(tensor.getType());
    Value target = tensor;
    if (!inPlace) {
      target = memref::AllocOp::create(
          b, loc, memref,
          ValueRange{memref::DimOp::create(b, loc, tensor, 0).getResult()});
      memref::CopyOp::create(b, loc, tensor, target);
    }
    Value position = lookup(insert.getIndices()[0]);
    Value value = lookup(insert.getValue());
    for (int64_t c = 0, n = numComponents(insert.getValue().getType()); c < n;
         ++c)
      memref::StoreOp::create(b, loc,
                              component(insert.getValue().getType(), value, c),
                              target, blockIndices(memref, {position}, c));
    map(insert, target);
    return success();
  }
  if (auto extract = dyn_cast<ExtractOp>(op)) {
    auto type = cast<SystemTensorType>(extract.getTensor().getType());
    if (type.getOrder() != 1)
      return lowerMatrixBlockAccess(op);
    // A block of an index expression waiting for this read (blockRead):
    // mapped here when computed alone, else read from the whole result.
    if (auto expr = extract.getTensor().getDefiningOp<IndexExprOp>();
        expr && blockRead(expr) == extract) {
      if (failed(lowerIndexExpr(expr, extract)))
        return failure();
      if (values.contains(extract.getResult()))
        return success();
    }
    Value array = lookup(extract.getTensor());
    Value position = lookup(extract.getIndices()[0]);
    int64_t n = numComponents(extract.getType());
    SmallVector<Value> components;
    auto memref = cast<MemRefType>(array.getType());
    for (int64_t c = 0; c < n; ++c)
      components.push_back(memref::LoadOp::create(
          b, loc, array, blockIndices(memref, {position}, c)));
    map(extract, n == 1 && !isa<ShapedType>(extract.getType())
                     ? components[0]
                     : fromComponents(convertType(extract.getType()),
                                      components));
    return success();
  }
  if (auto indexExpr = dyn_cast<IndexExprOp>(op))
    return lowerIndexExpr(indexExpr);
  if (auto solve = dyn_cast<SolveOp>(op))
    return lowerSolve(solve);
  if (auto matmul = dyn_cast<MatMulOp>(op))
    return lowerMatMul(matmul);
  if (auto slice = dyn_cast<SliceOp>(op))
    return lowerMatrixSlice(slice);
  if (isa<AddOp, SubOp, MulOp, DivOp, NegOp, ScaleOp, MatVecOp, MatMulOp,
          TransposeOp, DotOp, OuterOp, NormOp>(op))
    return op->emitError("linear algebra on system tensors must be rewritten "
                         "by simit-linalg-to-index-expr first");
  return op->emitError("'") << op->getName()
                            << "' on system tensors is not supported by the "
                               "loop lowering";
}
