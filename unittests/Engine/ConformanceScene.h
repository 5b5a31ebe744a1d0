//===--- ConformanceScene.h - Random sets for conformance -------*- C++ -*-===//
//
// The hypergraph every conformance program runs on: two vertex sets and
// edge sets of cardinality 2, 3 and 4 over the first (random endpoints, and
// one spring joining a vertex to itself), plus heterogeneous edge sets
// between them, with random field values from a fixed seed. Every
// element type carries the same fields, so any set can hold any role:
//
//   x, w        inputs over the set (float, or vector[3](float))
//   y, z, u     outputs over the set (same type)
//   k, l, s     vector[16](float): coefficients of element matrices
//   B, C, I     matrix[3,3](float): blocks of element matrices (I = identity)
//
// The test reads the same data back as dense Eigen objects.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_UNITTESTS_ENGINE_CONFORMANCESCENE_H
#define SIMIT_UNITTESTS_ENGINE_CONFORMANCESCENE_H

#include "simit/Runtime/Set.h"

#include "llvm/ADT/StringRef.h"

#include <Eigen/Dense>

#include <array>

namespace simit::conformance {

enum class SetId { Verts, Nodes, Springs, Tris, Tets, Links, Hinges };
constexpr std::array<SetId, 7> kAllSets = {
    SetId::Verts, SetId::Nodes, SetId::Springs, SetId::Tris,
    SetId::Tets,  SetId::Links, SetId::Hinges};

/// The extern set's name in the programs ("verts", ...).
llvm::StringRef setName(SetId set);
/// Its element type's name ("Vert", ...).
llvm::StringRef elementName(SetId set);
/// The sets its elements' endpoints belong to (empty for a vertex set).
llvm::ArrayRef<SetId> endpointSets(SetId set);

/// Components of the coefficient vectors k, l, s.
constexpr int kCoefficients = 16;

class Scene {
public:
  /// `blockSize` is 1 (float vector fields) or 3 (vector[3](float)).
  Scene(int blockSize, unsigned seed);

  int blockSize() const { return block; }
  Set &set(SetId id) { return *sets[static_cast<int>(id)]; }

  /// Field `name` (x, w, y, z or u) of every element, as one dense vector
  /// of size() * blockSize() components.
  Eigen::VectorXd vectorField(SetId id, llvm::StringRef name);
  /// Zeroes the outputs y, z, u of every set.
  void clearOutputs();

  /// Component `index` of coefficient vector `name` (k, l or s) at `element`.
  double coefficient(SetId id, llvm::StringRef name, int element, int index);
  /// Matrix field `name` (B, C or I) at `element`.
  Eigen::Matrix3d blockField(SetId id, llvm::StringRef name, int element);

private:
  int block;
  std::array<std::unique_ptr<Set>, kAllSets.size()> sets;
};

} // namespace simit::conformance

#endif // SIMIT_UNITTESTS_ENGINE_CONFORMANCESCENE_H
