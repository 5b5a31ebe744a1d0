//===- LoopBindings.cpp - Arguments of lowered functions ------------------===//
//
// The data a lowered function touches becomes its arguments as the lowering
// first needs it: one `simit.bindings` entry per argument (docs/lowering.md,
// "Host ABI of an entry point").
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

static StringRef bindingKindName(BindingKind kind) {
  std::string_view name = ::simit::abi::spelling(kind);
  return StringRef(name.data(), name.size());
}

Value FunctionLowering::getBinding(
    BindingKind kind, ArrayRef<StringRef> names, Type type,
    std::optional<ArrayRef<int64_t>> declaredShape) {
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
    // A vector over a set names the set its size comes from.
    if (names.size() > 1)
      entries.emplace_back(StringAttr::get(ctx, "set"),
                           StringAttr::get(ctx, names[1]));
    if (declaredShape)
      entries.emplace_back(StringAttr::get(ctx, "shape"),
                           DenseI64ArrayAttr::get(ctx, *declaredShape));
    break;
  case BindingKind::Field:
  case BindingKind::StencilRowPtr:
  case BindingKind::StencilColIdx:
  case BindingKind::StencilPositions:
    // A set and what of it: a field's name, a stencil's offsets.
    entries.emplace_back(StringAttr::get(ctx, "set"),
                         StringAttr::get(ctx, names[0]));
    entries.emplace_back(
        StringAttr::get(ctx, kind == BindingKind::Field ? "field" : "offsets"),
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
  llvm::append_range(shape, getLocalShape(fieldType));
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

Value FunctionLowering::incidenceEndpoints(const Storage &storage) {
  if (storage.positions.empty())
    return getEndpoints(storage.edges, storage.cardinality);
  // Some positions only: the runtime selects them by their endpoint set.
  StringAttr endpoints = storage.transposed ? storage.rows : storage.cols;
  return getBinding(BindingKind::IncidenceEndpoints,
                    {storage.edges.getValue(), storage.edges.getValue(),
                     endpoints.getValue()},
                    MemRefType::get({ShapedType::kDynamic, storage.cardinality},
                                    b.getI32Type()));
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

/// A product binding's "set": each chain's factors' edge sets,
/// '*'-separated, chains '|'-separated.
static std::string productKey(const Storage &storage) {
  std::string key;
  for (const ProductChain &chain : storage.chains) {
    if (&chain != &storage.chains.front())
      key += "|";
    for (const SmallVector<StringAttr, 2> &factor : chain.factors)
      key +=
          (&factor == &chain.factors.front() ? "" : "*") + joinSetNames(factor);
  }
  return key;
}

/// A product binding's "mid": each chain's sets between factors,
/// ','-separated, chains '|'-separated.
static std::string productMids(const Storage &storage) {
  std::string mids;
  for (const ProductChain &chain : storage.chains) {
    if (&chain != &storage.chains.front())
      mids += "|";
    for (auto [i, mid] : llvm::enumerate(chain.mids))
      mids += (i ? "," : "") + mid.getValue().str();
  }
  return mids;
}

std::pair<Value, Value>
FunctionLowering::runtimePattern(const Storage &storage) {
  if (std::optional<std::pair<Value, Value>> built =
          builtRuntimePattern(storage))
    return *built;
  buildRuntimePattern(function.getLoc(), storage);
  return runtimePatterns.lookup(storage.runtimeEncoding);
}

std::optional<std::pair<Value, Value>>
FunctionLowering::builtRuntimePattern(const Storage &storage) {
  auto it = runtimePatterns.find(storage.runtimeEncoding);
  if (it == runtimePatterns.end())
    return std::nullopt;
  // Arrays built in a block that does not hold the code being lowered (a
  // sibling branch, an earlier loop's body) are out of reach there. A
  // block not attached yet is the body of an op being built here.
  Block *defined = it->second.first.getParentBlock();
  for (Block *block = b.getInsertionBlock(); block != defined;) {
    Operation *parent = block->getParentOp();
    if (!parent)
      return it->second;
    block = parent->getBlock();
    if (!block)
      return std::nullopt;
  }
  return it->second;
}

Value FunctionLowering::rowPointers(const Storage &storage) {
  if (storage.kind == Storage::Kind::Host)
    return runtimePattern(storage).first;
  if (storage.kind == Storage::Kind::Product)
    return getBinding(BindingKind::ProductRowPtr,
                      {productKey(storage), storage.rows.getValue(),
                       storage.cols.getValue(), productMids(storage)},
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
  if (storage.kind == Storage::Kind::Host)
    return runtimePattern(storage).second;
  if (storage.kind == Storage::Kind::Product)
    return getBinding(BindingKind::ProductColIdx,
                      {productKey(storage), storage.rows.getValue(),
                       storage.cols.getValue(), productMids(storage)},
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

std::array<Value, 3> FunctionLowering::incidenceRows(const Storage &storage) {
  Type type = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  auto array = [&](BindingKind kind) {
    return getBinding(kind,
                      {storage.edges.getValue(), storage.rows.getValue(),
                       storage.cols.getValue()},
                      type);
  };
  return {array(BindingKind::IncidenceRowPtr),
          array(BindingKind::IncidenceColIdx),
          array(BindingKind::IncidencePositions)};
}

std::array<Value, 3> FunctionLowering::stencilPattern(const Storage &storage) {
  // "-1,0;0,0;1,0": the offsets as the runtime's StencilPattern reads them.
  std::string offsets;
  for (Attribute offset : storage.offsets) {
    offsets += offsets.empty() ? "" : ";";
    for (auto [i, v] :
         llvm::enumerate(cast<DenseI64ArrayAttr>(offset).asArrayRef()))
      offsets += (i ? "," : "") + std::to_string(v);
  }
  Type indexArray = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  auto binding = [&](BindingKind kind) {
    return getBinding(kind, {storage.edges.getValue(), offsets}, indexArray);
  };
  return {binding(BindingKind::StencilRowPtr),
          binding(BindingKind::StencilColIdx),
          binding(BindingKind::StencilPositions)};
}

std::array<Value, 3> FunctionLowering::stencilAsBCSR(Location loc,
                                                     const Storage &storage,
                                                     Value array) {
  auto [rowPtr, colIdx, positions] = stencilPattern(storage);
  // The blocks added at their BCSR positions (offsets naming one point
  // share one).
  auto type = cast<MemRefType>(array.getType());
  Value count = arith::IndexCastOp::create(
      b, loc, b.getIndexType(),
      memref::LoadOp::create(b, loc, rowPtr,
                             ValueRange{getSetSize(storage.rows)}));
  Value values = memref::AllocOp::create(b, loc, type, ValueRange{count});
  fill(loc, values, zeroOf(type.getElementType()));
  int64_t components = 1;
  for (int64_t dim : type.getShape().drop_front())
    components *= dim;
  forLoop(loc, memref::DimOp::create(b, loc, array, 0), [&](Value block) {
    Value at = arith::IndexCastOp::create(
        b, loc, b.getIndexType(),
        memref::LoadOp::create(b, loc, positions, ValueRange{block}));
    for (int64_t c = 0; c < components; ++c) {
      SmallVector<Value> to = blockIndices(type, {at}, c);
      Value sum =
          addNumbers(b, loc, memref::LoadOp::create(b, loc, values, to),
                     memref::LoadOp::create(b, loc, array,
                                            blockIndices(type, {block}, c)));
      memref::StoreOp::create(b, loc, sum, values, to);
    }
  });
  return {rowPtr, colIdx, values};
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
  // A vector over a set: one block per element of its set, as a field.
  if (auto system = dyn_cast<SystemTensorType>(type); system && isSystem(type))
    return getBinding(
        BindingKind::Extern,
        {global.getSymName(), cast<StringAttr>(system.getDims()[0]).getValue()},
        convertType(type));
  // Stored as a variable of its type is: complex tensors as their parts.
  auto memref =
      cast<MemRefType>(convertType(RefType::get(type.getContext(), type)));
  // Scalars and unblocked local tensors: the host checks the shape it binds
  // (a 3x2 array is no matrix[2,3], though it has as many numbers); complex
  // components are (re, im) pairs.
  std::optional<SmallVector<int64_t>> declared;
  if (isa<FloatType, IntegerType, ComplexType>(type))
    declared.emplace();
  else if (auto tensor = dyn_cast<RankedTensorType>(type))
    declared.emplace(tensor.getShape());
  if (declared && isa<ComplexType>(getComponentType(type)))
    declared->push_back(2);
  return getBinding(BindingKind::Extern, {global.getSymName()}, memref,
                    declared ? std::optional<ArrayRef<int64_t>>(*declared)
                             : std::nullopt);
}
