//===- ParallelLoops.cpp - Set loops that may run on all cores ------------===//
//
// The loop lowering emits every set loop as an scf.parallel, but only some of
// them are free of races, and a parallel reduction combines its partial
// results in an order that depends on the number of threads. This pass looks
// at every outermost scf.parallel and either marks it `simit.parallel` (its
// iterations may run concurrently, in any order, with the same result bit
// for bit) or leaves it alone (it then runs sequentially, as before):
//
// - owned: every location the loop writes is indexed by the iteration (an
//   induction variable, or a block of the iteration's row in a BCSR row
//   range): the loop is marked as it is;
// - reduction: an owned loop with scf.reduce results becomes a loop over
//   chunks of a fixed number of iterations, each reduced in order into a
//   partial result, and the partials are combined in chunk order after it;
// - scatter: an element loop whose other writes are indexed by an endpoint
//   of the element (vertex arrays) or by a block its location table gives
//   (BCSR values) runs colour by colour: the host colours fixed-size chunks
//   of consecutive elements so that no two chunks of one colour share an
//   endpoint (the `element_colours` binding), and the chunks of each colour
//   run in parallel.
//
// Chunk sizes are options, never the number of threads, so the order in
// which every value is combined is the same on any number of threads.
//
//===----------------------------------------------------------------------===//

#include "Accumulation.h"
#include "LoopTrips.h"
#include "RuntimeFunction.h"

#include "simit/ABI/BindingKind.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Interfaces/SideEffectInterfaces.h"
#include "mlir/Interfaces/ViewLikeInterface.h"

#include <set>

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITPARALLELLOOPS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// The `simit.bindings` entry of `value` when it is an argument of
/// `function`, else null.
DictionaryAttr bindingOf(func::FuncOp function, Value value) {
  auto arg = dyn_cast<BlockArgument>(value);
  auto bindings = function->getAttrOfType<ArrayAttr>(
      StringRef(::simit::abi::kBindingsAttr));
  if (!arg || !bindings || arg.getOwner() != &function.front() ||
      arg.getArgNumber() >= bindings.size())
    return {};
  return dyn_cast<DictionaryAttr>(bindings[arg.getArgNumber()]);
}

StringRef bindingString(DictionaryAttr binding, StringRef key) {
  auto value = binding ? binding.getAs<StringAttr>(key) : StringAttr();
  return value ? value.getValue() : StringRef();
}

/// `value` is the index_cast of a load of `table[indices]` from a memref;
/// returns the load.
memref::LoadOp castLoad(Value value) {
  auto cast = value.getDefiningOp<arith::IndexCastOp>();
  return cast ? cast.getIn().getDefiningOp<memref::LoadOp>() : nullptr;
}

/// Which iterations of the loop an index value can be equal for.
struct IndexOwner {
  enum class Kind {
    None,
    /// Induction variable `dim` itself.
    Iteration,
    /// An scf.for variable over `table[iv] .. table[iv + 1]` for induction
    /// variable `dim` and a BCSR row pointer array `table` (nondecreasing:
    /// the ranges of different rows are disjoint).
    RowRange,
    /// `table[iv, k]` of the element's endpoint array.
    Endpoint,
    /// `table[iv, k]` of the element's pattern location table.
    Location,
  };
  Kind kind = Kind::None;
  unsigned dim = 0;
  Value table;

  bool ownedByIteration() const {
    return kind == Kind::Iteration || kind == Kind::RowRange;
  }
  bool sharedThroughEndpoints() const {
    return kind == Kind::Endpoint || kind == Kind::Location;
  }
  bool operator==(const IndexOwner &other) const {
    return kind == other.kind && dim == other.dim && table == other.table;
  }
};

/// One read or write of a memref defined outside the loop.
struct Access {
  Operation *op;
  Value memref;
  SmallVector<Value> indices;
  /// Trailing dimensions a vector load or store spans.
  unsigned vectorRank = 0;
  bool writes = false;
};

