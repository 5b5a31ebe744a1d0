//===--- Common.cpp - Shared pieces of the simit Python module ------------===//

#include "Common.h"

#include <cstdint>
#include <limits>
#include <map>
#include <utility>

using namespace simit;
using namespace simit::python;

void simit::python::check(llvm::Error err) {
  if (err)
    throw SimitError(llvm::toString(std::move(err)));
}

py::dtype simit::python::dtypeOf(ComponentType type) {
  switch (type) {
  case ComponentType::Float64:
    return py::dtype::of<double>();
  case ComponentType::Float32:
    return py::dtype::of<float>();
  case ComponentType::Int32:
    return py::dtype::of<int32_t>();
  case ComponentType::Bool:
    return py::dtype::of<bool>();
  }
  throw std::logic_error("unknown component type");
}

ComponentType simit::python::componentTypeOf(const py::dtype &dtype) {
  for (ComponentType type : {ComponentType::Float64, ComponentType::Float32,
                             ComponentType::Int32, ComponentType::Bool})
    if (dtype.is(dtypeOf(type)) || dtype.equal(dtypeOf(type)))
      return type;
  throw py::type_error("simit fields and tensors hold float64, float32, "
                       "int32 or bool components, not " +
                       std::string(py::str(py::handle(dtype))));
}

py::array simit::python::viewOf(void *data, ComponentType type, size_t count,
                                const std::vector<int> &blockShape,
                                std::shared_ptr<void> owner, bool writeable) {
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(count)};
  shape.insert(shape.end(), blockShape.begin(), blockShape.end());
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = static_cast<py::ssize_t>(componentSize(type));
  for (size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  py::capsule base(new std::shared_ptr<void>(std::move(owner)), [](void *p) {
    delete static_cast<std::shared_ptr<void> *>(p);
  });
  py::array array(dtypeOf(type), shape, strides, data, base);
  if (!writeable)
    array.attr("flags").attr("writeable") = false;
  return array;
}

namespace {
/// Live field views by (set, field); all accessed with the GIL held.
std::map<std::pair<const Set *, std::string>, int> &liveViews() {
  static std::map<std::pair<const Set *, std::string>, int> views;
  return views;
}
/// Sets compiled code is running on, and how many runs.
std::map<const Set *, int> &runningSets() {
  static std::map<const Set *, int> running;
  return running;
}

/// What a view of a set's array keeps alive, and its place in liveViews()
/// (keyed by field name, or kEndpoints).
const char *const kEndpoints = "#endpoints";
struct FieldViewToken {
  std::shared_ptr<Set> set;
  std::string field;
  FieldViewToken(std::shared_ptr<Set> set, std::string field)
      : set(std::move(set)), field(std::move(field)) {
    ++liveViews()[{this->set.get(), this->field}];
  }
  ~FieldViewToken() {
    auto it = liveViews().find({set.get(), field});
    if (--it->second == 0)
      liveViews().erase(it);
  }
};
} // namespace

py::array simit::python::endpointView(const std::shared_ptr<Set> &set) {
  auto token = std::make_shared<FieldViewToken>(set, kEndpoints);
  return viewOf(set->endpointData(), ComponentType::Int32, set->size(),
                {set->cardinality()}, token, /*writeable=*/false);
}

py::array simit::python::fieldView(const std::shared_ptr<Set> &set,
                                   const std::string &field) {
  const FieldDescriptor *descriptor = set->fieldDescriptor(field);
  if (!descriptor)
    throw py::key_error("set '" + set->name().str() + "' has no field '" +
                        field + "'");
  auto token = std::make_shared<FieldViewToken>(set, field);
  return viewOf(set->fieldData(field), descriptor->type, set->size(),
                descriptor->shape, token);
}

void simit::python::requireUnshared(const Set &set, const std::string &field) {
  if (runningSets().count(&set))
    throw std::runtime_error("set '" + set.name().str() +
                             "' is in use by a running function");
  int views = 0;
  for (const auto &[key, count] : liveViews())
    if (key.first == &set && (field.empty() || key.second == field))
      views += count;
  if (views)
    throw py::buffer_error(
        "set '" + set.name().str() + "' has " + std::to_string(views) +
        " live NumPy view(s) of " +
        (field.empty() ? std::string("its fields or endpoints")
                       : "field '" + field + "'") +
        ", whose memory this change would move or free; delete them first");
}

RunningGuard::RunningGuard(std::vector<const Set *> sets)
    : sets(std::move(sets)) {
  for (const Set *set : this->sets)
    ++runningSets()[set];
}

RunningGuard::~RunningGuard() {
  for (const Set *set : sets) {
    auto it = runningSets().find(set);
    if (--it->second == 0)
      runningSets().erase(it);
  }
}

py::array simit::python::convertExactly(const py::object &value,
                                        ComponentType type,
                                        const std::string &what) {
  py::module_ numpy = py::module_::import("numpy");
  py::array source(numpy.attr("asarray")(value));
  py::dtype dtype = dtypeOf(type);
  // An array of the type already needs no checks and no copy (parameters
  // bound on every call, fields written every frame).
  if (source.dtype().equal(dtype))
    return py::array(numpy.attr("asarray")(source, py::arg("order") = "C"));
  char kind = source.dtype().kind();
  if (kind == 'c')
    throw py::type_error(what + ": complex values cannot be held in " +
                         std::string(py::str(py::handle(dtype))) +
                         " components");
  if (type == ComponentType::Int32 && source.size() > 0 &&
      (kind == 'f' || kind == 'i' || kind == 'u')) {
    if (kind == 'f' && !numpy
                            .attr("all")(numpy.attr("equal")(
                                numpy.attr("floor")(source), source))
                            .cast<bool>())
      throw py::value_error(what + ": expected integers for int32 values, "
                                   "found a fraction or a non-finite value");
    double low = numpy.attr("min")(source).cast<double>();
    double high = numpy.attr("max")(source).cast<double>();
    if (low < INT32_MIN || high > INT32_MAX)
      throw py::value_error(
          what +
          ": expected int32 values from -2147483648 to 2147483647, "
          "found " +
          std::string(py::str(low < INT32_MIN ? numpy.attr("min")(source)
                                              : numpy.attr("max")(source))));
  }
  bool numeric = kind == 'f' || kind == 'i' || kind == 'u';
  if (type == ComponentType::Bool && numeric && source.size() > 0 &&
      !numpy.attr("all")(numpy.attr("isin")(source, py::make_tuple(0, 1)))
           .cast<bool>())
    throw py::value_error(what + ": expected bool values (0 or 1), found " +
                          "another number");
  // A finite float64 beyond float32's range would become infinity.
  if (type == ComponentType::Float32 && kind == 'f' && source.size() > 0 &&
      numpy
          .attr("any")(numpy.attr("greater")(
              numpy.attr("abs")(numpy.attr("where")(
                  numpy.attr("isfinite")(source), source, 0.0)),
              std::numeric_limits<float>::max()))
          .cast<bool>())
    throw py::value_error(what + ": a value is too large for float32");
  return py::array(
      numpy.attr("asarray")(source, dtype, py::arg("order") = "C"));
}
