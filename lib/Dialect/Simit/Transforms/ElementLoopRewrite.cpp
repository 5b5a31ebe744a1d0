//===- ElementLoopRewrite.cpp - Element kernels across vector lanes -------===//
//
// The rewrite of a planned element loop: vector ops once per `lanes`
// elements, their results handed to the lane phase through stack buffers.
//
//===----------------------------------------------------------------------===//

#include "ElementLoopVectorizer.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Utils/IndexingUtils.h"
#include "mlir/Dialect/Utils/StaticValueUtils.h"
#include "mlir/Dialect/Vector/IR/VectorOps.h"
#include "mlir/Interfaces/FunctionInterfaces.h"

using namespace mlir;
using namespace mlir::simit::element_vectorize;

Value ElementLoopVectorizer::broadcastScalar(OpBuilder &b, Value scalar) {
  return vector::BroadcastOp::create(b, scalar.getLoc(),
                                     laneType(scalar.getType()), scalar);
}

/// The components of `value` as vectors over the lanes: a varying value's
/// own, a uniform value's broadcast to every lane.
ArrayRef<Value> ElementLoopVectorizer::wide(OpBuilder &b, Value value) {
  auto found = components.find(value);
  if (found != components.end())
    return found->second;
  Value scalar = uniform.lookupOrDefault(value);
  SmallVector<Value> parts;
  if (auto vector = dyn_cast<VectorType>(scalar.getType())) {
    SmallVector<int64_t> strides = computeStrides(vector.getShape());
    for (int64_t i = 0; i < vector.getNumElements(); ++i) {
      Value part = vector::ExtractOp::create(b, scalar.getLoc(), scalar,
                                             delinearize(i, strides));
      parts.push_back(broadcastScalar(b, part));
    }
  } else {
    parts.push_back(broadcastScalar(b, scalar));
  }
  return components[value] = std::move(parts);
}

/// `value` as lane `lane` sees it, as a scalar. Index computations from the
/// induction variable and gathered loads (endpoints) are redone per lane on
/// scalars rather than read back out of vectors.
Value ElementLoopVectorizer::laneScalar(OpBuilder &b, Value value,
                                        int64_t lane) {
  if (!varying.contains(value))
    return uniform.lookupOrDefault(value);
  SmallVector<Value> &perLane = laneScalars[value];
  if (perLane.empty())
    perLane.resize(lanes);
  if (perLane[lane])
    return perLane[lane];
  Location loc = value.getLoc();
  Operation *def = value.getDefiningOp();
  Value result;
  if (value == iv) {
    result = arith::MinSIOp::create(
        b, loc,
        arith::AddIOp::create(b, loc, base,
                              arith::ConstantIndexOp::create(b, loc, lane)),
        lastElement);
  } else if (def && !isa<VectorType>(value.getType()) &&
             def->getNumRegions() == 0 && isPure(def) &&
             def->hasTrait<OpTrait::Elementwise>() &&
             isa<arith::ArithDialect>(def->getDialect()) &&
             value.getType().isIntOrIndex()) {
    IRMapping mapping;
    for (Value operand : def->getOperands())
      mapping.map(operand, laneScalar(b, operand, lane));
    result = b.clone(*def, mapping)->getResult(0);
  } else {
    result = vector::ExtractOp::create(b, loc, wide(b, value)[0], lane);
  }
  return perLane[lane] = result;
}

SmallVector<Value> ElementLoopVectorizer::laneIndices(OpBuilder &b,
                                                      ValueRange indices,
                                                      int64_t lane) {
  return llvm::map_to_vector(
      indices, [&](Value index) { return laneScalar(b, index, lane); });
}

void ElementLoopVectorizer::prefetchLanes(OpBuilder &b,
                                          memref::PrefetchOp prefetch) {
  bool varies = llvm::any_of(prefetch.getIndices(),
                             [&](Value v) { return varying.contains(v); });
  for (int64_t lane = 0; lane < (varies ? lanes : 1); ++lane)
    memref::PrefetchOp::create(
        b, prefetch.getLoc(), prefetch.getMemref(),
        laneIndices(b, prefetch.getIndices(), lane), prefetch.getIsWrite(),
        prefetch.getLocalityHint(), prefetch.getIsDataCache());
}

