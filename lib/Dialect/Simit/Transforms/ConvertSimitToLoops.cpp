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
#include "SourcePosition.h"

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

//===----------------------------------------------------------------------===//
// Storage
//===----------------------------------------------------------------------===//

Storage Storage::unionOf(ArrayRef<StringAttr> edgeSets, StringAttr rows,
                         StringAttr cols) {
  SmallVector<StringAttr, 2> sorted(edgeSets);
  llvm::sort(sorted, [](StringAttr a, StringAttr b) {
    return a.getValue() < b.getValue();
  });
  sorted.erase(llvm::unique(sorted), sorted.end());
  if (sorted.size() == 1)
    return pattern(sorted.front(), rows, cols);
  Storage result{Kind::Union, nullptr, rows, cols};
  result.members = std::move(sorted);
  return result;
}

SmallVector<StringAttr, 2> Storage::patternSets() const {
  if (kind == Kind::Pattern)
    return {edges};
  return members;
}

bool Storage::contains(const Storage &o) const {
  if (*this == o)
    return true;
  // An edge pattern over (V, V) holds every diagonal block of V, and so do
  // a stencil (it always stores offset 0) and a union of patterns.
  if (o.kind == Kind::Diagonal)
    return (kind == Kind::Pattern || kind == Kind::Stencil ||
            kind == Kind::Union || kind == Kind::Product) &&
           rows == cols && rows == o.rows;
  // A union holds the patterns of its members over its sets.
  return kind == Kind::Union &&
         (o.kind == Kind::Pattern || o.kind == Kind::Union) && rows == o.rows &&
         cols == o.cols && llvm::all_of(o.patternSets(), [&](StringAttr e) {
           return llvm::is_contained(members, e);
         });
}

std::optional<Storage> mlir::simit::loops::transposedStorage(const Storage &s) {
  switch (s.kind) {
  case Storage::Kind::Dense:
  case Storage::Kind::Diagonal:
    return s;
  case Storage::Kind::Pattern:
    return Storage::pattern(s.edges, s.cols, s.rows);
  case Storage::Kind::Union:
    return Storage::unionOf(s.members, s.cols, s.rows);
  case Storage::Kind::Product:
  case Storage::Kind::Stencil:
  case Storage::Kind::Incidence:
    return std::nullopt;
  }
  llvm_unreachable("storage kind");
}

std::optional<Storage> mlir::simit::loops::joinStorages(const Storage &a,
                                                        const Storage &b) {
  if (a.contains(b))
    return a;
  if (b.contains(a))
    return b;
  // Patterns over the same sets join into their union; a diagonal joins
  // into any square one.
  auto combinable = [&](const Storage &s) {
    return s.kind == Storage::Kind::Pattern || s.kind == Storage::Kind::Union ||
           (s.kind == Storage::Kind::Diagonal && s.rows == s.cols);
  };
  if (!combinable(a) || !combinable(b) || a.rows != b.rows || a.cols != b.cols)
    return std::nullopt;
  SmallVector<StringAttr, 4> sets(a.patternSets());
  llvm::append_range(sets, b.patternSets());
  return Storage::unionOf(sets, a.rows, a.cols);
}

std::string Storage::describe() const {
  switch (kind) {
  case Kind::Dense:
    return "dense";
  case Kind::Diagonal:
    return ("diagonal of '" + rows.getValue() + "'").str();
  case Kind::Pattern:
    return ("pattern of '" + edges.getValue() + "' over ('" +
            rows.getValue() + "', '" + cols.getValue() + "')")
        .str();
  case Kind::Stencil:
    return ("stencil of grid '" + edges.getValue() + "' with " +
            Twine(offsets.size()) + " offsets")
        .str();
  case Kind::Incidence:
    return ((transposed ? "transposed incidence of '" : "incidence of '") +
            edges.getValue() + "' over ('" + rows.getValue() + "', '" +
            cols.getValue() + "')")
        .str();
  case Kind::Union: {
    std::string names;
    for (StringAttr member : members)
      names += (names.empty() ? "'" : ", '") + member.getValue().str() + "'";
    return ("union of the patterns of " + names + " over ('" +
            rows.getValue() + "', '" + cols.getValue() + "')")
        .str();
  }
  case Kind::Product:
    return ("product of matrices over ('" + rows.getValue() + "', '" +
            mid.getValue() + "') and ('" + mid.getValue() + "', '" +
            cols.getValue() + "')")
        .str();
  }
  llvm_unreachable("storage kind");
}

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

/// The shape of a local tensor's components: the builtin shape, or the
/// integer dimensions of a `!simit.tensor` followed by its block's.
static SmallVector<int64_t> localShape(Type type) {
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return SmallVector<int64_t>(tensor.getShape());
  SmallVector<int64_t> shape;
  if (auto system = dyn_cast<SystemTensorType>(type)) {
    for (Attribute dim : system.getDims())
      shape.push_back(cast<IntegerAttr>(dim).getInt());
    llvm::append_range(shape, localShape(system.getBlockType()));
  }
  return shape;
}

/// Whether a type is a tensor with a set dimension (a system tensor).
static bool isSystem(Type type) { return hasSetDimension(type); }

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

/// The numbers a local tensor of `component`s is stored as: complex
/// components are (re, im) pairs of their part type.
static Type storedNumberType(Type component) {
  if (auto complex = dyn_cast<ComplexType>(component))
    return complex.getElementType();
  return component;
}

/// The length of the flat vector or array that stores a local tensor.
static int64_t storedLength(Type type) {
  return numComponents(type) *
         (isa<ComplexType>(getComponentType(type)) ? 2 : 1);
}

