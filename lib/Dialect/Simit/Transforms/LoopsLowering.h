//===- LoopsLowering.h - State of the simit-to-loops lowering ---*- C++ -*-===//
//
// convert-simit-to-loops rebuilds every exported function op by op: a value
// map takes each simit value to its lowered form, each system matrix is
// stored as its type's encoding says, and bindings become new function
// arguments as the lowering first needs them. The implementation is split
// by subject: ConvertSimitToLoops.cpp (driver, types, op dispatch),
// LoopStorage.cpp (layouts of encodings, containment, joins), LoopBindings.cpp
// (function arguments), LowerControlFlow.cpp (scf ops), LowerSystemOps.cpp
// (host-level ops on system tensors), LowerLocalTensors.cpp (small dense
// tensors as flat vectors), LowerMaps.cpp (map/assemble as set loops),
// LowerGridStencils.cpp (maps through grids), LowerMatrixBlocks.cpp (blocks and
// slices of matrices), LowerConvert.cpp (simit.convert), LowerIndexExpr.cpp and
// IndexExprLoops.cpp (index expressions as loop nests),
// LowerProducts.cpp (matrix products), LowerSolvers.cpp (solves and
// factorisations), LowerHostCalls.cpp (extern funcs),
// LowerRuntimePatterns.cpp (patterns known only at run time),
// LowerPrint.cpp (printing and strings) and LowerCheckNumerics.cpp (scans
// of results for --check-numerics).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_LOOPSLOWERING_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_LOOPSLOWERING_H

#include "RuntimeFunction.h"

#include "simit/ABI/BindingKind.h"
#include "simit/Dialect/Simit/IR/SimitStorage.h"
#include "simit/Dialect/Simit/Transforms/LoopsTypeConverter.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/IR/Builders.h"
#include "llvm/ADT/MapVector.h"
#include "llvm/ADT/SetVector.h"
#include "llvm/ADT/StringMap.h"

#include <array>
#include <functional>
#include <optional>
#include <tuple>

namespace mlir {
namespace simit {
namespace loops {

/// How a system tensor is stored (its sparsity).
/// A chain of factors of a product over (rows, cols): each factor's edge
/// sets (a pattern or a union of patterns), factor i over (mids[i-1],
/// mids[i]), the first from rows, the last to cols.
struct ProductChain {
  SmallVector<SmallVector<StringAttr, 2>, 3> factors;
  SmallVector<StringAttr, 2> mids;

  bool operator==(const ProductChain &o) const {
    return factors == o.factors && mids == o.mids;
  }
  /// An order to keep a product's chains sorted by.
  bool operator<(const ProductChain &o) const;
};

struct Storage {
  enum class Kind {
    /// A vector (or tensor with one set dimension): one block per element.
    Dense,
    /// A matrix over (set, set) with only diagonal blocks: block r is (r, r).
    Diagonal,
    /// A BCSR matrix over (rows, cols) on the pattern of an edge set.
    Pattern,
    /// A matrix over (points, points) assembled through a grid: one dense
    /// array of blocks per stencil offset, block k * |points| + r is
    /// (r, r + offsets[k]) with periodic wrap-around; no index arrays.
    Stencil,
    /// A matrix over (edges, endpoint set) assembled from the edge set:
    /// row e holds one block per endpoint, block e * c + k at column
    /// endpoint_k(e) (the edge set's endpoint array is the column index).
    /// Transposed (`transposed`): over (endpoint set, edges), block e * c + k
    /// is (endpoint_k(e), e), still written edge by edge without conflicts.
    Incidence,
    /// A BCSR matrix over (rows, cols) on the union of the patterns of
    /// several edge sets (`members`): a sum of matrices assembled from
    /// different edge sets. Built once per binding by the runtime
    /// (simit::unionPattern), with gather maps from it to its parts.
    Union,
    /// A BCSR matrix over (rows, cols) on the pattern of a product of two
    /// or more patterns or unions (a ProductChain), whichever way the
    /// product is associated, each square part with the diagonal; or on the
    /// union of the patterns of several such chains and of patterns (a
    /// chain of one factor): a sum of products, `P + P'`. Built once per
    /// binding (simit::chainProductPattern, simit::unionPattern). A factor
    /// may be an incidence or its transpose: its edge set is then its rows
    /// or cols.
    Product,
    /// A matrix over (rows, cols) with every block stored: block
    /// r * |cols| + c is (r, c). The solution of `lumatsolve` and
    /// `lltmatsolve` (A^-1 B is dense); no index arrays.
    DenseMatrix,
    /// A BCSR matrix over (rows, cols) on a pattern known only at run
    /// time (`runtimeEncoding`): one a host function returned (`edges`
    /// names the function), or a product or sum with one, whose pattern
    /// the runtime builds each time it is computed. Its row pointers and
    /// column indices are arrays the lowering made, not bindings
    /// (FunctionLowering::runtimePatterns).
    Host
  };
  Kind kind = Kind::Dense;
  /// Diagonal: rows == cols == the set. Pattern: the edge set and the two
  /// endpoint sets. Stencil: the grid and its point set (rows == cols).
  /// Incidence: rows == edges, cols the endpoint set.
  StringAttr edges, rows, cols;
  /// Stencil: the point offsets (one DenseI64ArrayAttr of grid-rank
  /// entries each), sorted and unique.
  ArrayAttr offsets;
  /// Incidence: blocks per row, one per endpoint position of the edge set
  /// in the endpoint set: the cardinality, or the size of `positions`.
  int64_t cardinality = 0;
  /// Incidence: the endpoint positions in the endpoint set, ascending, when
  /// they are not all of them (a heterogeneous edge set: `matrix[E,W]` of
  /// `E(V,W)` holds position 1); empty for all.
  SmallVector<int64_t, 4> positions;
  /// Incidence: stored over (endpoint set, edges).
  bool transposed = false;
  /// Union: the member edge sets, sorted by name, at least two.
  SmallVector<StringAttr, 2> members;
  /// Product: its chains, sorted and unique.
  SmallVector<ProductChain, 0> chains;
  /// Host: the encoding, which names the pattern.
  StorageAttr runtimeEncoding;