/// The memref from which one vector load reads all lanes' blocks of a field
/// (`memref`, defined outside the loop), flattened, and the shift of its
/// positions: element e's first component is at e * blockSize - shift.
/// When the set has at least `lanes` elements, every step's lanes hold
/// elements: the field itself, shift 0. A smaller set is copied, padded
/// with zeros, into a stack buffer, shift lb * blockSize. Chosen once
/// before the loop: a choice per step (or a masked load) cost fem-dragon's
/// assembly 3-7 %.
std::pair<Value, Value> ElementLoopVectorizer::blocksSource(OpBuilder &b,
                                                            Value memref,
                                                            int64_t blockSize) {
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPoint(base.getParentBlock()->getParentOp());
  Location loc = memref.getLoc();
  auto type = cast<MemRefType>(memref.getType());
  SmallVector<ReassociationIndices> all(1);
  for (int64_t d = 0; d < type.getRank(); ++d)
    all[0].push_back(d);
  Value flat =
      type.getRank() == 1
          ? memref
          : memref::CollapseShapeOp::create(b, loc, memref, all).getResult();
  auto flatType = cast<MemRefType>(flat.getType());
  Type element = flatType.getElementType();
  auto vectorType = VectorType::get({blockSize * lanes}, element);
  // At the function's entry: a slot made where the loop is would grow the
  // stack in every iteration of a loop around it.
  Value padded;
  {
    OpBuilder::InsertionGuard entry(b);
    b.setInsertionPointToStart(&loop->getParentOfType<FunctionOpInterface>()
                                    .getFunctionBody()
                                    .front());
    padded = memref::AllocaOp::create(
        b, loc, MemRefType::get({blockSize * lanes}, element));
  }
  Value lb = loop.getLowerBound()[0], ub = loop.getUpperBound()[0];
  Value zero = arith::ConstantIndexOp::create(b, loc, 0);
  Value bs = arith::ConstantIndexOp::create(b, loc, blockSize);
  Value elements = arith::SubIOp::create(b, loc, ub, lb);
  Value small =
      arith::CmpIOp::create(b, loc, arith::CmpIPredicate::slt, elements,
                            arith::ConstantIndexOp::create(b, loc, lanes));
  Value start = arith::MulIOp::create(b, loc, lb, bs);
  auto copy = scf::IfOp::create(b, loc, small, /*withElseRegion=*/false);
  b.setInsertionPointToStart(copy.thenBlock());
  vector::StoreOp::create(
      b, loc,
      arith::ConstantOp::create(
          b, loc, vectorType,
          DenseElementsAttr::get(vectorType, b.getZeroAttr(element))),
      padded, ValueRange{zero});
  auto copyLoop = scf::ForOp::create(
      b, loc, zero,
      arith::MulIOp::create(b, loc,
                            arith::MaxSIOp::create(b, loc, elements, zero), bs),
      arith::ConstantIndexOp::create(b, loc, 1));
  b.setInsertionPointToStart(copyLoop.getBody());
  Value c = copyLoop.getInductionVar();
  memref::StoreOp::create(
      b, loc,
      memref::LoadOp::create(
          b, loc, flat, ValueRange{arith::AddIOp::create(b, loc, start, c)}),
      padded, ValueRange{c});
  b.setInsertionPointAfter(copy);
  return {arith::SelectOp::create(
              b, loc, small, memref::CastOp::create(b, loc, flatType, padded),
              flat),
          arith::SelectOp::create(b, loc, small, start, zero)};
}

/// The components of a field of the loop's own elements, `memref[iv, c...]`
/// with a static block shape: the lanes' blocks lie next to each other in
/// memory, so one vector load reads all of them and shuffles pick the
/// component.
Value ElementLoopVectorizer::elementBlockComponent(OpBuilder &b,
                                                   memref::LoadOp load) {
  auto type = cast<MemRefType>(load.getMemRef().getType());
  ValueRange indices = load.getIndices();
  if (indices.empty() || indices[0] != iv ||
      !allConstantIndices(indices.drop_front()) ||
      !type.getLayout().isIdentity() ||
      llvm::any_of(type.getShape().drop_front(), ShapedType::isDynamic))
    return {};
  int64_t blockSize = 1;
  for (int64_t size : type.getShape().drop_front())
    blockSize *= size;
  // A field defined in the loop (a view made per element) is gathered.
  if (blockSize * lanes > 128 ||
      loop.getRegion().isAncestor(load.getMemRef().getParentRegion()))
    return {};
  Location loc = load.getLoc();
  Value &blocks = elementBlocks[load.getMemRef()];
  if (!blocks) {
    auto [source, shift] = blocksSource(b, load.getMemRef(), blockSize);
    Value at = arith::SubIOp::create(
        b, loc,
        arith::MulIOp::create(
            b, loc, base, arith::ConstantIndexOp::create(b, loc, blockSize)),
        shift);
    blocks = vector::LoadOp::create(
        b, loc, VectorType::get({blockSize * lanes}, type.getElementType()),
        source, ValueRange{at});
  }
  if (blockSize == 1)
    return blocks;
  int64_t component = 0;
  for (auto [size, index] :
       llvm::zip(type.getShape().drop_front(), indices.drop_front()))
    component = component * size + *getConstantIntValue(index);
  SmallVector<int64_t> mask;
  for (int64_t lane = 0; lane < lanes; ++lane)
    mask.push_back(lane * blockSize + component);
  return vector::ShuffleOp::create(b, loc, blocks, blocks, mask);
}

