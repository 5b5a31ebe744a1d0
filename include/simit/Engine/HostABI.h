//===--- HostABI.h - Arguments of a compiled Simit function -----*- C++ -*-===//
//
// The lowering gives every exported function one argument per piece of host
// data it touches and describes each with an entry of the function's
// `simit.bindings` attribute (docs/lowering.md): set sizes, field arrays,
// endpoint arrays, the BCSR pattern arrays of assembled matrices, extern
// tensors and the function's own parameters. A HostSignature is that
// description read back from the IR, with each argument's machine type, so
// the engine can fill the arguments from Sets and host buffers in place.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ENGINE_HOSTABI_H
#define SIMIT_ENGINE_HOSTABI_H

#include "simit/ABI/BindingKind.h"
#include "simit/Runtime/Set.h"

#include "llvm/Support/Error.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace mlir {
class Operation;
class Type;
} // namespace mlir

namespace simit {

/// The scalar types that cross the host boundary.
/// String: a C string (`!llvm.ptr`, a `const char *`), scalars only.
enum class ScalarKind : uint8_t {
  Float64,
  Float32,
  Int32,
  Int64,
  Index,
  Bool,
  String
};

/// Bytes per value in memory (Bool: one byte).
size_t scalarSize(ScalarKind kind);
/// "f64", "f32", "i32", "i64", "index", "i1".
llvm::StringRef scalarKindName(ScalarKind kind);
/// The runtime component type stored by arrays of `kind`, if there is one
/// (Int64 and Index have none).
bool componentTypeFor(ScalarKind kind, ComponentType &type);

/// The machine type of one argument or result: a scalar, a memref, or a
/// vector passed by value (the lowering's form of small dense tensors).
struct ValueType {
  static constexpr int64_t kDynamic = -1;

  ScalarKind scalar = ScalarKind::Float64;
  bool isMemRef = false;
  bool isVector = false;
  /// Every component is a (real, imaginary) pair of `scalar`s (Float64 or
  /// Float32): a `complex<T>` scalar, or a `vector<N x 2 x T>` of N complex
  /// components (the lowering's form of a local complex tensor).
  bool isComplex = false;
  /// Memref or vector dimensions, kDynamic for `?`; empty for a scalar or
  /// a rank-0 memref. A complex vector's pair dimension is not included.
  std::vector<int64_t> shape;

  int64_t rank() const { return static_cast<int64_t>(shape.size()); }
  /// Components of a vector (1 for a scalar).
  int64_t numComponents() const;
  /// Scalars per component: 2 for complex, else 1.
  int64_t partsPerComponent() const { return isComplex ? 2 : 1; }
  /// The shape of a host buffer of `scalar`s holding the value: `shape`,
  /// then 2 for the (re, im) pairs of a complex value.
  std::vector<int64_t> hostShape() const;
  /// "memref<?x3xf64>", "vector<9xf64>", "vector<2x2xf64>", "f64",
  /// "complex<f64>".
  std::string str() const;
};

/// Reads an MLIR type (index, i1/i32/i64, f32/f64, complex<f32/f64>, a
/// memref of numbers with the identity layout, a static vector of numbers,
/// or a `vector<N x 2 x f32/f64>` of complex pairs) as a ValueType.
llvm::Expected<ValueType> toValueType(mlir::Type type);

/// "[?, 3]": a shape as errors print it (kDynamic as '?').
std::string shapeString(llvm::ArrayRef<int64_t> shape);
std::string shapeString(llvm::ArrayRef<int> shape);

/// What one argument carries.
struct ArgumentBinding {
  /// The kinds are spelled once for the lowering and the engine.
  using Kind = abi::BindingKind;
  Kind kind = Kind::Parameter;
  std::string set, field, rows, cols, name;
  /// Union bindings: the edge sets of the union and of the gathered part
  /// (written '+'-joined in `simit.bindings`, the part prefixed by '~' when
  /// read transposed).
  std::vector<std::string> edgeSets, partSets;
  bool partTransposed = false;
  /// Product bindings: the union of one or more chains of factors, each
  /// with its factors' edge sets and the sets between its factors (written
  /// "A*B+C|E" and "M1|" in `simit.bindings`: chains '|'-separated, factors
  /// '*'-separated, a factor's edge sets '+'-joined, mids ','-separated).
  struct ProductChain {
    std::vector<std::vector<std::string>> factorSets;
    std::vector<std::string> mids;
  };
  std::vector<ProductChain> chains;
  /// Stencil bindings: the offsets, ';'-separated points of ','-separated
  /// coordinates ("-1,0;0,0;1,0"); `set` is the grid.
  std::string offsets;
  /// Parameter: its position among the Simit function's parameters.
  int64_t index = -1;
  /// ElementColours: elements per chunk.
  int64_t chunk = 0;
  /// Extern scalars and local tensors, and local tensor parameters: the
  /// shape the program declares ([] for a scalar); a bound value must have
  /// it, or be flat.
  std::optional<std::vector<int64_t>> declaredShape;
  ValueType type;

  /// The key Function binds it under: the extern's name, or "#<index>" for
  /// a parameter.
  std::string bufferKey() const;

  /// How errors name it: "field 'points.x'", "extern 'h'", ...
  std::string describe() const;
};

/// The host ABI of one compiled function.
struct HostSignature {
  std::string function;
  std::vector<ArgumentBinding> arguments;
  std::vector<ValueType> results;
};

/// Reads the signature of `function`, a func.func or an llvm.func, from its
/// `simit.bindings` and `simit.host_type` attributes (simit-record-host-abi;
/// a func.func without the latter has its own type read instead). Errors
/// name the function and the malformed entry.
llvm::Expected<HostSignature> readHostSignature(mlir::Operation *function);

} // namespace simit

#endif // SIMIT_ENGINE_HOSTABI_H
