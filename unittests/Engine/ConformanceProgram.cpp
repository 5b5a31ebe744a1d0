//===--- ConformanceProgram.cpp - Simit text of conformance cases ---------===//

#include "ConformanceProgram.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FormatVariadic.h"

using namespace simit;
using namespace simit::conformance;

namespace {
constexpr const char *kOperandNames[] = {"A", "B", "C"};

std::string blockType(int blockSize) {
  return blockSize == 1 ? "float" : "matrix[3,3](float)";
}

/// The element types, all with the fields of ConformanceScene.h, and the
/// extern sets.
std::string declarations(int blockSize) {
  std::string vector = blockSize == 1 ? "float" : "vector[3](float)";
  std::string text;
  for (SetId id : kAllSets) {
    text += llvm::formatv("element {0}\n", elementName(id)).str();
    for (const char *name : {"x", "w", "y", "z", "u"})
      text += llvm::formatv("  {0} : {1};\n", name, vector).str();
    for (const char *name : {"k", "l", "s"})
      text +=
          llvm::formatv("  {0} : vector[{1}](float);\n", name, kCoefficients)
              .str();
    for (const char *name : {"B", "C", "I"})
      text += llvm::formatv("  {0} : matrix[3,3](float);\n", name).str();
    text += "end\n\n";
  }
  for (SetId id : kAllSets) {
    text +=
        llvm::formatv("extern {0} : set{{{1}}", setName(id), elementName(id))
            .str();
    if (!endpointSets(id).empty())
      text += "(" +
              llvm::join(llvm::map_range(endpointSets(id), setName), ", ") +
              ")";
    text += ";\n";
  }
  return text + "\n";
}

bool isHomogeneous(SetId id) { return llvm::all_equal(endpointSets(id)); }

std::string assemblyName(const Source &source, const Fields &fields) {
  return std::string("asm_") + source.name + "_" + fields.coefficients;
}

/// `func asm_<source>_<coefficients>(e : E, p : endpoints) -> (A : ...)`
/// writing each of the source's blocks.
std::string assemblyFunction(const Source &source, const Fields &fields,
                             int blockSize) {
  llvm::ArrayRef<SetId> endpoints = endpointSets(source.mapped);
  std::string parameters =
      llvm::formatv("e : {0}", elementName(source.mapped)).str();
  if (!endpoints.empty() && isHomogeneous(source.mapped)) {
    parameters += llvm::formatv(", p : ({0}*{1})", elementName(endpoints[0]),
                                endpoints.size())
                      .str();
  } else if (!endpoints.empty()) {
    std::vector<std::string> named;
    for (auto [i, endpoint] : llvm::enumerate(endpoints))
      named.push_back(
          llvm::formatv("p{0} : {1}", i, elementName(endpoint)).str());
    parameters += ", p : (" + llvm::join(named, ", ") + ")";
  }
  auto position = [&](int endpoint) -> std::string {
    if (endpoint == kElement)
      return "e";
    if (isHomogeneous(source.mapped))
      return llvm::formatv("p({0})", endpoint).str();
    return llvm::formatv("p.p{0}", endpoint).str();
  };

  std::string text = llvm::formatv(
      "func {0}({1})\n    -> (A : matrix[{2},{3}]({4}))\n",
      assemblyName(source, fields), parameters, setName(source.rows),
      setName(source.cols), blockType(blockSize));
  for (const BlockWrite &write : source.writes) {
    std::string value =
        llvm::formatv("e.{0}({1})", fields.coefficients, write.coefficient);
    if (blockSize == 3)
      value += llvm::formatv(" * e.{0}", fields.block).str();
    text += llvm::formatv("  A({0}, {1}) = {2};\n", position(write.row),
                          position(write.col), value)
                .str();
  }
  return text + "end\n\n";
}

/// The (source, fields) of each operand of `c`, the shift last.
std::vector<std::pair<const Source *, const Fields *>>
operandsOf(const Case &c) {
  std::vector<std::pair<const Source *, const Fields *>> operands;
  for (auto [i, source] : llvm::enumerate(c.sources))
    operands.push_back({source, &kOperandFields[i % 2]});
  if (c.operation->shifted)
    operands.push_back({&shiftSource(), &kShiftFields});
  return operands;
}

/// `text` with $R0 and $C0 replaced by the first operand's sets.
std::string substitute(std::string text, const Case &c) {
  for (auto [placeholder, set] : {std::make_pair("$R0", c.sources[0]->rows),
                                  std::make_pair("$C0", c.sources[0]->cols)}) {
    for (size_t at = text.find(placeholder); at != std::string::npos;
         at = text.find(placeholder))
      text.replace(at, 3, setName(set).str());
  }
  return text;
}

std::string exportedFunction(const Case &c) {
  const Operation &operation = *c.operation;
  bool scalar = operation.observed == Observed::Scalar;
  std::string text = llvm::formatv("export func {0}(){1}\n", c.name(),
                                   scalar ? " -> (r : float)" : "");
  for (auto [i, operand] : llvm::enumerate(operandsOf(c))) {
    auto [source, fields] = operand;
    bool shift = source == &shiftSource();
    text += llvm::formatv(
        "  {0} = map {1} to {2} reduce +;\n", shift ? "S" : kOperandNames[i],
        assemblyName(*source, *fields), setName(source->mapped));
  }
  text += substitute(operation.statements, c);
  std::string expression = substitute(operation.expression, c);
  switch (operation.observed) {
  case Observed::Matrix: {
    auto [rows, cols] = c.shape();
    text += llvm::formatv("  M = {0};\n"
                          "  {1}.y = M * {2}.x;\n"
                          "  {1}.z = M * {2}.w;\n"
                          "  {1}.u = ({0}) * {2}.x;\n",
                          expression, setName(rows), setName(cols))
                .str();
    break;
  }
  case Observed::Vector:
    break;
  case Observed::Scalar:
    text += "  r = " + expression + ";\n";
    break;
  }
  return text + "end\n\n";
}
} // namespace

std::string simit::conformance::generateProgram(const Case &c) {
  std::string text = declarations(c.blockSize);
  std::vector<std::pair<const Source *, const Fields *>> assembled;
  for (auto operand : operandsOf(c)) {
    if (llvm::is_contained(assembled, operand))
      continue;
    assembled.push_back(operand);
    text += assemblyFunction(*operand.first, *operand.second, c.blockSize);
  }
  return text + exportedFunction(c);
}
