//===- LowerMaps.cpp - map and assemble as loops over sets ----------------===//
//
// A map becomes an scf.parallel loop over the set's elements whose body is
// the element function, lowered in place: the element is the loop index, an
// endpoint is read from the edge set's endpoint array, fields are loads and
// stores of field arrays. The element function's results are never built:
// every simit.insert into a value that flows to result r scatters into the
// output array of r, at the location the sparsity gives (the element itself,
// a diagonal block, the block an edge's location table names, or a grid
// point's block for a stencil offset, LowerGridStencils.cpp).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

#include "mlir/Dialect/Utils/IndexingUtils.h"
#include "mlir/Dialect/Utils/StaticValueUtils.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

/// Whether a map result of `type` is accumulated in one slot: a scalar, or
/// a local tensor (a result whose dimensions are ranges, language.md 8.3),
/// one slot component per tensor component.
static bool isSlotResult(Type type) {
  auto tensor = dyn_cast<RankedTensorType>(type);
  return isa<FloatType, IntegerType, ComplexType>(type) ||
         (tensor && tensor.hasStaticShape() &&
          isa<FloatType, IntegerType, ComplexType>(tensor.getElementType()));
}

/// Finds the values of `callee` that stand for its results: everything a
/// returned value is built from by inserts, loop-carried values, branches
/// and variables; a scalar or local tensor result must be the value of a
/// variable (the frontend's result variable), which goes to `scalarSlots`.
static LogicalResult collectSinks(func::FuncOp callee,
                                  DenseMap<Value, unsigned> &sinks,
                                  DenseMap<Value, unsigned> &scalarSlots) {
  auto ret = cast<func::ReturnOp>(callee.front().getTerminator());
  SmallVector<std::pair<Value, unsigned>> work;
  for (auto [i, v] : llvm::enumerate(ret.getOperands())) {
    if (!isSlotResult(v.getType())) {
      work.push_back({v, i});
      continue;
    }
    auto load = v.getDefiningOp<LoadOp>();
    if (!load || !load.getRef().getDefiningOp<AllocOp>())
      return ret.emitError("result ")
             << i << " of element function '" << callee.getSymName()
             << "' must be the value of a variable";
    scalarSlots[load.getRef()] = i;
  }
  while (!work.empty()) {
    auto [v, r] = work.pop_back_val();
    auto [it, inserted] = sinks.try_emplace(v, r);
    if (!inserted) {
      if (it->second != r)
        return callee.emitError("one value flows into results ")
               << it->second << " and " << r << " of an element function";
      continue;
    }
    if (auto arg = dyn_cast<BlockArgument>(v)) {
      auto loop = dyn_cast<scf::ForOp>(arg.getOwner()->getParentOp());
      if (!loop || arg == loop.getInductionVar())
        return callee.emitError("a result of element function '")
               << callee.getSymName()
               << "' comes from a parameter or an unsupported loop";
      unsigned i = arg.getArgNumber() - 1;
      work.push_back({loop.getInitArgs()[i], r});
      work.push_back({loop.getYieldedValues()[i], r});
      work.push_back({loop.getResult(i), r});
      continue;
    }
    Operation *def = v.getDefiningOp();
    if (auto insert = dyn_cast<InsertOp>(def)) {
      work.push_back({insert.getTensor(), r});
    } else if (isa<ZerosOp>(def)) {
    } else if (auto load = dyn_cast<LoadOp>(def)) {
      work.push_back({load.getRef(), r});
    } else if (isa<AllocOp>(def)) {
      for (Operation *user : v.getUsers()) {
        if (auto store = dyn_cast<StoreOp>(user))
          work.push_back({store.getValue(), r});
        else if (auto load = dyn_cast<LoadOp>(user))
          work.push_back({load.getResult(), r});
      }
    } else if (auto loop = dyn_cast<scf::ForOp>(def)) {
      unsigned i = cast<OpResult>(v).getResultNumber();
      work.push_back({loop.getInitArgs()[i], r});
      work.push_back({loop.getYieldedValues()[i], r});
      work.push_back({loop.getRegionIterArgs()[i], r});
    } else if (auto branch = dyn_cast<scf::IfOp>(def)) {
      unsigned i = cast<OpResult>(v).getResultNumber();
      work.push_back({branch.thenYield().getOperand(i), r});
      if (!branch.getElseRegion().empty())
        work.push_back({branch.elseYield().getOperand(i), r});
    } else {
      return def->emitError("the loop lowering cannot trace this value to "
                            "the writes of a map result");
    }
  }
  return success();
}