  static Storage dense() { return Storage(); }
  static Storage diagonal(StringAttr set) {
    return Storage{Kind::Diagonal, nullptr, set, set};
  }
  static Storage pattern(StringAttr edges, StringAttr rows, StringAttr cols) {
    return Storage{Kind::Pattern, edges, rows, cols};
  }
  static Storage stencil(StringAttr grid, StringAttr points,
                         ArrayAttr offsets) {
    return Storage{Kind::Stencil, grid, points, points, offsets};
  }
  static Storage denseMatrix(StringAttr rows, StringAttr cols) {
    return Storage{Kind::DenseMatrix, nullptr, rows, cols};
  }
  /// A pattern known at run time: `encoding` is host(...) or holds one.
  static Storage runtimePattern(StorageAttr encoding, StringAttr rows,
                                StringAttr cols) {
    Storage s{Kind::Host, nullptr, rows, cols};
    if (encoding.getKind() == StorageKind::Host)
      s.edges = encoding.getSet();
    s.runtimeEncoding = encoding;
    return s;
  }
  /// The incidence of an edge set of `cardinality` endpoints over (edges,
  /// cols), cols at endpoint `positions` (all when empty).
  static Storage incidence(StringAttr edges, StringAttr cols,
                           int64_t cardinality,
                           ArrayRef<int64_t> positions = {}) {
    Storage s{Kind::Incidence, edges, edges, cols, nullptr, cardinality};
    if (!positions.empty() &&
        static_cast<int64_t>(positions.size()) != cardinality) {
      s.cardinality = positions.size();
      s.positions.assign(positions.begin(), positions.end());
    }
    return s;
  }
  /// The incidence over (rows, edges): the transpose of incidence(edges,
  /// rows, ...) in the same layout.
  static Storage incidenceTransposed(const Storage &incidence) {
    Storage s = incidence;
    std::swap(s.rows, s.cols);
    s.transposed = !incidence.transposed;
    return s;
  }
  /// The union of the patterns of `edgeSets` over (rows, cols): a pattern
  /// for one edge set.
  static Storage unionOf(ArrayRef<StringAttr> edgeSets, StringAttr rows,
                         StringAttr cols);
  bool isMatrix() const { return kind != Kind::Dense; }
  /// Whether the matrix is a BCSR array with row pointers and column
  /// indices (rowPointers/columnIndices of FunctionLowering).
  bool isBCSR() const {
    return kind == Kind::Pattern || kind == Kind::Union ||
           kind == Kind::Product || kind == Kind::Host;
  }
  /// Whether the storage is a pattern or union of edge sets' patterns:
  /// gather maps between two such over the same sets are built once per
  /// binding (union_gather, keyed by their edge sets).
  bool hasGatherMaps() const {
    return kind == Kind::Pattern || kind == Kind::Union;
  }
  /// The edge sets whose patterns this storage is the union of (pattern or
  /// union).
  SmallVector<StringAttr, 2> patternSets() const;
  bool operator==(const Storage &o) const {
    return kind == o.kind && edges == o.edges && rows == o.rows &&
           cols == o.cols && offsets == o.offsets &&
           cardinality == o.cardinality && positions == o.positions &&
           transposed == o.transposed && members == o.members &&
           chains == o.chains && runtimeEncoding == o.runtimeEncoding;
  }
  bool operator!=(const Storage &o) const { return !(*this == o); }
  /// Whether every block of `o` is a block of this storage (an edge pattern
  /// over (V, V) holds the whole diagonal of V).
  bool contains(const Storage &o) const;
  std::string describe() const;
};

/// Whether a matrix stored as `s` can be read as BCSR arrays
/// (FunctionLowering::bcsrArrays): a BCSR storage, or a square diagonal,
/// stencil or dense one.
bool hasBCSRView(const Storage &s);

/// Whether a pattern known at run time depends on the bound sets alone (a
/// union or transpose of patterns, stencils and diagonals, no host
/// function's matrix): it is built once where the function's body starts
/// to need it, so values stored on it can be carried by loops, ifs and
/// variable slots.
bool isBindingPattern(StorageAttr runtimeEncoding);

/// Bytes of one stored component (a complex one holds two parts; a bool
/// takes a byte).
inline int64_t componentBytes(Type component) {
  if (auto complex = dyn_cast<ComplexType>(component))
    return 2 * componentBytes(complex.getElementType());
  if (component.isIntOrFloat())
    return std::max<int64_t>(1, component.getIntOrFloatBitWidth() / 8);
  return 8;
}

/// lhs op rhs of float, int or complex numbers, scalars or vectors, by the
/// op of their kind.
template <typename ComplexOp, typename FloatOp, typename IntOp>
Value combineNumbers(OpBuilder &b, Location loc, Value lhs, Value rhs) {
  if (isa<ComplexType>(lhs.getType()))
    return ComplexOp::create(b, loc, lhs, rhs);
  if (isa<FloatType>(getElementTypeOrSelf(lhs.getType())))
    return FloatOp::create(b, loc, lhs, rhs);
  return IntOp::create(b, loc, lhs, rhs);
}
/// lhs + rhs and lhs * rhs (ints wrap, as the language's do).
inline Value addNumbers(OpBuilder &b, Location loc, Value lhs, Value rhs) {
  return combineNumbers<complex::AddOp, arith::AddFOp, arith::AddIOp>(b, loc,
                                                                      lhs, rhs);
}
inline Value multiplyNumbers(OpBuilder &b, Location loc, Value lhs, Value rhs) {
  return combineNumbers<complex::MulOp, arith::MulFOp, arith::MulIOp>(b, loc,
                                                                      lhs, rhs);
}

/// The storage of the transpose of a matrix stored as `s` (a pattern over
/// (C, R) for one over (R, C): the same endpoint pairs, swapped; a stencil
/// of the negated offsets); none for products and incidences.
std::optional<Storage> transposedStorage(const Storage &s);

/// The smallest storage holding the blocks of both `a` and `b`: the one
/// that contains the other, or the union of their patterns over the same
/// sets; none when neither holds and they do not combine.
std::optional<Storage> joinStorages(const Storage &a, const Storage &b);

/// The storage the loop lowering gives a matrix over (rows, cols) whose type
/// carries `encoding` (simit-assign-storage), or none where it has no layout
/// for the encoding. `sets` gives the types of the edge sets and grids the
/// encoding names.
std::optional<Storage>
storageOfEncoding(StorageAttr encoding, StringAttr rows, StringAttr cols,
                  const DenseMap<StringAttr, SetType> &sets);

/// The kinds of function arguments of a lowered exported function.
using BindingKind = ::simit::abi::BindingKind;

/// What is known of the element function being inlined into a set loop.
struct ElementContext {
  /// The mapped set and the loop's element index.
  SetType set;
  Value element;
  /// The lowered output arrays of the map's results and their storage.
  SmallVector<Value> outputs;
  SmallVector<Storage> outputStorages;
  /// Whether writes to results combine with the reduction (assemble) or
  /// store (map).
  bool accumulate = false;
  ReductionKind reduction = ReductionKind::Add;
  /// The element function's values that stand for one of its results
  /// (the result position): they are not materialised; every insert into
  /// one scatters into the output.
  DenseMap<Value, unsigned> sinks;
  /// The element function's variables (simit.alloc) holding a scalar
  /// result, by result position: they are the output itself, so a store
  /// combines into it and a load reads the accumulated value.
  DenseMap<Value, unsigned> scalarSlots;
  /// Whether some write goes to a location shared with other elements.
  bool scatters = false;
  /// The results (positions) that accumulate into blocks of a Pattern
  /// matrix, with the positions in the element's location table row they
  /// accumulate into (none: positions not known when lowering, all of
  /// them): those blocks are prefetched at the start of the element.
  llvm::MapVector<unsigned, llvm::SmallSetVector<int64_t, 16>>
      patternAccumulations;
};

class FunctionLowering {
public:
  FunctionLowering(ModuleOp module, func::FuncOp function);