void ElementLoopVectorizer::gather(OpBuilder &b, memref::LoadOp load) {
  // Loads of memory the loop does not write give the same value for the
  // same indices: each is read once.
  SmallVector<const void *> key{load.getMemRef().getAsOpaquePointer()};
  for (Value index : load.getIndices())
    key.push_back(index.getAsOpaquePointer());
  auto [known, inserted] = gathered.try_emplace(key, load.getResult());
  if (!inserted) {
    components[load.getResult()] = components[known->second];
    laneScalars[load.getResult()] = laneScalars[known->second];
    return;
  }
  // Integers (endpoints) are mostly used as indices, lane by lane: those
  // are loaded lane by lane.
  if (Value block = isa<FloatType>(load.getType())
                        ? elementBlockComponent(b, load)
                        : Value()) {
    components[load.getResult()] = {block};
    return;
  }
  Location loc = load.getLoc();
  SmallVector<Value> elements;
  for (int64_t lane = 0; lane < lanes; ++lane)
    elements.push_back(memref::LoadOp::create(
        b, loc, uniform.lookupOrDefault(load.getMemRef()),
        laneIndices(b, load.getIndices(), lane)));
  laneScalars[load.getResult()] = elements;
  components[load.getResult()] = {vector::FromElementsOp::create(
      b, loc, laneType(load.getType()), elements)};
}

void ElementLoopVectorizer::widenAllocaAccess(OpBuilder &b, Operation *op,
                                              Value alloca) {
  auto type = cast<MemRefType>(alloca.getType());
  SmallVector<Value> &state = allocaState[alloca];
  if (state.empty()) {
    // Components read before any write: zero.
    Type element = type.getElementType();
    Value zero = arith::ConstantOp::create(
        b, op->getLoc(), laneType(element),
        DenseElementsAttr::get(laneType(element), b.getZeroAttr(element)));
    state.assign(type.getNumElements(), zero);
  }
  if (auto load = dyn_cast<vector::LoadOp>(op)) {
    components[load.getResult()] = state;
  } else if (auto store = dyn_cast<vector::StoreOp>(op)) {
    state = llvm::to_vector(wide(b, store.getValueToStore()));
  } else if (auto load = dyn_cast<memref::LoadOp>(op)) {
    components[load.getResult()] = {
        state[linearPosition(type.getShape(), load.getIndices())]};
  } else if (auto store = dyn_cast<memref::StoreOp>(op)) {
    state[linearPosition(type.getShape(), store.getIndices())] =
        wide(b, store.getValueToStore())[0];
  } else {
    auto fill =
        cast<memref::StoreOp>(cast<scf::ParallelOp>(op).getBody()->front());
    Value value = wide(b, fill.getValueToStore())[0];
    state.assign(type.getNumElements(), value);
  }
}

