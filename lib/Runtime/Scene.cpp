//===--- Scene.cpp - Reading and checking scene files ---------------------===//
//
// Every check that needs only the JSON happens here, so that a scene with a
// typo fails before any mesh is loaded. Errors read
// "<file>: <json.path>: expected ...".
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/Scene.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/SmallString.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"

#include <nlohmann/json.hpp>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>

using namespace simit;
using Json = nlohmann::ordered_json;

namespace {

class SceneParser {
public:
  SceneParser(llvm::StringRef name, llvm::StringRef directory)
      : name(name.str()), directory(directory.str()) {}

  llvm::Error parse(const Json &root, SceneDescription &scene);

private:
  llvm::Error error(const std::string &path, const llvm::Twine &message) {
    return llvm::createStringError(name + ": " + path + ": " + message);
  }
  static std::string child(const std::string &path, llvm::StringRef key) {
    return path.empty() ? key.str() : path + "." + key.str();
  }
  static std::string element(const std::string &path, size_t index) {
    return path + "[" + std::to_string(index) + "]";
  }
  std::string resolve(llvm::StringRef file) const {
    if (llvm::sys::path::is_absolute(file) || directory.empty())
      return file.str();
    llvm::SmallString<256> full(directory);
    llvm::sys::path::append(full, file);
    return std::string(full);
  }

  llvm::Error checkKeys(const Json &object, const std::string &path,
                        std::initializer_list<llvm::StringRef> allowed);
  llvm::Error expectObject(const Json &value, const std::string &path);
  llvm::Expected<std::string> getString(const Json &value,
                                        const std::string &path);
  llvm::Expected<int> getInt(const Json &value, const std::string &path,
                             int minimum, int maximum = INT32_MAX);
  llvm::Expected<std::vector<std::string>>
  getNames(const Json &value, const std::string &path);
  llvm::Expected<std::vector<int>> getShape(const Json &value,
                                            const std::string &path);
  /// Flattens a number, a boolean or a (nested) array of them into
  /// `values`, appending the nesting's shape to `shape`.
  struct Kinds {
    bool anyBoolean = false, anyNumber = false, anyFraction = false;
  };
  llvm::Error flatten(const Json &value, const std::string &path,
                      std::vector<double> &values, std::vector<int> &shape,
                      Kinds &kinds);
  /// Reads a constant of `type` and `shape` (inferred when empty and
  /// `inferShape`).
  llvm::Error readConstant(const Json &value, const std::string &path,
                           ComponentType type, std::vector<int> &shape,
                           bool inferShape, std::vector<double> &values);
  /// Checks that `values` fit in `type` (int32 and float32 hold less than
  /// the doubles JSON numbers are read as).
  llvm::Error checkRange(const std::string &path, ComponentType type,
                         llvm::ArrayRef<double> values);

  /// Reads an array of constant blocks, one per element, appending their
  /// components to `values`; the first block gives the shape when inferred.
  llvm::Error readBlocks(const Json &value, const std::string &path,
                         ComponentType type, std::vector<int> &shape,
                         bool inferShape, std::vector<double> &values);

  llvm::Error parseMeshes(const Json &value, SceneDescription &scene);
  llvm::Error parseSets(const Json &value, SceneDescription &scene);
  llvm::Error parseSet(const Json &value, const std::string &path,
                       SetSpec &set, const SceneDescription &scene);
  /// Reads the endpoint index lists of a Listed set.
  llvm::Error parseListedElements(const Json &value, const std::string &path,
                                  SetSpec &set);
  /// Repeats a single endpoint set name to the elements' arity, or checks
  /// that one name is given per endpoint.
  llvm::Error matchListedArity(SetSpec &set, const std::string &path,
                               bool oneSetForAll);
  /// Checks that endpoint sets exist and that no set is, through its
  /// endpoints, its own endpoint.
  llvm::Error checkEndpointSets(const SceneDescription &scene);
  llvm::Error parseField(const Json &value, const std::string &path,
                         const SetSpec &set, FieldSpec &field);
  llvm::Error parseExterns(const Json &value, SceneDescription &scene);
  llvm::Error parseOutput(const Json &value, const std::string &path,
                          const SceneDescription &scene, OutputSpec &output);
  llvm::Error parseSolver(const Json &value, SolveSettings &settings);

  std::string name, directory;
};

/// Each level multiplies the tets by 8: past this, no machine holds the
/// result of even a one-tet mesh.
constexpr int kMaxRefine = 10;

const char *jsonKind(const Json &value) {
  switch (value.type()) {
  case Json::value_t::null:
    return "null";
  case Json::value_t::object:
    return "an object";
  case Json::value_t::array:
    return "an array";
  case Json::value_t::string:
    return "a string";
  case Json::value_t::boolean:
    return "a boolean";
  default:
    return "a number";
  }
}

std::string shapeText(llvm::ArrayRef<int> shape) {
  std::string text = "[";
  for (size_t i = 0; i < shape.size(); ++i)
    text += (i ? ", " : "") + std::to_string(shape[i]);
  return text + "]";
}

std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", value);
  return text;
}

size_t product(llvm::ArrayRef<int> shape) {
  size_t n = 1;
  for (int d : shape)
    n *= d;
  return n;
}

std::optional<ComponentType> parseType(llvm::StringRef text) {
  if (text == "float64" || text == "float" || text == "double")
    return ComponentType::Float64;
  if (text == "float32")
    return ComponentType::Float32;
  if (text == "int32" || text == "int")
    return ComponentType::Int32;
  if (text == "bool")
    return ComponentType::Bool;
  return std::nullopt;
}

