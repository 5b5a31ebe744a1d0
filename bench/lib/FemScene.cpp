//===--- FemScene.cpp - fem-dragon and fem-bar: Neo-Hookean FEM -----------===//

#include "FemScene.h"
#include "Timer.h"

#include <algorithm>

namespace simit::bench {

template <typename Scalar>
FemScene<Scalar>::FemScene(const Mesh &mesh, const FemParams &params,
                           SolverOptions solverOptions)
    : ImplicitScene<Scalar>(params.timeStep, solverOptions), params_(params),
      material_(NeoHookeanMaterial::fromYoungPoisson(params.youngsModulus,
                                                     params.poissonRatio)),
      tets_(mesh.tets) {
  Timer timer;
  const int numPoints = static_cast<int>(mesh.points.size());
  this->fixed_.resize(numPoints);
  this->positions_.resize(3 * numPoints);
  this->velocities_.resize(3 * numPoints);
  this->rhs_.resize(3 * numPoints);
  for (int v = 0; v < numPoints; ++v) {
    this->fixed_[v] = mesh.points[v][1] < params.fixedBelowY;
    for (int axis = 0; axis < 3; ++axis) {
      this->positions_[3 * v + axis] =
          static_cast<Scalar>(mesh.points[v][axis]);
      this->velocities_[3 * v + axis] =
          this->fixed_[v] ? Scalar(0)
                          : static_cast<Scalar>(params.initialVelocity[axis]);
    }
  }
  this->initialPositions_ = this->positions_;

  // Rest shapes in double whatever Scalar is, so a float32 run starts from
  // the same rest state.
  std::vector<double> volume(tets_.size());
  restShapes_.resize(tets_.size());
  for (size_t t = 0; t < tets_.size(); ++t) {
    std::array<Vec3<double>, 4> x;
    for (int i = 0; i < 4; ++i)
      x[i] = Eigen::Vector3d(mesh.points[tets_[t][i]].data());
    TetRestShape<double> rest = tetRestShape(x);
    volume[t] = rest.volume;
    restShapes_[t] = {rest.inverseDm.cast<Scalar>(),
                      static_cast<Scalar>(rest.volume)};
  }
  this->setupTimes_.restShapeMs = timer.lapMs();

  std::vector<double> mass(numPoints, 0.0);
  for (size_t t = 0; t < tets_.size(); ++t)
    for (int v : tets_[t])
      mass[v] += params.density * volume[t] / 4;
  mass_.assign(mass.begin(), mass.end());
  this->setupTimes_.massMs = timer.lapMs();

  std::vector<std::pair<int, int>> blocks;
  for (const auto &tet : tets_)
    for (int a : tet)
      for (int b : tet)
        if (a != b && !this->fixed_[a] && !this->fixed_[b])
          blocks.emplace_back(a, b);
  this->buildSystem(blocks);
  const BlockSparseMatrix<Scalar> &system = *this->system_;
  blockOffsets_.resize(tets_.size());
  for (size_t t = 0; t < tets_.size(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        int a = tets_[t][i], b = tets_[t][j];
        blockOffsets_[t][4 * i + j] = this->fixed_[a] || this->fixed_[b]
                                          ? -1
                                          : system.blockOffset(a, b);
      }
  auto &matrix = this->system_->matrix();
  for (int v = 0; v < numPoints; ++v) {
    int offset = system.blockOffset(v, v), stride = system.rowStride(v);
    for (int r = 0; r < 3; ++r)
      matrix.valuePtr()[offset + r * stride + r] = mass_[v];
  }
  massValues_.assign(matrix.valuePtr(), matrix.valuePtr() + matrix.nonZeros());
  this->setupTimes_.sparsityMs = timer.lapMs();
}

template <typename Scalar> void FemScene<Scalar>::assemble() {
  BlockSparseMatrix<Scalar> &system = *this->system_;
  std::copy(massValues_.begin(), massValues_.end(), system.matrix().valuePtr());

  // b = M v + h f_gravity for free vertices, 0 for fixed ones (whose v is 0).
  const Scalar h = this->timeStep_;
  const Vec3<Scalar> gravity =
      Eigen::Vector3d(params_.gravity.data()).cast<Scalar>();
  const int numPoints = this->numVertices();
  Scalar *rhs = this->rhs_.data();
  const Scalar *v = this->velocities_.data();
  for (int p = 0; p < numPoints; ++p) {
    Eigen::Map<Vec3<Scalar>> b(rhs + 3 * p);
    if (this->fixed_[p])
      b.setZero();
    else
      b = mass_[p] * (Eigen::Map<const Vec3<Scalar>>(v + 3 * p) + h * gravity);
  }

  // b += h f_elastic and A -= h^2 K, free vertices only.
  const Scalar minusH2 = -h * h;
  const Scalar *x = this->positions_.data();
  for (size_t t = 0; t < tets_.size(); ++t) {
    const std::array<int, 4> &tet = tets_[t];
    std::array<Vec3<Scalar>, 4> corners;
    for (int i = 0; i < 4; ++i)
      corners[i] = Eigen::Map<const Vec3<Scalar>>(x + 3 * tet[i]);
    tetElasticity(corners, restShapes_[t], material_, /*withStiffness=*/true,
                  elasticity_);
    const std::array<int, 16> &offsets = blockOffsets_[t];
    for (int i = 0; i < 4; ++i) {
      if (this->fixed_[tet[i]])
        continue;
      Eigen::Map<Vec3<Scalar>>(rhs + 3 * tet[i]) += h * elasticity_.force[i];
      int stride = system.rowStride(tet[i]);
      for (int j = 0; j < 4; ++j)
        if (offsets[4 * i + j] >= 0)
          system.addBlock(offsets[4 * i + j], stride,
                          minusH2 * elasticity_.stiffness[i][j]);
    }
  }
}

template class FemScene<float>;
template class FemScene<double>;

} // namespace simit::bench
