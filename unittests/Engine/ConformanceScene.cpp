//===--- ConformanceScene.cpp - Random sets of the conformance suite ------===//

#include "ConformanceScene.h"

#include <algorithm>
#include <random>

using namespace simit;
using namespace simit::conformance;

namespace {
struct SetInfo {
  const char *name;
  const char *element;
  int size;
  std::vector<SetId> endpoints;
};

/// Sizes chosen so that every edge set revisits vertices (shared blocks,
/// repeated edges) while the dense matrices stay tiny; `springs` gets one
/// more edge, joining a vertex to itself.
const SetInfo &info(SetId id) {
  static const std::array<SetInfo, kAllSets.size()> infos = {{
      {"verts", "Vert", 8, {}},
      {"nodes", "Node", 5, {}},
      {"springs", "Spring", 10, {SetId::Verts, SetId::Verts}},
      {"tris", "Tri", 6, {SetId::Verts, SetId::Verts, SetId::Verts}},
      {"tets",
       "Tet",
       4,
       {SetId::Verts, SetId::Verts, SetId::Verts, SetId::Verts}},
      {"links", "Link", 7, {SetId::Verts, SetId::Nodes}},
      {"hinges", "Hinge", 5, {SetId::Verts, SetId::Nodes, SetId::Nodes}},
  }};
  return infos[static_cast<int>(id)];
}

/// The endpoints of a random edge of `id`: distinct where they belong to
/// the same set.
std::vector<int> randomEdge(SetId id, Scene &scene, std::mt19937 &random) {
  std::vector<int> endpoints;
  for (SetId endpointSet : info(id).endpoints) {
    int size = scene.set(endpointSet).size();
    std::uniform_int_distribution<int> pick(0, size - 1);
    auto taken = [&](int candidate) {
      for (size_t i = 0; i < endpoints.size(); ++i)
        if (info(id).endpoints[i] == endpointSet && endpoints[i] == candidate)
          return true;
      return false;
    };
    int chosen = pick(random);
    while (taken(chosen))
      chosen = pick(random);
    endpoints.push_back(chosen);
  }
  return endpoints;
}
} // namespace

llvm::StringRef simit::conformance::setName(SetId set) {
  return info(set).name;
}

llvm::StringRef simit::conformance::elementName(SetId set) {
  return info(set).element;
}

llvm::ArrayRef<SetId> simit::conformance::endpointSets(SetId set) {
  return info(set).endpoints;
}

Scene::Scene(int blockSize, unsigned seed) : block(blockSize) {
  for (SetId id : kAllSets) {
    std::vector<Set *> endpoints;
    for (SetId endpointSet : info(id).endpoints)
      endpoints.push_back(&set(endpointSet));
    sets[static_cast<int>(id)] =
        std::make_unique<Set>(info(id).name, endpoints);
  }

  // The elements first, so that both block sizes get the same sets.
  std::mt19937 random(seed);
  for (SetId id : kAllSets)
    for (int e = 0; e < info(id).size; ++e) {
      if (set(id).isEdgeSet())
        set(id).add(randomEdge(id, *this, random));
      else
        set(id).add();
    }
  // An edge whose endpoints repeat: each of its writes adds (language.md
  // 8.2), also where two land in one block.
  set(SetId::Springs).add(3, 3);

  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<int> vectorShape;
  if (block > 1)
    vectorShape.push_back(block);
  for (SetId id : kAllSets) {
    Set &elements = set(id);
    for (const char *name : {"x", "w", "y", "z", "u"})
      elements.addField<double>(name, vectorShape);
    for (const char *name : {"k", "l", "s"})
      elements.addField<double>(name, {kCoefficients});
    for (const char *name : {"B", "C", "I"})
      elements.addField<double>(name, {3, 3});
    auto fill = [&](const char *name, auto value) {
      DynamicFieldRef<double> field = elements.dynamicField<double>(name);
      for (int e = 0; e < elements.size(); ++e)
        for (double &component : field.get(e))
          component = value();
    };
    auto randomValue = [&] { return uniform(random); };
    for (const char *name : {"x", "w", "k", "l", "B", "C"})
      fill(name, randomValue);
    // Shifts large enough to make A + A' + S diagonally dominant.
    fill("s", [&] { return 100.0 + 10.0 * uniform(random); });
    DynamicFieldRef<double> identity = elements.dynamicField<double>("I");
    for (int e = 0; e < elements.size(); ++e)
      for (int i = 0; i < 3; ++i)
        identity.get(e)[i * 3 + i] = 1.0;
  }
}

Eigen::VectorXd Scene::vectorField(SetId id, llvm::StringRef name) {
  Set &elements = set(id);
  DynamicFieldRef<double> field = elements.dynamicField<double>(name);
  Eigen::VectorXd result(elements.size() * block);
  for (int e = 0; e < elements.size(); ++e)
    for (int a = 0; a < block; ++a)
      result[e * block + a] = field.get(e)[a];
  return result;
}

void Scene::clearOutputs() {
  for (SetId id : kAllSets)
    for (const char *name : {"y", "z", "u"}) {
      DynamicFieldRef<double> field = set(id).dynamicField<double>(name);
      for (int e = 0; e < set(id).size(); ++e)
        std::fill(field.get(e).begin(), field.get(e).end(), 0.0);
    }
}

double Scene::coefficient(SetId id, llvm::StringRef name, int element,
                          int index) {
  return set(id).dynamicField<double>(name).get(element)[index];
}

Eigen::Matrix3d Scene::blockField(SetId id, llvm::StringRef name, int element) {
  llvm::MutableArrayRef<double> values =
      set(id).dynamicField<double>(name).get(element);
  Eigen::Matrix3d result;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      result(i, j) = values[i * 3 + j];
  return result;
}