/// Combines an old and a new component with the reduction.
static Value combine(OpBuilder &b, Location loc, ReductionKind kind, Value old,
                     Value value) {
  bool isFloat = isa<FloatType>(getElementTypeOrSelf(value.getType()));
  switch (kind) {
  case ReductionKind::Add:
    return addNumbers(b, loc, old, value);
  case ReductionKind::Mul:
    return multiplyNumbers(b, loc, old, value);
  case ReductionKind::Min:
    return isFloat ? arith::MinimumFOp::create(b, loc, old, value).getResult()
                   : arith::MinSIOp::create(b, loc, old, value).getResult();
  case ReductionKind::Max:
    return isFloat ? arith::MaximumFOp::create(b, loc, old, value).getResult()
                   : arith::MaxSIOp::create(b, loc, old, value).getResult();
  }
  llvm_unreachable("reduction kind");
}

namespace {
/// One write of a component write chain: `write` puts its value at `path`
/// (indices below the result's block position, through nested blocks),
/// one scalar or one whole block of builtin shape.
struct ComponentWrite {
  InsertOp write;
  SmallVector<Value> path;
};

/// The component writes of `K(i, j)(a, b) = v` (or `f(i)(a) = v`,
/// `W(t)(1)(2) = v`), which arrive as insert(insert(v, extract(K, i, j), a,
/// b), K, i, j), nested once per block level: the writes, outermost
/// first, the block read they start from and every op of the chain.
struct ComponentWrites {
  SmallVector<ComponentWrite> writes;
  ExtractOp base;
  llvm::SmallPtrSet<Operation *, 8> ops;
};
} // namespace

/// The root of a chain of inserts ending in `block`.
static Value insertRoot(Value block) {
  while (auto inner = block.getDefiningOp<InsertOp>())
    block = inner.getTensor();
  return block;
}

/// Adds the writes that turn `base` into `block` below `path`; false when
/// `block` is not built from `base` by inserts.
static bool collectWrites(Value block, Value base, ArrayRef<Value> path,
                          ComponentWrites &tree) {
  SmallVector<InsertOp> chain;
  while (auto inner = block.getDefiningOp<InsertOp>()) {
    chain.push_back(inner);
    tree.ops.insert(inner);
    block = inner.getTensor();
  }
  if (block != base)
    return false;
  for (InsertOp write : chain) {
    SmallVector<Value> at(path);
    llvm::append_range(at, write.getIndices());
    // A sub-block rebuilt from its own read of this block: a write one
    // block level deeper.
    Value root = insertRoot(write.getValue());
    auto sub = root.getDefiningOp<ExtractOp>();
    if (root != write.getValue() && sub && sub.getTensor() == base &&
        sub.getIndices() == write.getIndices()) {
      tree.ops.insert(sub);
      if (!collectWrites(write.getValue(), sub.getResult(), at, tree))
        return false;
      continue;
    }
    tree.writes.push_back({write, std::move(at)});
  }
  return true;
}

/// The component writes of `insert`; none when it writes a whole block.
static std::optional<ComponentWrites> componentWrites(InsertOp insert) {
  Value root = insertRoot(insert.getValue());
  auto read = root.getDefiningOp<ExtractOp>();
  if (root == insert.getValue() || !read ||
      read.getTensor() != insert.getTensor() ||
      read.getIndices() != insert.getIndices())
    return std::nullopt;
  ComponentWrites tree;
  tree.base = read;
  tree.ops.insert(read);
  if (!collectWrites(insert.getValue(), read.getResult(), {}, tree))
    return std::nullopt;
  return tree;
}

/// Whether `read` reads a block of a map result only to have components
/// written into it and the block written back (componentWrites): no other
/// use sees its value or a value of the chain.
static bool feedsComponentWrites(ExtractOp read) {
  for (Operation *user : read.getTensor().getUsers()) {
    auto insert = dyn_cast<InsertOp>(user);
    if (!insert || insert.getTensor() != read.getTensor())
      continue;
    std::optional<ComponentWrites> tree = componentWrites(insert);
    if (!tree || tree->base != read)
      continue;
    return llvm::all_of(tree->ops, [&](Operation *op) {
      return llvm::all_of(op->getUsers(), [&](Operation *use) {
        return use == insert.getOperation() || tree->ops.contains(use);
      });
    });
  }
  return false;
}