  /// Lowers the original function into `function`'s new body.
  LogicalResult run(func::FuncOp original);

  //===--- Values and types ---------------------------------------------===//

  /// The lowered type of a simit value type (LoopsTypeConverter), or null
  /// when unsupported.
  Type convertType(Type type);
  Value lookup(Value original);
  void map(Value original, Value lowered) { values[original] = lowered; }
  /// How `original` is stored: by the encoding of its type (or of the
  /// type a variable holds), dense for vectors; a value whose type has no
  /// encoding (a runtime function's operand, an element function's
  /// parameter) is stored like the value it stands for (`alias`).
  Storage storageOf(Value original);
  void alias(Value original, Value source) {
    storages[original] = storageOf(source);
  }
  /// Gives `to`, when its type has no encoding (a value of an element
  /// function, a loop-carried value there), the storage of `from`.
  void carryStorage(Value to, Value from);
  /// Whether `original` is a result slot of the element function being
  /// inlined (it has no lowered value).
  bool isSink(Value original) const {
    return element && element->sinks.count(original);
  }

  //===--- Blocks and operations ----------------------------------------===//

  /// Lowers the operations of `block` except its terminator at the
  /// builder's insertion point.
  LogicalResult lowerOps(Block &block);
  LogicalResult lowerOp(Operation *op);