/// Where an access is indexed by something that keeps iterations apart.
struct Place {
  unsigned position;
  IndexOwner owner;
  bool operator==(const Place &other) const {
    return position == other.position && owner == other.owner;
  }
};

enum class LoopKind { Serial, Owned, Reduction, Scatter };

class LoopClassifier {
public:
  LoopClassifier(func::FuncOp function, scf::ParallelOp loop)
      : function(function), loop(loop) {}

  LoopKind classify();
  /// The element set of a scatter loop.
  StringRef elementSet() const { return set; }

private:
  bool isPrivate(Value memref) const {
    return loop.getRegion().isAncestor(memref.getParentRegion());
  }
  LogicalResult collectAccesses();
  IndexOwner ownerOf(Value index) const;
  bool isElementLoop();
  std::optional<SmallVector<Place>> ownedPlaces(const Access &access) const;
  std::optional<Place> endpointPlace(const Access &access) const;
  /// Whether no iteration can read what another writes through the
  /// element's endpoints (the accesses of a memref that is written only at
  /// its endpoint place).
  static bool onlyAccumulates(ArrayRef<const Access *> uses);

  // Op handles: their accessors are not const.
  mutable func::FuncOp function;
  mutable scf::ParallelOp loop;
  SmallVector<Access> accesses;
  StringRef set;
};

LogicalResult LoopClassifier::collectAccesses() {
  WalkResult result = loop.getRegion().walk([&](Operation *op) {
    auto record = [&](Value memref, ValueRange indices, unsigned vectorRank,
                      bool writes) {
      if (!isPrivate(memref))
        accesses.push_back(
            {op, memref, llvm::to_vector(indices), vectorRank, writes});
    };
    if (auto load = dyn_cast<memref::LoadOp>(op)) {
      record(load.getMemRef(), load.getIndices(), 0, false);
    } else if (auto store = dyn_cast<memref::StoreOp>(op)) {
      record(store.getMemRef(), store.getIndices(), 0, true);
    } else if (auto load = dyn_cast<vector::LoadOp>(op)) {
      record(load.getBase(), load.getIndices(),
             load.getVectorType().getRank(), false);
    } else if (auto store = dyn_cast<vector::StoreOp>(op)) {
      record(store.getBase(), store.getIndices(),
             store.getVectorType().getRank(), true);
    } else if (isa<memref::PrefetchOp>(op)) {
      // A prefetch changes no value, wherever it points.
    } else if (auto call = dyn_cast<func::CallOp>(op);
               call && call.getCallee() == kRuntimeFail) {
      // A failed assertion (simit-lower-assertions): inside a parallel
      // region the runtime records it and the region's end raises it.
    } else if (!op->hasTrait<OpTrait::HasRecursiveMemoryEffects>()) {
      // Anything else may only touch memory private to the iteration (its
      // stack slots and temporaries); a call, or an effect on memory the
      // loop does not own, keeps the loop sequential.
      auto effects = dyn_cast<MemoryEffectOpInterface>(op);
      if (!effects)
        return WalkResult::interrupt();
      SmallVector<MemoryEffects::EffectInstance> instances;
      effects.getEffects(instances);
      for (const MemoryEffects::EffectInstance &effect : instances) {
        Value value = effect.getValue();
        if (!value || !isa<MemRefType>(value.getType()) || !isPrivate(value))
          return WalkResult::interrupt();
      }
    }
    return WalkResult::advance();
  });
  if (result.wasInterrupted())
    return failure();
  // Two different views of one buffer would hide a shared location.
  DenseMap<Value, Value> viewOfRoot;
  DenseSet<Value> writtenRoots;
  for (const Access &access : accesses) {
    Value root = access.memref;
    while (auto view = root.getDefiningOp<ViewLikeOpInterface>())
      root = view.getViewSource();
    auto [it, inserted] = viewOfRoot.try_emplace(root, access.memref);
    if (!inserted && it->second != access.memref)
      it->second = Value();
    if (access.writes)
      writtenRoots.insert(root);
  }
  for (Value root : writtenRoots)
    if (!viewOfRoot.lookup(root))
      return failure();
  return success();
}

