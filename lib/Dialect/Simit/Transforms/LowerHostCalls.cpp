//===- LowerHostCalls.cpp - Calls of host functions (extern func) ---------===//
//
// `extern func f(...)` is implemented by the host, in C, with the argument
// conventions of the original Simit runtime (docs/lowering.md, "Host
// functions"): the C symbol is the name with the precision's prefix ('d'
// for float64, 's' for float32) when any parameter or result holds floats,
// returns an int status (0 for success), and takes the parameters, then
// the results:
//   scalar             by value; a result by pointer
//   local tensor       (int n, T *components), n components, row major
//   vector over a set  (int n, T *blocks), n components (elements times
//                       the block's components), blocks row major
//   matrix (BCSR)      (int rows, int cols, int *rowptr, int *colidx,
//                       int blockRows, int blockCols, T *blocks), rows and
//                       cols in components (blocks times the block's
//                       extent), rowptr of rows / blockRows + 1 entries
//   opaque             void **, the address of (a copy of) the handle,
//                       as the original runtime passes it; a result too
//   matrix result      (int rows, int cols, int **rowptr, int **colidx,
//                       int blockRows, int blockCols, T **blocks): the host
//                       mallocs the three arrays and stores them; Simit
//                       checks them, takes a copy and frees them
// A non-zero status ends the run with the call's position, except from
// functions with matrix results, which the original runtime's tests declare
// void (their arrays are checked instead). A function without floats may
// also be defined with the prefix (ObjectCode.cpp).
//
// Arrays travel as pointers, which the buffer deallocation would not see
// as uses: the call goes through a private shim whose memref parameters
// keep them alive up to the call, and which takes the pointers inside.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include "mlir/Interfaces/DataLayoutInterfaces.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// The address of the first component of `memref` (!llvm.ptr).
static Value addressOf(OpBuilder &b, Location loc, ModuleOp module,
                       Value memref) {
  auto type = cast<MemRefType>(memref.getType());
  auto metadata = memref::ExtractStridedMetadataOp::create(b, loc, memref);
  Value base = memref::ExtractAlignedPointerAsIndexOp::create(b, loc, memref);
  // Bytes per component: an opaque result's slot holds !llvm.ptr.
  Value width = arith::ConstantIndexOp::create(
      b, loc,
      DataLayout(module).getTypeSize(type.getElementType()).getFixedValue());
  Value offset = arith::MulIOp::create(b, loc, metadata.getOffset(), width);
  Value address = arith::IndexCastOp::create(
      b, loc, b.getI64Type(), arith::AddIOp::create(b, loc, base, offset));
  return LLVM::IntToPtrOp::create(
      b, loc, LLVM::LLVMPointerType::get(b.getContext()), address);
}

namespace {
/// The shim `name`(args) -> i32 that passes its memref arguments to the
/// host symbol as pointers to their first component.
func::FuncOp getOrCreateShim(OpBuilder &b, ModuleOp module, Location loc,
                             StringRef symbol, TypeRange argTypes) {
  MLIRContext *ctx = module.getContext();
  Type i32 = b.getI32Type();
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  auto shimType = FunctionType::get(ctx, argTypes, {i32});
  std::string base = ("simit_host." + symbol).str(), name = base;
  for (int n = 1; auto existing = module.lookupSymbol<func::FuncOp>(name);
       ++n) {
    if (existing.getFunctionType() == shimType)
      return existing;
    name = base + "." + std::to_string(n);
  }

  SmallVector<Type> hostTypes;
  for (Type type : argTypes)
    hostTypes.push_back(isa<MemRefType>(type) ? ptr : type);
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPointToEnd(module.getBody());
  if (!module.lookupSymbol<func::FuncOp>(symbol))
    func::FuncOp::create(b, loc, symbol,
                         FunctionType::get(ctx, hostTypes, {i32}))
        .setPrivate();
  auto shim = func::FuncOp::create(b, loc, name, shimType);
  shim.setPrivate();
  Block *entry = shim.addEntryBlock();
  b.setInsertionPointToStart(entry);
  SmallVector<Value> hostArgs;
  for (BlockArgument arg : entry->getArguments())
    hostArgs.push_back(isa<MemRefType>(arg.getType())
                           ? addressOf(b, loc, module, arg)
                           : Value(arg));
  auto call = func::CallOp::create(b, loc, symbol, TypeRange{i32}, hostArgs);
  func::ReturnOp::create(b, loc, call.getResults());
  return shim;
}
} // namespace