  //===--- Bindings (arguments of the lowered function) -----------------===//

  Value getSetSize(StringAttr set);
  Value getField(StringAttr set, StringAttr field, Type fieldType);
  Value getEndpoints(SetType set);
  Value getEndpoints(StringAttr set, int64_t cardinality);
  /// The columns of an incidence storage, or its rows when transposed: per
  /// edge its endpoints at the storage's positions (memref<?x c x i32>).
  Value incidenceEndpoints(const Storage &storage);
  /// A BCSR array of the pattern of (edges; rows, cols); the location table
  /// needs the edge set's cardinality.
  Value getPatternArray(BindingKind kind, StringAttr edges, StringAttr rows,
                        StringAttr cols, int64_t cardinality = 0);
  /// The row pointers and column indices of a BCSR storage (pattern or
  /// union; Storage::isBCSR).
  Value rowPointers(const Storage &storage);
  Value columnIndices(const Storage &storage);
  /// The rows of an incidence storage (or its transpose) as the runtime's
  /// product reads them: per row its first block, per block its column and
  /// value position (incidence_* bindings, simit::IncidenceView).
  std::array<Value, 3> incidenceRows(const Storage &storage);
  /// A stencil matrix `array` as BCSR for the runtime's sparse solvers:
  /// the bind-time pattern of the stencil (stencil_* bindings,
  /// simit::StencilPattern) and a fresh array of values on it.
  std::array<Value, 3> stencilAsBCSR(Location loc, const Storage &storage,
                                     Value array);
  /// The bind-time BCSR pattern of a stencil storage: row pointers, column
  /// indices, and the BCSR position of each of the stencil's blocks.
  std::array<Value, 3> stencilPattern(const Storage &storage);
  /// The BCSR row pointers and column indices of a matrix stored as
  /// `storage` (hasBCSRView): its own, a stencil's bind-time pattern, or
  /// arrays of the pattern of a diagonal or dense layout made here.
  std::pair<Value, Value> bcsrIndexArrays(Location loc, const Storage &storage);
  /// The BCSR row pointers, column indices and blocks of `matrix`, stored
  /// as `storage` (hasBCSRView): its own, or for a diagonal or dense
  /// matrix arrays of its layout's pattern made here and its blocks, for a
  /// stencil its bind-time pattern and a copy of its blocks on it.
  std::array<Value, 3> bcsrArrays(Location loc, const Storage &storage,
                                  Value matrix);
  /// Asserts, at run time, that a matrix stored as `storage` over two sets
  /// (that of the solve `what`) is square; nothing over one set.
  /// (Factorisations take matrix[N,N]: their verifier rules two sets out.)
  void assertSquare(Operation *op, const Storage &storage, StringRef what);
  /// An empty memref<?xi32> for runtime functions whose index arrays a
  /// layout does not use.
  Value emptyIndexArray();
  /// The gather map from a union storage to a BCSR storage it contains
  /// (`part`: one member's pattern or a smaller union): per union block
  /// position, the part's position of the block or -1 (memref<?xi32>).
  /// With `transposed`, the position of block (c, r) of `part` for each
  /// block (r, c) of `storage` (the part is read transposed).
  Value gatherMap(const Storage &storage, const Storage &part,
                  bool transposed = false);
  Value getExtern(ExternOp global);
  /// The extents of grid `grid` (memref<rank x i32>).
  Value getGridDims(StringAttr grid, unsigned rank);