/// The memref indices of the block at `indices` of map result `r` in its
/// output array: where `write` (an insert into the result slot) combines
/// its block, recording the pattern blocks it accumulates into for the
/// prefetch, or, without `write`, where `op` reads the accumulator.
/// `shared`: other elements may write the block too.
static FailureOr<SmallVector<Value>> resultBlock(FunctionLowering &l,
                                                 Operation *op,
                                                 ValueRange indices, unsigned r,
                                                 InsertOp write, bool &shared) {
  ElementContext &ctx = *l.element;
  OpBuilder &b = l.b;
  Location loc = op->getLoc();
  const Storage &storage = ctx.outputStorages[r];
  SmallVector<Value> prefix;
  switch (storage.kind) {
  case Storage::Kind::Dense:
    for (Value index : indices)
      prefix.push_back(l.lookup(index));
    if (prefix.front() != ctx.element)
      shared = true;
    break;
  case Storage::Kind::Diagonal: {
    Value row = l.lookup(indices[0]);
    if (row != l.lookup(indices[1]))
      return op->emitError("a map over a vertex set can only write the "
                           "diagonal block of its element");
    prefix.push_back(row);
    break;
  }
  case Storage::Kind::Pattern: {
    Value i = l.endpointPositions.lookup(indices[0]);
    Value j = l.endpointPositions.lookup(indices[1]);
    if (!i || !j)
      return op->emitError("a matrix assembled from an edge set can only "
                           "be written at pairs of the edge's endpoints");
    int64_t c = ctx.set.getCardinality();
    Value locations =
        l.getPatternArray(BindingKind::PatternLocations, storage.edges,
                          storage.rows, storage.cols, c);
    Value flat = arith::AddIOp::create(
        b, loc, arith::MulIOp::create(b, loc, i, l.indexConstant(c)), j);
    Value block =
        memref::LoadOp::create(b, loc, locations, ValueRange{ctx.element, flat});
    prefix.push_back(
        arith::IndexCastOp::create(b, loc, b.getIndexType(), block));
    shared = true;
    if (write && ctx.accumulate) {
      auto &written = ctx.patternAccumulations[r];
      std::optional<int64_t> ci = getConstantIntValue(i);
      std::optional<int64_t> cj = getConstantIntValue(j);
      for (int64_t k = 0; k < c * c; ++k)
        if (!ci || !cj || k == *ci * c + *cj)
          written.insert(k);
    }
    break;
  }
  case Storage::Kind::Stencil: {
    // Each point writes and reads its own row: no location is shared.
    FailureOr<Value> block = l.stencilBlockAt(op, indices, storage);
    if (failed(block))
      return failure();
    prefix.push_back(*block);
    break;
  }
  case Storage::Kind::Incidence: {
    // (the edge, its endpoint k), or (endpoint k, the edge) when
    // transposed: block e * c + k, written by this edge only.
    Value edge = indices[storage.transposed ? 1 : 0];
    Value k = l.endpointPositions.lookup(indices[storage.transposed ? 0 : 1]);
    if (l.lookup(edge) != ctx.element || !k)
      return op->emitError("a matrix over (edges, endpoints) or "
                           "(endpoints, edges) can only be written at "
                           "the edge and one of its endpoints");
    // Of some positions only (a heterogeneous edge set), block j holds the
    // j-th of them; the endpoint's set type makes k one of them.
    if (!storage.positions.empty()) {
      std::optional<int64_t> position = getConstantIntValue(k);
      const int64_t *at =
          position ? llvm::find(storage.positions, *position) : nullptr;
      if (!position || at == storage.positions.end())
        return op->emitError("cannot tell which endpoint position of '")
               << storage.edges.getValue() << "' this block is written at";
      k = l.indexConstant(at - storage.positions.begin());
    }
    prefix.push_back(arith::AddIOp::create(
        b, loc,
        arith::MulIOp::create(b, loc, ctx.element,
                              l.indexConstant(storage.cardinality)),
        k));
    break;
  }
  case Storage::Kind::Union:
  case Storage::Kind::DenseMatrix:
  case Storage::Kind::Host:
    return op->emitError("a map result cannot be stored as ")
           << storage.describe();
  }
  return prefix;
}

