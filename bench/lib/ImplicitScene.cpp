//===--- ImplicitScene.cpp - Linearly implicit time stepping --------------===//

#include "ImplicitScene.h"
#include "Timer.h"

#include <algorithm>

namespace simit::bench {

template <typename Scalar>
ImplicitScene<Scalar>::ImplicitScene(double timeStep,
                                     SolverOptions solverOptions)
    : timeStep_(static_cast<Scalar>(timeStep)), solver_(solverOptions) {}

template <typename Scalar> ImplicitScene<Scalar>::~ImplicitScene() = default;

template <typename Scalar> int ImplicitScene<Scalar>::numFreeVertices() const {
  return static_cast<int>(std::count(fixed_.begin(), fixed_.end(), 0));
}

template <typename Scalar>
void ImplicitScene<Scalar>::buildSystem(
    const std::vector<std::pair<int, int>> &blocks) {
  system_ = std::make_unique<BlockSparseMatrix<Scalar>>(numVertices(), blocks);
  solver_.analyzePattern(system_->matrix());
}

template <typename Scalar> FrameStats ImplicitScene<Scalar>::step() {
  FrameStats stats;
  Timer timer;
  assemble();
  stats.assemblyMs = timer.lapMs();

  SolveResult solve = solver_.solve(system_->matrix(), rhs_, velocities_);
  stats.succeeded = solve.succeeded;
  stats.iterations = solve.iterations;
  stats.residualNormSq = solve.residualNormSq;
  if (solve.succeeded)
    positions_ += timeStep_ * velocities_;
  stats.solveMs = timer.lapMs();
  return stats;
}

template class ImplicitScene<float>;
template class ImplicitScene<double>;

} // namespace simit::bench