llvm::Error SceneParser::checkKeys(const Json &object, const std::string &path,
                                   std::initializer_list<llvm::StringRef> allowed) {
  for (auto it = object.begin(); it != object.end(); ++it)
    if (!llvm::is_contained(allowed, llvm::StringRef(it.key()))) {
      std::string list;
      for (llvm::StringRef key : allowed)
        list += (list.empty() ? "" : ", ") + key.str();
      return error(child(path, it.key()),
                   "unknown key (expected one of " + list + ")");
    }
  return llvm::Error::success();
}

llvm::Error SceneParser::expectObject(const Json &value,
                                      const std::string &path) {
  if (value.is_object())
    return llvm::Error::success();
  return error(path, llvm::Twine("expected an object, found ") +
                         jsonKind(value));
}

llvm::Expected<std::string> SceneParser::getString(const Json &value,
                                                   const std::string &path) {
  if (!value.is_string() || value.get<std::string>().empty())
    return error(path, llvm::Twine("expected a non-empty string, found ") +
                           (value.is_string() ? "\"\"" : jsonKind(value)));
  return value.get<std::string>();
}

llvm::Expected<int> SceneParser::getInt(const Json &value,
                                        const std::string &path, int minimum,
                                        int maximum) {
  // Large unsigned numbers do not fit in a long long: compare as doubles
  // first.
  if (!value.is_number_integer() || value.get<double>() < minimum ||
      value.get<double>() > maximum) {
    if (maximum == INT32_MAX)
      return error(path, "expected an integer of at least " +
                             llvm::Twine(minimum) + " (and at most " +
                             llvm::Twine(maximum) + ")");
    return error(path, "expected an integer from " + llvm::Twine(minimum) +
                           " to " + llvm::Twine(maximum));
  }
  return static_cast<int>(value.get<long long>());
}

llvm::Expected<std::vector<std::string>>
SceneParser::getNames(const Json &value, const std::string &path) {
  std::vector<std::string> names;
  if (value.is_string()) {
    auto single = getString(value, path);
    if (!single)
      return single.takeError();
    names.push_back(*single);
    return names;
  }
  if (!value.is_array())
    return error(path, llvm::Twine("expected a name or an array of names, "
                                   "found ") +
                           jsonKind(value));
  for (size_t i = 0; i < value.size(); ++i) {
    auto entry = getString(value[i], element(path, i));
    if (!entry)
      return entry.takeError();
    names.push_back(*entry);
  }
  return names;
}

llvm::Expected<std::vector<int>> SceneParser::getShape(const Json &value,
                                                       const std::string &path) {
  if (!value.is_array())
    return error(path, llvm::Twine("expected an array of positive integers, "
                                   "found ") +
                           jsonKind(value));
  std::vector<int> shape;
  for (size_t i = 0; i < value.size(); ++i) {
    auto dim = getInt(value[i], element(path, i), 1);
    if (!dim)
      return dim.takeError();
    shape.push_back(*dim);
  }
  return shape;
}

llvm::Error SceneParser::flatten(const Json &value, const std::string &path,
                                 std::vector<double> &values,
                                 std::vector<int> &shape, Kinds &kinds) {
  if (value.is_boolean()) {
    values.push_back(value.get<bool>() ? 1.0 : 0.0);
    kinds.anyBoolean = true;
    return llvm::Error::success();
  }
  if (value.is_number()) {
    double number = value.get<double>();
    values.push_back(number);
    kinds.anyNumber = true;
    kinds.anyFraction |= std::floor(number) != number;
    return llvm::Error::success();
  }
  if (!value.is_array() || value.empty())
    return error(path, llvm::Twine("expected a number, a boolean or a "
                                   "non-empty array of them, found ") +
                           (value.is_array() ? "an empty array"
                                             : jsonKind(value)));
  // Every row of a nested array must have the first row's shape.
  std::vector<int> rowShape;
  for (size_t i = 0; i < value.size(); ++i) {
    std::vector<int> thisShape;
    if (auto err = flatten(value[i], element(path, i), values, thisShape,
                           kinds))
      return err;
    if (i == 0)
      rowShape = thisShape;
    else if (thisShape != rowShape)
      return error(element(path, i), "expected shape " +
                                         shapeText(rowShape) +
                                         " like the first entry, found " +
                                         shapeText(thisShape));
  }
  shape.push_back(static_cast<int>(value.size()));
  shape.insert(shape.end(), rowShape.begin(), rowShape.end());
  return llvm::Error::success();
}

llvm::Error SceneParser::readConstant(const Json &value,
                                      const std::string &path,
                                      ComponentType type,
                                      std::vector<int> &shape, bool inferShape,
                                      std::vector<double> &values) {
  std::vector<int> found;
  Kinds kinds;
  values.clear();
  if (auto err = flatten(value, path, values, found, kinds))
    return err;
  if (inferShape && shape.empty())
    shape = found;
  // A flat list of the right length also fills a matrix block.
  size_t expected = product(shape);
  bool shapeMatches = found == shape ||
                      (found.size() == 1 && values.size() == expected);
  if (!shapeMatches) {
    const char *unit = type == ComponentType::Bool    ? "boolean"
                       : type == ComponentType::Int32 ? "integer"
                                                      : "number";
    std::string what;
    if (shape.empty())
      what = std::string("a single ") + unit;
    else if (shape.size() == 1)
      what = "an array of " + std::to_string(expected) + " " + unit + "s";
    else
      what = "an array of shape " + shapeText(shape) + " (or a flat array " +
             "of " + std::to_string(expected) + ") of " + unit + "s";
    return error(path, "expected " + what + ", found " +
                           (found.empty() ? std::string("a single value")
                                          : "an array of shape " +
                                                shapeText(found)));
  }
  switch (type) {
  case ComponentType::Bool:
    if (kinds.anyNumber)
      return error(path, "expected true or false for a bool value");
    break;
  case ComponentType::Int32:
    if (kinds.anyBoolean || kinds.anyFraction)
      return error(path, "expected integers for an int32 value");
    break;
  case ComponentType::Float64:
  case ComponentType::Float32:
    if (kinds.anyBoolean)
      return error(path, "expected numbers for a " +
                             componentTypeName(type) + " value, found a "
                                                       "boolean");
    break;
  }
  return checkRange(path, type, values);
}