IndexOwner LoopClassifier::ownerOf(Value index) const {
  ValueRange ivs = loop.getInductionVars();
  for (auto [dim, iv] : llvm::enumerate(ivs))
    if (index == iv)
      return {IndexOwner::Kind::Iteration, static_cast<unsigned>(dim), {}};

  // for k = rowptr[iv] to rowptr[iv + 1]
  if (auto forLoop = scf::getForInductionVarOwner(index)) {
    memref::LoadOp lower = castLoad(forLoop.getLowerBound());
    memref::LoadOp upper = castLoad(forLoop.getUpperBound());
    if (!lower || !upper || lower.getMemRef() != upper.getMemRef() ||
        lower.getIndices().size() != 1 || !matchPattern(forLoop.getStep(), m_One()) ||
        !bindingString(bindingOf(function, lower.getMemRef()), "kind")
             .ends_with("_rowptr"))
      return {};
    auto next = upper.getIndices()[0].getDefiningOp<arith::AddIOp>();
    for (auto [dim, iv] : llvm::enumerate(ivs)) {
      if (lower.getIndices()[0] != iv || !next)
        continue;
      if ((next.getLhs() == iv && matchPattern(next.getRhs(), m_One())) ||
          (next.getRhs() == iv && matchPattern(next.getLhs(), m_One())))
        return {IndexOwner::Kind::RowRange, static_cast<unsigned>(dim),
                lower.getMemRef()};
    }
    return {};
  }

  // endpoints[iv, k] or locations[iv, k] of the loop's element.
  memref::LoadOp load = castLoad(index);
  if (!load || ivs.size() != 1 || load.getIndices().size() != 2 ||
      load.getIndices()[0] != ivs[0] ||
      !matchPattern(load.getIndices()[1], m_Constant()))
    return {};
  StringRef kind = bindingString(bindingOf(function, load.getMemRef()), "kind");
  if (kind == "endpoints")
    return {IndexOwner::Kind::Endpoint, 0, load.getMemRef()};
  if (kind == "pattern_locations")
    return {IndexOwner::Kind::Location, 0, load.getMemRef()};
  return {};
}

/// The positions of an access that keep the iterations' locations apart:
/// one per induction variable (a vector access must not span them).
std::optional<SmallVector<Place>>
LoopClassifier::ownedPlaces(const Access &access) const {
  SmallVector<Place> places;
  unsigned scalarDims = access.indices.size() - access.vectorRank;
  for (unsigned dim = 0; dim < loop.getNumLoops(); ++dim) {
    std::optional<Place> found;
    for (unsigned position = 0; position < scalarDims && !found; ++position) {
      IndexOwner owner = ownerOf(access.indices[position]);
      if (owner.ownedByIteration() && owner.dim == dim)
        found = Place{position, owner};
    }
    if (!found)
      return std::nullopt;
    places.push_back(*found);
  }
  return places;
}

/// The position of an access indexed by an endpoint of the element, or by
/// the location of a block between two of its endpoints.
std::optional<Place>
LoopClassifier::endpointPlace(const Access &access) const {
  unsigned scalarDims = access.indices.size() - access.vectorRank;
  for (unsigned position = 0; position < scalarDims; ++position) {
    IndexOwner owner = ownerOf(access.indices[position]);
    if (owner.sharedThroughEndpoints() &&
        bindingString(bindingOf(function, owner.table), "set") == set)
      return Place{position, owner};
  }
  return std::nullopt;
}

/// The load whose value `store` adds to at the location it reads, when
/// that load and the sum are used for nothing else.
static Operation *accumulatedLoad(Operation *store) {
  std::optional<Accumulation> acc = matchAccumulation(store);
  if (!acc || !acc->combine->hasOneUse() || !acc->load->hasOneUse())
    return nullptr;
  return acc->load;
}

