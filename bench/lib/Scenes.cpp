//===--- Scenes.cpp - The benchmark scenes by name ------------------------===//

#include "Scenes.h"
#include "FemScene.h"
#include "SpringsScene.h"
#include "Timer.h"

#include "simit/Runtime/Mesh.h"

#include <algorithm>

namespace simit::bench {

const std::vector<std::string> &sceneNames() {
  static const std::vector<std::string> names = {"springs-bunny", "fem-dragon",
                                                 "fem-bar"};
  return names;
}

int defaultIterationCap(llvm::StringRef sceneName) {
  return sceneName == "fem-bar" ? 100 : 50;
}

static double minY(const Mesh &mesh) {
  double lo = mesh.points.empty() ? 0 : mesh.points[0][1];
  for (const auto &p : mesh.points)
    lo = std::min(lo, p[1]);
  return lo;
}

static double maxY(const Mesh &mesh) {
  double hi = mesh.points.empty() ? 0 : mesh.points[0][1];
  for (const auto &p : mesh.points)
    hi = std::max(hi, p[1]);
  return hi;
}

template <typename Scalar>
llvm::Expected<LoadedScene<Scalar>> createScene(const SceneOptions &options) {
  const std::vector<std::string> &names = sceneNames();
  if (std::find(names.begin(), names.end(), options.name) == names.end())
    return llvm::createStringError(
        "unknown scene '" + options.name +
        "'; expected springs-bunny, fem-dragon or fem-bar");
  const bool springs = options.name == "springs-bunny";
  if (springs && options.refinements > 0)
    return llvm::createStringError(
        "springs-bunny takes its springs from the mesh's edges and cannot be "
        "refined");

  LoadedScene<Scalar> loaded;
  const char *base = springs                        ? "bunny.1"
                     : options.name == "fem-dragon" ? "dragon40k"
                                                    : "bar2k";
  loaded.meshPath = options.meshDirectory + "/" + base;
  Timer timer;
  llvm::Expected<Mesh> mesh = loadTetGen(loaded.meshPath);
  if (!mesh)
    return mesh.takeError();
  loaded.meshLoadMs = timer.lapMs();
  for (int k = 0; k < options.refinements; ++k)
    *mesh = refineTets(*mesh);
  loaded.refineMs = timer.lapMs();

  if (springs) {
    if (mesh->edges.empty())
      return llvm::createStringError(loaded.meshPath +
                                     ".edge: springs-bunny needs the mesh's "
                                     "edges and none were read");
    loaded.numElements = static_cast<int>(mesh->edges.size());
    loaded.scene = std::make_unique<SpringsScene<Scalar>>(
        *mesh, SpringsParams(), options.solver);
    return loaded;
  }

  if (mesh->tets.empty())
    return llvm::createStringError(loaded.meshPath +
                                   ".ele: the FEM scenes need tetrahedra and "
                                   "none were read");
  FemParams params;
  if (options.name == "fem-dragon") {
    double lo = minY(*mesh), hi = maxY(*mesh);
    params.fixedBelowY = lo + 0.05 * (hi - lo);
  } else {
    params.youngsModulus = 5e3;
    params.timeStep = 0.005;
    params.fixedBelowY = 1e-4;
    params.initialVelocity = {0.1, 0, 0.1};
  }
  loaded.numElements = static_cast<int>(mesh->tets.size());
  loaded.scene =
      std::make_unique<FemScene<Scalar>>(*mesh, params, options.solver);
  return loaded;
}

template llvm::Expected<LoadedScene<float>>
createScene<float>(const SceneOptions &);
template llvm::Expected<LoadedScene<double>>
createScene<double>(const SceneOptions &);

} // namespace simit::bench
