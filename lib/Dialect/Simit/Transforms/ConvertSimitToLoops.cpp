//===- ConvertSimitToLoops.cpp - simit to loops over sets -----------------===//
//
// The driver of convert-simit-to-loops: every exported (public) function is
// rebuilt with the data it touches as arguments (its `simit.bindings`),
// element functions are inlined into the set loops of their maps, and the
// element functions and externs are then erased. This file holds the
// bindings, structured control flow and the host-level operations on system
// vectors; the other parts are named in LoopsLowering.h.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "StorageAnalysis.h"
#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include "mlir/IR/IRMapping.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/xxhash.h"
#include "llvm/ADT/DenseSet.h"

#include <numeric>
#include <tuple>

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_CONVERTSIMITTOLOOPS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;
using ::simit::abi::RuntimeFunction;

int64_t mlir::simit::loops::numComponents(Type type) {
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return tensor.getNumElements();
  if (auto vector = dyn_cast<VectorType>(type))
    return vector.getNumElements();
  if (auto system = dyn_cast<SystemTensorType>(type)) {
    int64_t n = numComponents(system.getBlockType());
    for (Attribute dim : system.getDims())
      n *= cast<IntegerAttr>(dim).getInt();
    return n;
  }
  return 1;
}

/// Whether a type is a tensor with a set dimension (a system tensor).
bool mlir::simit::loops::isSystem(Type type) { return hasSetDimension(type); }

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

Type FunctionLowering::convertType(Type type) {
  return typeConverter.convertType(type);
}

Value FunctionLowering::lookup(Value original) {
  auto it = values.find(original);
  return it == values.end() ? Value() : it->second;
}

/// The matrix type `type` is or a variable of `type` holds, if any.
static SystemTensorType matrixTypeOf(Type type) {
  if (auto ref = dyn_cast<RefType>(type))
    type = ref.getValueType();
  auto tensor = dyn_cast<SystemTensorType>(type);
  return tensor && tensor.isSetMatrix() ? tensor : nullptr;
}

Storage FunctionLowering::storageOf(Value original) {
  auto it = storages.find(original);
  if (it != storages.end())
    return it->second;
  SystemTensorType type = matrixTypeOf(original.getType());
  StorageAttr encoding = type ? getStorage(type) : StorageAttr();
  if (!encoding)
    return Storage::dense();
  // checkStorages reported every encoding without a layout.
  std::optional<Storage> storage = storageOfEncoding(
      encoding, cast<StringAttr>(type.getDims()[0]),
      cast<StringAttr>(type.getDims()[1]), setTypes);
  assert(storage && "encoding without a layout");
  return storages[original] = *storage;
}

void FunctionLowering::carryStorage(Value to, Value from) {
  SystemTensorType type = matrixTypeOf(to.getType());
  if (type && !getStorage(type) && storages.count(from))
    storages[to] = storages[from];
}

LogicalResult FunctionLowering::checkStorages(func::FuncOp original) {
  auto collect = [&](Type type) {
    if (auto set = dyn_cast<SetType>(type))
      setTypes[set.getName()] = set;
  };
  for (auto global : module.getOps<ExternOp>())
    collect(global.getType());
  original.walk([&](Operation *op) {
    for (Type type : op->getOperandTypes())
      collect(type);
    for (Type type : op->getResultTypes())
      collect(type);
  });
  bool unsupported = false;
  // Each encoding is reported once, where it first appears.
  DenseSet<StorageAttr> reported;
  auto check = [&](Value value) {
    SystemTensorType type = matrixTypeOf(value.getType());
    StorageAttr encoding = type ? getStorage(type) : StorageAttr();
    if (!encoding || reported.contains(encoding))
      return;
    Location loc = value.getDefiningOp() ? value.getDefiningOp()->getLoc()
                                         : value.getLoc();
    std::optional<Storage> storage =
        storageOfEncoding(encoding, cast<StringAttr>(type.getDims()[0]),
                          cast<StringAttr>(type.getDims()[1]), setTypes);
    // The arrays of a pattern known at run time exist from the op that
    // computes the value on: a value that a loop or an if carries, or a
    // slot, would need them carried too.
    Operation *producer = value.getDefiningOp();
    if (storage && storage->kind == Storage::Kind::Host &&
        isBindingPattern(storage->runtimeEncoding)) {
      reported.insert(encoding);
      entryPatterns.push_back(*storage);
      return;
    }
    if (storage && storage->kind == Storage::Kind::Host &&
        (!producer || isa<RegionBranchOpInterface>(producer) ||
         isa<RefType>(value.getType()))) {
      unsupported = true;
      reported.insert(encoding);
      emitError(loc, "a matrix stored as '")
          << encoding.str()
          << "' (a pattern known only at run time, of a host function's "
             "matrix) cannot be carried by a loop, an if or a variable slot "
             "yet";
      return;
    }
    if (storage)
      return;
    unsupported = true;
    reported.insert(encoding);
    if (StorageAttr host = storage::findHost(encoding)) {
      emitError(loc, "a matrix stored as '")
          << encoding.str() << "' (with the pattern host function '"
          << host.getSet().getValue()
          << "' returns) is not supported by the loop lowering yet: of "
             "such patterns, products, transposes, and sums with matrices "
             "stored BCSR or block diagonal have a layout";
      return;
    }
    emitError(loc, "a matrix stored as '")
        << encoding.str() << "' is not supported by the loop lowering yet";
  };
  original.walk([&](Operation *op) {
    for (Value result : op->getResults())
      check(result);
    for (Region &region : op->getRegions())
      for (Block &block : region)
        for (Value arg : block.getArguments())
          check(arg);
  });
  return failure(unsupported);
}