/// A 1-D view of a contiguous array (the shim's canonical argument type).
static Value flatten(OpBuilder &b, Location loc, Value array) {
  auto type = cast<MemRefType>(array.getType());
  if (type.getRank() == 1)
    return memref::CastOp::create(
        b, loc, MemRefType::get({ShapedType::kDynamic}, type.getElementType()),
        array);
  ReassociationIndices all;
  for (int64_t d = 0; d < type.getRank(); ++d)
    all.push_back(d);
  return memref::CollapseShapeOp::create(b, loc, array,
                                         ArrayRef<ReassociationIndices>{all});
}

LogicalResult FunctionLowering::lowerHostCall(func::CallOp call,
                                              func::FuncOp callee) {
  Location loc = call.getLoc();
  StringRef name =
      callee->getAttrOfType<StringAttr>("simit.extern_function").getValue();
  Type i32 = b.getI32Type();

  // The precision's prefix, from the first float component.
  std::string symbol = name.str();
  for (Type type : llvm::concat<const Type>(callee.getArgumentTypes(),
                                            callee.getResultTypes()))
    if (Type c = getComponentType(type); isa<FloatType>(c)) {
      symbol = (c.isF32() ? "s" : "d") + symbol;
      break;
    }

  auto i32Of = [&](Value index) -> Value {
    return arith::IndexCastOp::create(b, loc, i32, index);
  };
  auto i32Constant = [&](int64_t v) -> Value {
    return arith::ConstantIntOp::create(b, loc, i32, v);
  };
  // The number of components of a vector over a set: its elements times
  // the components of a block.
  auto components = [&](Value array) -> Value {
    auto type = cast<MemRefType>(array.getType());
    Value n = memref::DimOp::create(b, loc, array, 0);
    int64_t perBlock = 1;
    for (int64_t d : type.getShape().drop_front())
      perBlock *= d;
    if (perBlock != 1)
      n = arith::MulIOp::create(b, loc, n, indexConstant(perBlock));
    return i32Of(n);
  };
  auto unsupported = [&](Type type, StringRef what) {
    return call.emitError("extern func '")
           << name << "': " << what << " of type " << type
           << " cannot cross to the host";
  };

  // A matrix's blocks are blockRows x blockCols (1 x 1 for scalars); its
  // rows and columns cross counted in components.
  auto blockShape = [](SystemTensorType system) {
    SmallVector<int64_t> block = system.getBlockShape();
    while (block.size() < 2)
      block.push_back(1);
    return block;
  };
  auto extent = [&](StringAttr set, int64_t blockExtent) {
    Value n = getSetSize(set);
    if (blockExtent != 1)
      n = arith::MulIOp::create(b, loc, n, indexConstant(blockExtent));
    return i32Of(n);
  };

  // Local tensors go through a stack slot (vector values have no address),
  // allocated once however often the call runs.
  SmallVector<Value> args;
  SmallVector<std::function<Value()>> readResults;

  for (Value operand : call.getOperands()) {
    Type type = operand.getType();
    Value lowered = lookup(operand);
    if (isa<IntegerType, FloatType>(type)) {
      args.push_back(type.isInteger(1)
                         ? arith::ExtUIOp::create(b, loc, i32, lowered)
                         : lowered);
      continue;
    }
    if (isa<OpaqueType>(type)) {
      // By the address of a copy of the handle, as the original runtime
      // passes its variable (what the host stores there is not seen).
      Value slot = allocaSlot(loc, MemRefType::get({1}, lowered.getType()));
      memref::StoreOp::create(b, loc, lowered, slot,
                              ValueRange{indexConstant(0)});
      args.push_back(flatten(b, loc, slot));
      continue;
    }
    auto system = dyn_cast<SystemTensorType>(type);
    if (!system || !system.isSystem()) {
      auto vector = dyn_cast_or_null<VectorType>(lowered.getType());
      if (!vector)
        return unsupported(type, "a parameter");
      auto slotType = MemRefType::get(vector.getShape(),
                                      vector.getElementType());
      Value slot = allocaSlot(loc, slotType);
      storeWhole(loc, lowered, slot);
      args.append({i32Constant(vector.getNumElements()),
                   flatten(b, loc, slot)});
      continue;
    }
    Storage storage = storageOf(operand);
    if (storage.kind == Storage::Kind::Dense) {
      args.append({components(lowered), flatten(b, loc, lowered)});
      continue;
    }
    // Block diagonal, stencil and dense matrices cross as BCSR too.
    if (!hasBCSRView(storage))
      return call.emitError("extern func '")
             << name << "': matrices stored as " << storage.describe()
             << " cannot cross to the host (BCSR matrices, and square "
                "diagonal, stencil and dense ones, can)";
    auto [rowptr, colidx, blocks] = bcsrArrays(loc, storage, operand);
    SmallVector<int64_t> block = blockShape(system);
    args.append({extent(storage.rows, block[0]), extent(storage.cols, block[1]),
                 flatten(b, loc, rowptr), flatten(b, loc, colidx),
                 i32Constant(block[0]), i32Constant(block[1]),
                 flatten(b, loc, blocks)});
  }

  SmallVector<Value> resultValues;
  for (Value result : call.getResults()) {
    Type type = result.getType();
    if (isa<IntegerType, FloatType, OpaqueType>(type)) {
      Type slotElement = convertType(type);
      if (type.isInteger(1))
        slotElement = i32;
      Value slot = allocaSlot(loc, MemRefType::get({1}, slotElement));
      args.push_back(flatten(b, loc, slot));
      readResults.push_back([&, slot, type]() -> Value {
        Value v = memref::LoadOp::create(b, loc, slot,
                                         ValueRange{indexConstant(0)});
        if (type.isInteger(1))
          v = arith::TruncIOp::create(b, loc, b.getI1Type(), v);
        return v;
      });
      continue;
    }
    auto system = dyn_cast<SystemTensorType>(type);
    if (!system || !system.isSystem()) {
      auto vector = dyn_cast_or_null<VectorType>(convertType(type));
      if (!vector)
        return unsupported(type, "a result");
      Value slot = allocaSlot(
          loc, MemRefType::get(vector.getShape(), vector.getElementType()));
      args.append({i32Constant(vector.getNumElements()),
                   flatten(b, loc, slot)});
      readResults.push_back([&, slot, vector]() -> Value {
        return loadWhole(loc, vector, slot);
      });
      continue;
    }
    if (system.getOrder() != 1) {
      // simit-assign-storage gives the result its storage with a
      // simit.convert after the call.
      auto convert = result.hasOneUse()
                         ? dyn_cast<ConvertOp>(*result.getUsers().begin())
                         : ConvertOp();
      Storage storage = convert ? storageOf(convert) : Storage();
      if (storage.kind != Storage::Kind::Host)
        return unsupported(type, "a result");
      SmallVector<int64_t> block = blockShape(system);
      Type ptr = LLVM::LLVMPointerType::get(b.getContext());
      auto slotType = MemRefType::get({1}, ptr);
      Value rowptrSlot = allocaSlot(loc, slotType);
      Value colidxSlot = allocaSlot(loc, slotType);
      Value blocksSlot = allocaSlot(loc, slotType);
      args.append({extent(storage.rows, block[0]),
                   extent(storage.cols, block[1]), flatten(b, loc, rowptrSlot),
                   flatten(b, loc, colidxSlot), i32Constant(block[0]),
                   i32Constant(block[1]), flatten(b, loc, blocksSlot)});
      readResults.push_back(
          [&, result, storage, rowptrSlot, colidxSlot, blocksSlot]() -> Value {
            return adoptHostMatrix(call, result, storage,
                                   {rowptrSlot, colidxSlot, blocksSlot});
          });
      continue;
    }
    Value array = allocSystem(loc, type, Storage::dense());
    args.append({components(array), flatten(b, loc, array)});
    readResults.push_back([array]() { return array; });
  }

  func::FuncOp shim =
      getOrCreateShim(b, module, loc, symbol, ValueRange(args).getTypes());
  Value status = func::CallOp::create(b, loc, shim, args).getResult(0);
  // The original runtime's functions with matrix results return void; their
  // arrays are checked instead.
  bool returnsMatrix = llvm::any_of(call.getResultTypes(), [](Type type) {
    auto system = dyn_cast<SystemTensorType>(type);
    return system && system.isSystem() && system.getOrder() == 2;
  });
  if (!returnsMatrix) {
    Value ok = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq, status,
                                     i32Constant(0));
    cf::AssertOp::create(b, loc, ok,
                         ("extern func '" + name + "' (host symbol '" + symbol +
                          "') returned a non-zero status" +
                          sourcePositionSuffix(call))
                             .str());
  }
  for (auto [result, read] : llvm::zip_equal(call.getResults(), readResults))
    map(result, read());
  return success();
}