Type FunctionLowering::convertType(Type type) {
  if (isa<FloatType, IntegerType, IndexType, ComplexType>(type))
    return type;
  if (isa<StringType, OpaqueType>(type))
    return LLVM::LLVMPointerType::get(type.getContext());
  if (isa<SetType, ElementType>(type))
    return IndexType::get(type.getContext());
  if (auto system = dyn_cast<SystemTensorType>(type)) {
    Type component = system.getComponentType();
    if (!system.isSystem())
      return VectorType::get({storedLength(type)}, storedNumberType(component));
    if (isa<ComplexType>(component))
      return nullptr;
    // Outer dimensions: a set is dynamic; a matrix over two sets stores a
    // dynamic number of blocks. Then the block shape.
    SmallVector<int64_t> shape;
    unsigned sets = 0;
    for (Attribute dim : system.getDims()) {
      if (isa<StringAttr>(dim))
        ++sets;
      else if (sets == 0 || system.getOrder() > 1)
        shape.push_back(cast<IntegerAttr>(dim).getInt());
    }
    if (sets > 2 || (sets == 2 && system.getOrder() != 2))
      return nullptr;
    shape.insert(shape.begin(), ShapedType::kDynamic);
    if (isa<SystemTensorType>(system.getBlockType()) &&
        isSystem(system.getBlockType()))
      return nullptr;
    llvm::append_range(shape, localShape(system.getBlockType()));
    return MemRefType::get(shape, component);
  }
  if (auto tensor = dyn_cast<RankedTensorType>(type)) {
    if (tensor.getRank() == 0)
      return tensor.getElementType();
    return VectorType::get({storedLength(type)},
                           storedNumberType(tensor.getElementType()));
  }
  if (auto ref = dyn_cast<RefType>(type)) {
    Type value = ref.getValueType();
    if (isSystem(value))
      return convertType(value);
    if (isa<FloatType, IntegerType, IndexType, ComplexType>(value))
      return MemRefType::get({}, value);
    if (isa<StringType>(value))
      return MemRefType::get({}, LLVM::LLVMPointerType::get(type.getContext()));
    if (isa<RankedTensorType, SystemTensorType>(value))
      return MemRefType::get({storedLength(value)},
                             storedNumberType(getComponentType(value)));
    return nullptr;
  }
  return nullptr;
}

Value FunctionLowering::lookup(Value original) {
  auto it = values.find(original);
  return it == values.end() ? Value() : it->second;
}

//===----------------------------------------------------------------------===//
// Bindings
//===----------------------------------------------------------------------===//

static StringRef bindingKindName(BindingKind kind) {
  switch (kind) {
  case BindingKind::SetSize:
    return "set_size";
  case BindingKind::GridDims:
    return "grid_dims";
  case BindingKind::Field:
    return "field";
  case BindingKind::Endpoints:
    return "endpoints";
  case BindingKind::PatternRowPtr:
    return "pattern_rowptr";
  case BindingKind::PatternColIdx:
    return "pattern_colidx";
  case BindingKind::PatternLocations:
    return "pattern_locations";
  case BindingKind::UnionRowPtr:
    return "union_rowptr";
  case BindingKind::UnionColIdx:
    return "union_colidx";
  case BindingKind::UnionGather:
    return "union_gather";
  case BindingKind::ProductRowPtr:
    return "product_rowptr";
  case BindingKind::ProductColIdx:
    return "product_colidx";
  case BindingKind::Extern:
    return "extern";
  }
  llvm_unreachable("binding kind");
}

Value FunctionLowering::getBinding(BindingKind kind, ArrayRef<StringRef> names,
                                   Type type) {
  std::string key = bindingKindName(kind).str();
  for (StringRef name : names)
    key += ":" + name.str();
  auto it = bindingPositions.find(key);
  if (it != bindingPositions.end())
    return bindings[it->second].second;

  MLIRContext *ctx = b.getContext();
  SmallVector<NamedAttribute> entries;
  entries.emplace_back(StringAttr::get(ctx, "kind"),
                       StringAttr::get(ctx, bindingKindName(kind)));
  // A union gather map names its part, a product its factors' shared set.
  const char *const setKeys[] = {
      "set", "rows", "cols",
      kind == BindingKind::UnionGather ? "part" : "mid"};
  switch (kind) {
  case BindingKind::Extern:
    entries.emplace_back(StringAttr::get(ctx, "name"),
                         StringAttr::get(ctx, names[0]));
    break;
  case BindingKind::Field:
    entries.emplace_back(StringAttr::get(ctx, "set"),
                         StringAttr::get(ctx, names[0]));
    entries.emplace_back(StringAttr::get(ctx, "field"),
                         StringAttr::get(ctx, names[1]));
    break;
  default:
    for (auto [i, name] : llvm::enumerate(names))
      entries.emplace_back(StringAttr::get(ctx, setKeys[i]),
                           StringAttr::get(ctx, name));
  }
  Value argument =
      function.front().addArgument(type, function.getLoc());
  bindingPositions[key] = bindings.size();
  bindings.push_back({DictionaryAttr::get(ctx, entries), argument});
  return argument;
}

Value FunctionLowering::getSetSize(StringAttr set) {
  return getBinding(BindingKind::SetSize, {set.getValue()},
                    b.getIndexType());
}

Value FunctionLowering::getField(StringAttr set, StringAttr field,
                                 Type fieldType) {
  SmallVector<int64_t> shape{ShapedType::kDynamic};
  llvm::append_range(shape, localShape(fieldType));
  return getBinding(BindingKind::Field, {set.getValue(), field.getValue()},
                    MemRefType::get(shape, getComponentType(fieldType)));
}