/// Elements run colour by colour, not in set order, so an element must not
/// see another's writes: every write adds to the value read at its own
/// location (an accumulation, whose other writers' contributions then
/// commute, or with `reduce +` are summed in a fixed order), and every read
/// is such an accumulation's, used for nothing else. An element reading an
/// endpoint other than to add to it (`p(1).x = p(0).x`, `p(1).h = p(1).h +
/// p(0).h`, `w(p(0)) = k * w(p(0))`), or overwriting one (a map without
/// `reduce`, where the last writer in set order wins), runs in set order.
bool LoopClassifier::onlyAccumulates(ArrayRef<const Access *> uses) {
  SmallPtrSet<Operation *, 8> accumulationLoads;
  for (const Access *access : uses) {
    if (!access->writes)
      continue;
    Operation *load = accumulatedLoad(access->op);
    if (!load)
      return false;
    accumulationLoads.insert(load);
  }
  return llvm::all_of(uses, [&](const Access *access) {
    return access->writes || accumulationLoads.contains(access->op);
  });
}

/// A loop over all elements of a set, in order: `for e = 0 to |set|`.
bool LoopClassifier::isElementLoop() {
  if (loop.getNumLoops() != 1 || !matchPattern(loop.getLowerBound()[0], m_Zero()) ||
      !matchPattern(loop.getStep()[0], m_One()))
    return false;
  DictionaryAttr size = bindingOf(function, loop.getUpperBound()[0]);
  if (bindingString(size, "kind") != "set_size")
    return false;
  set = bindingString(size, "set");
  return !set.empty();
}

LoopKind LoopClassifier::classify() {
  if (failed(collectAccesses()))
    return LoopKind::Serial;
  bool elementLoop = isElementLoop();
  // Each memref the loop writes must be accessed through one place, the
  // same in every access.
  llvm::MapVector<Value, SmallVector<const Access *>> byMemref;
  for (const Access &access : accesses)
    byMemref[access.memref].push_back(&access);
  bool scatters = false;
  for (auto &[memref, uses] : byMemref) {
    if (llvm::none_of(uses, [](const Access *a) { return a->writes; }))
      continue;
    auto owned = ownedPlaces(*uses.front());
    if (owned && llvm::all_of(uses, [&](const Access *a) {
          return ownedPlaces(*a) == owned;
        }))
      continue;
    if (!elementLoop)
      return LoopKind::Serial;
    auto shared = endpointPlace(*uses.front());
    if (!shared || llvm::any_of(uses, [&](const Access *a) {
          return !(endpointPlace(*a) == shared);
        }))
      return LoopKind::Serial;
    if (!onlyAccumulates(uses))
      return LoopKind::Serial;
    scatters = true;
  }
  if (scatters)
    return loop.getNumResults() == 0 ? LoopKind::Scatter : LoopKind::Serial;
  if (loop.getNumResults() == 0)
    return LoopKind::Owned;
  return LoopKind::Reduction;
}

/// The combining operation of a reduction region (`^bb(a, b): return
/// op(a, b)`) when it has a neutral element, else null.
Operation *matchCombiner(Region &reduction) {
  Block &block = reduction.front();
  auto yield = dyn_cast<scf::ReduceReturnOp>(block.getTerminator());
  if (!yield || block.getOperations().size() != 2)
    return nullptr;
  Operation *combine = yield.getResult().getDefiningOp();
  if (!combine || combine->getBlock() != &block ||
      combine->getNumOperands() != 2 ||
      !llvm::is_contained(combine->getOperands(), block.getArgument(0)) ||
      !llvm::is_contained(combine->getOperands(), block.getArgument(1)) ||
      !arith::getNeutralElement(combine))
    return nullptr;
  return combine;
}