  //===--- Helpers shared by the parts ----------------------------------===//

  Value indexConstant(int64_t value);
  /// The whole rank-1 `memref` as a vector, and the reverse: a vector.load
  /// or vector.store, except for bools, component by component: a
  /// vector<N x i1> in memory is N packed bits, while bool arrays (the
  /// host's, and scalar i1 loads) hold a byte per component.
  Value loadWhole(Location loc, VectorType type, Value memref);
  void storeWhole(Location loc, Value value, Value memref);
  /// Emits `body(i)` in a sequential scf.for over [0, upper).
  void forLoop(Location loc, Value upper, function_ref<void(Value)> body);
  Value zeroOf(Type scalarType);
  /// A fresh array for a system tensor of `type` stored as `storage`, zero
  /// filled unless the caller writes every component.
  Value allocSystem(Location loc, Type type, const Storage &storage,
                    bool zeroFill = true);
  /// The number of blocks of an array stored as `storage`.
  Value numBlocks(const Storage &storage, StringAttr denseSet);
  /// The memref indices of component `c` (flat, row major) of the block
  /// that `prefix` selects in an array of `type`.
  SmallVector<Value> blockIndices(MemRefType type, ArrayRef<Value> prefix,
                                  int64_t c);
  /// Prefetches block `block` of the block array `array`: a component in
  /// each cache line the block covers, and its last.
  void prefetchBlock(Location loc, Value array, Value block, bool isWrite);
  /// A stack slot of `type` at the start of `allocaBlock`: allocated once
  /// per function (or set loop body), however often the code that needs it
  /// runs, so the stack does not grow with a loop's iterations.
  Value allocaSlot(Location loc, MemRefType type);
  /// Fills an array with a scalar.
  void fill(Location loc, Value array, Value scalar);
  /// The set of element value `original`, if known.
  StringAttr elementSetOf(Value original);

  // Local tensors (LowerLocalTensors.cpp).
  LogicalResult lowerLocalOp(Operation *op, bool &handled);
  /// Component `position` (flat, row major) of `lowered`, the lowered
  /// value of a local tensor or scalar of type `type`: a complex component
  /// is rebuilt from its (re, im) pair.
  Value component(Type type, Value lowered, Value position);
  Value component(Type type, Value lowered, int64_t position);
  /// `lowered` (a flat vector) with component `position` set to `scalar`.
  Value insertComponent(Value lowered, Value scalar, Value position);
  /// The lowered local value made of `components` (complex ones stored as
  /// (re, im) pairs).
  Value fromComponents(Type loweredType, ArrayRef<Value> components);

  // Maps (LowerMaps.cpp).
  LogicalResult lowerMapLike(Operation *op);
  /// elem_read, elem_write and inserts into result slots.
  LogicalResult lowerElementAccess(Operation *op, bool &handled);

  // Grid stencils (LowerGridStencils.cpp).
  /// grid_point and grid_edge.
  LogicalResult lowerGridAccess(Operation *op);
  /// The block of a stencil matrix that a write or read `access` of the
  /// element function at `indices` goes to (the first offset naming the
  /// same point).
  FailureOr<Value> stencilBlockAt(Operation *access, ValueRange indices,
                                  const Storage &storage);
  /// Row `row`'s block for offset number `k` of a stencil matrix and the
  /// column it stands for.
  Value stencilBlock(const Storage &storage, Value row, Value k);
  Value stencilColumn(const Storage &storage, Value row, Value k);