Value FunctionLowering::adoptHostMatrix(func::CallOp call, Value result,
                                        const Storage &storage,
                                        std::array<Value, 3> slots) {
  Location loc = call.getLoc();
  Type i64 = b.getI64Type();
  SmallVector<Value, 3> host;
  for (Value slot : slots)
    host.push_back(
        memref::LoadOp::create(b, loc, slot, ValueRange{indexConstant(0)}));
  auto i64Of = [&](Value index) -> Value {
    return arith::IndexCastOp::create(b, loc, i64, index);
  };
  Value rowBlocks = getSetSize(storage.rows);
  Value where =
      stringConstant(loc, ("extern func '" + storage.edges.getValue() + "'" +
                           sourcePositionSuffix(call))
                              .str());
  Value blocks = callRuntime(
      loc, runtimeName(::simit::abi::RuntimeFunction::HostMatrixBlocks), {i64},
      {host[0], host[1], host[2], i64Of(rowBlocks),
       i64Of(getSetSize(storage.cols)), where});
  Value count = arith::IndexCastOp::create(b, loc, b.getIndexType(), blocks);

  auto indexArray = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  Value rowptr = memref::AllocOp::create(
      b, loc, indexArray,
      ValueRange{arith::AddIOp::create(b, loc, rowBlocks, indexConstant(1))});
  Value colidx = memref::AllocOp::create(b, loc, indexArray, ValueRange{count});
  auto valuesType = cast<MemRefType>(convertType(result.getType()));
  Value values = memref::AllocOp::create(b, loc, valuesType, ValueRange{count});
  int64_t blockBytes = DataLayout(module)
                           .getTypeSize(valuesType.getElementType())
                           .getFixedValue();
  for (int64_t d : valuesType.getShape().drop_front())
    blockBytes *= d;
  // Through a shim, like the host's own functions: the arrays it fills are
  // memref arguments the buffer deallocation sees.
  SmallVector<Value> adoptArgs = {
      host[0],
      host[1],
      host[2],
      i64Of(rowBlocks),
      arith::ConstantIntOp::create(b, loc, i64, blockBytes),
      rowptr,
      colidx,
      flatten(b, loc, values)};
  func::FuncOp adopt = getOrCreateShim(
      b, module, loc,
      runtimeName(::simit::abi::RuntimeFunction::HostMatrixAdopt),
      ValueRange(adoptArgs).getTypes());
  func::CallOp::create(b, loc, adopt, adoptArgs);
  runtimePatterns[storage.runtimeEncoding] = {rowptr, colidx};
  return values;
}
