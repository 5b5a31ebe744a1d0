//===--- FemScene.h - fem-dragon and fem-bar: Neo-Hookean FEM ---*- C++ -*-===//
//
// bench/scenes.md, fem-dragon and fem-bar: linear tetrahedra with the
// Neo-Hookean model, lumped masses, vertices below a height fixed (no force,
// no stiffness, mass block kept), and the linearly implicit step
// (M - h^2 K) v' = M v + h (f + f_gravity).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_FEMSCENE_H
#define SIMIT_BENCH_FEMSCENE_H

#include "ImplicitScene.h"
#include "NeoHookean.h"

#include "simit/Runtime/Mesh.h"

#include <array>

namespace simit::bench {

struct FemParams {
  double density = 1000;
  double youngsModulus = 1e6;
  double poissonRatio = 0.45;
  double timeStep = 0.01;
  std::array<double, 3> gravity = {0, -10, 0};
  double fixedBelowY = 0;                             // absolute height
  std::array<double, 3> initialVelocity = {0, 0, 0}; // of free vertices
};

template <typename Scalar> class FemScene : public ImplicitScene<Scalar> {
public:
  FemScene(const Mesh &mesh, const FemParams &params,
           SolverOptions solverOptions);

  Scalar mass(int vertex) const { return mass_[vertex]; }

private:
  void assemble() override;

  FemParams params_;
  NeoHookeanMaterial material_;
  std::vector<std::array<int, 4>> tets_;
  std::vector<TetRestShape<Scalar>> restShapes_;
  std::vector<Scalar> mass_;
  // Per tet, the value offset of block (i, j) at 4 * i + j, -1 when vertex
  // i or j is fixed.
  std::vector<std::array<int, 16>> blockOffsets_;
  // The system's values with only the diagonal mass blocks.
  std::vector<Scalar> massValues_;
  TetElasticity<Scalar> elasticity_;
};

} // namespace simit::bench

#endif // SIMIT_BENCH_FEMSCENE_H
