//===--- SceneTest.cpp - The benchmark scenes on the shipped meshes -------===//

#include "FemScene.h"
#include "Scenes.h"
#include "SpringsScene.h"

#include "simit/Runtime/Mesh.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace simit::bench;

namespace {

const std::string kMeshDir = SIMIT_SHARED_DIR "/data/meshes";

template <typename Scalar = double>
LoadedScene<Scalar> load(const std::string &name, SolverOptions solver,
                         int refinements = 0) {
  llvm::Expected<LoadedScene<Scalar>> loaded =
      createScene<Scalar>({name, kMeshDir, refinements, solver});
  if (!loaded) {
    ADD_FAILURE() << llvm::toString(loaded.takeError());
    return {};
  }
  return std::move(*loaded);
}

simit::Mesh loadMesh(const std::string &base) {
  llvm::Expected<simit::Mesh> mesh = simit::loadTetGen(kMeshDir + "/" + base);
  EXPECT_TRUE(static_cast<bool>(mesh));
  return mesh ? std::move(*mesh) : simit::Mesh();
}

const SolverOptions kDirect = {SolverKind::Direct, 0, 0};

TEST(FemBar, LumpedMassIsDensityTimesVolume) {
  LoadedScene<double> bar = load("fem-bar", kDirect);
  ASSERT_TRUE(bar.scene);
  simit::Mesh mesh = loadMesh("bar2k");
  double volume = 0;
  for (const auto &tet : mesh.tets)
    volume += std::abs(simit::signedTetVolume(mesh, tet));
  auto &scene = static_cast<FemScene<double> &>(*bar.scene);
  double mass = 0;
  for (int v = 0; v < scene.numVertices(); ++v)
    mass += scene.mass(v);
  EXPECT_NEAR(mass, 1000 * volume, 1e-12 * mass);
  EXPECT_EQ(bar.numElements, 1151);
}

TEST(FemBar, FixedVerticesAreTheBottomOnes) {
  LoadedScene<double> bar = load("fem-bar", kDirect);
  ASSERT_TRUE(bar.scene);
  simit::Mesh mesh = loadMesh("bar2k");
  int fixed = 0;
  for (int v = 0; v < bar.scene->numVertices(); ++v) {
    EXPECT_EQ(bar.scene->isFixed(v), mesh.points[v][1] < 1e-4);
    fixed += bar.scene->isFixed(v);
  }
  EXPECT_GT(fixed, 0);
  EXPECT_EQ(bar.scene->numFreeVertices(), bar.scene->numVertices() - fixed);
}

// Converged CG and the direct factorisation solve the same systems, so ten
// frames agree far below the difference capped CG makes; fixed vertices
// never move.
TEST(FemBar, ConvergedCGMatchesDirectSolve) {
  LoadedScene<double> direct = load("fem-bar", kDirect);
  LoadedScene<double> cg = load("fem-bar", {SolverKind::CG, 10000, 1e-26});
  ASSERT_TRUE(direct.scene && cg.scene);
  for (int frame = 0; frame < 10; ++frame) {
    ASSERT_TRUE(direct.scene->step().succeeded);
    ASSERT_GT(cg.scene->step().iterations, 0);
  }
  const Eigen::VectorXd &x = cg.scene->positions();
  const Eigen::VectorXd &ref = direct.scene->positions();
  const Eigen::VectorXd &x0 = direct.scene->initialPositions();
  EXPECT_LT((x - ref).norm() / (ref - x0).norm(), 1e-9);
  EXPECT_GT((ref - x0).norm(), 1e-3);
  for (int v = 0; v < direct.scene->numVertices(); ++v) {
    if (!direct.scene->isFixed(v))
      continue;
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_EQ(ref[3 * v + axis], x0[3 * v + axis]);
  }
}

TEST(FemBar, SinglePrecisionStaysCloseToDouble) {
  LoadedScene<double> exact = load("fem-bar", kDirect);
  LoadedScene<float> single = load<float>("fem-bar", kDirect);
  ASSERT_TRUE(exact.scene && single.scene);
  for (int frame = 0; frame < 10; ++frame) {
    ASSERT_TRUE(exact.scene->step().succeeded);
    ASSERT_TRUE(single.scene->step().succeeded);
  }
  const Eigen::VectorXd &ref = exact.scene->positions();
  Eigen::VectorXd x = single.scene->positions().cast<double>();
  EXPECT_LT((x - ref).norm() / (ref - exact.scene->initialPositions()).norm(),
            1e-3);
}

TEST(FemBar, RefinementMultipliesTets) {
  LoadedScene<double> refined = load("fem-bar", kDirect, 1);
  ASSERT_TRUE(refined.scene);
  EXPECT_EQ(refined.numElements, 8 * 1151);
  EXPECT_GT(refined.scene->numVertices(), 439);
}

// scenes.md: capped at 50 iterations, CG leaves fem-dragon 0.73 of the
// motion away from the exact solve after 10 frames. Capped CG amplifies
// rounding (about 1e-2 between instruction sets), hence the band.
TEST(FemDragon, CappedCGErrorMatchesScenesMd) {
  LoadedScene<double> direct = load("fem-dragon", kDirect);
  LoadedScene<double> cg = load("fem-dragon", {SolverKind::CG, 50, 1e-12});
  ASSERT_TRUE(direct.scene && cg.scene);
  EXPECT_EQ(direct.scene->numVertices(), 11083);
  for (int frame = 0; frame < 10; ++frame) {
    ASSERT_TRUE(direct.scene->step().succeeded);
    EXPECT_EQ(cg.scene->step().iterations, 50);
  }
  const Eigen::VectorXd &ref = direct.scene->positions();
  double error = (cg.scene->positions() - ref).norm() /
                 (ref - direct.scene->initialPositions()).norm();
  EXPECT_GT(error, 0.70);
  EXPECT_LT(error, 0.76);
}

TEST(SpringsBunny, NormalisedPositionsMassesAndFixedPoints) {
  LoadedScene<double> bunny = load("springs-bunny", kDirect);
  ASSERT_TRUE(bunny.scene);
  auto &scene = static_cast<SpringsScene<double> &>(*bunny.scene);
  EXPECT_EQ(scene.numVertices(), 3607);
  EXPECT_EQ(scene.numSprings(), 19233);
  Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> x(
      scene.positions().data(), 3, scene.numVertices());
  EXPECT_EQ(x.rowwise().minCoeff(), Eigen::Vector3d::Zero());
  EXPECT_EQ(x.rowwise().maxCoeff(), Eigen::Vector3d::Ones());
  double restLength = 0, mass = 0;
  for (int s = 0; s < scene.numSprings(); ++s)
    restLength += scene.restLength(s);
  for (int v = 0; v < scene.numVertices(); ++v) {
    mass += scene.mass(v);
    EXPECT_EQ(scene.isFixed(v), x(2, v) < 0.1);
  }
  EXPECT_NEAR(mass, 1e3 * M_PI * 1e-4 * restLength, 1e-12 * mass);
  EXPECT_GT(scene.numFreeVertices(), 0);
  EXPECT_LT(scene.numFreeVertices(), scene.numVertices());
}

TEST(SpringsBunny, ConvergedCGMatchesDirectSolve) {
  LoadedScene<double> direct = load("springs-bunny", kDirect);
  LoadedScene<double> cg =
      load("springs-bunny", {SolverKind::JacobiCG, 10000, 1e-28});
  ASSERT_TRUE(direct.scene && cg.scene);
  for (int frame = 0; frame < 3; ++frame) {
    ASSERT_TRUE(direct.scene->step().succeeded);
    cg.scene->step();
  }
  const Eigen::VectorXd &ref = direct.scene->positions();
  const Eigen::VectorXd &x0 = direct.scene->initialPositions();
  EXPECT_LT((cg.scene->positions() - ref).norm() / (ref - x0).norm(), 1e-9);
}

TEST(Scenes, ErrorsNameTheProblem) {
  auto message = [](SceneOptions options) {
    llvm::Expected<LoadedScene<double>> loaded = createScene<double>(options);
    return loaded ? std::string() : llvm::toString(loaded.takeError());
  };
  EXPECT_NE(
      message({"fem-cow", kMeshDir, 0, {}}).find("unknown scene 'fem-cow'"),
      std::string::npos);
  EXPECT_NE(
      message({"springs-bunny", kMeshDir, 1, {}}).find("cannot be refined"),
      std::string::npos);
  EXPECT_NE(message({"fem-bar", "/nonexistent", 0, {}}).find("/nonexistent"),
            std::string::npos);
}

} // namespace