void ElementLoopVectorizer::widen(OpBuilder &b, Operation *op) {
  Value result = op->getResult(0);
  Type resultType = result.getType();
  SmallVector<Value> &parts = components[result];
  if (auto load = dyn_cast<memref::LoadOp>(op))
    return gather(b, load);
  if (auto extract = dyn_cast<vector::ExtractOp>(op)) {
    int64_t first = firstComponent(extract.getSourceVectorType(),
                                   extract.getStaticPosition());
    ArrayRef<Value> from = wide(b, extract.getSource());
    parts.assign(from.begin() + first,
                 from.begin() + first + componentCount(resultType));
    return;
  }
  if (auto insert = dyn_cast<vector::InsertOp>(op)) {
    int64_t first =
        firstComponent(insert.getDestVectorType(), insert.getStaticPosition());
    SmallVector<Value> into = llvm::to_vector(wide(b, insert.getDest()));
    ArrayRef<Value> from = wide(b, insert.getValueToStore());
    llvm::copy(from, into.begin() + first);
    components[result] = std::move(into);
    return;
  }
  if (auto broadcast = dyn_cast<vector::BroadcastOp>(op)) {
    // Source dimensions line up with the result's last ones; a source
    // dimension of 1 repeats.
    ArrayRef<Value> from = wide(b, broadcast.getSource());
    auto target = cast<VectorType>(resultType);
    ArrayRef<int64_t> shape = target.getShape();
    SmallVector<int64_t> sourceShape;
    if (auto source = dyn_cast<VectorType>(broadcast.getSourceType()))
      sourceShape = llvm::to_vector(source.getShape());
    SmallVector<int64_t> strides = computeStrides(shape);
    SmallVector<int64_t> sourceStrides = computeStrides(sourceShape);
    size_t offset = shape.size() - sourceShape.size();
    for (int64_t i = 0; i < target.getNumElements(); ++i) {
      SmallVector<int64_t> position = delinearize(i, strides);
      int64_t from_i = 0;
      for (size_t d = 0; d < sourceShape.size(); ++d)
        if (sourceShape[d] != 1)
          from_i += position[offset + d] * sourceStrides[d];
      parts.push_back(from[from_i]);
    }
    return;
  }
  if (auto elements = dyn_cast<vector::FromElementsOp>(op)) {
    for (Value element : elements.getElements())
      parts.push_back(wide(b, element)[0]);
    return;
  }
  if (auto cast = dyn_cast<vector::ShapeCastOp>(op)) {
    parts = llvm::to_vector(wide(b, cast.getSource()));
    return;
  }
  if (auto transpose = dyn_cast<vector::TransposeOp>(op)) {
    ArrayRef<Value> from = wide(b, transpose.getVector());
    ArrayRef<int64_t> permutation = transpose.getPermutation();
    VectorType source = transpose.getSourceVectorType();
    SmallVector<int64_t> sourceStrides = computeStrides(source.getShape());
    SmallVector<int64_t> strides =
        computeStrides(transpose.getResultVectorType().getShape());
    for (int64_t i = 0; i < source.getNumElements(); ++i) {
      SmallVector<int64_t> position = delinearize(i, strides);
      int64_t from_i = 0;
      for (auto [d, p] : llvm::enumerate(permutation))
        from_i += position[d] * sourceStrides[p];
      parts.push_back(from[from_i]);
    }
    return;
  }
  // Element-wise: one op per component, on vectors over the lanes.
  for (int64_t c = 0; c < componentCount(resultType); ++c) {
    OperationState state(op->getLoc(), op->getName());
    for (Value operand : op->getOperands()) {
      ArrayRef<Value> from = wide(b, operand);
      state.addOperands(from.size() == 1 ? from[0] : from[c]);
    }
    state.addTypes(laneType(componentType(resultType)));
    state.addAttributes(op->getAttrs());
    components[result].push_back(b.create(state)->getResult(0));
  }
}