/// Lowers an insert into result slot `r` of the element function: the
/// block is combined into (or stored to) its place in the output.
static LogicalResult scatter(FunctionLowering &l, InsertOp insert, unsigned r,
                             bool &scatters) {
  ElementContext &ctx = *l.element;
  OpBuilder &b = l.b;
  Location loc = insert.getLoc();
  Value output = ctx.outputs[r];
  FailureOr<SmallVector<Value>> block =
      resultBlock(l, insert, insert.getIndices(), r, insert, scatters);
  if (failed(block))
    return failure();
  SmallVector<Value> &prefix = *block;
  auto type = cast<MemRefType>(output.getType());
  auto combineInto = [&](ArrayRef<Value> indices, Value component) {
    if (ctx.accumulate) {
      Value old = memref::LoadOp::create(b, loc, output, indices);
      component = combine(b, loc, ctx.reduction, old, component);
    }
    memref::StoreOp::create(b, loc, component, output, indices);
  };
  // Component writes combine only the written components; the last write
  // of a component in the chain is the one that counts.
  if (std::optional<ComponentWrites> tree = componentWrites(insert)) {
    SmallVector<SmallVector<Value>> done;
    for (ComponentWrite &write : tree->writes) {
      Value value = write.write.getValue();
      SmallVector<Value> at(prefix);
      for (Value index : write.path)
        at.push_back(l.lookup(index));
      // A scalar, or a whole block of builtin shape: each of its
      // components at its own indices.
      ArrayRef<int64_t> shape;
      if (auto block = dyn_cast<RankedTensorType>(value.getType()))
        shape = block.getShape();
      else if (!isa<FloatType, IntegerType>(value.getType()))
        return write.write.emitError("a component write into a map result "
                                     "must write a scalar or a block of "
                                     "scalars");
      if (at.size() + shape.size() != static_cast<size_t>(type.getRank()))
        return write.write.emitError("this component write does not name "
                                     "one component of the map result's "
                                     "block");
      Value lowered = l.lookup(value);
      SmallVector<int64_t> strides = computeStrides(shape);
      for (int64_t c = 0, n = computeProduct(shape); c < n; ++c) {
        SmallVector<Value> indices(at);
        for (int64_t index : delinearize(c, strides))
          indices.push_back(l.indexConstant(index));
        if (llvm::is_contained(done, indices))
          continue;
        combineInto(indices, l.component(value.getType(), lowered, c));
        done.push_back(indices);
      }
    }
    return success();
  }
  Value value = l.lookup(insert.getValue());
  int64_t n = numComponents(insert.getValue().getType());
  for (int64_t c = 0; c < n; ++c) {
    combineInto(l.blockIndices(type, prefix, c),
                l.component(insert.getValue().getType(), value, c));
  }
  return success();
}

/// Prefetches, at the start of the element, every block of the element's
/// pattern that the element accumulates into: the blocks of a large matrix
/// are scattered over memory, and without the prefetch each accumulation
/// (a load, an add, a store) waits for its block at the end of the element
/// function, where the loads of the next element cannot overlap it.
static void prefetchPatternBlocks(FunctionLowering &l,
                                  const ElementContext &ctx) {
  OpBuilder &b = l.b;
  Location loc = ctx.element.getLoc();
  int64_t c = ctx.set.getCardinality();
  for (const auto &[r, written] : ctx.patternAccumulations) {
    const Storage &storage = ctx.outputStorages[r];
    Value output = ctx.outputs[r];
    Value locations =
        l.getPatternArray(BindingKind::PatternLocations, storage.edges,
                          storage.rows, storage.cols, c);
    for (int64_t k : written) {
      Value block = arith::IndexCastOp::create(
          b, loc, b.getIndexType(),
          memref::LoadOp::create(b, loc, locations,
                                 ValueRange{ctx.element, l.indexConstant(k)}));
      l.prefetchBlock(loc, output, block, /*isWrite=*/true);
    }
  }
}