Value FunctionLowering::getEndpoints(SetType set) {
  return getEndpoints(set.getName(), set.getCardinality());
}

Value FunctionLowering::getEndpoints(StringAttr set, int64_t cardinality) {
  return getBinding(
      BindingKind::Endpoints, {set.getValue()},
      MemRefType::get({ShapedType::kDynamic, cardinality}, b.getI32Type()));
}

Value FunctionLowering::getPatternArray(BindingKind kind, StringAttr edges,
                                        StringAttr rows, StringAttr cols,
                                        int64_t cardinality) {
  Type type = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  if (kind == BindingKind::PatternLocations)
    type = MemRefType::get({ShapedType::kDynamic, cardinality * cardinality},
                           b.getI32Type());
  return getBinding(kind,
                    {edges.getValue(), rows.getValue(), cols.getValue()},
                    type);
}

/// Set names joined by '+', as union and product bindings name them.
static std::string joinSetNames(ArrayRef<StringAttr> sets) {
  std::string key;
  for (StringAttr set : sets)
    key += (key.empty() ? "" : "+") + set.getValue().str();
  return key;
}

/// A union binding's "set": the edge sets of a pattern or union storage.
static std::string unionKey(const Storage &storage) {
  return joinSetNames(storage.patternSets());
}

/// A product binding's "set": the factors' edge sets, '*'-separated.
static std::string productKey(const Storage &storage) {
  return joinSetNames(storage.members) + "*" +
         joinSetNames(storage.rightMembers);
}

Value FunctionLowering::rowPointers(const Storage &storage) {
  if (storage.kind == Storage::Kind::Product)
    return getBinding(BindingKind::ProductRowPtr,
                      {productKey(storage), storage.rows.getValue(),
                       storage.cols.getValue(), storage.mid.getValue()},
                      MemRefType::get({ShapedType::kDynamic}, b.getI32Type()));
  if (storage.kind == Storage::Kind::Union)
    return getBinding(BindingKind::UnionRowPtr,
                      {unionKey(storage), storage.rows.getValue(),
                       storage.cols.getValue()},
                      MemRefType::get({ShapedType::kDynamic}, b.getI32Type()));
  return getPatternArray(BindingKind::PatternRowPtr, storage.edges,
                         storage.rows, storage.cols);
}

Value FunctionLowering::columnIndices(const Storage &storage) {
  if (storage.kind == Storage::Kind::Product)
    return getBinding(BindingKind::ProductColIdx,
                      {productKey(storage), storage.rows.getValue(),
                       storage.cols.getValue(), storage.mid.getValue()},
                      MemRefType::get({ShapedType::kDynamic}, b.getI32Type()));
  if (storage.kind == Storage::Kind::Union)
    return getBinding(BindingKind::UnionColIdx,
                      {unionKey(storage), storage.rows.getValue(),
                       storage.cols.getValue()},
                      MemRefType::get({ShapedType::kDynamic}, b.getI32Type()));
  return getPatternArray(BindingKind::PatternColIdx, storage.edges,
                         storage.rows, storage.cols);
}

Value FunctionLowering::gatherMap(const Storage &storage, const Storage &part,
                                  bool transposed) {
  return getBinding(BindingKind::UnionGather,
                    {unionKey(storage), storage.rows.getValue(),
                     storage.cols.getValue(),
                     (transposed ? "~" : "") + unionKey(part)},
                    MemRefType::get({ShapedType::kDynamic}, b.getI32Type()));
}

Value FunctionLowering::emptyIndexArray() {
  // One stack slot at the function entry, so loops do not grow the stack.
  if (!noIndices) {
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(&function.front());
    Location loc = function.getLoc();
    noIndices = memref::CastOp::create(
        b, loc, MemRefType::get({ShapedType::kDynamic}, b.getI32Type()),
        memref::AllocaOp::create(b, loc,
                                 MemRefType::get({0}, b.getI32Type())));
  }
  return noIndices;
}

Value FunctionLowering::getExtern(ExternOp global) {
  Type type = global.getType();
  Type memref = isa<FloatType, IntegerType>(type)
                    ? MemRefType::get({}, type)
                    : MemRefType::get({numComponents(type)},
                                      getComponentType(type));
  return getBinding(BindingKind::Extern, {global.getSymName()}, memref);
}

//===----------------------------------------------------------------------===//
// Helpers
//===----------------------------------------------------------------------===//