  // Blocks of system matrices outside maps (LowerMatrixBlocks.cpp):
  // simit.extract / simit.insert at (row, col).
  LogicalResult lowerMatrixBlockAccess(Operation *op);
  /// simit.slice of a system matrix: a row A(p, :) or column A(:, q) as a
  /// system vector.
  LogicalResult lowerMatrixSlice(SliceOp op);
  /// The position of block (row, col) in a matrix stored as `storage`
  /// (diagonal, stencil or BCSR), or -1 where it stores none.
  Value findBlock(Location loc, const Storage &storage, Value row, Value col);
  /// Calls `body(endpoint, position)` for each block of edge `edge` in a
  /// matrix stored as incidence `storage` (or its transpose): the edge's
  /// k-th endpoint and block e * c + k, unrolled over the cardinality c.
  void forEachEdgeBlock(Location loc, const Storage &storage, Value edge,
                        function_ref<void(Value endpoint, Value position)>
                            body);
  /// The `n` components of block (row, col) of `array`, a matrix stored as
  /// `storage`: zeros where it stores no block, the sum of an incidence's
  /// blocks there.
  SmallVector<Value> readMatrixBlock(Location loc, const Storage &storage,
                                     Value array, Value row, Value col,
                                     int64_t n);
  /// The sum over the blocks of an incidence (or transposed incidence)
  /// matrix at (row, col) of `read(position)`: an edge naming one endpoint
  /// twice has two blocks there, and none is zero.
  Value sumIncidenceBlocks(Location loc, const Storage &storage, Value row,
                           Value col, Type scalar,
                           function_ref<Value(Value)> read);
  /// The sum over the blocks of row `row` of a stencil matrix whose offset
  /// names column `col` of `read(position)`: on a grid narrower than the
  /// offsets several do.
  Value sumStencilBlocks(Location loc, const Storage &storage, Value row,
                         Value col, Type scalar,
                         function_ref<Value(Value)> read);
  /// simit.convert: a matrix moved to a storage that contains its own.
  LogicalResult lowerConvert(ConvertOp op);
  /// The positions of blocks (row, col) of pattern matrices found so far.
  SmallVector<std::tuple<Storage, Value, Value, Value>> blockPositions;

  // --check-numerics (LowerCheckNumerics.cpp).
  /// Calls the runtime's scan of each float system tensor result of `op`,
  /// which simit-check-numerics marked, after `op` is lowered.
  LogicalResult scanForNonFinite(Operation *op);

  // Index expressions (LowerIndexExpr.cpp).
  /// With `at` (blockRead), lowers `op` with its block read: the block
  /// alone where it can (A(p,:) * x of a blocked A is (A x)(p)).
  LogicalResult lowerIndexExpr(IndexExprOp op, ExtractOp at = nullptr);
  /// The read of one block of `op`'s vector result when it is `op`'s only
  /// use and the next operation (so nothing runs between them): lowering
  /// `op` waits for it.
  ExtractOp blockRead(IndexExprOp op);