llvm::Error SceneParser::checkRange(const std::string &path,
                                    ComponentType type,
                                    llvm::ArrayRef<double> values) {
  double low, high;
  if (type == ComponentType::Int32)
    low = INT32_MIN, high = INT32_MAX;
  else if (type == ComponentType::Float32)
    low = -FLT_MAX, high = FLT_MAX;
  else
    return llvm::Error::success();
  for (size_t i = 0; i < values.size(); ++i) {
    if (values[i] >= low && values[i] <= high)
      continue;
    std::string where =
        values.size() == 1 ? path : path + ": component " + std::to_string(i);
    return error(where, "expected " + componentTypeName(type) +
                            " values from " + numberText(low) + " to " +
                            numberText(high) + ", found " +
                            numberText(values[i]));
  }
  return llvm::Error::success();
}

//===--- Sections ---------------------------------------------------------===//

llvm::Error SceneParser::parseMeshes(const Json &value,
                                     SceneDescription &scene) {
  if (auto err = expectObject(value, "meshes"))
    return err;
  for (auto it = value.begin(); it != value.end(); ++it) {
    std::string path = child("meshes", it.key());
    MeshSpec mesh;
    mesh.name = it.key();
    const Json &entry = it.value();
    if (entry.is_string()) {
      mesh.path = resolve(entry.get<std::string>());
    } else {
      if (!entry.is_object())
        return error(path, llvm::Twine("expected a file name or an object, "
                                       "found ") +
                               jsonKind(entry));
      if (auto err = checkKeys(entry, path, {"file", "refine", "strict"}))
        return err;
      if (!entry.contains("file"))
        return error(path, "expected a \"file\"");
      auto file = getString(entry["file"], child(path, "file"));
      if (!file)
        return file.takeError();
      mesh.path = resolve(*file);
      if (entry.contains("refine")) {
        auto refine = getInt(entry["refine"], child(path, "refine"), 0,
                             kMaxRefine);
        if (!refine)
          return refine.takeError();
        mesh.refine = *refine;
      }
      if (entry.contains("strict")) {
        if (!entry["strict"].is_boolean())
          return error(child(path, "strict"),
                       llvm::Twine("expected true or false, found ") +
                           jsonKind(entry["strict"]));
        mesh.strict = entry["strict"].get<bool>();
      }
    }
    scene.meshes.push_back(std::move(mesh));
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::readBlocks(const Json &value, const std::string &path,
                                    ComponentType type,
                                    std::vector<int> &shape, bool inferShape,
                                    std::vector<double> &values) {
  if (!value.is_array())
    return error(path, llvm::Twine("expected an array with one value per "
                                   "element, found ") +
                           jsonKind(value));
  values.clear();
  std::vector<double> block;
  for (size_t i = 0; i < value.size(); ++i) {
    if (auto err = readConstant(value[i], element(path, i), type, shape,
                                inferShape && i == 0, block))
      return err;
    values.insert(values.end(), block.begin(), block.end());
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::parseField(const Json &value, const std::string &path,
                                    const SetSpec &set, FieldSpec &field) {
  field.jsonPath = path;
  FieldInit &init = field.init;
  if (!value.is_object()) {
    // A bare constant: float64 (or bool for true/false) of its own shape.
    if (value.is_boolean() ||
        (value.is_array() && !value.empty() && value[0].is_boolean()))
      field.type = ComponentType::Bool;
    init.kind = FieldInit::Constant;
    return readConstant(value, path, field.type, field.shape, true,
                        init.values);
  }
  if (auto err = checkKeys(value, path,
                           {"type", "shape", "value", "values", "coordinates",
                            "file", "expr", "if", "then", "else", "space"}))
    return err;
  if (value.contains("type")) {
    auto text = getString(value["type"], child(path, "type"));
    if (!text)
      return text.takeError();
    auto type = parseType(*text);
    if (!type)
      return error(child(path, "type"), "expected float64, float32, int32 "
                                        "or bool, found \"" +
                                            *text + "\"");
    field.type = *type;
  }
  bool explicitShape = value.contains("shape");
  if (explicitShape) {
    auto shape = getShape(value["shape"], child(path, "shape"));
    if (!shape)
      return shape.takeError();
    field.shape = std::move(*shape);
  }

  const char *kinds[] = {"value", "values", "coordinates", "file", "expr",
                         "if"};
  std::vector<std::string> present;
  for (const char *kind : kinds)
    if (value.contains(kind))
      present.push_back(kind);
  if (present.size() > 1)
    return error(path, "expected one of value, values, coordinates, file, "
                       "expr or if, found both \"" +
                           present[0] + "\" and \"" + present[1] + "\"");
  llvm::StringRef kind = present.empty() ? "" : llvm::StringRef(present[0]);
  if (kind != "if" && (value.contains("then") || value.contains("else")))
    return error(path, "expected \"then\" and \"else\" only with \"if\"");

  if (value.contains("space")) {
    if (kind != "expr" && kind != "if")
      return error(child(path, "space"),
                   "expected \"space\" only with \"expr\" or \"if\"");
    auto space = getString(value["space"], child(path, "space"));
    if (!space)
      return space.takeError();
    if (*space != "mesh" && *space != "normalized")
      return error(child(path, "space"),
                   "expected \"mesh\" or \"normalized\", found \"" + *space +
                       "\"");
    init.normalized = *space == "normalized";
  }

  bool meshBacked =
      set.kind == SetSpec::Points || set.kind == SetSpec::Elements;
  if ((kind == "coordinates" || kind == "expr" || kind == "if") &&
      !meshBacked)
    return error(child(path, kind),
                 "expected a set built from a mesh, which has coordinates");
  bool isFloat = field.type == ComponentType::Float64 ||
                 field.type == ComponentType::Float32;

  if (kind.empty()) {
    init.kind = FieldInit::Zero;
  } else if (kind == "value") {
    init.kind = FieldInit::Constant;
    return readConstant(value["value"], child(path, "value"), field.type,
                        field.shape, !explicitShape, init.values);
  } else if (kind == "values") {
    init.kind = FieldInit::PerElement;
    return readBlocks(value["values"], child(path, "values"), field.type,
                      field.shape, !explicitShape, init.values);
  } else if (kind == "coordinates") {
    init.kind = FieldInit::Coordinates;
    auto space = getString(value["coordinates"], child(path, "coordinates"));
    if (!space)
      return space.takeError();
    if (*space != "mesh" && *space != "normalized")
      return error(child(path, "coordinates"),
                   "expected \"mesh\" or \"normalized\", found \"" + *space +
                       "\"");
    init.normalized = *space == "normalized";
    if (!explicitShape)
      field.shape = {3};
    if (field.shape != std::vector<int>{3} || !isFloat)
      return error(path, "expected a float64 or float32 field of shape [3] "
                         "for coordinates");
  } else if (kind == "file") {
    init.kind = FieldInit::File;
    auto file = getString(value["file"], child(path, "file"));
    if (!file)
      return file.takeError();
    init.file = resolve(*file);
  } else if (kind == "expr") {
    init.kind = FieldInit::Expression;
    auto text = getString(value["expr"], child(path, "expr"));
    if (!text)
      return text.takeError();
    auto expression = SceneExpression::parse(*text);
    if (!expression)
      return error(child(path, "expr"),
                   llvm::toString(expression.takeError()));
    if (!field.shape.empty())
      return error(path, "expected a scalar field (shape []) for \"expr\"");
    if (field.type == ComponentType::Bool && !expression->isBoolean())
      return error(child(path, "expr"),
                   "expected a boolean expression for a bool field");
    init.expression =
        std::make_shared<const SceneExpression>(std::move(*expression));
  } else {
    init.kind = FieldInit::Select;
    auto text = getString(value["if"], child(path, "if"));
    if (!text)
      return text.takeError();
    auto expression = SceneExpression::parse(*text);
    if (!expression)
      return error(child(path, "if"), llvm::toString(expression.takeError()));
    if (!expression->isBoolean())
      return error(child(path, "if"), "expected a boolean condition");
    init.expression =
        std::make_shared<const SceneExpression>(std::move(*expression));
    if (!value.contains("then") || !value.contains("else"))
      return error(path, "expected both \"then\" and \"else\" with \"if\"");
    if (auto err = readConstant(value["then"], child(path, "then"),
                                field.type, field.shape, !explicitShape,
                                init.then))
      return err;
    return readConstant(value["else"], child(path, "else"), field.type,
                        field.shape, false, init.otherwise);
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::parseListedElements(const Json &value,
                                             const std::string &path,
                                             SetSpec &set) {
  for (size_t i = 0; i < value.size(); ++i) {
    const Json &entry = value[i];
    std::string entryPath = element(path, i);
    if (!entry.is_array() || entry.empty())
      return error(entryPath, llvm::Twine("expected an array of endpoint "
                                          "indices, found ") +
                                  jsonKind(entry));
    std::vector<int> ends;
    for (size_t j = 0; j < entry.size(); ++j) {
      auto index = getInt(entry[j], element(entryPath, j), 0);
      if (!index)
        return index.takeError();
      ends.push_back(*index);
    }
    if (i > 0 && ends.size() != set.listed[0].size())
      return error(entryPath, "expected " +
                                  llvm::Twine(set.listed[0].size()) +
                                  " endpoints, as in element 0, found " +
                                  llvm::Twine(ends.size()));
    set.listed.push_back(std::move(ends));
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::matchListedArity(SetSpec &set,
                                          const std::string &path,
                                          bool oneSetForAll) {
  if (set.listed.empty()) {
    if (oneSetForAll)
      return error(path, "expected an array naming the set of each endpoint "
                         "(the \"elements\" array is empty, so it does not "
                         "give the number of endpoints)");
    return llvm::Error::success();
  }
  size_t arity = set.listed[0].size();
  if (oneSetForAll)
    set.endpoints.assign(arity, set.endpoints[0]);
  if (set.endpoints.size() != arity)
    return error(path, "expected " + llvm::Twine(arity) +
                           " set names, one per endpoint of an element, "
                           "found " +
                           llvm::Twine(set.endpoints.size()));
  return llvm::Error::success();
}


llvm::Error SceneParser::parseSet(const Json &value, const std::string &path,
                                  SetSpec &set, const SceneDescription &scene) {
  if (auto err = expectObject(value, path))
    return err;
  if (auto err = checkKeys(value, path,
                           {"mesh", "elements", "endpoints", "size", "grid",
                            "fields"}))
    return err;
  bool hasMesh = value.contains("mesh"), hasSize = value.contains("size"),
       hasGrid = value.contains("grid"),
       hasList = value.contains("elements") && value["elements"].is_array();
  if (hasMesh + hasSize + hasGrid + hasList != 1)
    return error(path, "expected exactly one of \"mesh\", \"size\", "
                       "\"grid\" or an \"elements\" array");
  if (hasMesh) {
    auto mesh = getString(value["mesh"], child(path, "mesh"));
    if (!mesh)
      return mesh.takeError();
    if (!llvm::any_of(scene.meshes,
                      [&](const MeshSpec &m) { return m.name == *mesh; }))
      return error(child(path, "mesh"),
                   "expected the name of a mesh in \"meshes\", found \"" +
                       *mesh + "\"");
    set.mesh = *mesh;
    set.kind = value.contains("elements") ? SetSpec::Elements
                                          : SetSpec::Points;
  } else if (hasSize) {
    set.kind = SetSpec::Sized;
    auto size = getInt(value["size"], child(path, "size"), 0);
    if (!size)
      return size.takeError();
    set.size = *size;
  } else if (hasGrid) {
    set.kind = SetSpec::Grid;
    auto dims = getShape(value["grid"], child(path, "grid"));
    if (!dims)
      return dims.takeError();
    if (dims->empty())
      return error(child(path, "grid"), "expected at least one dimension");
    set.dims = std::move(*dims);
  } else {
    set.kind = SetSpec::Listed;
    if (auto err = parseListedElements(value["elements"],
                                       child(path, "elements"), set))
      return err;
  }

  if (value.contains("elements") && set.kind != SetSpec::Elements &&
      set.kind != SetSpec::Listed)
    return error(child(path, "elements"),
                 "expected \"elements\" only with \"mesh\", or as an "
                 "array of endpoint index lists");
  if (set.kind == SetSpec::Elements) {
    auto elements = getString(value["elements"], child(path, "elements"));
    if (!elements)
      return elements.takeError();
    if (*elements != "edges" && *elements != "triangles" &&
        *elements != "tets")
      return error(child(path, "elements"),
                   "expected \"edges\", \"triangles\" or \"tets\", found \"" +
                       *elements + "\"");
    set.elements = *elements;
  }
  bool needsEndpoints = set.kind == SetSpec::Elements ||
                        set.kind == SetSpec::Grid ||
                        set.kind == SetSpec::Listed;
  if (needsEndpoints != value.contains("endpoints"))
    return error(path, needsEndpoints
                           ? "expected \"endpoints\": the name of the point "
                             "set"
                           : "expected \"endpoints\" only with "
                             "\"elements\" or \"grid\"");
  if (needsEndpoints) {
    std::string endpointsPath = child(path, "endpoints");
    const Json &endpoints = value["endpoints"];
    bool oneSetForAll = !endpoints.is_array();
    if (set.kind == SetSpec::Listed && !oneSetForAll) {
      auto names = getNames(endpoints, endpointsPath);
      if (!names)
        return names.takeError();
      set.endpoints = std::move(*names);
    } else {
      auto endpoint = getString(endpoints, endpointsPath);
      if (!endpoint)
        return endpoint.takeError();
      set.endpoints = {*endpoint};
    }
    if (set.kind == SetSpec::Listed)
      if (auto err = matchListedArity(set, endpointsPath, oneSetForAll))
        return err;
  }

  if (value.contains("fields")) {
    const Json &fields = value["fields"];
    std::string fieldsPath = child(path, "fields");
    if (auto err = expectObject(fields, fieldsPath))
      return err;
    for (auto it = fields.begin(); it != fields.end(); ++it) {
      FieldSpec field;
      field.name = it.key();
      if (auto err = parseField(it.value(), child(fieldsPath, it.key()), set,
                                field))
        return err;
      set.fields.push_back(std::move(field));
    }
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::parseSets(const Json &value,
                                   SceneDescription &scene) {
  if (auto err = expectObject(value, "sets"))
    return err;
  for (auto it = value.begin(); it != value.end(); ++it) {
    SetSpec set;
    set.name = it.key();
    if (auto err = parseSet(it.value(), child("sets", it.key()), set, scene))
      return err;
    scene.sets.push_back(std::move(set));
  }
  return checkEndpointSets(scene);
}

llvm::Error SceneParser::checkEndpointSets(const SceneDescription &scene) {
  // Mesh elements and grids join the points of their own mesh or grid;
  // listed elements may join any sets, edge sets included.
  for (const SetSpec &set : scene.sets) {
    std::string path = child(child("sets", set.name), "endpoints");
    for (size_t i = 0; i < set.endpoints.size(); ++i) {
      const std::string &endpoint = set.endpoints[i];
      std::string endpointPath =
          set.kind == SetSpec::Listed && set.endpoints.size() > 1
              ? element(path, i)
              : path;
      const SetSpec *target = scene.findSet(endpoint);
      if (!target)
        return error(endpointPath,
                     "expected the name of a set in \"sets\", found \"" +
                         endpoint + "\"");
      bool targetIsEdgeSet = !target->endpoints.empty();
      if (set.kind != SetSpec::Listed && targetIsEdgeSet)
        return error(endpointPath, "expected a vertex set, found the edge "
                                   "set \"" +
                                       endpoint + "\"");
      if (set.kind == SetSpec::Elements &&
          (target->kind != SetSpec::Points || target->mesh != set.mesh))
        return error(endpointPath, "expected a set of the points of mesh \"" +
                                       set.mesh + "\"");
    }
  }
  // Sets are built after their endpoint sets, so endpoints may not cycle.
  std::map<std::string, int> state; // 1: on the current path, 2: done
  std::function<llvm::Error(const SetSpec &)> visit =
      [&](const SetSpec &set) -> llvm::Error {
    int &mark = state[set.name];
    if (mark == 2)
      return llvm::Error::success();
    if (mark == 1)
      return error(child(child("sets", set.name), "endpoints"),
                   "expected endpoint sets that do not lead back to \"" +
                       set.name + "\"");
    mark = 1;
    for (const std::string &endpoint : set.endpoints)
      if (auto err = visit(*scene.findSet(endpoint)))
        return err;
    state[set.name] = 2;
    return llvm::Error::success();
  };
  for (const SetSpec &set : scene.sets)
    if (auto err = visit(set))
      return err;
  return llvm::Error::success();
}

/// Whether `value` is a boolean or a nested array starting with one: a
/// bool extern without a "type" (readConstant then wants them all
/// booleans).
static bool holdsBooleans(const Json &value) {
  const Json *first = &value;
  while (first->is_array() && !first->empty())
    first = &(*first)[0];
  return first->is_boolean();
}

llvm::Error SceneParser::parseExterns(const Json &value,
                                      SceneDescription &scene) {
  if (auto err = expectObject(value, "externs"))
    return err;
  for (auto it = value.begin(); it != value.end(); ++it) {
    std::string path = child("externs", it.key());
    ExternTensor tensor;
    const Json *constant = &it.value();
    if (it.value().is_object()) {
      if (auto err = checkKeys(it.value(), path, {"type", "value", "constant"}))
        return err;
      if (it.value().contains("constant")) {
        const Json &flag = it.value()["constant"];
        if (!flag.is_boolean())
          return error(child(path, "constant"),
                       llvm::Twine("expected true or false, found ") +
                           jsonKind(flag));
        tensor.constant = flag.get<bool>();
      }
      if (!it.value().contains("value"))
        return error(path, "expected a \"value\"");
      if (it.value().contains("type")) {
        auto text = getString(it.value()["type"], child(path, "type"));
        if (!text)
          return text.takeError();
        auto type = parseType(*text);
        if (!type)
          return error(child(path, "type"), "expected float64, float32, "
                                            "int32 or bool, found \"" +
                                                *text + "\"");
        tensor.type = *type;
      } else if (holdsBooleans(it.value()["value"])) {
        tensor.type = ComponentType::Bool;
      }
      constant = &it.value()["value"];
      path = child(path, "value");
    } else if (holdsBooleans(it.value())) {
      tensor.type = ComponentType::Bool;
    }
    if (auto err = readConstant(*constant, path, tensor.type, tensor.shape,
                                true, tensor.values))
      return err;
    tensor.store();
    scene.externs.emplace_back(it.key(), std::move(tensor));
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::parseOutput(const Json &value,
                                     const std::string &path,
                                     const SceneDescription &scene,
                                     OutputSpec &output) {
  output.jsonPath = path;
  if (auto err = expectObject(value, path))
    return err;
  if (auto err = checkKeys(value, path,
                           {"format", "path", "set", "position", "cells",
                            "fields", "cell_fields", "every", "last"}))
    return err;
  for (const char *key : {"format", "path", "set"})
    if (!value.contains(key))
      return error(path, llvm::Twine("expected a \"") + key + "\"");
  auto format = getString(value["format"], child(path, "format"));
  if (!format)
    return format.takeError();
  if (*format != "vtk" && *format != "csv")
    return error(child(path, "format"),
                 "expected \"vtk\" or \"csv\", found \"" + *format + "\"");
  output.kind = *format == "vtk" ? OutputSpec::VTK : OutputSpec::CSV;
  bool vtk = output.kind == OutputSpec::VTK;
  auto file = getString(value["path"], child(path, "path"));
  if (!file)
    return file.takeError();
  output.path = *file;
  auto set = getString(value["set"], child(path, "set"));
  if (!set)
    return set.takeError();
  output.set = *set;
  const SetSpec *setSpec = scene.findSet(output.set);
  if (!setSpec)
    return error(child(path, "set"),
                 "expected the name of a set in \"sets\", found \"" +
                     output.set + "\"");
  if (!vtk)
    for (const char *key : {"position", "cells", "cell_fields"})
      if (value.contains(key))
        return error(child(path, key), "expected only with \"format\": "
                                       "\"vtk\"");
  if (value.contains("position")) {
    auto position = getString(value["position"], child(path, "position"));
    if (!position)
      return position.takeError();
    output.position = *position;
  }
  if (value.contains("fields")) {
    auto fields = getNames(value["fields"], child(path, "fields"));
    if (!fields)
      return fields.takeError();
    output.fields = std::move(*fields);
  }
  if (value.contains("cells")) {
    auto cells = getNames(value["cells"], child(path, "cells"));
    if (!cells)
      return cells.takeError();
    output.cells = std::move(*cells);
    for (size_t i = 0; i < output.cells.size(); ++i) {
      const SetSpec *cellSet = scene.findSet(output.cells[i]);
      if (!cellSet || cellSet->endpoints.empty() ||
          llvm::any_of(cellSet->endpoints, [&](const std::string &name) {
            return name != output.set;
          }))
        return error(element(child(path, "cells"), i),
                     "expected an edge set over \"" + output.set +
                         "\", found \"" + output.cells[i] + "\"");
    }
  }
  if (value.contains("cell_fields")) {
    auto cellFields = getNames(value["cell_fields"],
                               child(path, "cell_fields"));
    if (!cellFields)
      return cellFields.takeError();
    output.cellFields = std::move(*cellFields);
    if (output.cells.size() != 1)
      return error(child(path, "cell_fields"),
                   "expected exactly one set in \"cells\" to take cell "
                   "fields from");
  }
  if (vtk && setSpec->kind != SetSpec::Points &&
      setSpec->kind != SetSpec::Sized)
    return error(child(path, "set"), "expected a vertex set for VTK output");
  if (value.contains("every")) {
    auto every = getInt(value["every"], child(path, "every"), 1);
    if (!every)
      return every.takeError();
    output.every = *every;
  }
  if (value.contains("last")) {
    if (!value["last"].is_boolean())
      return error(child(path, "last"), "expected true or false");
    output.lastOnly = value["last"].get<bool>();
  }
  size_t frameAt = output.path.find("{frame}");
  if (frameAt != std::string::npos &&
      output.path.find("{frame}", frameAt + 1) != std::string::npos)
    return error(child(path, "path"),
                 "expected \"{frame}\" at most once in the path");
  bool manyFiles = !output.lastOnly && (vtk || output.path.find("{frame}") !=
                                                   std::string::npos);
  if (manyFiles && output.path.find("{frame}") == std::string::npos)
    return error(child(path, "path"), "expected \"{frame}\" in the path of "
                                      "a VTK output written every frame "
                                      "(or \"last\": true)");
  return llvm::Error::success();
}

/// "solver": "method", or {"method": ..., "tol": ..., "maxIters": ...,
/// "strict": ..., "warmStart": ..., "refactorIters": ...}.
llvm::Error SceneParser::parseSolver(const Json &value,
                                     SolveSettings &settings) {
  auto method = [&](const Json &name, const std::string &path) -> llvm::Error {
    auto text = getString(name, path);
    if (!text)
      return text.takeError();
    std::optional<SolveMethod> parsed = parseSolveMethod(*text);
    if (!parsed)
      return error(path, "unknown solver method \"" + *text +
                             "\" (expected one of " + solveMethodNames() +
                             ")");
    settings.method = *parsed;
    return llvm::Error::success();
  };
  if (value.is_string())
    return method(value, "solver");
  if (auto err = expectObject(value, "solver"))
    return err;
  if (auto err = checkKeys(value, "solver",
                           {"method", "tol", "maxIters", "strict",
                            "warmStart", "refactorIters"}))
    return err;
  if (value.contains("method"))
    if (auto err = method(value["method"], "solver.method"))
      return err;
  if (value.contains("tol")) {
    const Json &tol = value["tol"];
    if (!tol.is_number() || !(tol.get<double>() > 0 && tol.get<double>() < 1))
      return error("solver.tol",
                   llvm::Twine("expected a number between 0 and 1, found ") +
                       (tol.is_number() ? numberText(tol.get<double>())
                                        : std::string(jsonKind(tol))));
    settings.tolerance = tol.get<double>();
  }
  if (value.contains("maxIters")) {
    auto cap = getInt(value["maxIters"], "solver.maxIters", 1);
    if (!cap)
      return cap.takeError();
    settings.maxIterations = *cap;
  }
  if (value.contains("refactorIters")) {
    auto threshold =
        getInt(value["refactorIters"], "solver.refactorIters", 1);
    if (!threshold)
      return threshold.takeError();
    settings.refactorIterations = *threshold;
  }
  if (value.contains("strict")) {
    if (!value["strict"].is_boolean())
      return error("solver.strict", llvm::Twine("expected a boolean, found ") +
                                        jsonKind(value["strict"]));
    settings.strict = value["strict"].get<bool>();
  }
  if (value.contains("warmStart")) {
    if (!value["warmStart"].is_boolean())
      return error("solver.warmStart",
                   llvm::Twine("expected a boolean, found ") +
                       jsonKind(value["warmStart"]));
    settings.warmStart = value["warmStart"].get<bool>();
  }
  return llvm::Error::success();
}

llvm::Error SceneParser::parse(const Json &root, SceneDescription &scene) {
  if (!root.is_object())
    return llvm::createStringError(name + ": expected a JSON object, found " +
                                   jsonKind(root));
  if (auto err = checkKeys(root, "",
                           {"program", "libraries", "meshes", "sets",
                            "externs", "init", "step", "frames", "outputs",
                            "solver"}))
    return err;
  if (root.contains("solver"))
    if (auto err = parseSolver(root["solver"], scene.solver))
      return err;
  if (root.contains("program")) {
    auto program = getString(root["program"], "program");
    if (!program)
      return program.takeError();
    scene.program = resolve(*program);
  }
  if (root.contains("libraries")) {
    auto libraries = getNames(root["libraries"], "libraries");
    if (!libraries)
      return libraries.takeError();
    // dlopen looks for a bare file name on the system's library path, not
    // beside the scene (`--scene scene.json` has no directory).
    for (auto [i, library] : llvm::enumerate(*libraries)) {
      std::string path = resolve(library);
      if (!llvm::StringRef(path).contains('/'))
        path = "./" + path;
      // Named here, not when the program loads it and only its file is
      // known.
      if (!llvm::sys::fs::exists(path))
        return error("libraries[" + std::to_string(i) + "]",
                     "no host library '" + path + "'");
      scene.libraries.push_back(std::move(path));
    }
  }
  if (root.contains("meshes"))
    if (auto err = parseMeshes(root["meshes"], scene))
      return err;
  if (!root.contains("sets"))
    return llvm::createStringError(name + ": expected a \"sets\" object");
  if (auto err = parseSets(root["sets"], scene))
    return err;
  if (root.contains("externs"))
    if (auto err = parseExterns(root["externs"], scene))
      return err;
  for (auto [key, list] : {std::pair<const char *, std::vector<std::string> *>{
                               "init", &scene.init},
                           {"step", &scene.step}})
    if (root.contains(key)) {
      auto names = getNames(root[key], key);
      if (!names)
        return names.takeError();
      *list = std::move(*names);
    }
  if (root.contains("frames")) {
    auto frames = getInt(root["frames"], "frames", 0);
    if (!frames)
      return frames.takeError();
    scene.frames = *frames;
  }
  if (scene.frames > 0 && scene.step.empty())
    return error("frames", "expected a \"step\" function to run per frame");
  if (root.contains("outputs")) {
    const Json &outputs = root["outputs"];
    if (!outputs.is_array())
      return error("outputs", llvm::Twine("expected an array, found ") +
                                  jsonKind(outputs));
    for (size_t i = 0; i < outputs.size(); ++i) {
      OutputSpec output;
      if (auto err = parseOutput(outputs[i], element("outputs", i), scene,
                                 output))
        return err;
      scene.outputs.push_back(std::move(output));
    }
  }
  return llvm::Error::success();
}

} // namespace

const SetSpec *SceneDescription::findSet(llvm::StringRef setName) const {
  for (const SetSpec &set : sets)
    if (set.name == setName)
      return &set;
  return nullptr;
}

namespace {

/// Deeper JSON than this is no scene; the readers below recurse on arrays.
constexpr int kMaxJsonNesting = 64;

/// Follows the JSON path of the value being parsed, for errors that the
/// JSON library raises without one (a number out of range) and for nesting
/// too deep to read.
class JsonPathTracker {
public:
  struct TooDeep {};
  /// A key given twice in one object: JSON readers keep one of the values,
  /// so the other would be ignored without a word.
  struct DuplicateKey {};

  bool operator()(int depth, nlohmann::detail::parse_event_t event,
                  Json &parsed) {
    using Event = nlohmann::detail::parse_event_t;
    switch (event) {
    case Event::object_start:
    case Event::array_start:
      if (depth >= kMaxJsonNesting)
        throw TooDeep();
      frames.push_back({event == Event::array_start, "", 0, {}});
      break;
    case Event::key:
      frames.back().key = parsed.get<std::string>();
      if (!frames.back().keys.insert(frames.back().key).second)
        throw DuplicateKey();
      break;
    case Event::object_end:
    case Event::array_end:
      frames.pop_back();
      finishedValue();
      break;
    case Event::value:
      finishedValue();
      break;
    }
    return true;
  }

  /// The path of the value being read, as the scene errors spell it.
  std::string path() const {
    std::string text;
    for (const Frame &frame : frames) {
      if (frame.isArray)
        text += "[" + std::to_string(frame.index) + "]";
      else
        text += (text.empty() ? "" : ".") + frame.key;
    }
    return text.empty() ? "the top level" : text;
  }

private:
  struct Frame {
    bool isArray;
    std::string key;
    size_t index;
    std::set<std::string> keys;
  };
  void finishedValue() {
    if (!frames.empty() && frames.back().isArray)
      ++frames.back().index;
  }
  std::vector<Frame> frames;
};

} // namespace

llvm::Expected<SceneDescription> simit::parseScene(llvm::StringRef text,
                                                   llvm::StringRef name,
                                                   llvm::StringRef directory) {
  Json root;
  auto tracker = std::make_shared<JsonPathTracker>();
  try {
    root = Json::parse(
        text.begin(), text.end(),
        [tracker](int depth, nlohmann::detail::parse_event_t event,
                  Json &parsed) { return (*tracker)(depth, event, parsed); });
  } catch (const JsonPathTracker::TooDeep &) {
    return llvm::createStringError(name + ": " + tracker->path() +
                                   ": arrays and objects nested too deeply "
                                   "(more than " +
                                   llvm::Twine(kMaxJsonNesting) + " levels)");
  } catch (const JsonPathTracker::DuplicateKey &) {
    return llvm::createStringError(name + ": " + tracker->path() +
                                   ": the key is given twice in one object");
  } catch (const Json::parse_error &e) {
    // Turn the byte offset into line:column.
    size_t offset = std::min<size_t>(e.byte ? e.byte - 1 : 0, text.size());
    llvm::StringRef before = text.take_front(offset);
    size_t line = before.count('\n') + 1;
    size_t lineStart = before.rfind('\n');
    size_t column = offset - (lineStart == llvm::StringRef::npos
                                  ? 0
                                  : lineStart + 1) +
                    1;
    llvm::StringRef what = e.what();
    size_t colon = what.find(": ");
    if (colon != llvm::StringRef::npos)
      what = what.drop_front(colon + 2);
    return llvm::createStringError(name + ":" + llvm::Twine(line) + ":" +
                                   llvm::Twine(column) +
                                   ": invalid JSON: " + what);
  } catch (const Json::exception &e) {
    // A number too large for a double ("number overflow parsing '1e999'").
    llvm::StringRef what = e.what();
    size_t bracket = what.find("] ");
    if (bracket != llvm::StringRef::npos)
      what = what.drop_front(bracket + 2);
    return llvm::createStringError(name + ": " + tracker->path() +
                                   ": invalid JSON: " + what);
  }
  SceneDescription scene;
  scene.path = name.str();
  scene.directory = directory.str();
  if (auto err = SceneParser(name, directory).parse(root, scene))
    return err;
  return scene;
}

llvm::Expected<SceneDescription> simit::loadScene(llvm::StringRef path) {
  auto buffer = llvm::MemoryBuffer::getFile(path, /*IsText=*/true);
  if (!buffer)
    return llvm::createStringError(path + ": cannot open: " +
                                   buffer.getError().message());
  return parseScene((*buffer)->getBuffer(), path,
                    llvm::sys::path::parent_path(path));
}