//===----------------------------------------------------------------------===//
// Helpers
//===----------------------------------------------------------------------===//

void FunctionLowering::forLoop(Location loc, Value upper,
                               function_ref<void(Value)> body) {
  scf::ForOp::create(
      b, loc, indexConstant(0), upper, indexConstant(1), ValueRange{},
      [&](OpBuilder &nb, Location, Value i, ValueRange) {
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
        body(i);
        scf::YieldOp::create(b, loc);
      });
}

Value FunctionLowering::indexConstant(int64_t value) {
  return arith::ConstantIndexOp::create(b, function.getLoc(), value);
}

Value FunctionLowering::loadWhole(Location loc, VectorType type, Value memref) {
  int64_t rank = cast<MemRefType>(memref.getType()).getRank();
  SmallVector<Value> origin(rank, indexConstant(0));
  if (!type.getElementType().isInteger(1))
    return vector::LoadOp::create(b, loc, type, memref, origin);
  SmallVector<Value> components;
  for (int64_t i = 0, n = type.getNumElements(); i < n; ++i)
    components.push_back(
        memref::LoadOp::create(b, loc, memref, indexConstant(i)));
  return vector::FromElementsOp::create(b, loc, type, components);
}

void FunctionLowering::storeWhole(Location loc, Value value, Value memref) {
  auto type = cast<VectorType>(value.getType());
  int64_t rank = cast<MemRefType>(memref.getType()).getRank();
  SmallVector<Value> origin(rank, indexConstant(0));
  if (!type.getElementType().isInteger(1)) {
    vector::StoreOp::create(b, loc, value, memref, origin);
    return;
  }
  for (int64_t i = 0, n = type.getNumElements(); i < n; ++i)
    memref::StoreOp::create(b, loc, vector::ExtractOp::create(b, loc, value, i),
                            memref, indexConstant(i));
}

Value FunctionLowering::zeroOf(Type scalarType) {
  // A string variable starts empty.
  if (isa<LLVM::LLVMPointerType>(scalarType))
    return stringConstant(function.getLoc(), "");
  if (auto complex = dyn_cast<ComplexType>(scalarType)) {
    Attribute zero = b.getFloatAttr(complex.getElementType(), 0.0);
    return complex::ConstantOp::create(b, function.getLoc(), complex,
                                       b.getArrayAttr({zero, zero}));
  }
  return arith::ConstantOp::create(b, function.getLoc(),
                                   b.getZeroAttr(scalarType));
}