void ElementLoopVectorizer::rewrite() {
  Location loc = loop.getLoc();
  OpBuilder b(loop);
  Value lb = loop.getLowerBound()[0], ub = loop.getUpperBound()[0];
  Value width = arith::ConstantIndexOp::create(b, loc, lanes);
  // Each step owns `lanes` elements from its start on. The last step, when
  // fewer are left, computes the `lanes` elements before the end instead
  // (their arithmetic has no effects) and runs the lane ops of its own
  // elements only: no scalar copy of the loop for the remainder, which
  // made the compile a third longer. In a set smaller than `lanes` the
  // lanes past its end repeat its last element (blocksSource()).
  auto vectorLoop = scf::ParallelOp::create(b, loc, ValueRange{lb},
                                            ValueRange{ub}, ValueRange{width});
  b.setInsertionPoint(vectorLoop.getBody()->getTerminator());
  Value start = vectorLoop.getInductionVars()[0];
  base = arith::MaxSIOp::create(
      b, loc,
      arith::MinSIOp::create(b, loc, start,
                             arith::SubIOp::create(b, loc, ub, width)),
      lb);
  Value one = arith::ConstantIndexOp::create(b, loc, 1);
  lastElement = arith::SubIOp::create(b, loc, ub, one);
  elementsInLanes = arith::MinSIOp::create(
      b, loc, arith::SubIOp::create(b, loc, ub, base), width);
  SmallVector<Attribute> laneNumbers;
  for (int64_t lane = 0; lane < lanes; ++lane)
    laneNumbers.push_back(b.getIndexAttr(lane));
  Value laneOffsets = arith::ConstantOp::create(
      b, loc, DenseElementsAttr::get(laneType(b.getIndexType()), laneNumbers));
  components[iv] = {arith::MinSIOp::create(
      b, loc,
      arith::AddIOp::create(b, loc, broadcastScalar(b, base), laneOffsets),
      broadcastScalar(b, lastElement))};

  for (Operation &op : body->without_terminator()) {
    if (laneOps.contains(&op))
      continue;
    if (isa<memref::AllocaOp>(op) && promoted.contains(op.getResult(0)))
      continue;
    Value alloca;
    if (prefetches.contains(&op))
      prefetchLanes(b, cast<memref::PrefetchOp>(op));
    else if (isPromotedAccess(&op, alloca))
      widenAllocaAccess(b, &op, alloca);
    else if (op.getNumResults() == 1 && varying.contains(op.getResult(0)))
      widen(b, &op);
    else
      b.clone(op, uniform);
  }

  // What the lane ops read of the vector ops goes through the stack:
  // scalars of one type side by side in one buffer, in the order the lane
  // ops read them, so that a lane's components of one block lie together
  // as the scatter reads them; other values in buffers of their own.
  llvm::MapVector<Type, SmallVector<Value>> scalars;
  for (Value value : needed) {
    if (componentCount(value.getType()) == 1)
      scalars[componentType(value.getType())].push_back(value);
    else
      storeForLanes(b, value);
  }
  for (auto &[type, values] : scalars)
    storeForLanes(b, values);

  // Over all lanes, each skipped unless it holds an element of this step:
  // a loop of constant trip count, which LLVM may unroll into straight code
  // with constant buffer offsets.
  Value firstLane = arith::SubIOp::create(b, loc, start, base);
  Value zero = arith::ConstantIndexOp::create(b, loc, 0);
  auto laneLoop = scf::ForOp::create(b, loc, zero, width, one);
  b.setInsertionPoint(laneLoop.getBody()->getTerminator());
  lane = laneLoop.getInductionVar();
  Value owned = arith::AndIOp::create(
      b, loc,
      arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge, lane, firstLane),
      arith::CmpIOp::create(b, loc, arith::CmpIPredicate::slt, lane,
                            elementsInLanes));
  auto ownedLane = scf::IfOp::create(b, loc, owned, /*withElseRegion=*/false);
  b.setInsertionPoint(ownedLane.thenBlock()->getTerminator());
  IRMapping mapping = uniform;
  mapping.map(iv, arith::AddIOp::create(b, loc, base, lane));
  for (Operation &op : body->without_terminator()) {
    if (!laneOps.contains(&op))
      continue;
    // The clone still reads the buffered values of the original body: each
    // read becomes a load next to it, in the same block, so that a lane's
    // scatter of a block reads its components from consecutive slots there.
    Operation *clone = b.clone(op, mapping);
    SmallVector<OpOperand *> reads;
    clone->walk([&](Operation *user) {
      for (OpOperand &use : user->getOpOperands())
        if (laneBuffers.contains(use.get()))
          reads.push_back(&use);
    });
    for (OpOperand *read : reads)
      loadForLane(*read);
  }
  loop.erase();
}

