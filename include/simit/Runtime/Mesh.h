//===--- Mesh.h - Mesh loaders and tetrahedral refinement -------*- C++ -*-===//
//
// Point coordinates plus the simplices of a mesh, read from TetGen, Gmsh or
// Wavefront OBJ files. Every index is 0-based after loading, whatever the
// file's own convention. Errors are llvm::Error values whose message reads
// "file:line: what was expected". The loaders reserve room for no more
// records than the rest of a file can hold, whatever its header declares,
// and reject coordinates that are not finite.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_MESH_H
#define SIMIT_RUNTIME_MESH_H

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <array>
#include <vector>

namespace simit {

struct Mesh {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 2>> edges; // all indices 0-based after loading
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 4>> tets;
};

/// Reads <base>.node and whichever of <base>.ele, <base>.edge and <base>.face
/// exist. The first record index of the .node file fixes the numbering base
/// (0 or 1) of every file: records follow it in order and vertex references
/// use it. Attribute and boundary-marker columns are skipped, and `#` starts
/// a comment. Second-order elements keep their four corner vertices.
/// Tetrahedra need a 3-D .node file.
llvm::Expected<Mesh> loadTetGen(llvm::StringRef basePath);

/// Reads an ASCII Gmsh file, format 2.x or 4.x: nodes, 2-node lines,
/// 3-node triangles and 4-node tetrahedra; other element types are skipped.
llvm::Expected<Mesh> loadGmsh(llvm::StringRef path);

/// Reads Wavefront OBJ `v` and `f` records (other records are ignored).
/// Polygons are fan-triangulated from their first vertex, `v/vt/vn` forms are
/// accepted and negative indices count back from the last vertex read.
llvm::Expected<Mesh> loadObj(llvm::StringRef path);

/// Dispatches on the extension: .msh to Gmsh, .obj to OBJ, and .node, .ele,
/// .edge, .face (or no extension) to TetGen with the extension removed.
llvm::Expected<Mesh> loadMesh(llvm::StringRef path);

/// The deterministic 1-to-8 refinement of bench/scenes.md (fem-dragon):
/// original vertices keep their ids; every distinct edge gets its midpoint,
/// numbered from the vertex count upward in order of first encounter (tets
/// in order, edges 01, 02, 03, 12, 13, 23); the children are the four corner
/// tets and the four tets around the shortest diagonal of the inner octahedron
/// (ties: m01-m23, then m02-m13, then m03-m12); a child whose orientation
/// differs from its parent's gets its last two vertices swapped. Only tets
/// are refined: the result has the refined points and tets, no edges or
/// triangles.
Mesh refineTets(const Mesh &m);

/// Signed volume of tet `t` of `m`: det[x1-x0, x2-x0, x3-x0] / 6, which is
/// -det(Dm) / 6 for the rest-shape matrix Dm with columns x_i - x_3.
double signedTetVolume(const Mesh &m, const std::array<int, 4> &t);

} // namespace simit

#endif // SIMIT_RUNTIME_MESH_H
