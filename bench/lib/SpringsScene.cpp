//===--- SpringsScene.cpp - springs-bunny: implicit mass-spring system ----===//

#include "SpringsScene.h"
#include "SpringModel.h"
#include "Timer.h"

#include <algorithm>
#include <cmath>

namespace simit::bench {

template <typename Scalar>
SpringsScene<Scalar>::SpringsScene(const Mesh &mesh,
                                   const SpringsParams &params,
                                   SolverOptions solverOptions)
    : ImplicitScene<Scalar>(params.timeStep, solverOptions), params_(params),
      springs_(mesh.edges) {
  Timer timer;
  const int numPoints = static_cast<int>(mesh.points.size());
  std::array<double, 3> lo, hi;
  for (int axis = 0; axis < 3; ++axis) {
    lo[axis] = hi[axis] = numPoints ? mesh.points[0][axis] : 0.0;
    for (const auto &p : mesh.points) {
      lo[axis] = std::min(lo[axis], p[axis]);
      hi[axis] = std::max(hi[axis], p[axis]);
    }
  }
  std::vector<std::array<double, 3>> normalised(numPoints);
  this->fixed_.resize(numPoints);
  for (int v = 0; v < numPoints; ++v) {
    for (int axis = 0; axis < 3; ++axis)
      normalised[v][axis] =
          (mesh.points[v][axis] - lo[axis]) / (hi[axis] - lo[axis]);
    this->fixed_[v] = normalised[v][2] < params.fixedBelowZ;
  }
  this->positions_.resize(3 * numPoints);
  for (int v = 0; v < numPoints; ++v)
    for (int axis = 0; axis < 3; ++axis)
      this->positions_[3 * v + axis] = static_cast<Scalar>(normalised[v][axis]);
  this->initialPositions_ = this->positions_;
  this->velocities_ = Base::Vector::Zero(3 * numPoints);
  this->rhs_.resize(3 * numPoints);

  std::vector<double> restLength(springs_.size());
  for (size_t s = 0; s < springs_.size(); ++s) {
    const auto &a = normalised[springs_[s][0]], &b = normalised[springs_[s][1]];
    restLength[s] = std::sqrt((b[0] - a[0]) * (b[0] - a[0]) +
                              (b[1] - a[1]) * (b[1] - a[1]) +
                              (b[2] - a[2]) * (b[2] - a[2]));
  }
  restLength_.assign(restLength.begin(), restLength.end());
  this->setupTimes_.restShapeMs = timer.lapMs();

  const double crossSection = M_PI * params.radius * params.radius;
  std::vector<double> mass(numPoints, 0.0);
  for (size_t s = 0; s < springs_.size(); ++s) {
    double half = 0.5 * params.density * crossSection * restLength[s];
    mass[springs_[s][0]] += half;
    mass[springs_[s][1]] += half;
  }
  mass_.assign(mass.begin(), mass.end());
  this->setupTimes_.massMs = timer.lapMs();

  std::vector<std::pair<int, int>> blocks;
  for (const auto &[a, b] : springs_)
    if (!this->fixed_[a] && !this->fixed_[b]) {
      blocks.emplace_back(a, b);
      blocks.emplace_back(b, a);
    }
  this->buildSystem(blocks);
  const BlockSparseMatrix<Scalar> &system = *this->system_;
  blockOffsets_.resize(springs_.size());
  for (size_t s = 0; s < springs_.size(); ++s) {
    auto [a, b] = springs_[s];
    bool freeA = !this->fixed_[a], freeB = !this->fixed_[b];
    blockOffsets_[s] = {freeA ? system.blockOffset(a, a) : -1,
                        freeB ? system.blockOffset(b, b) : -1,
                        freeA && freeB ? system.blockOffset(a, b) : -1,
                        freeA && freeB ? system.blockOffset(b, a) : -1};
  }
  // MD: (m + h viscous) I for free points, I for fixed ones.
  auto &matrix = this->system_->matrix();
  for (int v = 0; v < numPoints; ++v) {
    double diagonal = this->fixed_[v] ? 1.0
                                      : mass[v] + params.timeStep *
                                                      params.viscousDamping;
    int offset = system.blockOffset(v, v), stride = system.rowStride(v);
    for (int r = 0; r < 3; ++r)
      matrix.valuePtr()[offset + r * stride + r] =
          static_cast<Scalar>(diagonal);
  }
  diagonalValues_.assign(matrix.valuePtr(),
                         matrix.valuePtr() + matrix.nonZeros());
  this->setupTimes_.sparsityMs = timer.lapMs();
}

template <typename Scalar> void SpringsScene<Scalar>::assemble() {
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  BlockSparseMatrix<Scalar> &system = *this->system_;
  std::copy(diagonalValues_.begin(), diagonalValues_.end(),
            system.matrix().valuePtr());

  const Scalar h = this->timeStep_;
  const Vec3 gravity = Eigen::Vector3d(params_.gravity.data()).cast<Scalar>();
  const int numPoints = this->numVertices();
  Scalar *rhs = this->rhs_.data();
  const Scalar *v = this->velocities_.data();
  for (int p = 0; p < numPoints; ++p) {
    Eigen::Map<Vec3> fmg(rhs + 3 * p);
    if (this->fixed_[p])
      fmg.setZero();
    else
      fmg = mass_[p] * (Eigen::Map<const Vec3>(v + 3 * p) + h * gravity);
  }

  const Scalar stiffness = static_cast<Scalar>(params_.stiffness);
  const Scalar h2 = h * h;
  const Scalar *x = this->positions_.data();
  for (size_t s = 0; s < springs_.size(); ++s) {
    auto [a, b] = springs_[s];
    const std::array<int, 4> &offsets = blockOffsets_[s];
    SpringResponse<Scalar> spring =
        springResponse<Scalar>(Eigen::Map<const Vec3>(x + 3 * a),
                               Eigen::Map<const Vec3>(x + 3 * b), stiffness,
                               restLength_[s]);
    Eigen::Matrix<Scalar, 3, 3> kb = h2 * spring.hessianBlock;
    if (offsets[0] >= 0) {
      Eigen::Map<Vec3>(rhs + 3 * a) += h * spring.forceOnFirst;
      system.addBlock(offsets[0], system.rowStride(a), kb);
    }
    if (offsets[1] >= 0) {
      Eigen::Map<Vec3>(rhs + 3 * b) -= h * spring.forceOnFirst;
      system.addBlock(offsets[1], system.rowStride(b), kb);
    }
    if (offsets[2] >= 0) {
      system.subtractBlock(offsets[2], system.rowStride(a), kb);
      system.subtractBlock(offsets[3], system.rowStride(b), kb);
    }
  }
}

template class SpringsScene<float>;
template class SpringsScene<double>;

} // namespace simit::bench