Value FunctionLowering::numBlocks(const Storage &storage,
                                  StringAttr denseSet) {
  Location loc = function.getLoc();
  switch (storage.kind) {
  case Storage::Kind::Dense:
    return getSetSize(denseSet);
  case Storage::Kind::Diagonal:
    return getSetSize(storage.rows);
  case Storage::Kind::Pattern:
  case Storage::Kind::Union:
  case Storage::Kind::Product:
  case Storage::Kind::Host: {
    Value rowPtr = rowPointers(storage);
    Value last = memref::LoadOp::create(b, loc, rowPtr,
                                        ValueRange{getSetSize(storage.rows)});
    return arith::IndexCastOp::create(b, loc, b.getIndexType(), last);
  }
  case Storage::Kind::Stencil:
    return arith::MulIOp::create(b, loc, getSetSize(storage.rows),
                                 indexConstant(storage.offsets.size()));
  case Storage::Kind::Incidence:
    return arith::MulIOp::create(b, loc, getSetSize(storage.edges),
                                 indexConstant(storage.cardinality));
  case Storage::Kind::DenseMatrix:
    return arith::MulIOp::create(b, loc, getSetSize(storage.rows),
                                 getSetSize(storage.cols));
  }
  llvm_unreachable("storage kind");
}

SmallVector<Value> FunctionLowering::blockIndices(MemRefType type,
                                                 ArrayRef<Value> prefix,
                                                 int64_t c) {
  SmallVector<Value> indices(prefix);
  SmallVector<int64_t> inner;
  for (int64_t d = type.getRank() - 1; d >= static_cast<int64_t>(prefix.size());
       --d) {
    inner.push_back(c % type.getDimSize(d));
    c /= type.getDimSize(d);
  }
  for (int64_t i : llvm::reverse(inner))
    indices.push_back(indexConstant(i));
  return indices;
}

void FunctionLowering::prefetchBlock(Location loc, Value array, Value block,
                                     bool isWrite) {
  auto type = cast<MemRefType>(array.getType());
  int64_t components = 1;
  for (int64_t d = 1; d < type.getRank(); ++d)
    components *= type.getDimSize(d);
  int64_t perLine =
      std::max<int64_t>(1, 64 / componentBytes(type.getElementType()));
  SmallVector<int64_t> touched;
  for (int64_t c = 0; c < components; c += perLine)
    touched.push_back(c);
  if (touched.back() != components - 1)
    touched.push_back(components - 1);
  for (int64_t c : touched)
    memref::PrefetchOp::create(b, loc, array, blockIndices(type, {block}, c),
                               isWrite, /*localityHint=*/3,
                               /*isDataCache=*/true);
}

void FunctionLowering::fill(Location loc, Value array, Value scalar) {
  auto type = cast<MemRefType>(array.getType());
  SmallVector<Value> lbs, ubs, steps;
  for (int64_t d = 0; d < type.getRank(); ++d) {
    lbs.push_back(indexConstant(0));
    ubs.push_back(type.isDynamicDim(d)
                      ? memref::DimOp::create(b, loc, array, d).getResult()
                      : indexConstant(type.getDimSize(d)));
    steps.push_back(indexConstant(1));
  }
  if (type.getRank() == 0) {
    memref::StoreOp::create(b, loc, scalar, array, ValueRange{});
    return;
  }
  scf::ParallelOp::create(b, loc, lbs, ubs, steps,
                          [&](OpBuilder &nb, Location l, ValueRange ivs) {
                            memref::StoreOp::create(nb, l, scalar, array, ivs);
                          });
}

Value FunctionLowering::allocSystem(Location loc, Type type,
                                    const Storage &storage, bool zeroFill) {
  auto memref = cast<MemRefType>(convertType(type));
  auto system = cast<SystemTensorType>(type);
  StringAttr denseSet;
  for (Attribute dim : system.getDims())
    if (auto set = dyn_cast<StringAttr>(dim)) {
      denseSet = set;
      break;
    }
  Value size = numBlocks(storage, denseSet);
  Value array = memref::AllocOp::create(b, loc, memref, ValueRange{size});
  if (zeroFill)
    fill(loc, array, zeroOf(memref.getElementType()));
  return array;
}

StringAttr FunctionLowering::elementSetOf(Value original) {
  if (StringAttr set = elementSets.lookup(original))
    return set;
  // A computed endpoint (the frontend selects among a tuple's endpoints)
  // belongs to the set its choices share.
  if (auto select = original.getDefiningOp<arith::SelectOp>()) {
    StringAttr set = elementSetOf(select.getTrueValue());
    if (set && set == elementSetOf(select.getFalseValue()))
      return set;
  }
  return {};
}

