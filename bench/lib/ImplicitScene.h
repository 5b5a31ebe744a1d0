//===--- ImplicitScene.h - Linearly implicit time stepping -----*- C++ -*-===//
//
// What the benchmark scenes share: per frame, assemble a sparse system
// A v' = b over the vertex velocities (3x3 blocks on a pattern fixed at
// set-up), solve it from the current v, then x <- x + h v'. The scenes
// differ only in how they assemble A and b.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_IMPLICITSCENE_H
#define SIMIT_BENCH_IMPLICITSCENE_H

#include "BlockSparseMatrix.h"
#include "LinearSolver.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace simit::bench {

/// Milliseconds spent in one-off set-up, reported apart from the frames.
struct SetupTimes {
  double restShapeMs = 0; // normalisation, rest lengths or rest shapes
  double massMs = 0;
  double sparsityMs = 0;  // pattern, location tables, symbolic factorisation
};

struct FrameStats {
  bool succeeded = true; // false when the direct factorisation failed
  double assemblyMs = 0;
  double solveMs = 0;    // the linear solve and the position update
  int iterations = 0;
  double residualNormSq = 0;
};

template <typename Scalar> class ImplicitScene {
public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  virtual ~ImplicitScene();

  FrameStats step();

  int numVertices() const { return static_cast<int>(positions_.size() / 3); }
  int numFreeVertices() const;
  bool isFixed(int vertex) const { return fixed_[vertex]; }
  /// x y z per vertex, 3 * numVertices values.
  const Vector &positions() const { return positions_; }
  const Vector &initialPositions() const { return initialPositions_; }
  const Vector &velocities() const { return velocities_; }
  const BlockSparseMatrix<Scalar> &systemMatrix() const { return *system_; }
  const SetupTimes &setupTimes() const { return setupTimes_; }

protected:
  ImplicitScene(double timeStep, SolverOptions solverOptions);

  /// Fills system_'s values and rhs_ for the current positions and
  /// velocities.
  virtual void assemble() = 0;

  /// Creates system_ with the given off-diagonal blocks (all diagonal
  /// blocks are always present) and prepares the solver for its pattern.
  void buildSystem(const std::vector<std::pair<int, int>> &blocks);

  Scalar timeStep_;
  Vector positions_, initialPositions_, velocities_, rhs_;
  std::vector<char> fixed_;
  std::unique_ptr<BlockSparseMatrix<Scalar>> system_;
  SetupTimes setupTimes_;

private:
  LinearSolver<Scalar> solver_;
};

} // namespace simit::bench

#endif // SIMIT_BENCH_IMPLICITSCENE_H
