//===--- SetBindings.cpp - simit.Set ----------------------------------------===//
//
// simit.Set wraps simit::Set. Fields are NumPy arrays over the Set's own
// field arrays (no copies): set["x"] is an array of shape (size, *block)
// whose writes the next compiled call reads, and which shows what the call
// wrote. Adding elements may move those arrays, so it is refused while a
// view is alive (as bytearray refuses to resize while exported).
//
//===----------------------------------------------------------------------===//

#include "Common.h"

#include <pybind11/stl.h>

#include <sstream>

using namespace simit;
using namespace simit::python;

namespace {
/// A Set created from Python, with the endpoint sets it points at.
struct OwnedSet {
  std::vector<std::shared_ptr<Set>> endpoints; // destroyed after `set`
  std::unique_ptr<Set> set;
};

SetHandle own(std::unique_ptr<Set> set,
              std::vector<std::shared_ptr<Set>> endpoints) {
  auto owned = std::make_shared<OwnedSet>();
  owned->endpoints = std::move(endpoints);
  owned->set = std::move(set);
  Set *raw = owned->set.get();
  return {std::shared_ptr<Set>(owned, raw)};
}

/// Adds the edges of an (n, cardinality) integer array, all or none.
int addEdges(Set &set, const py::handle &endpointArray) {
  if (!set.isEdgeSet())
    throw py::type_error("set '" + set.name().str() +
                         "' is a vertex set: add vertices with add(count)");
  // Indices are integers: a float array must hold whole numbers (forcecast
  // alone would truncate 0.5 to 0).
  py::module_ numpy = py::module_::import("numpy");
  py::array source(numpy.attr("asarray")(endpointArray));
  char kind = source.dtype().kind();
  if (kind == 'f' && source.size() > 0 &&
      !numpy
           .attr("all")(
               numpy.attr("equal")(numpy.attr("floor")(source), source))
           .cast<bool>())
    throw py::value_error("endpoints: expected integer indices, found a "
                          "fraction or a non-finite value");
  if (kind != 'f' && kind != 'i' && kind != 'u' && source.size() > 0)
    throw py::type_error("endpoints: expected an integer array");
  auto array =
      py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(
          source);
  if (!array)
    throw py::type_error("endpoints: expected an integer array");
  int card = set.cardinality();
  if (array.ndim() != 2 || array.shape(1) != card)
    throw py::value_error("set '" + set.name().str() + "': expected endpoints of shape (n, " +
                          std::to_string(card) + ")");
  py::ssize_t rows = array.shape(0);
  auto data = array.unchecked<2>();
  std::vector<int> row(card);
  for (py::ssize_t r = 0; r < rows; ++r) {
    for (int i = 0; i < card; ++i) {
      int64_t index = data(r, i);
      if (index < INT32_MIN || index > INT32_MAX)
        throw py::value_error("endpoints row " + std::to_string(r) +
                              ": endpoint " + std::to_string(i) + " is " +
                              std::to_string(index) +
                              ", beyond 32-bit indices");
      row[i] = static_cast<int>(index);
    }
    if (llvm::Error err = set.checkEndpoints(row))
      throw py::value_error("endpoints row " + std::to_string(r) + ": " +
                            llvm::toString(std::move(err)));
  }
  requireUnshared(set);
  int first = set.size();
  set.reserve(first + static_cast<int>(rows));
  for (py::ssize_t r = 0; r < rows; ++r) {
    for (int i = 0; i < card; ++i)
      row[i] = static_cast<int>(data(r, i));
    set.add(row);
  }
  return first;
}

int addVertices(Set &set, int count) {
  if (set.isEdgeSet())
    throw py::type_error("set '" + set.name().str() +
                         "' is an edge set: add edges with add_edges(endpoints)");
  if (count < 0)
    throw py::value_error("add: expected a count >= 0");
  requireUnshared(set);
  int first = set.size();
  set.reserve(first + count);
  for (int i = 0; i < count; ++i)
    set.add();
  return first;
}

std::vector<int> toShape(const py::object &shape) {
  if (py::isinstance<py::int_>(shape))
    return {shape.cast<int>()};
  return shape.cast<std::vector<int>>();
}

py::array addField(const SetHandle &handle, const std::string &name,
                   const py::object &dtype, const py::object &shape) {
  ComponentType type = componentTypeOf(py::dtype::from_args(dtype));
  check(handle.set->addField(name, type, toShape(shape)));
  return fieldView(handle.set, name);
}

/// set[name] = value: copies into the existing field (NumPy broadcasting),
/// or adds a field with the array's block shape and component type
/// (integers as int32, other floats as float64).
void setField(const SetHandle &handle, const std::string &name,
              const py::object &value) {
  Set &set = *handle.set;
  std::string what = "set '" + set.name().str() + "': field '" + name + "'";
  if (set.hasField(name)) {
    py::array field = fieldView(handle.set, name);
    field[py::ellipsis()] =
        convertExactly(value, componentTypeOf(field.dtype()), what);
    return;
  }
  py::module_ numpy = py::module_::import("numpy");
  py::array array(numpy.attr("asarray")(value));
  if (array.ndim() == 0 || array.shape(0) != set.size())
    throw py::value_error("set '" + set.name().str() + "' has " +
                          std::to_string(set.size()) +
                          " elements; a new field needs one block per "
                          "element, got an array of shape " +
                          std::string(py::str(array.attr("shape"))));
  char kind = array.dtype().kind();
  ComponentType type = kind == 'b'                  ? ComponentType::Bool
                       : kind == 'i' || kind == 'u' ? ComponentType::Int32
                       : array.dtype().equal(dtypeOf(ComponentType::Float32))
                           ? ComponentType::Float32
                           : ComponentType::Float64;
  // Checked before the field exists: nothing is added when values do not
  // fit (int64 beyond int32, complex).
  py::array values = convertExactly(array, type, what);
  std::vector<int> shape(array.shape() + 1, array.shape() + array.ndim());
  check(set.addField(name, type, shape));
  fieldView(handle.set, name)[py::ellipsis()] = values;
}

py::dict fieldTable(const Set &set) {
  py::dict fields;
  for (const FieldDescriptor *field : set.fields())
    fields[py::str(field->name)] =
        py::make_tuple(dtypeOf(field->type), py::tuple(py::cast(field->shape)));
  return fields;
}

std::string describe(const Set &set) {
  std::ostringstream os;
  os << "<simit.Set '" << set.name().str() << "': " << set.size()
     << (set.isEdgeSet() ? " edges over (" : " vertices");
  if (set.isEdgeSet()) {
    for (int i = 0; i < set.cardinality(); ++i)
      os << (i ? ", " : "") << "'" << set.endpointSet(i).name().str() << "'";
    os << ")";
  }
  os << ", fields:";
  for (const FieldDescriptor *field : set.fields())
    os << " " << field->name;
  os << ">";
  return os.str();
}
} // namespace

