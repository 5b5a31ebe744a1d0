//===--- SpringsScene.h - springs-bunny: implicit springs ----*- C++ -*-===//
//
// bench/scenes.md, springs-bunny: positions normalised per axis to [0, 1],
// one spring per mesh edge, masses from the springs' volumes, points with
// normalised z below a threshold fixed, and the linearly implicit step
// (MD + K) v' = fmg + fe.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_SPRINGSSCENE_H
#define SIMIT_BENCH_SPRINGSSCENE_H

#include "ImplicitScene.h"

#include "simit/Runtime/Mesh.h"

#include <array>

namespace simit::bench {

struct SpringsParams {
  double stiffness = 1e4;
  double density = 1e3;
  double radius = 0.01;
  double timeStep = 1e-2;
  double viscousDamping = 2.0;
  std::array<double, 3> gravity = {0, -9.81, 0};
  double fixedBelowZ = 0.1; // on normalised coordinates
};

template <typename Scalar> class SpringsScene : public ImplicitScene<Scalar> {
public:
  /// Springs are the mesh's edges.
  SpringsScene(const Mesh &mesh, const SpringsParams &params,
               SolverOptions solverOptions);

  int numSprings() const { return static_cast<int>(springs_.size()); }
  Scalar mass(int vertex) const { return mass_[vertex]; }
  Scalar restLength(int spring) const { return restLength_[spring]; }

private:
  void assemble() override;

  using Base = ImplicitScene<Scalar>;
  SpringsParams params_;
  std::vector<std::array<int, 2>> springs_;
  std::vector<Scalar> restLength_, mass_;
  // Per spring, the value offsets of blocks (0,0), (1,1), (0,1), (1,0),
  // -1 for a block that involves a fixed endpoint.
  std::vector<std::array<int, 4>> blockOffsets_;
  // The system's values with only the diagonal mass-damping blocks.
  std::vector<Scalar> diagonalValues_;
};

} // namespace simit::bench

#endif // SIMIT_BENCH_SPRINGSSCENE_H