LogicalResult FunctionLowering::lowerElementAccess(Operation *op,
                                                   bool &handled) {
  handled = true;
  Location loc = op->getLoc();
  // A scalar result's variable is the output; loads read it as it is.
  if (auto alloc = dyn_cast<AllocOp>(op);
      alloc && element && element->scalarSlots.count(alloc)) {
    map(alloc, element->outputs[element->scalarSlots.lookup(alloc)]);
    return success();
  }
  if (auto store = dyn_cast<StoreOp>(op);
      store && element && element->scalarSlots.count(store.getRef())) {
    // Every element writes the one slot.
    element->scatters = true;
    Value output = lookup(store.getRef());
    Value value = lookup(store.getValue());
    auto slotType = cast<MemRefType>(output.getType());
    if (slotType.getRank() == 0) {
      if (element->accumulate)
        value = combine(b, loc, element->reduction,
                        memref::LoadOp::create(b, loc, output, ValueRange{}),
                        value);
      memref::StoreOp::create(b, loc, value, output, ValueRange{});
      return success();
    }
    // A local tensor result: `m(i, j) = v` (an insert into the variable's
    // value) combines v into its one component, so that every write adds
    // (language.md 8.2); any other value combines component by component.
    auto insert = store.getValue().getDefiningOp<InsertOp>();
    auto base = insert ? insert.getTensor().getDefiningOp<LoadOp>() : LoadOp();
    if (element->accumulate && base && base.getRef() == store.getRef() &&
        isa<FloatType, IntegerType, ComplexType>(insert.getValue().getType())) {
      // The insert's own lowering, before this store, asserted that a
      // dynamic index lies in its dimension.
      auto tensorType = cast<RankedTensorType>(insert.getTensor().getType());
      Value position = indexConstant(0);
      for (auto [dim, index] : llvm::enumerate(insert.getIndices())) {
        Value scaled = arith::MulIOp::create(
            b, loc, position, indexConstant(tensorType.getDimSize(dim)));
        position = arith::AddIOp::create(b, loc, scaled, lookup(index));
      }
      Value inserted = lookup(insert.getValue());
      // A complex component is stored as its (re, im) parts, each reduced.
      SmallVector<std::pair<Value, Value>> parts;
      if (isa<ComplexType>(inserted.getType())) {
        Value re = arith::MulIOp::create(b, loc, position, indexConstant(2));
        parts.push_back({re, complex::ReOp::create(b, loc, inserted)});
        parts.push_back({arith::AddIOp::create(b, loc, re, indexConstant(1)),
                         complex::ImOp::create(b, loc, inserted)});
      } else {
        parts.push_back({position, inserted});
      }
      for (auto [at, part] : parts) {
        Value old = memref::LoadOp::create(b, loc, output, at);
        memref::StoreOp::create(
            b, loc, combine(b, loc, element->reduction, old, part), output, at);
      }
      return success();
    }
    if (!element->accumulate) {
      storeWhole(loc, value, output);
      return success();
    }
    // One scalar update per component, as for a scalar result, so that
    // the GPU pipeline makes each an atomic (GPUScatterAtomics).
    // Complex components are reduced part by part, as they are stored.
    bool parts = isa<ComplexType>(getComponentType(store.getValue().getType()));
    for (int64_t c = 0, n = slotType.getNumElements(); c < n; ++c) {
      Value position = indexConstant(c);
      Value old = memref::LoadOp::create(b, loc, output, position);
      Value update =
          parts ? vector::ExtractOp::create(b, loc, value, ArrayRef<int64_t>{c})
                      .getResult()
                : component(store.getValue().getType(), value, c);
      memref::StoreOp::create(b, loc,
                              combine(b, loc, element->reduction, old, update),
                              output, position);
    }
    return success();
  }
  if (auto insert = dyn_cast<InsertOp>(op); insert && isSink(insert)) {
    bool scatters = false;
    if (failed(scatter(*this, insert, element->sinks.lookup(insert),
                       scatters)))
      return failure();
    if (scatters)
      element->scatters = true;
    return success();
  }
  // The block a component write starts from is not read: it stands for
  // zeros, into which the written components go (see scatter).
  if (auto read = dyn_cast<ExtractOp>(op);
      read && isSink(read.getTensor()) && feedsComponentWrites(read)) {
    Type blockType = convertType(read.getType());
    SmallVector<Value> zeros(numComponents(read.getType()),
                             zeroOf(getComponentType(read.getType())));
    map(read, fromComponents(blockType, zeros));
    return success();
  }
  // Reading a result sees the accumulator (§8.2): the block in the output
  // array. A block that component writes also start from may be read so:
  // only its written components are combined back (scatter).
  if (auto read = dyn_cast<ExtractOp>(op); read && isSink(read.getTensor())) {
    unsigned r = element->sinks.lookup(read.getTensor());
    bool shared = false;
    FailureOr<SmallVector<Value>> prefix =
        resultBlock(*this, read, read.getIndices(), r, nullptr, shared);
    if (failed(prefix))
      return failure();
    Value output = element->outputs[r];
    auto type = cast<MemRefType>(output.getType());
    SmallVector<Value> components;
    for (int64_t c = 0, n = numComponents(read.getType()); c < n; ++c)
      components.push_back(memref::LoadOp::create(
          b, read.getLoc(), output, blockIndices(type, *prefix, c)));
    map(read, fromComponents(convertType(read.getType()), components));
    return success();
  }
  if (element && !isa<StoreOp, scf::YieldOp, func::ReturnOp>(op))
    for (Value operand : op->getOperands())
      if (isSink(operand))
        return op->emitError("an element function cannot read its own "
                             "results");

  auto access = [&](Value elementValue, StringAttr field,
                    Type &fieldType) -> std::pair<Value, Value> {
    StringAttr set = elementSetOf(elementValue);
    fieldType = cast<ElementType>(elementValue.getType()).getFieldType(field);
    if (!set) {
      op->emitError("the loop lowering cannot tell which set this element "
                    "belongs to");
      return {};
    }
    return {getField(set, field, fieldType), lookup(elementValue)};
  };
  if (auto read = dyn_cast<ElemReadOp>(op)) {
    Type fieldType;
    auto [array, index] = access(read.getElement(), read.getFieldAttr(),
                                 fieldType);
    if (!array)
      return failure();
    auto type = cast<MemRefType>(array.getType());
    SmallVector<Value> components;
    for (int64_t c = 0, n = numComponents(fieldType); c < n; ++c)
      components.push_back(memref::LoadOp::create(
          b, loc, array, blockIndices(type, {index}, c)));
    map(read, fromComponents(convertType(read.getType()), components));
    return success();
  }
  if (auto write = dyn_cast<ElemWriteOp>(op)) {
    Type fieldType;
    auto [array, index] = access(write.getElement(), write.getFieldAttr(),
                                 fieldType);
    if (!array)
      return failure();
    auto type = cast<MemRefType>(array.getType());
    Value value = lookup(write.getValue());
    // Writing an endpoint's field touches an element other edges share.
    if (element && index != element->element)
      element->scatters = true;
    for (int64_t c = 0, n = numComponents(fieldType); c < n; ++c)
      memref::StoreOp::create(b, loc,
                              component(write.getValue().getType(), value, c),
                              array, blockIndices(type, {index}, c));
    return success();
  }
  handled = false;
  return success();
}