Value FunctionLowering::indexConstant(int64_t value) {
  return arith::ConstantIndexOp::create(b, function.getLoc(), value);
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
  case Storage::Kind::Product: {
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
  return elementSets.lookup(original);
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
// Blocks and control flow
//===----------------------------------------------------------------------===//

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
  // Storage of loop-carried matrices must not change across iterations.
  for (auto [init, yielded, result, arg] :
       llvm::zip(op.getInitArgs(), op.getYieldedValues(), op.getResults(),
                 op.getRegionIterArgs()))
    if (storages.count(init)) {
      storages[arg] = storages[init];
      storages[result] = storages[init];
    }
  bool failedBody = false;
  auto loop = scf::ForOp::create(
      b, op.getLoc(), lookup(op.getLowerBound()), lookup(op.getUpperBound()),
      lookup(op.getStep()), inits,
      [&](OpBuilder &nb, Location loc, Value iv, ValueRange args) {
        OpBuilder::InsertionGuard guard(b);
        b.setInsertionPoint(nb.getInsertionBlock(), nb.getInsertionPoint());
        map(op.getInductionVar(), iv);
        unsigned next = 0;
        for (Value arg : op.getRegionIterArgs())
          if (!isSink(arg))
            map(arg, args[next++]);
        if (failed(lowerOps(*op.getBody()))) {
          failedBody = true;
          return;
        }
        scf::YieldOp::create(b, loc,
                             keptOperands(*this, op.getYieldedValues()));
      });
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
  // A matrix chosen by a branch keeps the sparsity both branches agree on.
  if (op.getNumResults() && !op.getElseRegion().empty())
    for (auto [result, x, y] :
         llvm::zip(op.getResults(), op.thenYield().getOperands(),
                   op.elseYield().getOperands()))
      if (storages.count(x) && storages.count(y)) {
        if (storages[x] != storages[y])
          return op.emitError("the branches yield matrices stored as ")
                 << storages[x].describe() << " and "
                 << storages[y].describe();
        storages[result] = storages[x];
      }
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
    if (storages.count(init))
      storages[arg] = storages[init];

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
    if (storages.count(arg))
      storages[result] = storages[arg];
  scf::ConditionOp::create(b, condition.getLoc(),
                           lookup(condition.getCondition()),
                           keptOperands(*this, condition.getArgs()));

  for (auto [from, to] :
       llvm::zip(op.getAfterArguments(), after->getArguments())) {
    map(from, to);
    if (storages.count(condition.getArgs()[to.getArgNumber()]))
      storages[from] = storages[condition.getArgs()[to.getArgNumber()]];
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

//===----------------------------------------------------------------------===//
// Host-level operations on system vectors
//===----------------------------------------------------------------------===//

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

LogicalResult FunctionLowering::lowerSystemOp(Operation *op, bool &handled) {
  handled = true;
  Location loc = op->getLoc();
  if (auto read = dyn_cast<FieldReadOp>(op)) {
    auto set = cast<SetType>(read.getSet().getType());
    Type fieldType = set.getElement().getFieldType(read.getField());
    Value array = getField(set.getName(), read.getFieldAttr(), fieldType);
    storages[read] = Storage::dense();
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
    if (cast<SystemTensorType>(type).getOrder() != 1)
      return op->emitError("a system matrix of unknown sparsity cannot be "
                           "created here; assemble it with a map");
    Value array = allocSystem(loc, type, Storage::dense(),
                               /*zeroFill=*/isa<ZerosOp>(op));
    if (auto broadcast = dyn_cast<BroadcastOp>(op))
      fill(loc, array, lookup(broadcast.getValue()));
    storages[op->getResult(0)] = Storage::dense();
    map(op->getResult(0), array);
    return success();
  }
  if (auto alloc = dyn_cast<AllocOp>(op)) {
    Type type = cast<RefType>(alloc.getType()).getValueType();
    // A matrix variable's storage is that of the first matrix stored to
    // it: its array is made there.
    if (cast<SystemTensorType>(type).getOrder() != 1)
      return success();
    map(alloc, allocSystem(loc, type, Storage::dense()));
    storages[alloc] = Storage::dense();
    return success();
  }
  if (auto load = dyn_cast<LoadOp>(op)) {
    Value buffer = lookup(load.getRef());
    if (!buffer)
      return op->emitError("a variable holding a system matrix is read "
                           "before a matrix is stored to it");
    storages[load] = storages.lookup(load.getRef());
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
    Storage storage = storages.lookup(store.getValue());
    if (!buffer) {
      // The first store to a matrix variable, which must be where the
      // variable is declared so that its array dominates every use.
      Operation *alloc = store.getRef().getDefiningOp();
      if (!alloc || alloc->getBlock() != op->getBlock())
        return op->emitError("a variable holding a system matrix must be "
                             "first assigned where it is declared");
      if (!storage.isMatrix())
        return op->emitError("a variable holding a system matrix must be "
                             "first assigned an assembled matrix");
      storages[store.getRef()] = storage;
      // A fresh matrix used only here becomes the variable's array.
      if (store.getValue().hasOneUse() &&
          isa_and_present<MapOp, AssembleOp, IndexExprOp>(
              store.getValue().getDefiningOp())) {
        map(store.getRef(), value);
        return success();
      }
      buffer = allocSystem(loc, store.getValue().getType(), storage,
                           /*zeroFill=*/false);
      map(store.getRef(), buffer);
    } else if (storage != storages.lookup(store.getRef())) {
      return op->emitError("a variable stored as ")
             << storages.lookup(store.getRef()).describe()
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
    storages[insert] = Storage::dense();
    map(insert, target);
    return success();
  }
  if (auto extract = dyn_cast<ExtractOp>(op)) {
    auto type = cast<SystemTensorType>(extract.getTensor().getType());
    if (type.getOrder() != 1)
      return lowerMatrixBlockAccess(op);
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
  if (isa<AddOp, SubOp, MulOp, DivOp, NegOp, ScaleOp, MatVecOp, MatMulOp,
          TransposeOp, DotOp, OuterOp, NormOp>(op))
    return op->emitError("linear algebra on system tensors must be rewritten "
                         "by simit-linalg-to-index-expr first");
  return op->emitError("'") << op->getName()
                            << "' on system tensors is not supported by the "
                               "loop lowering";
}

func::FuncOp FunctionLowering::declareRuntime(Location loc, StringRef name,
                                              FunctionType type) {
  auto callee = module.lookupSymbol<func::FuncOp>(name);
  if (callee)
    return callee.getFunctionType() == type ? callee : func::FuncOp();
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPointToEnd(module.getBody());
  callee = func::FuncOp::create(b, loc, name, type);
  callee.setPrivate();
  callee->setAttr("llvm.emit_c_interface", UnitAttr::get(b.getContext()));
  return callee;
}

Value FunctionLowering::asRuntimeBlocks(Location loc, Value array,
                                        MemRefType target) {
  // memref<?xf64> becomes memref<?x1xf64> or memref<?x1x1xf64>.
  auto type = cast<MemRefType>(array.getType());
  int64_t rank = target.getRank();
  if (type.getRank() == 1 && rank > 1) {
    SmallVector<int64_t> shape(rank, 1);
    shape[0] = ShapedType::kDynamic;
    SmallVector<OpFoldResult> sizes(rank, b.getIndexAttr(1));
    sizes[0] = memref::DimOp::create(b, loc, array, 0).getResult();
    ReassociationIndices all(rank);
    std::iota(all.begin(), all.end(), 0);
    array = memref::ExpandShapeOp::create(
        b, loc, MemRefType::get(shape, type.getElementType()), array,
        ArrayRef<ReassociationIndices>{all}, sizes);
  }
  return memref::CastOp::create(b, loc, target, array);
}

/// The runtime's conjugate gradient solvers (lib/Engine/RuntimeFunctions).
LogicalResult FunctionLowering::lowerSolve(SolveOp op) {
  Location loc = op.getLoc();
  Storage storage = storages.lookup(op.getMatrix());
  auto matrixType = cast<SystemTensorType>(op.getMatrix().getType());
  bool diagonal = storage.kind == Storage::Kind::Diagonal;
  if (!diagonal && (!storage.isBCSR() || storage.rows != storage.cols))
    return op.emitError("solves are supported for square matrices assembled "
                        "from a set; this matrix is stored as ")
           << storage.describe();
  SmallVector<int64_t> block = matrixType.getBlockShape();
  // Scalar blocks are 1x1 blocks to the runtime.
  if (block.empty())
    block = {1, 1};
  Type component = matrixType.getComponentType();
  if (!component.isF64() && !component.isF32())
    return op.emitError("the runtime solver takes f64 or f32 matrices");
  if (block.size() != 2 || block[0] != block[1])
    return op.emitError("the runtime solver takes matrices of scalars or of "
                        "square blocks");

  // func.func private @simit_rt_solve_{bcsr,diag}[_f32]([rowptr, colidx,]
  //     values, b, x, where), declared once. The runtime picks the method
  // and ends the run with `where` in its message when the solve fails.
  MLIRContext *ctx = b.getContext();
  int64_t dyn = ShapedType::kDynamic;
  Type indexArray = MemRefType::get({dyn}, b.getI32Type());
  auto values = MemRefType::get({dyn, dyn, dyn}, component);
  auto vector = MemRefType::get({dyn, dyn}, component);
  SmallVector<Type> argTypes;
  if (!diagonal)
    argTypes.append({indexArray, indexArray});
  argTypes.append({values, vector, vector, LLVM::LLVMPointerType::get(ctx)});
  std::string solver = diagonal ? "simit_rt_solve_diag" : "simit_rt_solve_bcsr";
  if (component.isF32())
    solver += "_f32";
  func::FuncOp callee =
      declareRuntime(loc, solver, FunctionType::get(ctx, argTypes, {}));
  if (!callee)
    return op.emitError("@") << solver << " is declared with another type";

  Value x = allocSystem(loc, op.getType(), Storage::dense(),
                        /*zeroFill=*/false);
  SmallVector<Value> args;
  if (!diagonal)
    args.append({rowPointers(storage), columnIndices(storage)});
  args.append({asRuntimeBlocks(loc, lookup(op.getMatrix()), values),
               asRuntimeBlocks(loc, lookup(op.getRhs()), vector),
               asRuntimeBlocks(loc, x, vector),
               stringConstant(loc, "solve" + sourcePositionSuffix(op))});
  func::CallOp::create(b, loc, callee, args);
  storages[op] = Storage::dense();
  map(op, x);
  return success();
}

/// The dense solver runtime functions, with the i64 size arguments their
/// lowered form appends (see lowerSolverCall).
static bool isSolverFunction(StringRef name) {
  return llvm::is_contained(
      {StringRef("simit_rt_lu"), StringRef("simit_rt_chol"),
       StringRef("simit_rt_lusolve"), StringRef("simit_rt_lltsolve"),
       StringRef("simit_rt_lumatsolve"), StringRef("simit_rt_lltmatsolve"),
       StringRef("simit_rt_lufree"), StringRef("simit_rt_cholfree"),
       StringRef("simit_rt_triangularSolve")},
      name);
}

LogicalResult FunctionLowering::lowerSystemSolverCall(func::CallOp call) {
  Location loc = call.getLoc();
  StringRef name = call.getCallee();
  bool factorise = name == "simit_rt_lu" || name == "simit_rt_chol";
  bool solve = name == "simit_rt_lusolve" || name == "simit_rt_lltsolve";
  Value matrix = factorise ? call.getOperand(0) : Value();
  Storage storage = matrix ? storages.lookup(matrix) : Storage();
  auto f64Blocks = [](Type t, unsigned order) {
    auto type = dyn_cast<SystemTensorType>(t);
    if (!type || !type.isSystem() || type.getOrder() != order ||
        !type.getComponentType().isF64())
      return false;
    SmallVector<int64_t> block = type.getBlockShape();
    return block.empty() || (order == 2 && block.size() == 2 &&
                             block[0] == block[1]) ||
           (order == 1 && block.size() == 1);
  };
  if (factorise && !(f64Blocks(matrix.getType(), 2) && storage.isBCSR() &&
                     storage.rows == storage.cols))
    return call.emitError("'@")
           << name
           << "' on a system matrix needs a square f64 matrix of scalars or "
              "square blocks assembled from an edge set; this one is stored "
              "as "
           << storage.describe();
  if (solve && !(call.getNumOperands() == 2 &&
                 isa<OpaqueType>(call.getOperand(0).getType()) &&
                 f64Blocks(call.getOperand(1).getType(), 1) &&
                 call.getNumResults() == 1 &&
                 call.getResult(0).getType() == call.getOperand(1).getType()))
    return call.emitError("'@") << name
                                << "' on system vectors needs an f64 vector "
                                   "and a factorisation handle";
  if (!factorise && !solve)
    return call.emitError("'@") << name
                                << "' is not supported on system tensors by "
                                   "the loop lowering";

  MLIRContext *ctx = b.getContext();
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  int64_t dyn = ShapedType::kDynamic;
  auto indexArray = MemRefType::get({dyn}, b.getI32Type());
  auto values = MemRefType::get({dyn, dyn, dyn}, b.getF64Type());
  auto vector = MemRefType::get({dyn, dyn}, b.getF64Type());
  std::string runtimeName = (name + "_bcsr").str();
  if (factorise) {
    auto type = FunctionType::get(ctx, {indexArray, indexArray, values}, {ptr});
    func::FuncOp callee = declareRuntime(loc, runtimeName, type);
    if (!callee)
      return call.emitError("@") << runtimeName
                                 << " is declared with another type";
    auto lowered = func::CallOp::create(
        b, loc, callee,
        ValueRange{rowPointers(storage), columnIndices(storage),
                   asRuntimeBlocks(loc, lookup(matrix), values)});
    map(call.getResult(0), lowered.getResult(0));
    return success();
  }
  auto type = FunctionType::get(ctx, {ptr, vector, vector}, {});
  func::FuncOp callee = declareRuntime(loc, runtimeName, type);
  if (!callee)
    return call.emitError("@") << runtimeName
                               << " is declared with another type";
  Value x = allocSystem(loc, call.getResult(0).getType(), Storage::dense(),
                        /*zeroFill=*/false);
  func::CallOp::create(
      b, loc, callee,
      ValueRange{lookup(call.getOperand(0)),
                 asRuntimeBlocks(loc, lookup(call.getOperand(1)), vector),
                 asRuntimeBlocks(loc, x, vector)});
  storages[call.getResult(0)] = Storage::dense();
  map(call.getResult(0), x);
  return success();
}

LogicalResult FunctionLowering::lowerSolverCall(func::CallOp call,
                                                func::FuncOp callee) {
  Location loc = call.getLoc();
  if (llvm::any_of(call.getOperandTypes(), isSystem))
    return lowerSystemSolverCall(call);
  MLIRContext *ctx = b.getContext();
  StringRef name = call.getCallee();
  Type f64 = b.getF64Type();
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  Type flat = MemRefType::get({ShapedType::kDynamic}, f64);
  bool factorise = name == "simit_rt_lu" || name == "simit_rt_chol";
  bool free = name == "simit_rt_lufree" || name == "simit_rt_cholfree";
  bool matSolve =
      name == "simit_rt_lumatsolve" || name == "simit_rt_lltmatsolve";
  bool triangular = name == "simit_rt_triangularSolve";

  // Expected shapes: (handle | matrix)..., tensors of f64.
  auto tensorOf = [&](Type t, unsigned rank) -> RankedTensorType {
    auto tensor = dyn_cast<RankedTensorType>(t);
    if (!tensor || !tensor.getElementType().isF64() ||
        tensor.getRank() != rank || !tensor.hasStaticShape())
      return nullptr;
    return tensor;
  };
  auto isHandle = [](Type t) { return isa<OpaqueType>(t); };
  auto isSquare = [&](Type t) {
    auto m = tensorOf(t, 2);
    return m && m.getDimSize(0) == m.getDimSize(1);
  };
  TypeRange in = call.getOperandTypes(), out = call.getResultTypes();
  bool valid = false;
  if (factorise)
    valid = in.size() == 1 && isSquare(in[0]) && out.size() == 1 &&
            isHandle(out[0]);
  else if (free)
    valid = in.size() == 1 && isHandle(in[0]) && out.empty();
  else if (triangular)
    valid = in.size() == 2 && isSquare(in[0]) && tensorOf(in[1], 1) &&
            out.size() == 1 && out[0] == in[1] &&
            tensorOf(in[1], 1).getDimSize(0) ==
                cast<RankedTensorType>(in[0]).getDimSize(0);
  else
    valid = in.size() == 2 && isHandle(in[0]) &&
            tensorOf(in[1], matSolve ? 2 : 1) && out.size() == 1 &&
            out[0] == in[1];
  if (!valid)
    return call.emitError("'@")
           << name
           << "' is supported by the loop lowering on dense local f64 "
              "matrices and vectors (and opaque handles) only";

  // Local tensors (vectors) are stored to a stack buffer passed as
  // memref<?xf64>; tensor results come back through one.
  auto buffer = [&](int64_t size) {
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(allocaBlock);
    return memref::AllocaOp::create(b, loc, MemRefType::get({size}, f64))
        .getResult();
  };
  Value zero = free ? Value() : indexConstant(0);
  SmallVector<Value> args;
  SmallVector<Type> argTypes;
  for (Value operand : call.getOperands()) {
    Value value = lookup(operand);
    if (isHandle(operand.getType())) {
      args.push_back(value);
      argTypes.push_back(ptr);
      continue;
    }
    int64_t size = cast<RankedTensorType>(operand.getType()).getNumElements();
    Value slot = buffer(size);
    vector::StoreOp::create(b, loc, value, slot, ValueRange{zero});
    args.push_back(memref::CastOp::create(b, loc, flat, slot));
    argTypes.push_back(flat);
  }
  Value resultSlot;
  SmallVector<Type> resultTypes;
  if (factorise) {
    resultTypes.push_back(ptr);
  } else if (!free) {
    auto resultType = cast<RankedTensorType>(out[0]);
    resultSlot = buffer(resultType.getNumElements());
    args.push_back(memref::CastOp::create(b, loc, flat, resultSlot));
    argTypes.push_back(flat);
  }
  // Sizes: n of a factorised or triangular matrix, the columns of a
  // matrix right-hand side.
  auto sizeArg = [&](int64_t size) {
    args.push_back(arith::ConstantOp::create(b, loc, b.getI64IntegerAttr(size)));
    argTypes.push_back(b.getI64Type());
  };
  if (factorise || triangular)
    sizeArg(cast<RankedTensorType>(in[0]).getDimSize(0));
  else if (matSolve)
    sizeArg(cast<RankedTensorType>(in[1]).getDimSize(1));

  // The declaration takes the lowered signature (the JIT binds the
  // C interface, _mlir_ciface_<name>, of those with memrefs).
  auto type = FunctionType::get(ctx, argTypes, resultTypes);
  if (callee.getFunctionType() != type) {
    if (llvm::any_of(callee.getFunctionType().getInputs(),
                     [](Type t) { return isa<MemRefType, LLVM::LLVMPointerType>(t); }))
      return call.emitError("'@") << name
                                  << "' is called with different shapes";
    callee.setFunctionType(type);
  }
  if (!free)
    callee->setAttr("llvm.emit_c_interface", UnitAttr::get(ctx));
  auto lowered = func::CallOp::create(b, loc, name, resultTypes, args);
  if (factorise)
    map(call.getResult(0), lowered.getResult(0));
  else if (!free)
    map(call.getResult(0),
        vector::LoadOp::create(b, loc, cast<VectorType>(convertType(out[0])),
                               resultSlot, ValueRange{zero}));
  return success();
}

//===----------------------------------------------------------------------===//
// Operations
//===----------------------------------------------------------------------===//

LogicalResult FunctionLowering::lowerFunctionReturn(func::ReturnOp op) {
  SmallVector<Value> results;
  for (auto [operand, type] : llvm::zip_equal(op.getOperands(), resultTypes)) {
    if (storages.lookup(operand).isMatrix())
      return op.emitError("exported functions cannot return system matrices");
    Value result = lookup(operand);
    if (result.getType() != type)
      result = vector::ShapeCastOp::create(b, op.getLoc(), type, result);
    results.push_back(result);
  }
  func::ReturnOp::create(b, op.getLoc(), results);
  return success();
}

/// Whether `type` is a system tensor of complex components, or a variable
/// of one (set-sized arrays of complex numbers are not lowered yet).
static bool isComplexSystem(Type type) {
  if (auto ref = dyn_cast<RefType>(type))
    type = ref.getValueType();
  return isSystem(type) && isa<ComplexType>(getComponentType(type));
}

LogicalResult FunctionLowering::lowerOp(Operation *op) {
  auto complexSystem = [](Value v) { return isComplexSystem(v.getType()); };
  if (llvm::any_of(op->getResults(), complexSystem) ||
      llvm::any_of(op->getOperands(), complexSystem))
    return op->emitError("complex system tensors are not supported by the "
                         "loop lowering yet");
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
    // Runtime functions on scalars only (lib/Engine/RuntimeFunctions.cpp)
    // stay calls of their private declarations.
    auto isScalar = [](Type t) { return isa<FloatType, IntegerType>(t); };
    if (callee && callee.isExternal() &&
        callee->hasAttr("simit.runtime_function") &&
        llvm::is_contained({StringRef("simit_rt_clock"),
                            StringRef("simit_rt_storeTime"),
                            StringRef("simit_rt_phase_begin"),
                            StringRef("simit_rt_phase_end")},
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
        callee->hasAttr("simit.runtime_function") &&
        isSolverFunction(call.getCallee()))
      return lowerSolverCall(call, callee);
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
    if (isSystem(global.getType()))
      return op->emitError("extern system tensors are not supported by the "
                           "loop lowering");
    if (isa<ComplexType>(getComponentType(global.getType())))
      return op->emitError("complex externs are not supported by the loop "
                           "lowering yet");
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
  if (isa<GridPointOp, GridEdgeOp>(op))
    return lowerGridAccess(op);
  if (isa<PrintOp, StringConstantOp, StringConcatOp, StringCmpOp>(op))
    return lowerPrintOrString(op);

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
// Printing and strings
//===----------------------------------------------------------------------===//

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
  // One internal constant global per distinct text: simit_str_<hash>.
  MLIRContext *ctx = b.getContext();
  std::string name = "simit_str_" + llvm::utohexstr(llvm::xxh3_64bits(text));
  auto global = module.lookupSymbol<LLVM::GlobalOp>(name);
  if (!global) {
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(module.getBody());
    std::string data = text.str();
    data.push_back('\0');
    auto arrayType =
        LLVM::LLVMArrayType::get(IntegerType::get(ctx, 8), data.size());
    global = LLVM::GlobalOp::create(b, loc, arrayType, /*isConstant=*/true,
                                    LLVM::Linkage::Internal, name,
                                    b.getStringAttr(data));
  }
  return LLVM::AddressOfOp::create(b, loc, LLVM::LLVMPointerType::get(ctx),
                                   global.getSymName());
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
    map(concat, callRuntime(loc, "simit_rt_string_concat", {ptrType},
                            {lookup(concat.getLhs()), lookup(concat.getRhs())}));
    return success();
  }
  if (auto cmp = dyn_cast<StringCmpOp>(op)) {
    Value order =
        callRuntime(loc, "simit_rt_string_compare", {b.getI32Type()},
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
    callRuntime(loc, "simit_rt_print_str", {}, {stringConstant(text)});
  };
  auto printFloat = [&](Value scalar) -> LogicalResult {
    auto floatType = cast<FloatType>(scalar.getType());
    if (floatType.getWidth() < 64)
      scalar = arith::ExtFOp::create(b, loc, b.getF64Type(), scalar);
    else if (floatType.getWidth() > 64)
      return op->emitError("cannot print floats wider than 64 bits");
    callRuntime(loc, "simit_rt_print_f64", {}, {scalar});
    return success();
  };
  auto printScalar = [&](Value scalar) -> LogicalResult {
    Type type = scalar.getType();
    if (isa<LLVM::LLVMPointerType>(type)) {
      callRuntime(loc, "simit_rt_print_str", {}, {scalar});
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
      callRuntime(loc, "simit_rt_print_i64", {}, {scalar});
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
    if (auto system = dyn_cast<SystemTensorType>(type);
        system && system.isSystem()) {
      if (system.getOrder() != 1)
        return op->emitError("printing system matrices is not supported by "
                             "the loop lowering yet");
      // A system vector: its elements in set order, separated by spaces
      // when they are scalars, one element's block per line otherwise
      // (the block's components separated by spaces).
      Value array = lookup(value);
      auto memref = cast<MemRefType>(array.getType());
      int64_t blockSize = numComponents(system.getBlockType());
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
              callRuntime(loc, "simit_rt_print_str", {},
                          {stringConstant(blockSize == 1 ? " " : "\n")});
              scf::YieldOp::create(b, loc);
            });
            for (int64_t c = 0; c < blockSize; ++c) {
              if (c > 0)
                callRuntime(loc, "simit_rt_print_str", {},
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
  Block *entry = function.addEntryBlock();
  allocaBlock = entry;
  SmallVector<Attribute> bindingAttrs;
  b.setInsertionPointToEnd(entry);
  for (auto [i, arg] : llvm::enumerate(original.getArguments())) {
    Type type = convertType(arg.getType());
    if (isComplexSystem(arg.getType()))
      return original.emitError("exported function parameter ")
             << i << " of type " << arg.getType()
             << " cannot be lowered: complex system tensors are not supported "
                "by the loop lowering yet";
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
    if (isSystem(arg.getType()))
      storages[arg] = Storage::dense();
    bindingAttrs.push_back(DictionaryAttr::get(
        ctx, {NamedAttribute(StringAttr::get(ctx, "kind"),
                             StringAttr::get(ctx, "param")),
              NamedAttribute(StringAttr::get(ctx, "index"),
                             b.getI64IntegerAttr(i))}));
  }
  for (Type type : original.getResultTypes()) {
    Type lowered = convertType(type);
    if (!lowered)
      return original.emitError("exported function result of type ")
             << type << " cannot be lowered";
    resultTypes.push_back(hostType(type, lowered));
  }
  if (failed(lowerOps(original.front())))
    return failure();

  // Bindings in canonical order: by kind, then by the names they carry.
  SmallVector<unsigned> order(bindings.size());
  std::iota(order.begin(), order.end(), 0);
  auto sortKey = [&](unsigned i) {
    DictionaryAttr dict = bindings[i].first;
    static const char *const kinds[] = {
        "set_size",       "grid_dims",      "endpoints",
        "field",          "pattern_rowptr", "pattern_colidx",
        "pattern_locations", "extern"};
    StringRef kind = dict.getAs<StringAttr>("kind").getValue();
    unsigned rank = llvm::find(kinds, kind) - std::begin(kinds);
    auto text = [&](StringRef key) {
      auto value = dict.getAs<StringAttr>(key);
      return value ? value.getValue().str() : std::string();
    };
    bool isPattern = kind.starts_with("pattern_");
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
  function->setAttr("simit.bindings", ArrayAttr::get(ctx, bindingAttrs));
  function->setAttr("llvm.emit_c_interface", UnitAttr::get(ctx));
  return success();
}

namespace {
struct ConvertSimitToLoops
    : public simit::impl::ConvertSimitToLoopsBase<ConvertSimitToLoops> {
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

    bool failedAny = false;
    for (func::FuncOp original : exported) {
      OpBuilder builder(original);
      auto lowered = func::FuncOp::create(
          builder, original.getLoc(),
          (original.getSymName() + ".lowered").str(),
          builder.getFunctionType({}, {}));
      FunctionLowering lowering(module, lowered);
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
    SmallVector<Operation *> dead;
    for (Operation &op : module.getOps()) {
      auto function = dyn_cast<func::FuncOp>(op);
      bool unusedRuntime =
          function && function.isExternal() &&
          function->hasAttr("simit.runtime_function") &&
          SymbolTable::symbolKnownUseEmpty(function, module);
      if ((function && !function.isExternal() && usesSimitDialect(function)) ||
          unusedRuntime || isa<ExternOp>(op))
        dead.push_back(&op);
    }
    for (Operation *op : dead)
      op->erase();
  }
};
} // namespace