bool FunctionLowering::canAlias(Operation *read,
                                function_ref<bool(Operation *)> writes) {
  auto writesInside = [&](Operation *op) {
    return op
        ->walk([&](Operation *nested) {
          return writes(nested) ? WalkResult::interrupt()
                                : WalkResult::advance();
        })
        .wasInterrupted();
  };
  Block *block = read->getBlock();
  Operation *last = read;
  for (Operation *user : read->getResult(0).getUsers()) {
    Operation *ancestor = block->findAncestorOpInBlock(*user);
    if (!ancestor)
      return false;
    // A use inside a loop or branch may come after a write in that region
    // (a later iteration).
    if (ancestor != user && writesInside(ancestor))
      return false;
    if (last->isBeforeInBlock(ancestor))
      last = ancestor;
  }
  // A write between the read and its last use changes what the use sees;
  // the last user itself reads its operands before it writes.
  for (Operation *op = read->getNextNode(); op && op != last;
       op = op->getNextNode())
    if (writesInside(op))
      return false;
  return true;
}

//===----------------------------------------------------------------------===//
// Operations
//===----------------------------------------------------------------------===//

LogicalResult FunctionLowering::lowerFunctionReturn(func::ReturnOp op) {
  SmallVector<Value> results;
  for (auto [operand, type] : llvm::zip_equal(op.getOperands(), resultTypes)) {
    if (storageOf(operand).isMatrix())
      return op.emitError("exported functions cannot return system matrices");
    Value result = lookup(operand);
    if (result.getType() != type)
      result = vector::ShapeCastOp::create(b, op.getLoc(), type, result);
    results.push_back(result);
  }
  func::ReturnOp::create(b, op.getLoc(), results);
  return success();
}

