//===--- Scenes.h - The benchmark scenes by name ---------------*- C++ -*-===//
//
// Builds springs-bunny, fem-dragon or fem-bar of bench/scenes.md from the
// shipped meshes, with the numbers that document gives each scene.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_BENCH_SCENES_H
#define SIMIT_BENCH_SCENES_H

#include "ImplicitScene.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <memory>
#include <string>
#include <vector>

namespace simit::bench {

/// The names createScene accepts.
const std::vector<std::string> &sceneNames();

/// The CG iteration cap scenes.md gives the scene (50 or 100).
int defaultIterationCap(llvm::StringRef sceneName);

struct SceneOptions {
  std::string name;
  std::string meshDirectory;
  int refinements = 0; // 1-to-8 tet refinements, FEM scenes only
  SolverOptions solver;
};

template <typename Scalar> struct LoadedScene {
  std::unique_ptr<ImplicitScene<Scalar>> scene;
  std::string meshPath;
  int numElements = 0; // springs or tets
  double meshLoadMs = 0;
  double refineMs = 0;
};

template <typename Scalar>
llvm::Expected<LoadedScene<Scalar>> createScene(const SceneOptions &options);

} // namespace simit::bench

#endif // SIMIT_BENCH_SCENES_H