  ModuleOp module;
  func::FuncOp function;
  OpBuilder b;
  DenseMap<Value, Value> values;
  /// The types of the sets the function names, by name.
  DenseMap<StringAttr, SetType> setTypes;
  /// For lowered element values: the set they belong to, and for endpoints
  /// of the mapped edge the endpoint position (an index value).
  DenseMap<Value, StringAttr> elementSets;
  DenseMap<Value, Value> endpointPositions;
  /// Tuples: the edge set and lowered edge index.
  DenseMap<Value, std::pair<SetType, Value>> tuples;
  ElementContext *element = nullptr;
  /// Whether element loops prefetch the BCSR blocks they accumulate into
  /// (convert-simit-to-loops{prefetch-scatter-blocks}).
  bool prefetchScatterBlocks = false;
  /// How far ahead, in bytes, a loop over a BCSR row's blocks prefetches
  /// the matrices it reads (convert-simit-to-loops{prefetch-matrix-bytes});
  /// 0: not at all.
  int64_t prefetchMatrixBytes = 0;
  /// Where memref.alloca of local variables go: the function entry, or the
  /// alloca scope of the set loop's body (so stack use does not grow with
  /// the set).
  Block *allocaBlock = nullptr;

private:
  LoopsTypeConverter typeConverter;
  /// Storages by original value: those computed from types, and aliases.
  DenseMap<Value, Storage> storages;
  /// Collects setTypes and reports every matrix whose encoding has no
  /// layout in the loop lowering.
  LogicalResult checkStorages(func::FuncOp original);
  /// The function argument of binding `kind` of the named sets (for union
  /// bindings, the member sets joined by '+'; a union gather map names
  /// its part as a fourth, "part").
  /// `declaredShape`: an extern scalar's or local tensor's shape as the
  /// program declares it (the host checks the bound value against it; the
  /// memref holds the components flat).
  Value getBinding(BindingKind kind, ArrayRef<StringRef> names, Type type,
                   std::optional<ArrayRef<int64_t>> declaredShape = {});
  LogicalResult lowerFunctionReturn(func::ReturnOp op);
  /// Solves call the runtime's SolveSession (docs/solvers.md).
  LogicalResult lowerSolve(SolveOp op);
  /// `op`'s result = the solve `method` (Solve: A \ b; Triangular: with A's
  /// lower triangle; LowRank: the last step of simit.woodbury of `rank`
  /// outer products) of system matrix `matrix` and system vectors
  /// `vectors`, by the runtime's function for the method
  /// (::simit::abi::systemSolveFunction: @simit_rt_<method>_{bcsr,diag}
  /// [_f32]) with `where` = `what` and the source position.
  LogicalResult lowerSystemSolve(Operation *op, Value matrix,
                                 ValueRange vectors,
                                 ::simit::abi::SystemSolve method,
                                 StringRef what, unsigned rank = 0);
  /// Products of system matrices (LowerProducts.cpp): the runtime's
  /// numeric SpGEMM on the bind-time product pattern.
  LogicalResult lowerMatMul(MatMulOp op);
  /// H G of the transposed incidence H and the incidence G (stored as `g`)
  /// of one edge set, on the edge set's pattern `result`: a loop over the
  /// edges adding the products of their blocks.
  LogicalResult lowerIncidenceGram(MatMulOp op, const Storage &h,
                                   const Storage &g, const Storage &result);
  /// The incidence (stored as `incidence`) times a block diagonal matrix,
  /// or the diagonal times the incidence: each block of the incidence
  /// scaled by the diagonal's block at its column or row.
  LogicalResult lowerScaledIncidence(MatMulOp op, const Storage &incidence,
                                     bool diagonalOnRight);
  /// A product of stencils of one grid (or of a stencil and a block
  /// diagonal matrix), on the stencil of the sums of their offsets
  /// (`result`): a loop over the rows adding the products of their blocks.
  LogicalResult lowerStencilProduct(MatMulOp op, const Storage &result);
  /// simit.factorize, simit.factor_solve, simit.factor_free and
  /// simit.triangular_solve: the runtime's dense solvers for local tensors
  /// (through memref<?xf64>; handles are !llvm.ptr), else
  /// lowerSystemFactorisation.
  LogicalResult lowerFactorisation(Operation *op);
  /// A stack buffer of `size` f64 numbers, as memref<?xf64> (the dense
  /// runtime solvers' operands and results); one holding `vector` (a lowered
  /// local tensor, widened to f64).
  Value denseRuntimeBuffer(Location loc, int64_t size);
  Value denseRuntimeBuffer(Location loc, Value vector);
  /// The f64 numbers of `buffer` as a lowered local tensor of `type`.
  Value loadDenseRuntimeBuffer(Location loc, Value buffer, VectorType type);
  /// `matrix \ rhs` of a dense local n x n system by the runtime's LU with
  /// partial pivoting (lu, lusolve, lufree), for systems too large to
  /// invert in place; the runtime names `op` when it fails.
  Value solveByDenseLU(Location loc, Operation *op, Value matrix, Value rhs,
                       int64_t n);
  /// simit.woodbury: the runtime's Sherman–Morrison or Woodbury last step.
  LogicalResult lowerWoodbury(WoodburyOp op);
  /// Calls of host functions (`extern func`, LowerHostCalls.cpp) with the
  /// original Simit runtime's C conventions.
  LogicalResult lowerHostCall(func::CallOp call, func::FuncOp callee);
  /// Matrix result `result` (stored as `storage`, a host storage) of the
  /// host call `call`, from the pointers the host stored in `slots` (row
  /// pointers, column indices, blocks): checked by the runtime, copied into
  /// arrays of the lowered code, recorded in runtimePatterns; returns the
  /// blocks.
  Value adoptHostMatrix(func::CallOp call, Value result, const Storage &storage,
                        std::array<Value, 3> slots);
  /// The row pointers and column indices of the patterns known at run
  /// time built so far, by Storage::runtimeEncoding.
  DenseMap<Attribute, std::pair<Value, Value>> runtimePatterns;
  /// The storages of the function's values whose patterns are built at
  /// its start (isBindingPattern), found by checkStorages.
  SmallVector<Storage> entryPatterns;
  /// The index arrays of `storage` (Kind::Host) where the code is being
  /// lowered: built already and in reach, or a union's built now.
  std::pair<Value, Value> runtimePattern(const Storage &storage);
  /// The index arrays of `storage` built already and in reach, if any.
  std::optional<std::pair<Value, Value>>
  builtRuntimePattern(const Storage &storage);
  /// Builds the pattern of a union with a host member from its members'
  /// (simit_rt_union_pattern), or of the product `lhs` `rhs`
  /// (simit_rt_product_pattern), and records it in runtimePatterns.
  void buildRuntimePattern(Location loc, const Storage &storage);
  void buildProductPattern(Location loc, const Storage &storage,
                           const Storage &lhs, const Storage &rhs);
  /// The pattern the runtime's `function` (product, union or transpose
  /// pattern) builds from `args`, over the blocks of `rows`, copied into
  /// fresh arrays (simit_rt_pattern_blocks, simit_rt_pattern_take).
  std::pair<Value, Value>
  runtimePatternOf(Location loc, ::simit::abi::RuntimeFunction function,
                   ValueRange args, StringAttr rows);
  /// simit.print and strings (C strings as !llvm.ptr) through runtime
  /// functions (simit_rt_print_*, simit_rt_string_*).
  LogicalResult lowerPrintOrString(Operation *op);
  /// Prints system matrix `matrix` densely with `printScalar`.
  LogicalResult printMatrix(Location loc, Value matrix,
                            function_ref<LogicalResult(Value)> printScalar);
  /// The address of a global NUL-terminated copy of `text` (!llvm.ptr).
  Value stringConstant(Location loc, StringRef text);
  /// The private declaration of runtime function `name` with the C
  /// interface (the JIT binds _mlir_ciface_<name>), created on first use;
  /// null when it exists with another type.
  func::FuncOp declareRuntime(Location loc, StringRef name,
                              FunctionType type);
  /// A system tensor array as the fully dynamic memref `target` of the
  /// runtime's BCSR functions: arrays of scalars gain unit block
  /// dimensions (memref<?xf64> as memref<?x1x1xf64>).
  Value asRuntimeBlocks(Location loc, Value array, MemRefType target);
  /// A new array of `array`'s shape with components of type `element`:
  /// the runtime's factorisations are in double precision, so a float32
  /// program's matrices and vectors are widened for them.
  Value allocLike(Location loc, Value array, Type element);
  /// Copies `from` into `to` (same shape), converting each component to
  /// `to`'s float type.
  void copyConverted(Location loc, Value from, Value to);
  /// Factorisations of square system matrices assembled from a set, their
  /// solves of system vectors, and triangular solves: the runtime's sparse
  /// solvers.
  LogicalResult lowerSystemFactorisation(Operation *op);
  /// lumatsolve / lltmatsolve of a system matrix of scalars into a dense
  /// matrix, column by column with the runtime's vector solve.
  LogicalResult lowerFactorMatrixSolve(FactorSolveOp solve,
                                       func::FuncOp vectorSolve, Value where);
  /// A call to the runtime function `name`, declared on first use.
  Value callRuntime(Location loc, StringRef name, TypeRange results,
                    ValueRange args);
  LogicalResult lowerFor(scf::ForOp op);
  LogicalResult lowerIf(scf::IfOp op);
  LogicalResult lowerWhile(scf::WhileOp op);
  LogicalResult lowerGeneric(Operation *op);
  LogicalResult lowerSystemOp(Operation *op, bool &handled);
  /// Whether the value read by `read` may alias its source until its last
  /// use: no operation in between can write to the source.
  bool canAlias(Operation *read, function_ref<bool(Operation *)> writes);