LogicalResult FunctionLowering::lowerOp(Operation *op) {
  if (auto loop = dyn_cast<scf::ForOp>(op))
    return lowerFor(loop);
  if (auto branch = dyn_cast<scf::IfOp>(op))
    return lowerIf(branch);
  if (auto loop = dyn_cast<scf::WhileOp>(op))
    return lowerWhile(loop);
  if (auto ret = dyn_cast<func::ReturnOp>(op))
    return element ? success() : lowerFunctionReturn(ret);
  if (auto call = dyn_cast<func::CallOp>(op)) {
    auto callee = module.lookupSymbol<func::FuncOp>(call.getCalleeAttr());
    // Runtime functions on scalars only (lib/ABI/Timing.cpp)
    // stay calls of their private declarations.
    auto isScalar = [](Type t) { return isa<FloatType, IntegerType>(t); };
    if (callee && callee.isExternal() &&
        callee->hasAttr("simit.runtime_function") &&
        llvm::is_contained({runtimeName(RuntimeFunction::Clock),
                            runtimeName(RuntimeFunction::StoreTime),
                            runtimeName(RuntimeFunction::PhaseBegin),
                            runtimeName(RuntimeFunction::PhaseEnd)},
                           call.getCallee()) &&
        llvm::all_of(call.getOperandTypes(), isScalar) &&
        llvm::all_of(call.getResultTypes(), isScalar)) {
      SmallVector<Value> args;
      for (Value operand : call.getOperands())
        args.push_back(lookup(operand));
      auto lowered = func::CallOp::create(b, op->getLoc(), call.getCallee(),
                                          call.getResultTypes(), args);
      for (auto [from, to] :
           llvm::zip_equal(call.getResults(), lowered.getResults()))
        map(from, to);
      return success();
    }
    if (callee && callee.isExternal() &&
        callee->hasAttr("simit.extern_function"))
      return lowerHostCall(call, callee);
    if (callee && callee.isExternal())
      return op->emitError("'@")
             << call.getCallee()
             << "' is implemented by the host or runtime; calling it is not "
                "supported by the loop lowering yet";
    return op->emitError("calls must be inlined by simit-inline-functions "
                         "before the loop lowering");
  }
  if (op->getDialect() != op->getContext()->getLoadedDialect<SimitDialect>()) {
    bool handled = false;
    if (failed(lowerLocalOp(op, handled)))
      return failure();
    return handled ? success() : lowerGeneric(op);
  }

  // Result slots of an element function are not materialised.
  if (isa<ZerosOp, AllocOp, LoadOp>(op) && isSink(op->getResult(0)))
    return success();
  if (auto store = dyn_cast<StoreOp>(op); store && isSink(store.getRef()))
    return success();
  bool handled = false;
  if (failed(lowerElementAccess(op, handled)))
    return failure();
  if (handled)
    return success();

  if (isa<GetSetOp>(op))
    return success();
  if (auto size = dyn_cast<SetSizeOp>(op)) {
    map(size, getSetSize(cast<SetType>(size.getSet().getType()).getName()));
    return success();
  }
  if (auto ref = dyn_cast<ExternRefOp>(op)) {
    auto global = module.lookupSymbol<ExternOp>(ref.getGlobalAttr());
    if (!global)
      return op->emitError("no simit.extern named ") << ref.getGlobalAttr();
    if (auto system = dyn_cast<SystemTensorType>(global.getType());
        system && system.isSystem() && system.getOrder() != 1)
      return op->emitError("extern system matrices are not supported by the "
                           "loop lowering: they have no storage");
    map(ref, getExtern(global));
    return success();
  }
  if (auto element = dyn_cast<SetElementOp>(op)) {
    map(element, lookup(element.getIndex()));
    elementSets[element] = cast<SetType>(element.getSet().getType()).getName();
    return success();
  }
  if (auto endpoints = dyn_cast<EndpointsOp>(op)) {
    tuples[endpoints] = {cast<SetType>(endpoints.getSet().getType()),
                         lookup(endpoints.getElement())};
    return success();
  }
  if (auto get = dyn_cast<TupleGetOp>(op)) {
    auto it = tuples.find(get.getTuple());
    if (it == tuples.end())
      return op->emitError("the loop lowering cannot trace this tuple to its "
                           "edge");
    auto [set, edge] = it->second;
    Value endpoints = getEndpoints(set);
    Value k = indexConstant(get.getIndex());
    Location loc = op->getLoc();
    Value raw = memref::LoadOp::create(b, loc, endpoints, ValueRange{edge, k});
    map(get, arith::IndexCastOp::create(b, loc, b.getIndexType(), raw));
    elementSets[get] = set.getEndpoint(get.getIndex());
    if (this->element && edge == this->element->element)
      endpointPositions[get] = k;
    return success();
  }
  if (isa<MapOp, AssembleOp>(op))
    return lowerMapLike(op);
  if (auto convert = dyn_cast<ConvertOp>(op))
    return lowerConvert(convert);
  if (isa<GridPointOp, GridEdgeOp>(op))
    return lowerGridAccess(op);
  if (isa<PrintOp, StringConstantOp, StringConcatOp, StringCmpOp>(op))
    return lowerPrintOrString(op);
  if (isa<FactorizeOp, FactorSolveOp, FactorFreeOp, TriangularSolveOp>(op))
    return lowerFactorisation(op);
  if (auto woodbury = dyn_cast<WoodburyOp>(op))
    return lowerWoodbury(woodbury);

  if (failed(lowerSystemOp(op, handled)))
    return failure();
  if (handled)
    return success();
  if (failed(lowerLocalOp(op, handled)))
    return failure();
  if (!handled)
    return op->emitError("'") << op->getName()
                              << "' is not supported by the loop lowering";
  return success();
}

//===----------------------------------------------------------------------===//
// Functions
//===----------------------------------------------------------------------===//

FunctionLowering::FunctionLowering(ModuleOp module, func::FuncOp function)
    : module(module), function(function), b(function.getContext()) {}

/// The type an exported function's parameter or result of type `original`
/// (lowered to `lowered`) has at the host boundary: a local complex tensor
/// is `vector<N x 2 x T>`, so the host ABI can tell its (re, im) pairs from
/// a tensor of 2N floats; everything else is its lowered type.
static Type hostType(Type original, Type lowered) {
  auto vector = dyn_cast<VectorType>(lowered);
  if (!vector || !isa<ComplexType>(getComponentType(original)))
    return lowered;
  return VectorType::get({vector.getNumElements() / 2, 2},
                         vector.getElementType());
}

