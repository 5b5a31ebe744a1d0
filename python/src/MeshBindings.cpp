//===--- MeshBindings.cpp - simit.Mesh and simit.load_mesh ------------------===//
//
// Meshes read by the runtime's loaders (TetGen, Gmsh, OBJ), their arrays as
// read-only NumPy views of the loaded mesh.
//
//===----------------------------------------------------------------------===//

#include "Common.h"

#include "simit/Runtime/Mesh.h"

#include <pybind11/stl.h>

using namespace simit;
using namespace simit::python;

namespace {
using MeshHandle = std::shared_ptr<Mesh>;

template <typename T, size_t N>
py::array arrayOf(const MeshHandle &mesh, const std::vector<std::array<T, N>> &rows) {
  ComponentType type = std::is_same_v<T, double> ? ComponentType::Float64
                                                 : ComponentType::Int32;
  void *data = const_cast<std::array<T, N> *>(rows.data());
  return viewOf(data, type, rows.size(), {static_cast<int>(N)},
                mesh, /*writeable=*/false);
}

MeshHandle loadWith(llvm::Expected<Mesh> (*load)(llvm::StringRef),
                    const std::string &path) {
  llvm::Expected<Mesh> mesh = [&] {
    py::gil_scoped_release release;
    return load(path);
  }();
  return std::make_shared<Mesh>(check(std::move(mesh)));
}
} // namespace

void simit::python::defineMeshes(py::module_ &module) {
  py::class_<Mesh, MeshHandle>(module, "Mesh", R"doc(
Points and simplices of a mesh, 0-based: points (n, 3) float64, edges
(m, 2), triangles (m, 3) and tets (m, 4) int32, as read-only arrays.
)doc")
      .def_property_readonly("points",
                             [](const MeshHandle &m) { return arrayOf(m, m->points); })
      .def_property_readonly("edges",
                             [](const MeshHandle &m) { return arrayOf(m, m->edges); })
      .def_property_readonly(
          "triangles", [](const MeshHandle &m) { return arrayOf(m, m->triangles); })
      .def_property_readonly("tets",
                             [](const MeshHandle &m) { return arrayOf(m, m->tets); })
      .def(
          "refined",
          [](const MeshHandle &m) {
            return std::make_shared<Mesh>(refineTets(*m));
          },
          "The 1-to-8 refinement of the tets (bench/scenes.md, fem-dragon).")
      .def("__repr__", [](const MeshHandle &m) {
        return "<simit.Mesh: " + std::to_string(m->points.size()) +
               " points, " + std::to_string(m->edges.size()) + " edges, " +
               std::to_string(m->triangles.size()) + " triangles, " +
               std::to_string(m->tets.size()) + " tets>";
      });

  module.def(
      "load_mesh",
      [](const py::object &path, const std::string &format) {
        std::string file = py::str(py::module_::import("os").attr("fspath")(path));
        if (format == "auto")
          return loadWith(loadMesh, file);
        if (format == "tetgen")
          return loadWith(loadTetGen, file);
        if (format == "gmsh")
          return loadWith(loadGmsh, file);
        if (format == "obj")
          return loadWith(loadObj, file);
        throw py::value_error("load_mesh: format is 'auto', 'tetgen', "
                              "'gmsh' or 'obj', not '" + format + "'");
      },
      py::arg("path"), py::arg("format") = "auto",
      "Reads a TetGen (.node and its .ele/.edge/.face), Gmsh (.msh) or "
      "Wavefront OBJ mesh; 'auto' goes by the extension.");
}