/// The value `n` with `combine(n, x) == x` for every x. For addf that is
/// -0.0 (arith::getNeutralElement gives 0.0, which turns a sum of -0.0 into
/// 0.0).
TypedAttr neutralElement(Operation *combine) {
  if (auto add = dyn_cast<arith::AddFOp>(combine))
    return FloatAttr::get(add.getType(), -0.0);
  return *arith::getNeutralElement(combine);
}

/// Iterations [first, last) of dimension 0 of `loop`, as bounds:
/// lb + first * step, lb + last * step.
std::pair<Value, Value> iterationBounds(OpBuilder &b, Location loc,
                                        scf::ParallelOp loop, Value first,
                                        Value last) {
  Value lb = loop.getLowerBound()[0], step = loop.getStep()[0];
  auto bound = [&](Value i) {
    return b.createOrFold<arith::AddIOp>(
        loc, lb, b.createOrFold<arith::MulIOp>(loc, i, step));
  };
  return {bound(first), bound(last)};
}

/// Runs `loop` (dimension 0 restricted to the iterations [first, last)) as
/// one sequential piece of the loop built around it.
void restrictToIterations(OpBuilder &b, Location loc, scf::ParallelOp loop,
                          Value first, Value last) {
  auto [lower, upper] = iterationBounds(b, loc, loop, first, last);
  loop.getLowerBoundMutable()[0].assign(lower);
  loop.getUpperBoundMutable()[0].assign(upper);
}

class ParallelLoops
    : public mlir::simit::impl::SimitParallelLoopsBase<ParallelLoops> {
public:
  using Base::Base;

  void runOnOperation() override {
    if (reductionChunk < 1 || scatterChunk < 1) {
      getOperation().emitError("chunk sizes must be positive");
      return signalPassFailure();
    }
    for (auto function : getOperation().getOps<func::FuncOp>()) {
      if (function.isExternal())
        continue;
      SmallVector<scf::ParallelOp> outermost;
      function.walk([&](scf::ParallelOp loop) {
        if (!loop->getParentOfType<scf::ParallelOp>())
          outermost.push_back(loop);
      });
      for (scf::ParallelOp loop : outermost)
        parallelize(function, loop);
    }
  }

private:
  void parallelize(func::FuncOp function, scf::ParallelOp loop);
  void chunkReduction(scf::ParallelOp loop);
  static void runInSetOrder(scf::ParallelOp loop);
  void colourScatter(func::FuncOp function, scf::ParallelOp loop,
                     StringRef set);
  Value elementColours(func::FuncOp function, StringRef set);
  static void markParallel(scf::ParallelOp loop, StringRef kind) {
    loop->setAttr(kParallelLoopAttr,
                  StringAttr::get(loop.getContext(), kind));
  }
};

/// Loops with a small constant trip count cost more to start on other
/// threads than they take.
bool isSmallConstantLoop(scf::ParallelOp loop) {
  int64_t trips = 1;
  for (auto [lb, ub, step] :
       llvm::zip(loop.getLowerBound(), loop.getUpperBound(), loop.getStep())) {
    std::optional<int64_t> l = getConstantIntValue(lb),
                           u = getConstantIntValue(ub),
                           s = getConstantIntValue(step);
    if (!l || !u || !s || *s <= 0)
      return false;
    trips *= std::max<int64_t>(0, llvm::divideCeil(*u - *l, *s));
  }
  return trips <= 4096;
}

void ParallelLoops::parallelize(func::FuncOp function, scf::ParallelOp loop) {
  if (setOrderOnly) {
    if (loop->hasAttr("simit.scatter") && loop.getNumResults() == 0 &&
        loop.getNumLoops() == 1 &&
        LoopClassifier(function, loop).classify() == LoopKind::Serial)
      runInSetOrder(loop);
    return;
  }
  if (isSmallConstantLoop(loop))
    return;
  LoopClassifier classifier(function, loop);
  switch (classifier.classify()) {
  case LoopKind::Serial:
    return;
  case LoopKind::Owned:
    return markParallel(loop, kOwnedLoop);
  case LoopKind::Reduction:
    return chunkReduction(loop);
  case LoopKind::Scatter:
    return colourScatter(function, loop, classifier.elementSet());
  }
}

