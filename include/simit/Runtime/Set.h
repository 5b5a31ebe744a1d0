//===--- Set.h - Hypergraph sets with fields stored as arrays ---*- C++ -*-===//
//
// A Set is a vertex set or an edge set of a Simit hypergraph (paper, section
// 5.1 and 6.1). Elements are numbered 0..size()-1 and carry fields.
//
// Memory layout (the contract with JIT-compiled code, which reads and writes
// these arrays in place through the raw pointers):
//  - Each field is one contiguous array of size() blocks (struct of arrays).
//    A block is the field's tensor at one element, its components stored
//    row-major: element e, component (i0, ..., ik) of shape (n0, ..., nk) is
//    at data[e * blockSize + ((i0 * n1 + i1) * n2 + ...)].
//  - Components are Float64 = double, Float32 = float, Int32 = int32_t and
//    Bool = one byte holding 0 or 1 (C++ bool).
//  - Field arrays are 64-byte aligned and zero-filled when elements are added.
//  - An edge set of cardinality c stores its endpoints as one int32 array of
//    size() * c entries: endpoints[e * c + i] is the index of e's i-th
//    endpoint within endpointSet(i).
//  - A grid edge set over a point set of dims (n0, ..., n(d-1)) has the point
//    of grid coordinate (k0, ..., k(d-1)) at index (k0 * n1 + k1) * n2 + ...,
//    and d edges per point: edge p * d + a joins point p to its neighbour one
//    step up along axis a, wrapping around (the grid is periodic).
//  - Field and endpoint pointers stay valid until the arrays grow: add()
//    past the capacity, or reserve(). version() is bumped by every add(),
//    remove(), reserve() that grows, and field addition or removal, so a
//    binding that saw the same version may keep its pointers.
//
// Sets neither copy nor move: edge sets point at their endpoint sets, which
// must outlive them.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SET_H
#define SIMIT_RUNTIME_SET_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace simit {

class ElementColouring;
class SparsityPattern;

enum class ComponentType : uint8_t { Float64, Float32, Int32, Bool };

/// Bytes per component: 8, 4, 4, 1.
size_t componentSize(ComponentType type);
/// "float64", "float32", "int32", "bool".
llvm::StringRef componentTypeName(ComponentType type);

template <typename T> struct ComponentTypeOf;
template <> struct ComponentTypeOf<double> {
  static constexpr ComponentType value = ComponentType::Float64;
};
template <> struct ComponentTypeOf<float> {
  static constexpr ComponentType value = ComponentType::Float32;
};
template <> struct ComponentTypeOf<int32_t> {
  static constexpr ComponentType value = ComponentType::Int32;
};
template <> struct ComponentTypeOf<bool> {
  static constexpr ComponentType value = ComponentType::Bool;
};
static_assert(sizeof(bool) == 1, "Bool fields store one byte per component");

/// A field's name, component type and block shape ({} for a scalar).
struct FieldDescriptor {
  std::string name;
  ComponentType type;
  std::vector<int> shape;

  /// Components per element: the product of the shape (1 for a scalar).
  size_t blockSize() const;
  /// Bytes per element.
  size_t blockBytes() const { return blockSize() * componentSize(type); }
};

template <typename T, int... Dims> class FieldRef;
template <typename T> class DynamicFieldRef;

class Set {
public:
  /// A vertex set.
  explicit Set(llvm::StringRef name = "");
  /// An edge set whose i-th endpoint belongs to endpoints[i]; the sets may
  /// differ (heterogeneous) or repeat (homogeneous).
  Set(llvm::StringRef name, llvm::ArrayRef<Set *> endpoints);
  /// The paper's spelling: `Set tets(verts, verts, verts, verts);`.
  template <typename... Sets,
            typename = std::enable_if_t<(std::is_same_v<Sets, Set> && ...)>>
  explicit Set(Set &first, Sets &...rest)
      : Set("", llvm::ArrayRef<Set *>({&first, &rest...})) {}

  /// A grid edge set over `points` with the given dims (see the layout
  /// above). When `points` is empty its prod(dims) points are added;
  /// otherwise its size must equal prod(dims).
  static llvm::Expected<std::unique_ptr<Set>>
  makeGrid(Set &points, llvm::ArrayRef<int> dims, llvm::StringRef name = "");

  Set(const Set &) = delete;
  Set &operator=(const Set &) = delete;
  ~Set();

  llvm::StringRef name() const { return setName; }
  int size() const { return numElements; }
  /// Number of endpoints per element: 0 for a vertex set.
  int cardinality() const { return static_cast<int>(endpointSets.size()); }
  bool isEdgeSet() const { return !endpointSets.empty(); }
  Set &endpointSet(int i) const { return *endpointSets[i]; }
  llvm::ArrayRef<Set *> endpointSetList() const { return endpointSets; }