  /// The bindings in argument order, and their positions by key.
  SmallVector<std::pair<DictionaryAttr, Value>> bindings;
  Value noIndices;
  llvm::StringMap<unsigned> bindingPositions;
  SmallVector<Type> resultTypes;
};

/// Flat component count of a builtin tensor type (1 for a scalar).
int64_t numComponents(Type type);
/// Whether a type is a tensor with a set dimension (a system tensor).
bool isSystem(Type type);
/// Whether `type` is over a set and then ranges only (a vector over a set,
/// `matrix[V,2]`): stored as one block per element of the set.
inline bool hasBlockPerElement(SystemTensorType type) {
  return isa<StringAttr>(type.getDims()[0]) &&
         llvm::all_of(type.getDims().getValue().drop_front(),
                      [](Attribute d) { return isa<IntegerAttr>(d); });
}
/// The storage positions of a local tensor's components in the row-major
/// order of its unblocked shape, which goes to `shape`: levels of (r_l x c_l)
/// make a (prod r_l) x (prod c_l) matrix, vector levels a vector; a scalar
/// is its one component. None when the levels mix ranks.
std::optional<SmallVector<int64_t>> unblockedOrder(Type type,
                                                   SmallVector<int64_t> &shape);

} // namespace loops
} // namespace simit
} // namespace mlir

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_LOOPSLOWERING_H