LogicalResult FunctionLowering::lowerMapLike(Operation *op) {
  Location loc = op->getLoc();
  auto callee = module.lookupSymbol<func::FuncOp>(
      op->getAttrOfType<FlatSymbolRefAttr>("callee"));
  if (!callee || callee.isExternal())
    return op->emitError("the mapped function has no body");
  auto mapOp = dyn_cast<MapOp>(op);
  auto assembleOp = dyn_cast<AssembleOp>(op);
  Value setValue = mapOp ? mapOp.getSet() : assembleOp.getSet();
  ValueRange extras = mapOp ? mapOp.getExtras() : assembleOp.getExtras();
  Value grid = mapOp ? mapOp.getGrid() : assembleOp.getGrid();
  auto set = cast<SetType>(setValue.getType());
  if (element)
    return op->emitError("maps inside element functions are not supported");

  ElementContext ctx;
  ctx.set = set;
  ctx.accumulate = bool(assembleOp);
  if (assembleOp)
    ctx.reduction = assembleOp.getReduction();

  if (failed(collectSinks(callee, ctx.sinks, ctx.scalarSlots)))
    return failure();

  // Outputs, zero-filled or copied from the extra argument they start
  // from (an `inout` extra argument), stored as the sparsity analysis says.
  SmallVector<std::pair<Value, Value>> scalarResults;
  std::optional<ArrayRef<int64_t>> inits =
      mapOp ? mapOp.getResultInits() : std::nullopt;
  auto initOf = [&](unsigned r) {
    return inits && (*inits)[r] >= 0 ? lookup(extras[(*inits)[r]]) : Value();
  };
  for (auto [r, result] : llvm::enumerate(op->getResults())) {
    Value init = initOf(r);
    if (isSlotResult(result.getType())) {
      // Each write combines into (or, for a map, stores to) one slot that
      // starts at zero, laid out as a variable of the result's type.
      auto slotType = cast<MemRefType>(
          convertType(RefType::get(result.getContext(), result.getType())));
      Value slot = allocaSlot(loc, slotType);
      if (!init)
        fill(loc, slot, zeroOf(slotType.getElementType()));
      else if (slotType.getRank() == 0)
        memref::StoreOp::create(b, loc, init, slot, ValueRange{});
      else
        storeWhole(loc, init, slot);
      ctx.outputs.push_back(slot);
      ctx.outputStorages.push_back(Storage::dense());
      scalarResults.push_back({result, slot});
      continue;
    }
    auto type = dyn_cast<SystemTensorType>(result.getType());
    if (!type || !type.isSystem())
      return op->emitError("map results that are neither system tensors "
                           "nor scalars or local tensors of int or float "
                           "are not supported by the loop lowering");
    // Stored as simit-assign-storage found from the set (and, through a
    // grid, the offsets the element function writes).
    Storage storage = storageOf(result);
    if (!storage.isMatrix() && !hasBlockPerElement(type))
      return op->emitError("map result ")
             << type << " is not supported by the loop lowering";
    if (init && storage != storageOf(extras[(*inits)[r]]))
      return op->emitError("an inout extra argument stored as ")
             << storageOf(extras[(*inits)[r]]).describe()
             << " cannot be written by a map as " << storage.describe();
    Value output = allocSystem(loc, type, storage, /*zeroFill=*/!init);
    if (init)
      memref::CopyOp::create(b, loc, init, output);
    ctx.outputs.push_back(output);
    ctx.outputStorages.push_back(storage);
    storages[result] = storage;
    map(result, output);
  }

  // The loop over the set, the element function inlined in it.
  Value size = getSetSize(set.getName());
  auto loop = scf::ParallelOp::create(
      b, loc, ValueRange{indexConstant(0)}, ValueRange{size},
      ValueRange{indexConstant(1)},
      [](OpBuilder &, Location, ValueRange) {});
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPoint(loop.getBody()->getTerminator());
  auto scope = memref::AllocaScopeOp::create(b, loc, TypeRange{});
  Block *body = new Block();
  scope.getBodyRegion().push_back(body);
  b.setInsertionPointToStart(body);
  memref::AllocaScopeReturnOp::create(b, loc, ValueRange{});
  b.setInsertionPointToStart(body);
  b.setInsertionPoint(body->getTerminator());

  ctx.element = loop.getInductionVars()[0];
  Block &entry = callee.front();
  if (entry.getNumArguments() < extras.size() + 1)
    return op->emitError("the mapped function takes too few parameters");
  for (auto [arg, extra] : llvm::zip(entry.getArguments(), extras)) {
    map(arg, lookup(extra));
    carryStorage(arg, extra);
  }
  Value elementArg = entry.getArgument(extras.size());
  map(elementArg, ctx.element);
  elementSets[elementArg] = set.getName();
  // The parameter after the element is the endpoint tuple, or the grid
  // (grid_point and grid_edge use only its type).
  if (entry.getNumArguments() > extras.size() + 1 && !grid)
    tuples[entry.getArgument(extras.size() + 1)] = {set, ctx.element};

  Block *savedAllocaBlock = allocaBlock;
  element = &ctx;
  allocaBlock = body;
  LogicalResult lowered = lowerOps(entry);
  element = nullptr;
  allocaBlock = savedAllocaBlock;
  if (failed(lowered))
    return failure();
  b.setInsertionPointToStart(body);
  if (prefetchScatterBlocks)
    prefetchPatternBlocks(*this, ctx);
  // Iterations write shared locations (endpoints, matrix blocks, scalar
  // results): a parallel backend must make these updates atomic or colour
  // the set.
  if (ctx.scatters)
    loop->setAttr("simit.scatter", b.getUnitAttr());
  b.setInsertionPointAfter(loop);
  for (auto [result, slot] : scalarResults) {
    if (cast<MemRefType>(slot.getType()).getRank() == 0)
      map(result, memref::LoadOp::create(b, loc, slot, ValueRange{}));
    else
      map(result,
          loadWhole(loc, cast<VectorType>(convertType(result.getType())),
                    slot));
  }
  return success();
}