  bool isGrid() const { return !gridDims.empty(); }
  llvm::ArrayRef<int> gridDimensions() const { return gridDims; }

  /// Bumped by every structural change (see the layout notes above).
  uint64_t version() const { return setVersion; }

  //===--- Elements -------------------------------------------------------===//

  /// Adds a vertex (only on vertex sets); returns its index.
  int add();
  /// Adds an edge with the given endpoint indices, one per endpoint set.
  /// Reports a fatal error on a wrong count or an index out of range (use
  /// checkEndpoints first to validate untrusted input).
  int add(llvm::ArrayRef<int> endpoints);
  template <typename... Ints,
            typename = std::enable_if_t<(std::is_integral_v<Ints> && ...)>>
  int add(int first, Ints... rest) {
    return add(llvm::ArrayRef<int>({first, static_cast<int>(rest)...}));
  }
  /// Why `endpoints` cannot be added to this set, or success.
  llvm::Error checkEndpoints(llvm::ArrayRef<int> endpoints) const;

  /// Removes element `e`: the last element moves into its slot (its fields
  /// and endpoints with it). Edges of sets over this one that use `e` are
  /// removed as well, and references to the moved element are renumbered.
  void remove(int e);

  /// Makes room for `n` elements without reallocating later.
  void reserve(int n);

  /// endpoints[e * cardinality() + i]; see the layout above.
  const int32_t *endpointData() const { return endpoints.data(); }
  int32_t *endpointData() { return endpoints.data(); }
  int endpoint(int e, int i) const {
    return endpoints[static_cast<size_t>(e) * cardinality() + i];
  }
  llvm::ArrayRef<int32_t> endpointsOf(int e) const {
    return llvm::ArrayRef<int32_t>(endpoints).slice(
        static_cast<size_t>(e) * cardinality(), cardinality());
  }

  //===--- Fields ---------------------------------------------------------===//

  /// Adds a zero-filled field; an error if the name is taken or a dimension
  /// is not positive.
  llvm::Error addField(llvm::StringRef name, ComponentType type,
                       llvm::ArrayRef<int> shape);
  /// Statically shaped field: `addField<double, 3>("x")`. A fatal error if
  /// the name is taken.
  template <typename T, int... Dims> FieldRef<T, Dims...> addField(llvm::StringRef name);
  /// Field of a shape known at run time: `addField<double>("B", {3, 3})`.
  template <typename T>
  DynamicFieldRef<T> addField(llvm::StringRef name, llvm::ArrayRef<int> shape);

  /// The existing field's typed handle; a fatal error if it is missing or
  /// its type or shape differ.
  template <typename T, int... Dims> FieldRef<T, Dims...> field(llvm::StringRef name);
  template <typename T> DynamicFieldRef<T> dynamicField(llvm::StringRef name);

  bool hasField(llvm::StringRef name) const { return findField(name) >= 0; }
  void removeField(llvm::StringRef name);
  /// The descriptor of `name`, or null.
  const FieldDescriptor *fieldDescriptor(llvm::StringRef name) const;
  std::vector<const FieldDescriptor *> fields() const;

  /// Base address of the field's array (see the layout above), or null if
  /// there is no such field.
  void *fieldData(llvm::StringRef name);
  const void *fieldData(llvm::StringRef name) const;

private:
  struct FieldStorage {
    FieldDescriptor descriptor;
    std::unique_ptr<std::byte[], void (*)(std::byte *)> data;
  };
  struct GridTag {};

  int findField(llvm::StringRef name) const;
  /// Ensures room for `needed` elements in every field array.
  void grow(int needed);
  FieldStorage makeStorage(FieldDescriptor descriptor, int elements) const;
  /// Zero-fills element `e`'s block in every field.
  void zeroElement(int e);
  /// Moves element `from`'s data into slot `to` in every array.
  void moveElement(int from, int to);
  /// Removes edges that use `removed` of `endpointSet`, then renumbers the
  /// endpoints equal to `moved` to `removed`.
  void endpointRemoved(const Set &endpointSet, int removed, int moved);
  [[noreturn]] void fatal(const llvm::Twine &message) const;
  template <typename T>
  void checkFieldType(llvm::StringRef name, llvm::ArrayRef<int> shape);

  friend class ElementColouring;
  friend class SparsityPattern;

  std::string setName;
  int numElements = 0;
  int capacity = 0;
  uint64_t setVersion = 0;
  std::vector<Set *> endpointSets;
  std::vector<Set *> dependents; // edge sets with this set as an endpoint
  std::vector<int32_t> endpoints;
  std::vector<FieldStorage> fieldStorage;
  std::vector<int> gridDims;
  /// Sparsity patterns built over this edge set, keyed by (rows, columns).
  mutable std::map<std::pair<const Set *, const Set *>,
                   std::shared_ptr<const SparsityPattern>>
      patternCache;
  /// Colourings of this edge set's elements, keyed by chunk size.
  mutable std::map<int, std::shared_ptr<const ElementColouring>>
      colouringCache;
};

