//===--- SceneBuild.cpp - Building sets from a scene description ----------===//

#include "simit/Runtime/Scene.h"

#include "MemoryBudget.h"
#include "TextReader.h"

#include "llvm/Support/Format.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/raw_ostream.h"

#include <cmath>

using namespace simit;

//===--- ExternTensor -----------------------------------------------------===//

void ExternTensor::store() {
  size_t bytes = values.size() * componentSize(type);
  storage.assign((bytes + 7) / 8, 0);
  auto *base = reinterpret_cast<std::byte *>(storage.data());
  for (size_t i = 0; i < values.size(); ++i) {
    switch (type) {
    case ComponentType::Float64:
      reinterpret_cast<double *>(base)[i] = values[i];
      break;
    case ComponentType::Float32:
      reinterpret_cast<float *>(base)[i] = static_cast<float>(values[i]);
      break;
    case ComponentType::Int32:
      reinterpret_cast<int32_t *>(base)[i] = static_cast<int32_t>(values[i]);
      break;
    case ComponentType::Bool:
      reinterpret_cast<bool *>(base)[i] = values[i] != 0.0;
      break;
    }
  }
}

/// Why `value` cannot be a component of `type`, or "" when it can.
static std::string componentProblem(ComponentType type, double value) {
  // An expression may divide by zero or take the root of a negative number.
  if (!std::isfinite(value))
    return llvm::formatv("expected a finite number, found {0}", value).str();
  if (type == ComponentType::Int32 &&
      (std::floor(value) != value || value < INT32_MIN || value > INT32_MAX))
    return llvm::formatv("expected an int32 value, found {0}", value).str();
  if (type == ComponentType::Bool && value != 0.0 && value != 1.0)
    return llvm::formatv("expected a bool value (0 or 1), found {0}", value)
        .str();
  return "";
}

llvm::Error ExternTensor::convertTo(ComponentType newType) {
  // As for fields: true and false are not numbers.
  if (type == ComponentType::Bool && newType != ComponentType::Bool)
    return llvm::createStringError("expected numbers for a " +
                                   componentTypeName(newType) +
                                   " value, found a boolean");
  for (size_t i = 0; i < values.size(); ++i) {
    std::string problem = componentProblem(newType, values[i]);
    if (!problem.empty())
      return llvm::createStringError("component " + llvm::Twine(i) + ": " +
                                     problem);
  }
  type = newType;
  store();
  return llvm::Error::success();
}

//===--- SetRegistry ------------------------------------------------------===//

SetRegistry::~SetRegistry() {
  while (!setList.empty())
    setList.pop_back();
}

Set *SetRegistry::find(llvm::StringRef name) const {
  for (const std::unique_ptr<Set> &set : setList)
    if (set->name() == name)
      return set.get();
  return nullptr;
}

llvm::Error SetRegistry::add(std::unique_ptr<Set> set) {
  if (find(set->name()))
    return llvm::createStringError("a set named '" + set->name() +
                                   "' already exists");
  setList.push_back(std::move(set));
  return llvm::Error::success();
}

ExternTensor *SetRegistry::findExtern(llvm::StringRef name) {
  auto it = externTensors.find(name.str());
  return it == externTensors.end() ? nullptr : &it->second;
}

const Mesh *SetRegistry::meshOf(llvm::StringRef setName) const {
  auto it = meshes.find(setName.str());
  return it == meshes.end() ? nullptr : it->second.get();
}

void SetRegistry::setMeshOf(llvm::StringRef setName,
                            std::shared_ptr<const Mesh> mesh) {
  meshes[setName.str()] = std::move(mesh);
}

//===--- buildSets --------------------------------------------------------===//

namespace {

class SetBuilder {
public:
  SetBuilder(const SceneDescription &scene, SetRegistry &registry)
      : scene(scene), registry(registry) {}

  llvm::Error build();

private:
  llvm::Error error(const std::string &path, const llvm::Twine &message) {
    return llvm::createStringError(scene.path + ": " + path + ": " + message);
  }