void simit::python::defineSets(py::module_ &module) {
  py::class_<SetHandle>(module, "Set", R"doc(
A vertex set or an edge set of a Simit hypergraph (docs/python.md).

  points = simit.Set("points", size=4)
  points["x"] = np.zeros((4, 3))        # a float64 field of blocks (3,)
  springs = simit.Set("springs", [points, points], endpoints=[[0, 1], [1, 2]])

Fields read as NumPy arrays over the set's own memory: writes through them
are seen by the next compiled call, and the call's writes by them.
)doc")
      .def(py::init([](const std::string &name,
                       const std::vector<SetHandle> &endpointSets, int size,
                       const py::object &endpoints) {
             if (endpointSets.empty()) {
               if (!endpoints.is_none())
                 throw py::type_error("a vertex set has no endpoints");
               SetHandle handle = own(std::make_unique<Set>(name), {});
               addVertices(*handle.set, size);
               return handle;
             }
             if (size != 0)
               throw py::type_error("an edge set takes endpoints=, not size=");
             std::vector<Set *> raw;
             std::vector<std::shared_ptr<Set>> keep;
             for (const SetHandle &endpoint : endpointSets) {
               raw.push_back(endpoint.set.get());
               keep.push_back(endpoint.set);
             }
             SetHandle handle =
                 own(std::make_unique<Set>(name, raw), std::move(keep));
             if (!endpoints.is_none())
               addEdges(*handle.set, endpoints);
             return handle;
           }),
           py::arg("name"), py::arg("endpoint_sets") = std::vector<SetHandle>{},
           py::kw_only(), py::arg("size") = 0,
           py::arg("endpoints") = py::none())
      .def_static(
          "grid",
          [](const SetHandle &points, const std::vector<int> &dims,
             const std::string &name) {
            requireUnshared(*points.set);
            auto grid = check(Set::makeGrid(*points.set, dims, name));
            return own(std::move(grid), {points.set});
          },
          py::arg("points"), py::arg("dims"), py::arg("name") = "",
          "A periodic grid edge set over `points` (added when it is empty).")
      .def_property_readonly("name",
                             [](const SetHandle &h) { return h.set->name().str(); })
      .def_property_readonly("size", [](const SetHandle &h) { return h.set->size(); })
      .def("__len__", [](const SetHandle &h) { return h.set->size(); })
      .def_property_readonly("cardinality",
                             [](const SetHandle &h) { return h.set->cardinality(); })
      .def_property_readonly("is_edge_set",
                             [](const SetHandle &h) { return h.set->isEdgeSet(); })
      .def_property_readonly("is_grid",
                             [](const SetHandle &h) { return h.set->isGrid(); })
      .def_property_readonly("grid_dims",
                             [](const SetHandle &h) {
                               return std::vector<int>(
                                   h.set->gridDimensions().begin(),
                                   h.set->gridDimensions().end());
                             })
      .def_property_readonly(
          "endpoint_sets",
          [](const SetHandle &h) {
            std::vector<SetHandle> sets;
            for (int i = 0; i < h.set->cardinality(); ++i)
              sets.push_back({std::shared_ptr<Set>(h.set, &h.set->endpointSet(i))});
            return sets;
          })
      .def_property_readonly("endpoints",
                             [](const SetHandle &h) { return endpointView(h.set); },
                             "The (size, cardinality) int32 endpoint indices, "
                             "read-only.")
      .def("add",
           [](const SetHandle &h, int count) { return addVertices(*h.set, count); },
           py::arg("count") = 1,
           "Adds `count` zero-filled vertices; returns the first one's index.")
      .def("add_edges",
           [](const SetHandle &h, const py::object &endpoints) {
             return addEdges(*h.set, endpoints);
           },
           py::arg("endpoints"),
           "Adds one edge per row of an (n, cardinality) index array; "
           "returns the first one's index.")
      .def("remove",
           [](const SetHandle &h, int element) {
             if (element < 0 || element >= h.set->size())
               throw py::index_error("set '" + h.set->name().str() +
                                     "' has no element " +
                                     std::to_string(element));
             requireUnshared(*h.set);
             h.set->remove(element);
           },
           py::arg("element"),
           "Removes an element; the last one moves into its slot.")
      .def_property_readonly(
          "fields", [](const SetHandle &h) { return fieldTable(*h.set); },
          "{name: (dtype, block shape)}")
      .def("add_field", &addField, py::arg("name"),
           py::arg("dtype") = py::str("float64"),
           py::arg("shape") = py::tuple(),
           "Adds a zero-filled field and returns its view.")
      .def("remove_field",
           [](const SetHandle &h, const std::string &name) {
             if (!h.set->hasField(name))
               throw py::key_error(name);
             requireUnshared(*h.set, name);
             h.set->removeField(name);
           })
      .def("__getitem__",
           [](const SetHandle &h, const std::string &name) {
             return fieldView(h.set, name);
           })
      .def("__setitem__", &setField)
      .def("__contains__",
           [](const SetHandle &h, const std::string &name) {
             return h.set->hasField(name);
           })
      .def(
          "__eq__",
          [](const SetHandle &a, const SetHandle &b) {
            return a.set.get() == b.set.get();
          },
          py::is_operator())
      .def("__hash__",
           [](const SetHandle &h) {
             return std::hash<const void *>()(h.set.get());
           })
      .def("__repr__", [](const SetHandle &h) { return describe(*h.set); });
}