//===--- Typed field handles ----------------------------------------------===//

/// The array of a field of a set, looked up again only after a structural
/// change of the set. The typed field references share it.
template <typename T> class FieldArray {
public:
  llvm::StringRef name() const { return fieldName; }

protected:
  FieldArray() = default;
  FieldArray(Set *set, llvm::StringRef name) : set_(set), fieldName(name) {}
  T *base() const {
    if (cachedVersion != set_->version()) {
      cachedBase = static_cast<T *>(set_->fieldData(fieldName));
      cachedVersion = set_->version();
    }
    return cachedBase;
  }

private:
  Set *set_ = nullptr;
  std::string fieldName;
  mutable T *cachedBase = nullptr;
  mutable uint64_t cachedVersion = UINT64_MAX;
};

/// A field of statically known type and shape. get/set copy one block;
/// `ptr(e)` points at it in place.
template <typename T, int... Dims> class FieldRef : public FieldArray<T> {
public:
  static constexpr size_t kBlockSize = (size_t(1) * ... * size_t(Dims));
  using Block =
      std::conditional_t<sizeof...(Dims) == 0, T, std::array<T, kBlockSize>>;

  FieldRef() = default;

  Block get(int e) const {
    const T *p = ptr(e);
    if constexpr (sizeof...(Dims) == 0) {
      return *p;
    } else {
      Block block;
      std::copy(p, p + kBlockSize, block.begin());
      return block;
    }
  }
  void set(int e, const Block &value) const {
    T *p = ptr(e);
    if constexpr (sizeof...(Dims) == 0)
      *p = value;
    else
      std::copy(value.begin(), value.end(), p);
  }
  /// The element's block, in place; valid until the set changes structure.
  T *ptr(int e) const { return base() + static_cast<size_t>(e) * kBlockSize; }

private:
  friend class Set;
  using FieldArray<T>::base;
  FieldRef(Set *set, llvm::StringRef name) : FieldArray<T>(set, name) {}
};

/// A field whose shape is known only at run time.
template <typename T> class DynamicFieldRef : public FieldArray<T> {
public:
  DynamicFieldRef() = default;

  size_t blockSize() const { return blockElements; }
  llvm::MutableArrayRef<T> get(int e) const {
    return llvm::MutableArrayRef<T>(ptr(e), blockElements);
  }
  /// Copies `value` (blockSize() components) into e's block.
  void set(int e, llvm::ArrayRef<T> value) const {
    std::copy(value.begin(), value.begin() + blockElements, ptr(e));
  }
  T *ptr(int e) const {
    return base() + static_cast<size_t>(e) * blockElements;
  }

private:
  friend class Set;
  DynamicFieldRef(Set *set, llvm::StringRef name, size_t blockSize)
      : FieldArray<T>(set, name), blockElements(blockSize) {}
  using FieldArray<T>::base;
  size_t blockElements = 0;
};

template <typename T>
void Set::checkFieldType(llvm::StringRef name, llvm::ArrayRef<int> shape) {
  const FieldDescriptor *field = fieldDescriptor(name);
  if (!field)
    fatal("no field '" + name + "'");
  if (field->type != ComponentTypeOf<T>::value ||
      llvm::ArrayRef<int>(field->shape) != shape)
    fatal("field '" + name + "' has another component type or shape");
}

template <typename T, int... Dims>
FieldRef<T, Dims...> Set::addField(llvm::StringRef name) {
  if (llvm::Error err = addField(name, ComponentTypeOf<T>::value, {Dims...}))
    fatal(llvm::toString(std::move(err)));
  return FieldRef<T, Dims...>(this, name);
}

template <typename T>
DynamicFieldRef<T> Set::addField(llvm::StringRef name,
                                 llvm::ArrayRef<int> shape) {
  if (llvm::Error err = addField(name, ComponentTypeOf<T>::value, shape))
    fatal(llvm::toString(std::move(err)));
  return DynamicFieldRef<T>(this, name, fieldDescriptor(name)->blockSize());
}

template <typename T, int... Dims>
FieldRef<T, Dims...> Set::field(llvm::StringRef name) {
  checkFieldType<T>(name, {Dims...});
  return FieldRef<T, Dims...>(this, name);
}

template <typename T> DynamicFieldRef<T> Set::dynamicField(llvm::StringRef name) {
  const FieldDescriptor *descriptor = fieldDescriptor(name);
  if (!descriptor)
    fatal("no field '" + name + "'");
  checkFieldType<T>(name, descriptor->shape);
  return DynamicFieldRef<T>(this, name, descriptor->blockSize());
}

} // namespace simit

#endif // SIMIT_RUNTIME_SET_H
