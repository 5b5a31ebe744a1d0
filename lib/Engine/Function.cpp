//===--- Function.cpp - Binding host data and calling compiled code -------===//
//
// init() turns every argument of the host ABI into the values the lowered
// function takes: a memref becomes its descriptor (allocated and aligned
// pointers, offset, sizes, strides) pointing straight at the Set's field
// array, endpoint array or sparsity pattern; a scalar becomes a pointer to
// its value. The packed entry point receives pointers to all of them, so
// run() only checks set versions and calls.
//
//===----------------------------------------------------------------------===//

#include "simit/Engine/Function.h"
#include "simit/ABI/RuntimeFunctions.h"

#include "CompiledModule.h"
#include "Threads.h"

#include "simit/Runtime/ElementColouring.h"
#include "simit/Runtime/IncidenceView.h"
#include "simit/Runtime/StencilPattern.h"
#include "simit/Runtime/PatternAlgebra.h"
#include "simit/Runtime/SparsityPattern.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/MathExtras.h"

#include <cmath>
#include <map>
#include <cstring>
#include <limits>

using namespace simit;

double HostValue::component(size_t i) const {
  const uint8_t *p = bytes.data() + i * scalarSize(scalar);
  switch (scalar) {
  case ScalarKind::Float64: {
    double v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  case ScalarKind::Float32: {
    float v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  case ScalarKind::Int32: {
    int32_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  case ScalarKind::Int64:
  case ScalarKind::Index: {
    int64_t v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  }
  case ScalarKind::Bool:
    return *p ? 1.0 : 0.0;
  case ScalarKind::String:
    return 0.0; // the bytes hold a `const char *`
  }
  llvm_unreachable("unknown scalar kind");
}

namespace {
struct HostBuffer {
  void *data = nullptr;
  ComponentType type = ComponentType::Float64;
  std::vector<int> shape;
};

/// Alignment and byte size of a value in memory, as LLVM lays it out on
/// x86-64: a vector is aligned to its size rounded up to a power of two.
/// A complex scalar is a struct of two parts; a complex vector
/// (`vector<N x 2 x T>`) an array of N `<2 x T>` vectors.
size_t valueAlignment(const ValueType &type) {
  if (type.isMemRef)
    return 8;
  if (type.isVector && type.isComplex)
    return 2 * scalarSize(type.scalar);
  if (type.isVector)
    return llvm::PowerOf2Ceil(type.numComponents() * scalarSize(type.scalar));
  return scalarSize(type.scalar);
}
/// Bytes of the components of a scalar or vector.
size_t dataSize(const ValueType &type) {
  return type.numComponents() * type.partsPerComponent() *
         scalarSize(type.scalar);
}
size_t valueSize(const ValueType &type) {
  if (type.isMemRef)
    return 8 * (3 + 2 * type.rank());
  size_t align = valueAlignment(type);
  return (dataSize(type) + align - 1) / align * align;
}

/// Zeroed bytes aligned for any value the JIT loads or stores whole.
class AlignedBytes {
public:
  static constexpr size_t kAlignment = 256;
  void assign(size_t size) {
    storage.assign(size + kAlignment, 0);
    uintptr_t base = reinterpret_cast<uintptr_t>(storage.data());
    offset = (kAlignment - base % kAlignment) % kAlignment;
  }
  uint8_t *data() { return storage.data() + offset; }
  void clear() { std::fill(storage.begin(), storage.end(), 0); }

private:
  std::vector<uint8_t> storage;
  size_t offset = 0;
};

/// A vector argument: copied from its bound buffer before every call, since
/// the compiled code loads it whole with the vector's alignment.
struct VectorCopy {
  const void *source;
  size_t offset, bytes;
  size_t argument; // its position in Impl::args
};
} // namespace

struct Function::Impl {
  std::shared_ptr<CompiledModule> module;
  const CompiledFunction *compiled = nullptr;

  llvm::StringMap<Set *> sets;
  llvm::StringMap<HostBuffer> buffers;

  // Prepared by init().
  bool initialized = false;
  std::vector<std::pair<const Set *, uint64_t>> setVersions;
  std::vector<std::shared_ptr<const SparsityPattern>> patterns;
  std::vector<std::shared_ptr<const IncidenceView>> incidences;
  /// Stencils as BCSR patterns (stencil_* bindings).
  std::vector<std::shared_ptr<const StencilPattern>> stencils;
  /// Unions of patterns by their union binding's "set" (the joined edge
  /// sets), rows and cols, and the gather maps into them.
  std::map<std::string, std::shared_ptr<const SparsityPattern>> unions;
  std::vector<std::vector<int32_t>> gathers;
  /// Colourings of the edge sets that scatter loops run colour by colour.
  std::vector<std::shared_ptr<const ElementColouring>> colourings;
  /// Descriptors and scalar slots; args points into it, so it is sized once
  /// per init() and never reallocated afterwards.
  std::vector<int64_t> words;
  std::vector<void *> args;
  AlignedBytes vectorStorage;
  size_t vectorBytes = 0;
  std::vector<VectorCopy> vectorCopies;
  std::vector<size_t> resultOffsets;
  AlignedBytes resultStorage;
  std::vector<HostValue> results;

  const HostSignature &signature() const { return compiled->signature; }
  std::string prefix() const {
    return "function '" + signature().function + "': ";
  }
  llvm::Error error(const llvm::Twine &what) const {
    return llvm::createStringError(prefix() + what);
  }

  llvm::Expected<Set *> boundSet(llvm::StringRef name) const {
    auto it = sets.find(name);
    if (it == sets.end())
      return error("extern set '" + name + "' is not bound");
    return it->second;
  }

  llvm::Error init();
  /// The union of the patterns of `edgeSets` over (rows, cols), built
  /// once per init().
  llvm::Expected<std::shared_ptr<const SparsityPattern>>
  unionOf(const std::vector<std::string> &edgeSets, const std::string &rows,
          const std::string &cols);
  /// The pattern of the product of the unions of `left` over (rows, mid)
  /// and `right` over (mid, cols), built once per init().
  llvm::Expected<std::shared_ptr<const SparsityPattern>>
  productOf(const ArgumentBinding &arg);
  llvm::Error prepareArgument(const ArgumentBinding &arg, size_t &word);
  void pushMemRef(size_t &word, const void *data,
                  llvm::ArrayRef<int64_t> sizes);
  void decodeResults();
};

/// Room the arguments need in `words`.
static size_t wordsNeeded(const CompiledFunction &function) {
  size_t count = 0;
  for (const ArgumentBinding &arg : function.signature.arguments) {
    if (arg.type.isMemRef)
      count += function.convention == MemRefConvention::Descriptor
                   ? 3 + 2 * arg.type.rank()
                   : 2;
    else if (arg.kind == ArgumentBinding::Kind::SetSize)
      count += 1;
  }
  return count;
}

void Function::Impl::pushMemRef(size_t &word, const void *data,
                                llvm::ArrayRef<int64_t> sizes) {
  size_t base = word;
  size_t rank = sizes.size();
  int64_t pointer = static_cast<int64_t>(reinterpret_cast<intptr_t>(data));
  words[base] = pointer;     // allocated
  words[base + 1] = pointer; // aligned
  if (compiled->convention == MemRefConvention::BarePointer) {
    args.push_back(&words[base + 1]);
    word += 2;
    return;
  }
  words[base + 2] = 0; // offset
  int64_t stride = 1;
  for (size_t d = rank; d-- > 0;) {
    words[base + 3 + d] = sizes[d];
    words[base + 3 + rank + d] = stride;
    stride *= sizes[d];
  }
  for (size_t i = 0; i < 3 + 2 * rank; ++i)
    args.push_back(&words[base + i]);
  word += 3 + 2 * rank;
}

llvm::Error Function::Impl::prepareArgument(const ArgumentBinding &arg,
                                            size_t &word) {
  using Kind = ArgumentBinding::Kind;
  const ValueType &type = arg.type;
  switch (arg.kind) {
  case Kind::SetSize: {
    llvm::Expected<Set *> set = boundSet(arg.set);
    if (!set)
      return set.takeError();
    int64_t size = (*set)->size();
    if (type.scalar == ScalarKind::Int32) {
      int32_t narrow = static_cast<int32_t>(size);
      std::memcpy(&words[word], &narrow, sizeof narrow);
    } else {
      words[word] = size;
    }
    args.push_back(&words[word++]);
    return llvm::Error::success();
  }
  case Kind::Field: {
    llvm::Expected<Set *> set = boundSet(arg.set);
    if (!set)
      return set.takeError();
    ComponentType expected;
    componentTypeFor(type.scalar, expected);
    // A complex field is a field of its parts with a last dimension of 2.
    std::vector<int64_t> hostShape = type.hostShape();
    std::vector<int64_t> blockShape(hostShape.begin() + 1, hostShape.end());
    const FieldDescriptor *field = (*set)->fieldDescriptor(arg.field);
    auto expectation = [&] {
      return "the program expects " + componentTypeName(expected).str() +
             " components of shape " + shapeString(blockShape);
    };
    if (!field)
      return error("set '" + arg.set + "' has no field '" + arg.field +
                   "'; " + expectation());
    bool shapeMatches = field->shape.size() == blockShape.size();
    for (size_t d = 0; shapeMatches && d < blockShape.size(); ++d)
      shapeMatches = blockShape[d] == ValueType::kDynamic ||
                     blockShape[d] == field->shape[d];
    if (field->type != expected || !shapeMatches)
      return error(arg.describe() + " holds " +
                   componentTypeName(field->type).str() +
                   " components of shape " + shapeString(field->shape) +
                   ", but " + expectation());
    std::vector<int64_t> sizes{(*set)->size()};
    for (int d : llvm::ArrayRef(field->shape).drop_back(type.isComplex))
      sizes.push_back(d);
    pushMemRef(word, (*set)->fieldData(arg.field), sizes);
    return llvm::Error::success();
  }
  case Kind::GridDims: {
    llvm::Expected<Set *> set = boundSet(arg.set);
    if (!set)
      return set.takeError();
    llvm::ArrayRef<int> dims = (*set)->gridDimensions();
    if (static_cast<int64_t>(dims.size()) != type.shape[0]) {
      std::string actual =
          dims.empty() ? "not a grid"
                       : "a grid of rank " + std::to_string(dims.size());
      return error("set '" + arg.set + "' is " + actual +
                   ", but the program expects a grid of rank " +
                   llvm::Twine(type.shape[0]));
    }
    pushMemRef(word, dims.data(), {type.shape[0]});
    return llvm::Error::success();
  }
  case Kind::Endpoints: {
    llvm::Expected<Set *> set = boundSet(arg.set);
    if (!set)
      return set.takeError();
    int cardinality = (*set)->cardinality();
    if (cardinality == 0 ||
        (type.shape[1] != ValueType::kDynamic && type.shape[1] != cardinality))
      return error("set '" + arg.set + "' has " + llvm::Twine(cardinality) +
                   " endpoints per element, but the program expects " +
                   llvm::Twine(type.shape[1]));
    pushMemRef(word, (*set)->endpointData(), {(*set)->size(), cardinality});
    return llvm::Error::success();
  }
  case Kind::PatternRowPtr:
  case Kind::PatternColIdx:
  case Kind::PatternLocations: {
    llvm::Expected<Set *> edges = boundSet(arg.set);
    if (!edges)
      return edges.takeError();
    llvm::Expected<Set *> rows = boundSet(arg.rows);
    if (!rows)
      return rows.takeError();
    llvm::Expected<Set *> cols = boundSet(arg.cols);
    if (!cols)
      return cols.takeError();
    auto pattern = SparsityPattern::get(**edges, **rows, **cols);
    if (!pattern)
      return error(arg.describe() + ": " +
                   llvm::toString(pattern.takeError()));
    const SparsityPattern &p = **pattern;
    patterns.push_back(*pattern);
    if (arg.kind == Kind::PatternRowPtr) {
      pushMemRef(word, p.rowPointers().data(), {p.numRows() + 1});
    } else if (arg.kind == Kind::PatternColIdx) {
      pushMemRef(word, p.columnIndices().data(), {p.numBlocks()});
    } else {
      int64_t c = p.locationCardinality();
      if (type.shape[1] != ValueType::kDynamic && type.shape[1] != c * c)
        return error(arg.describe() + " has " + llvm::Twine(c * c) +
                     " locations per element, but the program expects " +
                     llvm::Twine(type.shape[1]));
      pushMemRef(word, p.locations().data(), {(*edges)->size(), c * c});
    }
    return llvm::Error::success();
  }
  case Kind::UnionRowPtr:
  case Kind::UnionColIdx:
  case Kind::UnionGather: {
    auto whole = unionOf(arg.edgeSets, arg.rows, arg.cols);
    if (!whole)
      return error(arg.describe() + ": " + llvm::toString(whole.takeError()));
    const SparsityPattern &p = **whole;
    if (arg.kind == Kind::UnionRowPtr) {
      pushMemRef(word, p.rowPointers().data(), {p.numRows() + 1});
    } else if (arg.kind == Kind::UnionColIdx) {
      pushMemRef(word, p.columnIndices().data(), {p.numBlocks()});
    } else {
      // A part read transposed is over (cols, rows).
      bool transposed = arg.partTransposed;
      auto part = transposed ? unionOf(arg.partSets, arg.cols, arg.rows)
                             : unionOf(arg.partSets, arg.rows, arg.cols);
      if (!part)
        return error(arg.describe() + ": " + llvm::toString(part.takeError()));
      gathers.push_back(transposed ? gatherTransposedPositions(p, **part)
                                   : gatherPositions(p, **part));
      pushMemRef(word, gathers.back().data(), {p.numBlocks()});
    }
    return llvm::Error::success();
  }
  case Kind::ProductRowPtr:
  case Kind::ProductColIdx: {
    auto product = productOf(arg);
    if (!product)
      return error(arg.describe() + ": " +
                   llvm::toString(product.takeError()));
    const SparsityPattern &p = **product;
    if (arg.kind == Kind::ProductRowPtr)
      pushMemRef(word, p.rowPointers().data(), {p.numRows() + 1});
    else
      pushMemRef(word, p.columnIndices().data(), {p.numBlocks()});
    return llvm::Error::success();
  }
  case Kind::IncidenceRowPtr:
  case Kind::IncidenceColIdx:
  case Kind::IncidencePositions:
  case Kind::IncidenceEndpoints: {
    llvm::Expected<Set *> edges = boundSet(arg.set);
    if (!edges)
      return edges.takeError();
    bool transposed = arg.cols == arg.set;
    llvm::Expected<Set *> endpoints = boundSet(transposed ? arg.rows : arg.cols);
    if (!endpoints)
      return endpoints.takeError();
    auto view = IncidenceView::get(**edges, **endpoints, transposed);
    if (!view)
      return error(arg.describe() + ": " + llvm::toString(view.takeError()));
    incidences.push_back(*view);
    const IncidenceView &v = **view;
    if (arg.kind == Kind::IncidenceEndpoints) {
      // Row e of the incidence is edge e's endpoints in `cols`.
      int64_t perEdge = type.shape[1];
      if (transposed ||
          static_cast<int64_t>(v.colIdx.size()) != v.rows * perEdge)
        return error(arg.describe() + ": expected " + std::to_string(perEdge) +
                     " endpoints in '" + arg.cols + "' per edge");
      pushMemRef(word, v.colIdx.data(), {v.rows, perEdge});
    } else if (arg.kind == Kind::IncidenceRowPtr)
      pushMemRef(word, v.rowPtr.data(), {v.rows + 1});
    else
      pushMemRef(word, (arg.kind == Kind::IncidenceColIdx ? v.colIdx
                                                          : v.positions)
                           .data(),
                 {static_cast<int64_t>(v.colIdx.size())});
    return llvm::Error::success();
  }
  case Kind::StencilRowPtr:
  case Kind::StencilColIdx:
  case Kind::StencilPositions: {
    llvm::Expected<Set *> grid = boundSet(arg.set);
    if (!grid)
      return grid.takeError();
    std::vector<std::vector<int64_t>> offsets;
    llvm::SmallVector<llvm::StringRef> points, coordinates;
    llvm::StringRef(arg.offsets).split(points, ';');
    for (llvm::StringRef point : points) {
      coordinates.clear();
      point.split(coordinates, ',');
      std::vector<int64_t> &offset = offsets.emplace_back();
      for (llvm::StringRef coordinate : coordinates)
        if (coordinate.getAsInteger(10, offset.emplace_back()))
          return error(arg.describe() + ": malformed offsets");
    }
    auto pattern = StencilPattern::get((*grid)->gridDimensions(), offsets);
    if (!pattern)
      return error(arg.describe() + ": " +
                   llvm::toString(pattern.takeError()));
    stencils.push_back(*pattern);
    const StencilPattern &p = **pattern;
    if (arg.kind == Kind::StencilRowPtr)
      pushMemRef(word, p.rowPtr.data(),
                 {static_cast<int64_t>(p.rowPtr.size())});
    else if (arg.kind == Kind::StencilColIdx)
      pushMemRef(word, p.colIdx.data(),
                 {static_cast<int64_t>(p.colIdx.size())});
    else
      pushMemRef(word, p.positions.data(),
                 {static_cast<int64_t>(p.positions.size())});
    return llvm::Error::success();
  }
  case Kind::ElementColours: {
    llvm::Expected<Set *> set = boundSet(arg.set);
    if (!set)
      return set.takeError();
    if ((*set)->cardinality() == 0)
      return error(arg.describe() + ": set '" + arg.set +
                   "' is not an edge set");
    if (arg.chunk < 1 || arg.chunk > std::numeric_limits<int>::max())
      return error(arg.describe() + ": the chunk size must be positive");
    colourings.push_back(
        ElementColouring::get(**set, static_cast<int>(arg.chunk)));
    llvm::ArrayRef<int32_t> words = colourings.back()->words();
    pushMemRef(word, words.data(), {static_cast<int64_t>(words.size())});
    return llvm::Error::success();
  }
  case Kind::Extern:
  case Kind::Parameter: {
    auto it = buffers.find(arg.bufferKey());
    if (it == buffers.end())
      return error(arg.describe() + " is not bound");
    const HostBuffer &buffer = it->second;
    // A string parameter is bound to a `const char *` variable; its
    // component type and shape are not checked.
    if (type.scalar == ScalarKind::String && !type.isMemRef &&
        !type.isVector) {
      args.push_back(buffer.data);
      return llvm::Error::success();
    }
    ComponentType expected;
    if (!componentTypeFor(type.scalar, expected))
      return error(arg.describe() + " has host type " + type.str() +
                   ", which no host buffer provides");
    std::vector<int64_t> bufferShape(buffer.shape.begin(), buffer.shape.end());
    // A vector is the lowering's flattened form of a local tensor, and a
    // memref of static shape holds one row major: any buffer of as many
    // numbers fits them (a 3x3 matrix given as nested rows or flat).
    int64_t bufferNumbers = 1;
    for (int64_t dim : bufferShape)
      bufferNumbers *= dim;
    std::vector<int64_t> hostShape = type.hostShape();
    std::vector<int64_t> sizes = type.shape;
    // A vector over a set has a block per element of the set bound now.
    if (!arg.set.empty()) {
      llvm::Expected<Set *> set = boundSet(arg.set);
      if (!set)
        return set.takeError();
      hostShape[0] = sizes[0] = (*set)->size();
    }
    int64_t hostNumbers = 1;
    for (int64_t dim : hostShape)
      hostNumbers *= dim;
    bool flat = type.isVector || llvm::none_of(hostShape, [](int64_t dim) {
                  return dim == ValueType::kDynamic;
                });
    bool shapeFits =
        flat ? bufferNumbers == hostNumbers : bufferShape == hostShape;
    // A declared shape: the value has it, or is flat (a matrix given as its
    // rows one after another); a scalar is one number, not an array.
    if (arg.declaredShape && shapeFits && bufferShape != *arg.declaredShape &&
        !(arg.declaredShape->size() > 1 && bufferShape.size() == 1))
      return error(arg.describe() + " is bound to " +
                   componentTypeName(buffer.type).str() + " of shape " +
                   shapeString(buffer.shape) + ", but the program declares " +
                   "shape " + shapeString(*arg.declaredShape));
    if (buffer.type != expected || !shapeFits)
      return error(arg.describe() + " is bound to " +
                   componentTypeName(buffer.type).str() + " of shape " +
                   shapeString(buffer.shape) + ", but the program expects " +
                   componentTypeName(expected).str() + " of shape " +
                   shapeString(hostShape));
    if (type.isMemRef) {
      pushMemRef(word, buffer.data, sizes);
    } else if (type.isVector) {
      size_t align = valueAlignment(type);
      size_t offset = (vectorBytes + align - 1) / align * align;
      vectorCopies.push_back(
          {buffer.data, offset, dataSize(type), args.size()});
      vectorBytes = offset + valueSize(type);
      args.push_back(nullptr); // set once vectorStorage is allocated
    } else {
      args.push_back(buffer.data);
    }
    return llvm::Error::success();
  }
  }
  llvm_unreachable("unknown binding kind");
}

llvm::Expected<std::shared_ptr<const SparsityPattern>>
Function::Impl::unionOf(const std::vector<std::string> &edgeSetNames,
                        const std::string &rows, const std::string &cols) {
  std::string key = llvm::join(edgeSetNames, "+") + ":" + rows + ":" + cols;
  if (auto it = unions.find(key); it != unions.end())
    return it->second;
  std::vector<const Set *> edgeSets;
  for (const std::string &name : edgeSetNames) {
    llvm::Expected<Set *> edges = boundSet(name);
    if (!edges)
      return edges.takeError();
    edgeSets.push_back(*edges);
  }
  llvm::Expected<Set *> rowSet = boundSet(rows);
  if (!rowSet)
    return rowSet.takeError();
  llvm::Expected<Set *> colSet = boundSet(cols);
  if (!colSet)
    return colSet.takeError();
  auto pattern = unionPattern(edgeSets, **rowSet, **colSet);
  if (!pattern)
    return pattern.takeError();
  unions[key] = *pattern;
  return *pattern;
}

llvm::Expected<std::shared_ptr<const SparsityPattern>>
Function::Impl::productOf(const ArgumentBinding &arg) {
  std::string key = arg.rows + ":" + arg.cols;
  for (const ArgumentBinding::ProductChain &chain : arg.chains) {
    key += "|";
    for (size_t i = 0; i < chain.factorSets.size(); ++i)
      key += (i ? "*" : ":") + llvm::join(chain.factorSets[i], "+") +
             (i < chain.mids.size() ? ":" + chain.mids[i] : "");
  }
  if (auto it = unions.find(key); it != unions.end())
    return it->second;
  std::vector<std::shared_ptr<const SparsityPattern>> chainPatterns;
  for (const ArgumentBinding::ProductChain &chain : arg.chains) {
    // The sets between the factors: rows, the mids, cols.
    std::vector<std::string> sets{arg.rows};
    llvm::append_range(sets, chain.mids);
    sets.push_back(arg.cols);
    std::vector<std::shared_ptr<const SparsityPattern>> factors;
    for (size_t i = 0; i < chain.factorSets.size(); ++i) {
      auto factor = unionOf(chain.factorSets[i], sets[i], sets[i + 1]);
      if (!factor)
        return factor.takeError();
      factors.push_back(*factor);
    }
    if (factors.size() == 1) {
      chainPatterns.push_back(factors.front());
      continue;
    }
    std::vector<const SparsityPattern *> views;
    for (const auto &factor : factors)
      views.push_back(factor.get());
    chainPatterns.push_back(chainProductPattern(views, sets));
  }
  std::shared_ptr<const SparsityPattern> product = chainPatterns.front();
  if (chainPatterns.size() > 1) {
    std::vector<const SparsityPattern *> members;
    for (const auto &chain : chainPatterns)
      members.push_back(chain.get());
    product = unionPattern(members);
  }
  unions[key] = product;
  return product;
}

llvm::Error Function::Impl::init() {
  initialized = false;
  setVersions.clear();
  patterns.clear();
  incidences.clear();
  stencils.clear();
  unions.clear();
  gathers.clear();
  colourings.clear();
  args.clear();
  vectorCopies.clear();
  vectorBytes = 0;
  words.assign(wordsNeeded(*compiled), 0);
  size_t word = 0;
  for (const ArgumentBinding &arg : signature().arguments)
    if (llvm::Error err = prepareArgument(arg, word))
      return llvm::make_error<ArgumentError>(arg,
                                             llvm::toString(std::move(err)));
  vectorStorage.assign(vectorBytes);
  for (const VectorCopy &copy : vectorCopies)
    args[copy.argument] = vectorStorage.data() + copy.offset;

  if (compiled->convention == MemRefConvention::BarePointer &&
      llvm::any_of(signature().results,
                   [](const ValueType &t) { return t.isMemRef; }))
    return error("memref results need the descriptor calling convention");
  size_t offset = 0;
  resultOffsets.clear();
  for (const ValueType &result : signature().results) {
    size_t align = valueAlignment(result);
    offset = (offset + align - 1) / align * align;
    resultOffsets.push_back(offset);
    offset += valueSize(result);
  }
  resultStorage.assign(offset);
  if (!signature().results.empty())
    args.push_back(resultStorage.data());

  for (const auto &entry : sets)
    setVersions.emplace_back(entry.second, entry.second->version());
  initialized = true;
  return llvm::Error::success();
}

void Function::Impl::decodeResults() {
  results.clear();
  const uint8_t *base = resultStorage.data();
  for (auto [type, offset] :
       llvm::zip_equal(signature().results, resultOffsets)) {
    HostValue value;
    value.scalar = type.scalar;
    value.isComplex = type.isComplex;
    size_t elementSize = scalarSize(type.scalar);
    if (!type.isMemRef) {
      value.shape = type.shape;
      value.bytes.assign(base + offset, base + offset + dataSize(type));
      results.push_back(std::move(value));
      continue;
    }
    // A returned memref is copied out, walking its strides. Its storage is
    // not freed: it may be a global or alias a bound buffer.
    const int64_t *desc = reinterpret_cast<const int64_t *>(base + offset);
    size_t rank = type.shape.size();
    const uint8_t *data = reinterpret_cast<const uint8_t *>(
        static_cast<intptr_t>(desc[1]));
    int64_t start = desc[2];
    value.shape.assign(desc + 3, desc + 3 + rank);
    int64_t count = 1;
    for (int64_t size : value.shape)
      count *= size;
    value.bytes.resize(count * elementSize);
    for (int64_t linear = 0; linear < count; ++linear) {
      int64_t rest = linear, element = start;
      for (size_t d = rank; d-- > 0;) {
        element += (rest % value.shape[d]) * desc[3 + rank + d];
        rest /= value.shape[d];
      }
      std::memcpy(value.bytes.data() + linear * elementSize,
                  data + element * elementSize, elementSize);
    }
    results.push_back(std::move(value));
  }
}

//===--- Function ---------------------------------------------------------===//

char ArgumentError::ID = 0;

/// The error of using a Function that no Program compiled.
static llvm::Error notCompiled() {
  return llvm::createStringError("the function was not compiled by a Program");
}

Function::Function() = default;
Function::Function(Function &&) = default;
Function &Function::operator=(Function &&) = default;
Function::~Function() = default;

Function::Function(std::shared_ptr<CompiledModule> module,
                   const HostSignature &signature)
    : impl(std::make_unique<Impl>()) {
  impl->compiled = &module->functions.find(signature.function)->second;
  impl->module = std::move(module);
}

llvm::StringRef Function::name() const {
  return impl->signature().function;
}

const HostSignature &Function::signature() const { return impl->signature(); }

std::vector<std::string> Function::requiredSets() const {
  std::vector<std::string> names;
  auto add = [&](const std::string &name) {
    if (!name.empty() && !llvm::is_contained(names, name))
      names.push_back(name);
  };
  for (const ArgumentBinding &arg : signature().arguments) {
    add(arg.set);
    add(arg.rows);
    add(arg.cols);
    for (const std::string &edges : arg.edgeSets)
      add(edges);
    for (const ArgumentBinding::ProductChain &chain : arg.chains) {
      for (const std::string &mid : chain.mids)
        add(mid);
      for (const std::vector<std::string> &factor : chain.factorSets)
        for (const std::string &edges : factor)
          add(edges);
    }
  }
  return names;
}

std::vector<std::string> Function::requiredTensors() const {
  std::vector<std::string> names;
  for (const ArgumentBinding &arg : signature().arguments)
    if (arg.kind == ArgumentBinding::Kind::Extern &&
        !llvm::is_contained(names, arg.name))
      names.push_back(arg.name);
  return names;
}

unsigned Function::numParameters() const {
  return llvm::count_if(signature().arguments, [](const ArgumentBinding &arg) {
    return arg.kind == ArgumentBinding::Kind::Parameter;
  });
}

llvm::Error Function::bind(llvm::StringRef name, Set &set) {
  if (!impl)
    return notCompiled();
  if (!llvm::is_contained(requiredSets(), name.str()))
    return impl->error("uses no set named '" + name + "'");
  impl->sets[name] = &set;
  impl->initialized = false;
  return llvm::Error::success();
}

llvm::Error Function::bind(llvm::StringRef name, void *data, ComponentType type,
                           llvm::ArrayRef<int> shape) {
  if (!impl)
    return notCompiled();
  if (!llvm::is_contained(requiredTensors(), name.str()))
    return impl->error("uses no extern tensor named '" + name + "'");
  impl->buffers[name] = HostBuffer{data, type, shape.vec()};
  impl->initialized = false;
  return llvm::Error::success();
}

llvm::Error Function::bindParameter(unsigned index, void *data,
                                    ComponentType type,
                                    llvm::ArrayRef<int> shape) {
  if (!impl)
    return notCompiled();
  if (index >= numParameters())
    return impl->error("has " + llvm::Twine(numParameters()) +
                       " parameters, not " + llvm::Twine(index + 1));
  impl->buffers["#" + std::to_string(index)] =
      HostBuffer{data, type, shape.vec()};
  impl->initialized = false;
  return llvm::Error::success();
}

llvm::Error Function::init() {
  if (!impl)
    return notCompiled();
  return impl->init();
}

llvm::Error Function::run() {
  if (!impl)
    return notCompiled();
  bool current = impl->initialized;
  for (auto [set, version] : impl->setVersions)
    current = current && set->version() == version;
  if (!current)
    if (llvm::Error err = impl->init())
      return err;
  impl->resultStorage.clear();
  for (const VectorCopy &copy : impl->vectorCopies)
    std::memcpy(impl->vectorStorage.data() + copy.offset, copy.source,
                copy.bytes);
  // The count belongs to the calling thread, and Functions of programs
  // compiled for different counts may share it.
  if (impl->module->threads > 1)
    useThreads(impl->module->threads);
  if (llvm::Error err =
          runGuarded(impl->compiled->entry, impl->args.data(),
                     impl->module->solver.get()))
    return err;
  impl->decodeResults();
  return llvm::Error::success();
}

llvm::ArrayRef<HostValue> Function::results() const { return impl->results; }

/// The first non-finite component of `count` values at `data`, or -1.
static int64_t firstNonFinite(const void *data, ScalarKind kind,
                              int64_t count) {
  for (int64_t i = 0; i < count; ++i) {
    double v = kind == ScalarKind::Float64
                   ? static_cast<const double *>(data)[i]
                   : static_cast<const float *>(data)[i];
    if (!std::isfinite(v))
      return i;
  }
  return -1;
}

std::string Function::findNonFinite() const {
  for (const ArgumentBinding &arg : signature().arguments) {
    ScalarKind kind = arg.type.scalar;
    if (kind != ScalarKind::Float64 && kind != ScalarKind::Float32)
      continue;
    if (arg.kind == ArgumentBinding::Kind::Field) {
      auto it = impl->sets.find(arg.set);
      if (it == impl->sets.end() || !it->second->hasField(arg.field))
        continue;
      Set &set = *it->second;
      size_t block = set.fieldDescriptor(arg.field)->blockSize();
      int64_t at = firstNonFinite(set.fieldData(arg.field), kind,
                                  set.size() * static_cast<int64_t>(block));
      if (at < 0)
        continue;
      double v = kind == ScalarKind::Float64
                     ? static_cast<const double *>(set.fieldData(arg.field))[at]
                     : static_cast<const float *>(set.fieldData(arg.field))[at];
      return llvm::formatv("{0} of element {1}, component {2}, is {3}",
                           arg.describe(), at / block, at % block,
                           std::isnan(v) ? "nan" : "inf")
          .str();
    }
    if (arg.kind == ArgumentBinding::Kind::Extern ||
        arg.kind == ArgumentBinding::Kind::Parameter) {
      auto it = impl->buffers.find(arg.bufferKey());
      if (it == impl->buffers.end())
        continue;
      int64_t count = 1;
      for (int d : it->second.shape)
        count *= d;
      int64_t at = firstNonFinite(it->second.data, kind, count);
      if (at >= 0)
        return llvm::formatv("{0}, component {1}, is not finite",
                             arg.describe(), at)
            .str();
    }
  }
  for (const HostValue &result : impl->results) {
    if (result.scalar != ScalarKind::Float64 &&
        result.scalar != ScalarKind::Float32)
      continue;
    for (size_t i = 0; i < result.numNumbers(); ++i)
      if (!std::isfinite(result.component(i)))
        return llvm::formatv("result component {0} is not finite", i).str();
  }
  return "";
}