  llvm::Error loadMeshes();
  /// The number of elements `spec` will have, or nothing when it does not
  /// fit in 64 bits.
  std::optional<uint64_t> elementCount(const SetSpec &spec);
  /// Checks that the elements of `spec` and their fields fit in memory.
  llvm::Error checkSetMemory(const SetSpec &spec);
  llvm::Error createSet(const SetSpec &spec);
  llvm::Error fillField(const SetSpec &spec, Set &set,
                        const FieldSpec &field);
  /// The coordinate frame (position, bounding box) of element e.
  CoordinateFrame frameOf(const SetSpec &spec, int e, bool normalized) const;
  void storeBlock(void *base, const FieldSpec &field, int e,
                  llvm::ArrayRef<double> block) const;
  /// Reads elements * blockSize numbers from the field's file.
  llvm::Error readFieldFile(const FieldSpec &field, size_t elements,
                            size_t blockSize, std::vector<double> &values);

  const SceneDescription &scene;
  SetRegistry &registry;
  std::map<std::string, std::shared_ptr<const Mesh>> meshes;
  struct Box {
    std::array<double, 3> min, max;
  };
  std::map<std::string, Box> boxes;
};

/// The bytes refineTets needs for one level of `mesh`, generously: eight
/// tets per tet, at most six new points per tet in a vector that may
/// double, and a hash map node and bucket per edge midpoint.
static std::optional<uint64_t> refinementBytes(const Mesh &mesh) {
  uint64_t tets = mesh.tets.size(), points = mesh.points.size();
  auto tetBytes = detail::checkedProduct({tets, 8, sizeof(mesh.tets[0])});
  auto midpoints = detail::checkedProduct({tets, 6});
  if (!tetBytes || !midpoints)
    return std::nullopt;
  auto pointBytes = detail::checkedProduct(
      {points + *midpoints, 2, sizeof(mesh.points[0])});
  auto mapBytes = detail::checkedProduct(*midpoints, 6 * sizeof(uint64_t));
  if (!pointBytes || !mapBytes)
    return std::nullopt;
  return *tetBytes + *pointBytes + *mapBytes;
}

/// Reports tets of zero volume and tets whose orientation is against that
/// of most of the mesh (the program's rest shapes would be singular or
/// inverted), naming the count and the first one: a warning, or the error
/// returned for a strict mesh.
static llvm::Error checkTets(const Mesh &mesh, const std::string &where,
                             bool strict) {
  size_t positive = 0, negative = 0;
  std::vector<double> volumes(mesh.tets.size());
  std::vector<bool> degenerate(mesh.tets.size());
  for (size_t t = 0; t < mesh.tets.size(); ++t) {
    const std::array<int, 4> &tet = mesh.tets[t];
    volumes[t] = signedTetVolume(mesh, tet);
    // Zero up to rounding, relative to the edges from the first vertex.
    double scale = 1;
    for (int k = 1; k < 4; ++k) {
      double length = 0;
      for (int d = 0; d < 3; ++d) {
        double delta = mesh.points[tet[k]][d] - mesh.points[tet[0]][d];
        length += delta * delta;
      }
      scale *= std::sqrt(length);
    }
    degenerate[t] = std::abs(volumes[t]) <= 1e-12 * scale;
    if (!degenerate[t])
      (volumes[t] > 0 ? positive : negative) += 1;
  }
  bool majorityPositive = positive >= negative;
  size_t bad = 0, first = 0;
  for (size_t t = 0; t < mesh.tets.size(); ++t)
    if (degenerate[t] || (volumes[t] > 0) != majorityPositive)
      if (bad++ == 0)
        first = t;
  if (bad == 0)
    return llvm::Error::success();
  std::string problem;
  llvm::raw_string_ostream(problem)
      << bad << " of " << mesh.tets.size()
      << " tetrahedra are degenerate or inverted (the first is tetrahedron "
      << first << ", of volume " << llvm::format("%g", volumes[first]) << ")";
  if (strict)
    return llvm::createStringError(problem);
  llvm::errs() << where << ": warning: " << problem << "\n";
  return llvm::Error::success();
}

llvm::Error SetBuilder::loadMeshes() {
  for (const MeshSpec &spec : scene.meshes) {
    std::string path = "meshes." + spec.name;
    auto mesh = loadMesh(spec.path);
    if (!mesh)
      return error(path, llvm::toString(mesh.takeError()));
    if (llvm::Error err =
            checkTets(*mesh, scene.path + ": " + path, spec.strict))
      return error(path, llvm::toString(std::move(err)));
    for (int i = 0; i < spec.refine; ++i) {
      if (llvm::Error err = detail::checkMemoryRequest(
              refinementBytes(*mesh),
              "refinement level " + llvm::Twine(i + 1) + " of the mesh"))
        return error(path + ".refine", llvm::toString(std::move(err)));
      *mesh = refineTets(*mesh);
    }
    Box box{{0, 0, 0}, {0, 0, 0}};
    for (size_t p = 0; p < mesh->points.size(); ++p)
      for (int d = 0; d < 3; ++d) {
        double c = mesh->points[p][d];
        box.min[d] = p == 0 ? c : std::min(box.min[d], c);
        box.max[d] = p == 0 ? c : std::max(box.max[d], c);
      }
    boxes[spec.name] = box;
    meshes[spec.name] = std::make_shared<const Mesh>(std::move(*mesh));
  }
  return llvm::Error::success();
}

template <size_t N>
llvm::Error addElements(Set &set,
                        const std::vector<std::array<int, N>> &elements) {
  set.reserve(static_cast<int>(elements.size()));
  for (const std::array<int, N> &element : elements) {
    llvm::ArrayRef<int> ends(element.data(), N);
    if (llvm::Error err = set.checkEndpoints(ends))
      return err;
    set.add(ends);
  }
  return llvm::Error::success();
}

std::optional<uint64_t> SetBuilder::elementCount(const SetSpec &spec) {
  switch (spec.kind) {
  case SetSpec::Points:
    return meshes[spec.mesh]->points.size();
  case SetSpec::Elements: {
    const Mesh &mesh = *meshes[spec.mesh];
    return spec.elements == "edges"       ? mesh.edges.size()
           : spec.elements == "triangles" ? mesh.triangles.size()
                                          : mesh.tets.size();
  }
  case SetSpec::Sized:
    return spec.size;
  case SetSpec::Grid: {
    // One edge per point and dimension.
    std::vector<uint64_t> factors(spec.dims.begin(), spec.dims.end());
    factors.push_back(spec.dims.size());
    return detail::checkedProduct(factors);
  }
  case SetSpec::Listed:
    return spec.listed.size();
  }
  return std::nullopt;
}

llvm::Error SetBuilder::checkSetMemory(const SetSpec &spec) {
  // Endpoint indices, then each field's block.
  std::optional<uint64_t> perElement =
      std::max<uint64_t>(1, spec.endpoints.size()) * sizeof(int);
  for (const FieldSpec &field : spec.fields) {
    std::vector<uint64_t> factors(field.shape.begin(), field.shape.end());
    factors.push_back(componentSize(field.type));
    std::optional<uint64_t> block = detail::checkedProduct(factors);
    if (!block || *perElement + *block < *block) {
      perElement = std::nullopt;
      break;
    }
    *perElement += *block;
  }
  std::optional<uint64_t> count = elementCount(spec);
  std::optional<uint64_t> bytes;
  if (count && perElement)
    bytes = detail::checkedProduct(*count, *perElement);
  std::string elements =
      count ? std::to_string(*count) : std::string("more than 2^64");
  if (llvm::Error err = detail::checkMemoryRequest(
          bytes, "the " + elements + " elements of set \"" + spec.name +
                     "\" and their fields"))
    return error("sets." + spec.name, llvm::toString(std::move(err)));
  return llvm::Error::success();
}

llvm::Error SetBuilder::createSet(const SetSpec &spec) {
  std::string path = "sets." + spec.name;
  if (llvm::Error err = checkSetMemory(spec))
    return err;
  std::unique_ptr<Set> set;
  switch (spec.kind) {
  case SetSpec::Points: {
    set = std::make_unique<Set>(spec.name);
    size_t count = meshes[spec.mesh]->points.size();
    set->reserve(static_cast<int>(count));
    for (size_t i = 0; i < count; ++i)
      set->add();
    break;
  }
  case SetSpec::Sized:
    set = std::make_unique<Set>(spec.name);
    set->reserve(spec.size);
    for (int i = 0; i < spec.size; ++i)
      set->add();
    break;
  case SetSpec::Elements: {
    const Mesh &mesh = *meshes[spec.mesh];
    Set *points = registry.find(spec.endpoints[0]);
    int c = spec.elements == "edges" ? 2 : spec.elements == "triangles" ? 3
                                                                        : 4;
    size_t count = c == 2 ? mesh.edges.size()
                          : c == 3 ? mesh.triangles.size() : mesh.tets.size();
    if (count == 0)
      return error(path + ".elements", "mesh \"" + spec.mesh + "\" has no " +
                                           spec.elements);
    std::vector<Set *> ends(c, points);
    set = std::make_unique<Set>(spec.name, ends);
    llvm::Error err = c == 2   ? addElements(*set, mesh.edges)
                      : c == 3 ? addElements(*set, mesh.triangles)
                               : addElements(*set, mesh.tets);
    if (err)
      return error(path, llvm::toString(std::move(err)));
    break;
  }
  case SetSpec::Grid: {
    auto grid = Set::makeGrid(*registry.find(spec.endpoints[0]), spec.dims,
                              spec.name);
    if (!grid)
      return error(path, llvm::toString(grid.takeError()));
    set = std::move(*grid);
    break;
  }
  case SetSpec::Listed: {
    std::vector<Set *> ends;
    for (const std::string &endpoint : spec.endpoints)
      ends.push_back(registry.find(endpoint));
    set = std::make_unique<Set>(spec.name, ends);
    set->reserve(static_cast<int>(spec.listed.size()));
    for (size_t e = 0; e < spec.listed.size(); ++e) {
      if (llvm::Error err = set->checkEndpoints(spec.listed[e]))
        return error(path + ".elements[" + std::to_string(e) + "]",
                     llvm::toString(std::move(err)));
      set->add(spec.listed[e]);
    }
    break;
  }
  }
  for (const FieldSpec &field : spec.fields) {
    if (llvm::Error err = set->addField(field.name, field.type, field.shape))
      return error(field.jsonPath, llvm::toString(std::move(err)));
    if (llvm::Error err = fillField(spec, *set, field))
      return err;
  }
  if (!spec.mesh.empty())
    registry.setMeshOf(spec.name, meshes[spec.mesh]);
  if (llvm::Error err = registry.add(std::move(set)))
    return error(path, llvm::toString(std::move(err)));
  return llvm::Error::success();
}

CoordinateFrame SetBuilder::frameOf(const SetSpec &spec, int e,
                                    bool normalized) const {
  const Mesh &mesh = *meshes.at(spec.mesh);
  const Box &box = boxes.at(spec.mesh);
  CoordinateFrame frame;
  frame.position = {0, 0, 0};
  auto addPoint = [&](int p, double weight) {
    for (int d = 0; d < 3; ++d)
      frame.position[d] += weight * mesh.points[p][d];
  };
  if (spec.kind == SetSpec::Points) {
    addPoint(e, 1.0);
  } else if (spec.elements == "edges") {
    for (int p : mesh.edges[e])
      addPoint(p, 0.5);
  } else if (spec.elements == "triangles") {
    for (int p : mesh.triangles[e])
      addPoint(p, 1.0 / 3);
  } else {
    for (int p : mesh.tets[e])
      addPoint(p, 0.25);
  }
  frame.min = box.min;
  frame.max = box.max;
  if (normalized) {
    for (int d = 0; d < 3; ++d) {
      double extent = box.max[d] - box.min[d];
      frame.position[d] =
          extent > 0 ? (frame.position[d] - box.min[d]) / extent : 0.0;
      frame.min[d] = 0;
      frame.max[d] = 1;
    }
  }
  return frame;
}

void SetBuilder::storeBlock(void *base, const FieldSpec &field, int e,
                            llvm::ArrayRef<double> block) const {
  size_t offset = static_cast<size_t>(e) * block.size();
  for (size_t i = 0; i < block.size(); ++i) {
    switch (field.type) {
    case ComponentType::Float64:
      static_cast<double *>(base)[offset + i] = block[i];
      break;
    case ComponentType::Float32:
      static_cast<float *>(base)[offset + i] = static_cast<float>(block[i]);
      break;
    case ComponentType::Int32:
      static_cast<int32_t *>(base)[offset + i] =
          static_cast<int32_t>(block[i]);
      break;
    case ComponentType::Bool:
      static_cast<bool *>(base)[offset + i] = block[i] != 0.0;
      break;
    }
  }
}

llvm::Error SetBuilder::readFieldFile(const FieldSpec &field, size_t elements,
                                      size_t blockSize,
                                      std::vector<double> &values) {
  size_t count = elements * blockSize;
  std::string path = field.jsonPath + ".file";
  auto reader = detail::TextReader::open(field.init.file);
  if (!reader)
    return error(path, llvm::toString(reader.takeError()));
  llvm::SmallVector<llvm::StringRef, 16> tokens;
  values.clear();
  values.reserve(count);
  while (reader->nextTokens(tokens)) {
    for (llvm::StringRef token : tokens) {
      if (values.size() == count)
        return error(path, llvm::toString(reader->error(
                               "expected " + llvm::Twine(count) +
                               " values, found more")));
      auto value = reader->parseFiniteDouble(token, "a field value");
      if (!value)
        return error(path, llvm::toString(value.takeError()));
      std::string problem = componentProblem(field.type, *value);
      if (!problem.empty())
        return error(path, llvm::toString(reader->error(problem)));
      values.push_back(*value);
    }
  }
  if (values.size() != count)
    return error(path, llvm::toString(reader->fileError(
                           "expected " + llvm::Twine(count) + " values (" +
                           llvm::Twine(elements) + " elements of " +
                           llvm::Twine(blockSize) + "), found " +
                           llvm::Twine(values.size()))));
  return llvm::Error::success();
}

llvm::Error SetBuilder::fillField(const SetSpec &spec, Set &set,
                                  const FieldSpec &field) {
  const FieldInit &init = field.init;
  void *base = set.fieldData(field.name);
  size_t blockSize = set.fieldDescriptor(field.name)->blockSize();
  int n = set.size();
  switch (init.kind) {
  case FieldInit::Zero:
    return llvm::Error::success();
  case FieldInit::Constant:
    for (int e = 0; e < n; ++e)
      storeBlock(base, field, e, init.values);
    return llvm::Error::success();
  case FieldInit::PerElement: {
    size_t blocks = init.values.size() / std::max<size_t>(blockSize, 1);
    if (blocks != static_cast<size_t>(n))
      return error(field.jsonPath + ".values",
                   "expected " + llvm::Twine(n) +
                       " values, one per element of the set, found " +
                       llvm::Twine(blocks));
    for (int e = 0; e < n; ++e)
      storeBlock(base, field, e,
                 llvm::ArrayRef<double>(init.values)
                     .slice(e * blockSize, blockSize));
    return llvm::Error::success();
  }
  case FieldInit::Coordinates:
    for (int e = 0; e < n; ++e)
      storeBlock(base, field, e, frameOf(spec, e, init.normalized).position);
    return llvm::Error::success();
  case FieldInit::File: {
    std::vector<double> values;
    if (llvm::Error err = readFieldFile(field, n, blockSize, values))
      return err;
    for (int e = 0; e < n; ++e)
      storeBlock(base, field, e,
                 llvm::ArrayRef<double>(values).slice(e * blockSize,
                                                      blockSize));
    return llvm::Error::success();
  }
  case FieldInit::Expression:
    for (int e = 0; e < n; ++e) {
      double value = init.expression->evaluate(
          frameOf(spec, e, init.normalized));
      std::string problem = componentProblem(field.type, value);
      if (!problem.empty())
        return error(field.jsonPath + ".expr",
                     "element " + llvm::Twine(e) + ": " + problem);
      storeBlock(base, field, e, value);
    }
    return llvm::Error::success();
  case FieldInit::Select:
    for (int e = 0; e < n; ++e) {
      bool holds = init.expression->evaluate(
                       frameOf(spec, e, init.normalized)) != 0.0;
      storeBlock(base, field, e, holds ? init.then : init.otherwise);
    }
    return llvm::Error::success();
  }
  return llvm::Error::success();
}

llvm::Error SetBuilder::build() {
  if (llvm::Error err = loadMeshes())
    return err;
  // Every set after its endpoint sets (loadScene rules out cycles).
  std::vector<const SetSpec *> pending;
  for (const SetSpec &spec : scene.sets)
    pending.push_back(&spec);
  while (!pending.empty()) {
    auto ready = llvm::find_if(pending, [&](const SetSpec *spec) {
      return llvm::all_of(spec->endpoints, [&](const std::string &endpoint) {
        return registry.find(endpoint) != nullptr;
      });
    });
    assert(ready != pending.end() && "cyclic endpoint sets");
    if (llvm::Error err = createSet(**ready))
      return err;
    pending.erase(ready);
  }
  for (const auto &[name, tensor] : scene.externs)
    registry.externs()[name] = tensor;
  return llvm::Error::success();
}

} // namespace

llvm::Error simit::buildSets(const SceneDescription &scene,
                             SetRegistry &registry) {
  return SetBuilder(scene, registry).build();
}
