//===--- Scene.h - Scene files of simit-run ---------------------*- C++ -*-===//
//
// A scene (JSON, described in docs/scene-format.md) says which sets to build
// from which meshes, how to initialise their fields, the values of extern
// tensors, which exported functions to run once and per frame, for how many
// frames, and what to write. loadScene checks the whole file and reports
// the first problem as "scene.json: sets.points.fields.x: expected ...";
// buildSets then loads the meshes and fills a SetRegistry.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SCENE_H
#define SIMIT_RUNTIME_SCENE_H

#include "simit/Runtime/Mesh.h"
#include "simit/Runtime/SceneExpression.h"
#include "simit/Runtime/Set.h"
#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/StringMap.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace simit {

struct MeshSpec {
  std::string name;
  std::string path; // resolved against the scene file's directory
  int refine = 0;   // times to apply refineTets
  bool strict = false; // degenerate or inverted tets are an error
};

/// How one field's initial values are computed.
struct FieldInit {
  enum Kind {
    Zero,        // no initialiser
    Constant,    // `values` (one block)
    Coordinates, // the element's mesh coordinates (vertex sets: the point)
    File,        // whitespace separated numbers, size * blockSize of them
    Expression,  // `expression` evaluated per element
    Select,      // `then` where `condition` holds, else `otherwise`
    PerElement,  // `values` holds one block per element, element after element
  };
  Kind kind = Zero;
  std::vector<double> values; // Constant: one block; PerElement: all blocks
  bool normalized = false; // Coordinates / Expression / Select: [0,1] axes
  std::string file;        // File: resolved path
  std::shared_ptr<const SceneExpression> expression; // Expression, Select
  std::vector<double> then, otherwise;                // Select: one block each
};

struct FieldSpec {
  std::string name;
  ComponentType type = ComponentType::Float64;
  std::vector<int> shape;
  FieldInit init;
  std::string jsonPath; // for errors found while building
};

struct SetSpec {
  enum Kind {
    Points,   // a vertex set with one element per mesh point
    Elements, // an edge set with one element per mesh edge/triangle/tet
    Sized,    // a vertex set of `size` elements, no mesh
    Grid,     // a grid edge set over `endpoints`
    Listed,   // an edge set whose elements are listed in the scene
  };
  std::string name;
  Kind kind = Points;
  std::string mesh;     // Points, Elements
  std::string elements; // Elements: "edges", "triangles" or "tets"
  /// Elements, Grid: the one endpoint (point) set; Listed: the set of each
  /// endpoint position (any sets, so edge sets may join edge sets).
  std::vector<std::string> endpoints;
  int size = 0;                         // Sized
  std::vector<int> dims;                // Grid
  std::vector<std::vector<int>> listed; // Listed: endpoint indices
  std::vector<FieldSpec> fields;
};

/// An extern tensor's value, stored as its component type.
struct ExternTensor {
  ComponentType type = ComponentType::Float64;
  std::vector<int> shape;
  /// Components row-major, as doubles; data() holds them as `type`.
  std::vector<double> values;
  /// The scene marks it `"constant": true`: it keeps its value while the
  /// scene runs, so the program may be compiled with it folded in.
  bool constant = false;

  /// Converts the stored components to `newType`; an error names the first
  /// value that does not fit (a fraction for int32, not 0/1 for bool).
  llvm::Error convertTo(ComponentType newType);
  /// Typed storage for bound code (valid until the next convertTo).
  void *data() { return storage.data(); }
  const void *data() const { return storage.data(); }
  /// Refreshes data() from `values` in the current type.
  void store();

private:
  std::vector<uint64_t> storage; // 8-byte aligned
};

struct OutputSpec {
  enum Kind { VTK, CSV };
  Kind kind = VTK;
  /// Relative to the output directory of simit-run; `{frame}` is replaced by
  /// the frame number (VTK: required unless only the last frame is written).
  std::string path;
  std::string set;                      // VTK: the point set; CSV: any set
  std::string position = "x";           // VTK: the point position field
  std::vector<std::string> cells;       // VTK: edge sets written as cells
  std::vector<std::string> fields;      // VTK: point data; CSV: columns
  std::vector<std::string> cellFields;  // VTK: cell data (one cell set)
  int every = 1;                        // write frames 0, every, 2 every, ...
  bool lastOnly = false;                // write only after the last frame
  std::string jsonPath;
};

struct SceneDescription {
  std::string path;      // the scene file
  std::string directory; // its directory, for relative inputs
  std::string program;   // optional .sim file (resolved)
  /// Shared libraries with the C functions of the program's extern funcs
  /// (resolved).
  std::vector<std::string> libraries;
  std::vector<MeshSpec> meshes;
  std::vector<SetSpec> sets;
  std::vector<std::pair<std::string, ExternTensor>> externs;
  std::vector<std::string> init, step;
  int frames = 0;
  std::vector<OutputSpec> outputs;
  /// "solver": how `x = A \ b` solves (docs/solvers.md).
  SolveSettings solver;

  const SetSpec *findSet(llvm::StringRef name) const;
};

/// Sets, extern tensors and meshes built from a scene.
class SetRegistry {
public:
  SetRegistry() = default;
  SetRegistry(const SetRegistry &) = delete;
  SetRegistry &operator=(const SetRegistry &) = delete;
  /// Destroys the sets newest first, edge sets before their endpoints.
  ~SetRegistry();

  /// The set called `name`, or null.
  Set *find(llvm::StringRef name) const;
  /// Adds `set` under its name; an error if the name is taken.
  llvm::Error add(std::unique_ptr<Set> set);
  /// Sets in the order they were added.
  const std::vector<std::unique_ptr<Set>> &sets() const { return setList; }

  ExternTensor *findExtern(llvm::StringRef name);
  std::map<std::string, ExternTensor> &externs() { return externTensors; }

  /// The (refined) mesh each mesh-built set came from.
  const Mesh *meshOf(llvm::StringRef setName) const;
  void setMeshOf(llvm::StringRef setName, std::shared_ptr<const Mesh> mesh);

private:
  std::vector<std::unique_ptr<Set>> setList;
  std::map<std::string, ExternTensor> externTensors;
  std::map<std::string, std::shared_ptr<const Mesh>> meshes;
};

/// Reads and checks a scene file.
llvm::Expected<SceneDescription> loadScene(llvm::StringRef path);
/// Checks scene text; `name` prefixes errors and `directory` resolves
/// relative paths.
llvm::Expected<SceneDescription> parseScene(llvm::StringRef text,
                                            llvm::StringRef name,
                                            llvm::StringRef directory);

/// Loads the meshes, creates the sets with their fields, fills the fields
/// and stores the extern tensors.
llvm::Error buildSets(const SceneDescription &scene, SetRegistry &registry);

} // namespace simit

#endif // SIMIT_RUNTIME_SCENE_H