/// Stores the lanes of `values` (of one component type) for the lane
/// phase in one buffer, their components one after another. Fewer
/// components than lanes are stored [component][lane] (one vector store
/// per component); more are transposed in registers and stored
/// [lane][component], so that the lane phase finds a lane's components
/// side by side.
void ElementLoopVectorizer::storeForLanes(OpBuilder &b,
                                          ArrayRef<Value> values) {
  Location loc = values.front().getLoc();
  Type component = componentType(values.front().getType());
  Type stored = component.isInteger(1) ? b.getI8Type() : component;
  SmallVector<Value> parts;
  SmallVector<int64_t> offsets;
  for (Value value : values) {
    offsets.push_back(parts.size());
    llvm::append_range(parts, wide(b, value));
  }
  for (Value &part : parts)
    if (stored != component)
      part = arith::ExtUIOp::create(b, loc, laneType(stored), part);
  int64_t count = parts.size();
  auto index = [&](int64_t i) {
    return arith::ConstantIndexOp::create(b, loc, i).getResult();
  };
  bool transposed = count >= lanes;
  Value buffer;
  if (!transposed) {
    buffer = memref::AllocaOp::create(b, loc,
                                      MemRefType::get({count, lanes}, stored));
    for (auto [c, part] : llvm::enumerate(parts))
      vector::StoreOp::create(b, loc, part, buffer,
                              ValueRange{index(c), index(0)});
  } else {
    int64_t padded = llvm::alignTo(count, lanes);
    buffer = memref::AllocaOp::create(b, loc,
                                      MemRefType::get({lanes, padded}, stored));
    Value filler = arith::ConstantOp::create(
        b, loc, laneType(stored),
        DenseElementsAttr::get(laneType(stored), b.getZeroAttr(stored)));
    for (int64_t first = 0; first < padded; first += lanes) {
      SmallVector<Value> rows;
      for (int64_t r = 0; r < lanes; ++r)
        rows.push_back(first + r < count ? parts[first + r] : filler);
      // Butterfly transpose: at each step, rows `step` apart exchange their
      // alternate runs of `step` components.
      for (int64_t step = 1; step < lanes; step *= 2) {
        SmallVector<int64_t> low, high;
        for (int64_t k = 0; k < lanes; ++k) {
          low.push_back((k & step) ? lanes + k - step : k);
          high.push_back((k & step) ? lanes + k : k + step);
        }
        for (int64_t r = 0; r < lanes; ++r) {
          if (r & step)
            continue;
          Value a = rows[r], c = rows[r + step];
          rows[r] = vector::ShuffleOp::create(b, loc, a, c, low);
          rows[r + step] = vector::ShuffleOp::create(b, loc, a, c, high);
        }
      }
      for (int64_t l = 0; l < lanes; ++l)
        vector::StoreOp::create(b, loc, rows[l], buffer,
                                ValueRange{index(l), index(first)});
    }
  }
  for (auto [value, offset] : llvm::zip(values, offsets))
    laneBuffers[value] = {buffer, transposed, offset};
}

/// Replaces `read` (a use of a buffered value in the lane phase) with loads
/// of the lane's components. A vector.extract of components loads only
/// those.
void ElementLoopVectorizer::loadForLane(OpOperand &read) {
  Operation *user = read.getOwner();
  Value value = read.get();
  const LaneBuffer &buffer = laneBuffers.find(value)->second;
  Type component = componentType(value.getType());
  OpBuilder b(user);
  Location loc = user->getLoc();
  auto load = [&](int64_t c) -> Value {
    Value &known = laneLoads[{user->getBlock(), value, c}];
    if (known)
      return known;
    Value position = arith::ConstantIndexOp::create(b, loc, buffer.offset + c);
    Value part =
        memref::LoadOp::create(b, loc, buffer.memref,
                               buffer.transposed ? ValueRange{lane, position}
                                                 : ValueRange{position, lane});
    if (part.getType() != component)
      part = arith::TruncIOp::create(b, loc, component, part);
    return known = part;
  };
  auto extract = dyn_cast<vector::ExtractOp>(user);
  if (extract && extract.getDynamicPosition().empty()) {
    int64_t first = firstComponent(extract.getSourceVectorType(),
                                   extract.getStaticPosition());
    Type resultType = extract.getType();
    Value result;
    if (!isa<VectorType>(resultType)) {
      result = load(first);
    } else {
      SmallVector<Value> parts;
      for (int64_t c = 0; c < componentCount(resultType); ++c)
        parts.push_back(load(first + c));
      result = vector::FromElementsOp::create(
          b, loc, cast<VectorType>(resultType), parts);
    }
    extract.replaceAllUsesWith(result);
    extract.erase();
    return;
  }
  Value whole;
  if (auto vector = dyn_cast<VectorType>(value.getType())) {
    SmallVector<Value> parts;
    for (int64_t c = 0; c < vector.getNumElements(); ++c)
      parts.push_back(load(c));
    whole = vector::FromElementsOp::create(b, loc, vector, parts);
  } else {
    whole = load(0);
  }
  read.set(whole);
}