void ParallelLoops::runInSetOrder(scf::ParallelOp loop) {
  // One iteration, whose body is the loop as an scf.for.
  Location loc = loop.getLoc();
  OpBuilder b(loop);
  Value zero = arith::ConstantIndexOp::create(b, loc, 0);
  Value one = arith::ConstantIndexOp::create(b, loc, 1);
  auto single = scf::ParallelOp::create(b, loc, ValueRange{zero},
                                        ValueRange{one}, ValueRange{one});
  b.setInsertionPoint(single.getBody()->getTerminator());
  auto inOrder = scf::ForOp::create(b, loc, loop.getLowerBound()[0],
                                    loop.getUpperBound()[0], loop.getStep()[0]);
  Block *body = loop.getBody();
  body->getTerminator()->erase();
  inOrder.getBody()->getOperations().splice(inOrder.getBody()->begin(),
                                            body->getOperations());
  loop.getInductionVars()[0].replaceAllUsesWith(inOrder.getInductionVar());
  loop.erase();
}

void ParallelLoops::chunkReduction(scf::ParallelOp loop) {
  auto reduce = cast<scf::ReduceOp>(loop.getBody()->getTerminator());
  SmallVector<Operation *> combiners;
  for (Region &region : reduce.getReductions()) {
    Operation *combine = matchCombiner(region);
    if (!combine)
      return;
    combiners.push_back(combine);
  }

  Location loc = loop.getLoc();
  OpBuilder b(loop);
  Value zero = arith::ConstantIndexOp::create(b, loc, 0);
  Value one = arith::ConstantIndexOp::create(b, loc, 1);
  Value chunk = arith::ConstantIndexOp::create(b, loc, reductionChunk);
  Value trips = tripCount(b, loc, loop.getLowerBound()[0],
                          loop.getUpperBound()[0], loop.getStep()[0]);
  Value numChunks = b.createOrFold<arith::CeilDivUIOp>(loc, trips, chunk);
  SmallVector<Value> partials;
  for (Type type : loop.getResultTypes())
    partials.push_back(memref::AllocOp::create(
        b, loc, MemRefType::get({ShapedType::kDynamic}, type), numChunks));
  SmallVector<Value> initial = loop.getInitVals();

  // Each chunk reduces its iterations, in order, starting from the neutral
  // element, into its partial.
  auto chunks = scf::ParallelOp::create(
      b, loc, zero, numChunks, one, [&](OpBuilder &, Location, ValueRange) {});
  markParallel(chunks, kReductionLoop);
  b.setInsertionPointToStart(chunks.getBody());
  Value c = chunks.getInductionVars()[0];
  Value first = arith::MulIOp::create(b, loc, c, chunk);
  Value last = arith::MinUIOp::create(
      b, loc, arith::AddIOp::create(b, loc, first, chunk), trips);
  restrictToIterations(b, loc, loop, first, last);
  for (auto [i, combine] : llvm::enumerate(combiners))
    loop.getInitValsMutable()[i].assign(
        arith::ConstantOp::create(b, loc, neutralElement(combine)));
  loop->moveBefore(chunks.getBody()->getTerminator());
  b.setInsertionPointAfter(loop);
  for (auto [partial, value] : llvm::zip(partials, loop.getResults()))
    memref::StoreOp::create(b, loc, value, partial, c);

  // The partials combine in chunk order.
  b.setInsertionPointAfter(chunks);
  auto combineLoop = scf::ForOp::create(
      b, loc, zero, numChunks, one, initial,
      [&](OpBuilder &nested, Location, Value k, ValueRange accumulated) {
        SmallVector<Value> next;
        for (auto [combine, partial, acc] :
             llvm::zip(combiners, partials, accumulated)) {
          IRMapping mapping;
          Block *block = combine->getBlock();
          mapping.map(block->getArgument(0), acc);
          mapping.map(block->getArgument(1),
                      memref::LoadOp::create(nested, loc, partial, k));
          next.push_back(nested.clone(*combine, mapping)->getResult(0));
        }
        scf::YieldOp::create(nested, loc, next);
      });
  for (auto [oldResult, newResult] :
       llvm::zip(loop.getResults(), combineLoop.getResults()))
    oldResult.replaceUsesWithIf(newResult, [&](OpOperand &use) {
      return !chunks->isAncestor(use.getOwner());
    });
}

