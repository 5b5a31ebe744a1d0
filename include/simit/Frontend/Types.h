//===- Types.h - Semantic types of Simit values -----------------*- C++ -*-===//
//
// The resolved types sema attaches to declarations and expressions. Types are
// immutable and shared. Tensor types carry their block hierarchy, dimension
// identities (integer ranges, sets by declaration, generic parameters) and
// vector orientation; element and tuple types carry the origin sets of the
// values when known (origins never take part in type equality).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_TYPES_H
#define SIMIT_FRONTEND_TYPES_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace simit::frontend {

class ElementDecl;
class VarDecl;
class GenericParamDecl;

enum class ScalarKind { Int, Float, Bool, Complex, String };

const char *scalarKindName(ScalarKind kind);
inline bool isNumeric(ScalarKind kind) {
  return kind == ScalarKind::Int || kind == ScalarKind::Float ||
         kind == ScalarKind::Complex;
}

/// One tensor dimension at one level of the block hierarchy.
struct Dim {
  enum class Kind { Range, Set, Generic };
  Kind kind = Kind::Range;
  int64_t size = 0;                         // Range: 0 .. size-1
  const VarDecl *set = nullptr;             // Set: its extern or parameter
  const GenericParamDecl *generic = nullptr; // Generic: the parameter

  static Dim range(int64_t size) {
    Dim d;
    d.size = size;
    return d;
  }
  static Dim ofSet(const VarDecl *set) {
    Dim d;
    d.kind = Kind::Set;
    d.set = set;
    return d;
  }
  static Dim ofGeneric(const GenericParamDecl *generic) {
    Dim d;
    d.kind = Kind::Generic;
    d.generic = generic;
    return d;
  }
  bool operator==(const Dim &o) const {
    return kind == o.kind && size == o.size && set == o.set &&
           generic == o.generic;
  }
  bool operator!=(const Dim &o) const { return !(*this == o); }
  std::string str() const;
};

class Type;
using TypePtr = std::shared_ptr<const Type>;

class Type {
public:
  enum class Kind {
    Error,   // the type of an erroneous expression; silences follow-up errors
    Void,    // a call without results
    Tensor,  // scalars are tensors of order 0
    Element,
    Set,     // vertex, edge and grid sets
    Tuple,
    Opaque,
    Results, // several results of a call or map
  };

  Kind kind = Kind::Error;

  // Tensor.
  ScalarKind component = ScalarKind::Float;
  std::vector<Dim> dims; // this level of the hierarchy
  TypePtr block;         // the block type, null for scalar components
  bool row = false;      // order-1 row vector

  // Element; Set (its elements); Tuple members use `members`.
  const ElementDecl *element = nullptr;
  const VarDecl *origin = nullptr; // Element: the set it belongs to, if known

  // Set: endpoint sets (edge set), or the point set of a grid.
  std::vector<const VarDecl *> endpoints;
  unsigned gridRank = 0; // > 0 for grids

  // Tuple.
  std::vector<const ElementDecl *> members;
  std::vector<std::string> memberNames; // empty for unnamed tuples
  std::vector<const VarDecl *> memberOrigins;

  // Results.
  std::vector<TypePtr> results;

  // Factories.
  static TypePtr error();
  static TypePtr voidType();
  static TypePtr opaque();
  static TypePtr scalar(ScalarKind kind);
  static TypePtr tensor(ScalarKind component, std::vector<Dim> dims,
                        TypePtr block, bool row);
  static TypePtr elementOf(const ElementDecl *element,
                           const VarDecl *origin = nullptr);
  static TypePtr resultsOf(std::vector<TypePtr> results);

  bool isError() const { return kind == Kind::Error; }
  bool isTensor() const { return kind == Kind::Tensor; }
  bool isScalar() const { return isTensor() && dims.empty(); }
  bool isScalar(ScalarKind k) const { return isScalar() && component == k; }
  bool isNumericTensor() const { return isTensor() && isNumeric(component); }
  unsigned order() const { return isTensor() ? dims.size() : 0; }
  bool isVector() const { return order() == 1; }
  bool isColumnVector() const { return isVector() && !row; }
  bool isRowVector() const { return isVector() && row; }
  bool isMatrix() const { return order() == 2; }
  bool isSet() const { return kind == Kind::Set; }
  bool isGrid() const { return isSet() && gridRank > 0; }
  bool isEdgeSet() const { return isSet() && !endpoints.empty(); }
  /// The number of endpoints of every element of a set: 2 for a grid (an
  /// edge joins two neighbouring points), as in the simit dialect.
  size_t cardinality() const { return isGrid() ? 2 : endpoints.size(); }
  /// The set of endpoint `m` (a grid's point set for both).
  const VarDecl *endpoint(size_t m) const {
    return isGrid() ? endpoints.front() : endpoints[m];
  }
  bool isElement() const { return kind == Kind::Element; }
  bool isTuple() const { return kind == Kind::Tuple; }
  bool isOpaque() const { return kind == Kind::Opaque; }
  bool isVoid() const { return kind == Kind::Void; }
  bool isResults() const { return kind == Kind::Results; }
  /// A tensor with a set dimension anywhere in its hierarchy.
  bool isSystem() const;
  bool isHomogeneous() const; // edge set whose endpoints are one set

  /// Dimension `i` through the whole block hierarchy (outer first).
  std::vector<Dim> hierarchy(unsigned i) const;

  std::string str() const;
};

/// Type equality: same kind, component, order, dimension hierarchies, block
/// structure and (when `orientation`) vector orientation; elements by
/// declaration; origins ignored.
bool typesEqual(const TypePtr &a, const TypePtr &b, bool orientation = true);

/// The same tensor type with a flipped (vector) or swapped (matrix) shape.
TypePtr transposed(const TypePtr &t);

/// The same type with every generic dimension replaced through `binding`.
TypePtr substitute(const TypePtr &t,
                   const std::vector<const GenericParamDecl *> &params,
                   const std::vector<Dim> &binding);

/// The same type with every dimension over a set in `sets` (set-typed
/// parameters) over the set it maps to (the argument of a call).
TypePtr substituteSets(
    const TypePtr &t,
    const std::vector<std::pair<const VarDecl *, const VarDecl *>> &sets);

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_TYPES_H