LogicalResult FunctionLowering::run(func::FuncOp original) {
  MLIRContext *ctx = original.getContext();
  if (failed(checkStorages(original)))
    return failure();
  Block *entry = function.addEntryBlock();
  allocaBlock = entry;
  SmallVector<Attribute> bindingAttrs;
  b.setInsertionPointToEnd(entry);
  for (auto [i, arg] : llvm::enumerate(original.getArguments())) {
    Type type = convertType(arg.getType());
    if (!type || isa<SetType, ElementType>(arg.getType()))
      return original.emitError("exported function parameter ")
             << i << " of type " << arg.getType()
             << " cannot be lowered (sets are bound as externs)";
    if (isSystem(arg.getType()) &&
        cast<SystemTensorType>(arg.getType()).getOrder() != 1)
      return original.emitError("exported functions cannot take system "
                                "matrices");
    Type host = hostType(arg.getType(), type);
    Value param = entry->addArgument(host, arg.getLoc());
    map(arg, host == type
                 ? param
                 : vector::ShapeCastOp::create(b, arg.getLoc(), type, param)
                       .getResult());
    SmallVector<NamedAttribute> entries = {
        NamedAttribute(StringAttr::get(ctx, "kind"),
                       StringAttr::get(ctx, ::simit::abi::spelling(
                                                BindingKind::Parameter))),
        NamedAttribute(StringAttr::get(ctx, "index"), b.getI64IntegerAttr(i))};
    // A local tensor of real components: the host checks the shape of what
    // it binds (a 3x2 array is no matrix[2,3], though it has as many
    // numbers), as for externs.
    if (auto tensor = dyn_cast<RankedTensorType>(arg.getType());
        tensor && !isa<ComplexType>(tensor.getElementType()))
      entries.emplace_back(StringAttr::get(ctx, "shape"),
                           DenseI64ArrayAttr::get(ctx, tensor.getShape()));
    // A vector over a set: a block per element of the set bound then.
    if (isSystem(arg.getType()))
      entries.emplace_back(
          StringAttr::get(ctx, "set"),
          cast<StringAttr>(cast<SystemTensorType>(arg.getType()).getDims()[0]));
    bindingAttrs.push_back(DictionaryAttr::get(ctx, entries));
  }
  SmallVector<Attribute> resultShapes;
  bool hasMatrixResult = false;
  for (Type type : original.getResultTypes()) {
    Type lowered = convertType(type);
    if (!lowered)
      return original.emitError("exported function result of type ")
             << type << " cannot be lowered";
    resultTypes.push_back(hostType(type, lowered));
    auto tensor = dyn_cast<RankedTensorType>(type);
    hasMatrixResult |= tensor && tensor.getRank() > 1;
    resultShapes.push_back(DenseI64ArrayAttr::get(
        ctx, tensor ? tensor.getShape() : ArrayRef<int64_t>()));
  }
  if (hasMatrixResult)
    function->setAttr(StringRef(::simit::abi::kResultShapesAttr),
                      ArrayAttr::get(ctx, resultShapes));
  // Patterns of the bound sets alone, built once here: every later use of
  // the function reaches them (a loop's body, a branch, a slot's load).
  for (const Storage &storage : entryPatterns)
    runtimePattern(storage);
  if (failed(lowerOps(original.front())))
    return failure();

  // Bindings in canonical order: by kind, then by the names they carry.
  SmallVector<unsigned> order(bindings.size());
  std::iota(order.begin(), order.end(), 0);
  auto sortKey = [&](unsigned i) {
    DictionaryAttr dict = bindings[i].first;
    // The kinds ranked as listed; unions and products after them.
    static const BindingKind ranked[] = {
        BindingKind::SetSize,       BindingKind::GridDims,
        BindingKind::Endpoints,     BindingKind::Field,
        BindingKind::PatternRowPtr, BindingKind::PatternColIdx,
        BindingKind::PatternLocations, BindingKind::Extern};
    StringRef spelled = dict.getAs<StringAttr>("kind").getValue();
    std::optional<BindingKind> kind = ::simit::abi::parseBindingKind(
        std::string_view(spelled.data(), spelled.size()));
    unsigned rank = llvm::find(ranked, *kind) - std::begin(ranked);
    auto text = [&](StringRef key) {
      auto value = dict.getAs<StringAttr>(key);
      return value ? value.getValue().str() : std::string();
    };
    bool isPattern = *kind == BindingKind::PatternRowPtr ||
                     *kind == BindingKind::PatternColIdx ||
                     *kind == BindingKind::PatternLocations;
    return std::make_tuple(isPattern ? 4u : rank,
                           text("set") + text("name"), text("field"),
                           text("rows"), text("cols"), rank);
  };
  llvm::stable_sort(order, [&](unsigned x, unsigned y) {
    return sortKey(x) < sortKey(y);
  });
  unsigned firstBinding = original.getNumArguments();
  for (unsigned i : order) {
    Value old = bindings[i].second;
    Value moved = entry->addArgument(old.getType(), old.getLoc());
    old.replaceAllUsesWith(moved);
    bindingAttrs.push_back(bindings[i].first);
  }
  entry->eraseArguments(firstBinding, bindings.size());
  function.setType(FunctionType::get(
      ctx, function.front().getArgumentTypes(), resultTypes));
  function->setAttr(StringRef(::simit::abi::kBindingsAttr),
                    ArrayAttr::get(ctx, bindingAttrs));
  function->setAttr("llvm.emit_c_interface", UnitAttr::get(ctx));
  return success();
}