Value ParallelLoops::elementColours(func::FuncOp function, StringRef set) {
  MLIRContext *ctx = function.getContext();
  OpBuilder b(ctx);
  NamedAttribute entries[] = {
      b.getNamedAttr("chunk", b.getI64IntegerAttr(scatterChunk)),
      b.getNamedAttr("kind",
                     b.getStringAttr(::simit::abi::spelling(
                         ::simit::abi::BindingKind::ElementColours))),
      b.getNamedAttr("set", b.getStringAttr(set))};
  auto binding = DictionaryAttr::get(ctx, entries);
  auto bindings = function->getAttrOfType<ArrayAttr>(
      StringRef(::simit::abi::kBindingsAttr));
  for (auto [i, existing] : llvm::enumerate(bindings))
    if (existing == binding)
      return function.getArgument(i);
  unsigned index = function.getNumArguments();
  Type type = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  if (failed(function.insertArgument(index, type, DictionaryAttr(),
                                     function.getLoc())))
    return {};
  SmallVector<Attribute> entriesAfter(bindings.begin(), bindings.end());
  entriesAfter.push_back(binding);
  function->setAttr(StringRef(::simit::abi::kBindingsAttr),
                    ArrayAttr::get(ctx, entriesAfter));
  return function.getArgument(index);
}

void ParallelLoops::colourScatter(func::FuncOp function, scf::ParallelOp loop,
                                  StringRef set) {
  Value colours = elementColours(function, set);
  if (!colours)
    return;
  // colours = [K, start_0, ..., start_K, chunks of colour 0, ...]: the
  // chunks of colour c are colours[start_c .. start_(c+1)].
  Location loc = loop.getLoc();
  OpBuilder b(loop);
  auto read = [&](Value position) {
    Value word = memref::LoadOp::create(b, loc, colours, position);
    return arith::IndexCastOp::create(b, loc, b.getIndexType(), word);
  };
  Value zero = arith::ConstantIndexOp::create(b, loc, 0);
  Value one = arith::ConstantIndexOp::create(b, loc, 1);
  Value two = arith::ConstantIndexOp::create(b, loc, 2);
  Value chunk = arith::ConstantIndexOp::create(b, loc, scatterChunk);
  Value trips = loop.getUpperBound()[0];
  Value numColours = read(zero);
  auto colourLoop = scf::ForOp::create(b, loc, zero, numColours, one);
  b.setInsertionPointToStart(colourLoop.getBody());
  Value colour = colourLoop.getInductionVar();
  Value start = read(arith::AddIOp::create(b, loc, colour, one));
  Value end = read(arith::AddIOp::create(b, loc, colour, two));
  auto chunks = scf::ParallelOp::create(
      b, loc, start, end, one, [&](OpBuilder &, Location, ValueRange) {});
  markParallel(chunks, kScatterLoop);
  b.setInsertionPointToStart(chunks.getBody());
  Value first = arith::MulIOp::create(
      b, loc, read(chunks.getInductionVars()[0]), chunk);
  Value last = arith::MinUIOp::create(
      b, loc, arith::AddIOp::create(b, loc, first, chunk), trips);
  restrictToIterations(b, loc, loop, first, last);
  loop->moveBefore(chunks.getBody()->getTerminator());
}
} // namespace