namespace {
struct ConvertSimitToLoops
    : public mlir::simit::impl::ConvertSimitToLoopsBase<ConvertSimitToLoops> {
  using Base::Base;

  void runOnOperation() override {
    ModuleOp module = getOperation();
    // Element functions are those maps apply; they are inlined, not
    // exported.
    llvm::DenseSet<StringAttr> elementFunctions;
    module.walk([&](Operation *op) {
      if (isa<MapOp, AssembleOp>(op))
        elementFunctions.insert(
            op->getAttrOfType<FlatSymbolRefAttr>("callee").getAttr());
    });
    SmallVector<func::FuncOp> exported;
    for (auto function : module.getOps<func::FuncOp>())
      if (isExportedFunction(function)) {
        if (function.isExternal() ||
            elementFunctions.contains(function.getSymNameAttr())) {
          function.emitError("an exported function needs a body and cannot "
                             "be mapped over a set");
          return signalPassFailure();
        }
        exported.push_back(function);
      }

    // Host functions keep their Simit declarations under another name, so
    // that the C symbol (the name itself when no float crosses) is free.
    SymbolTable symbols(module);
    for (auto function :
         llvm::make_early_inc_range(module.getOps<func::FuncOp>()))
      if (function.isExternal() && function->hasAttr("simit.extern_function"))
        if (failed(symbols.rename(
                function, ("simit.extern." + function.getSymName()).str())))
          return signalPassFailure();

    // Storage comes from the types; input that simit-assign-storage has
    // not seen gets it here.
    for (func::FuncOp original : exported)
      if (needsStorageAssignment(original) &&
          failed(assignStorage(original)))
        return signalPassFailure();

    bool failedAny = false;
    for (func::FuncOp original : exported) {
      OpBuilder builder(original);
      auto lowered = func::FuncOp::create(
          builder, original.getLoc(),
          (original.getSymName() + ".lowered").str(),
          builder.getFunctionType({}, {}));
      FunctionLowering lowering(module, lowered);
      lowering.prefetchScatterBlocks = prefetchScatterBlocks;
      lowering.prefetchMatrixBytes = prefetchMatrixBytes;
      if (failed(lowering.run(original))) {
        lowered.erase();
        failedAny = true;
        continue;
      }
      std::string name = original.getSymName().str();
      original.erase();
      lowered.setSymName(name);
    }
    if (failedAny)
      return signalPassFailure();

    // Element functions now live in the set loops and externs are
    // bindings: every other function on simit values is gone.
    // Declarations of runtime functions that no lowered call uses (those
    // replaced by their _bcsr forms) still have simit types: gone too.
    // The declarations go second: an element function's calls of host
    // functions were uses of them until the element function went.
    for (Operation &op : llvm::make_early_inc_range(module.getOps())) {
      auto function = dyn_cast<func::FuncOp>(op);
      if ((function && !function.isExternal() && usesSimitDialect(function)) ||
          isa<ExternOp>(op))
        op.erase();
    }
    // Runtime and host functions are only ever called.
    DenseSet<StringAttr> called;
    module.walk([&](func::CallOp call) {
      called.insert(call.getCalleeAttr().getAttr());
    });
    for (auto function :
         llvm::make_early_inc_range(module.getOps<func::FuncOp>()))
      if (function.isExternal() &&
          (function->hasAttr("simit.runtime_function") ||
           function->hasAttr("simit.extern_function")) &&
          !called.contains(function.getSymNameAttr()))
        function.erase();
  }
};
} // namespace
