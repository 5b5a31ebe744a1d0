//===- SimitTypes.cpp - Types of the simit dialect ------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/IR/DialectImplementation.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/TypeSwitch.h"

using namespace mlir;
using namespace mlir::simit;

#define GET_TYPEDEF_CLASSES
#include "simit/Dialect/Simit/IR/SimitTypes.cpp.inc"

void SimitDialect::registerTypes() {
  addTypes<
#define GET_TYPEDEF_LIST
#include "simit/Dialect/Simit/IR/SimitTypes.cpp.inc"
      >();
}

/// Parses `{name : type, ...}` (possibly empty) into names and types.
static ParseResult parseNamedTypeList(AsmParser &parser,
                                      SmallVectorImpl<StringAttr> &names,
                                      SmallVectorImpl<Type> &types) {
  return parser.parseCommaSeparatedList(
      AsmParser::Delimiter::Braces, [&]() -> ParseResult {
        std::string name;
        Type type;
        if (parser.parseKeywordOrString(&name) || parser.parseColon() ||
            parser.parseType(type))
          return failure();
        names.push_back(StringAttr::get(parser.getContext(), name));
        types.push_back(type);
        return success();
      });
}

static void printNamedTypeList(AsmPrinter &printer, ArrayRef<StringAttr> names,
                               ArrayRef<Type> types) {
  printer << "{";
  llvm::interleaveComma(llvm::zip(names, types), printer, [&](auto field) {
    printer.printKeywordOrString(std::get<0>(field).getValue());
    printer << " : " << std::get<1>(field);
  });
  printer << "}";
}

/// Parses a comma separated list of strings in square brackets.
static ParseResult parseStringList(AsmParser &parser,
                                   SmallVectorImpl<StringAttr> &strings) {
  return parser.parseCommaSeparatedList(
      AsmParser::Delimiter::Square, [&]() -> ParseResult {
        std::string value;
        if (parser.parseString(&value))
          return failure();
        strings.push_back(StringAttr::get(parser.getContext(), value));
        return success();
      });
}

/// Fails with a diagnostic naming `what` unless the names are unique.
static LogicalResult
verifyUniqueNames(function_ref<InFlightDiagnostic()> emitError,
                  ArrayRef<StringAttr> names, StringRef what) {
  llvm::DenseSet<StringAttr> seen;
  for (StringAttr name : names) {
    if (name.getValue().empty())
      return emitError() << what << " names must not be empty";
    if (!seen.insert(name).second)
      return emitError() << "duplicate " << what << " name '"
                         << name.getValue() << "'";
  }
  return success();
}

//===----------------------------------------------------------------------===//
// ElementType
//===----------------------------------------------------------------------===//

Type ElementType::parse(AsmParser &parser) {
  std::string name;
  SmallVector<StringAttr> fieldNames;
  SmallVector<Type> fieldTypes;
  if (parser.parseLess() || parser.parseString(&name) || parser.parseComma() ||
      parseNamedTypeList(parser, fieldNames, fieldTypes) ||
      parser.parseGreater())
    return {};
  return getChecked([&] { return parser.emitError(parser.getNameLoc()); },
                    parser.getContext(),
                    StringAttr::get(parser.getContext(), name), fieldNames,
                    fieldTypes);
}

void ElementType::print(AsmPrinter &printer) const {
  printer << "<\"" << getName().getValue() << "\", ";
  printNamedTypeList(printer, getFieldNames(), getFieldTypes());
  printer << ">";
}

/// Whether `type` may be the type of an element field: a scalar, a static
/// builtin tensor of scalars, or a !simit.tensor without set dimensions.
static bool isFieldType(Type type) {
  if (isScalarType(type))
    return true;
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return tensor.hasStaticShape() && isScalarType(tensor.getElementType());
  if (auto tensor = dyn_cast<SystemTensorType>(type))
    return !tensor.isSystem();
  return false;
}

LogicalResult ElementType::verify(function_ref<InFlightDiagnostic()> emitError,
                                  StringAttr name,
                                  ArrayRef<StringAttr> fieldNames,
                                  ArrayRef<Type> fieldTypes) {
  if (name.getValue().empty())
    return emitError() << "element type name must not be empty";
  if (fieldNames.size() != fieldTypes.size())
    return emitError() << "element type '" << name.getValue() << "' has "
                       << fieldNames.size() << " field names but "
                       << fieldTypes.size() << " field types";
  if (failed(verifyUniqueNames(emitError, fieldNames, "field")))
    return failure();
  for (auto [fieldName, fieldType] : llvm::zip(fieldNames, fieldTypes))
    if (!isFieldType(fieldType))
      return emitError() << "field '" << fieldName.getValue()
                         << "' must have a scalar or local tensor type, got "
                         << fieldType;
  return success();
}

std::optional<unsigned> ElementType::getFieldIndex(StringRef name) const {
  for (auto [index, fieldName] : llvm::enumerate(getFieldNames()))
    if (fieldName.getValue() == name)
      return index;
  return std::nullopt;
}

Type ElementType::getFieldType(StringRef name) const {
  std::optional<unsigned> index = getFieldIndex(name);
  return index ? getFieldTypes()[*index] : Type();
}

//===----------------------------------------------------------------------===//
// SetType
//===----------------------------------------------------------------------===//

Type SetType::parse(AsmParser &parser) {
  MLIRContext *ctx = parser.getContext();
  std::string name;
  Type elementType;
  SmallVector<StringAttr> endpoints;
  unsigned gridRank = 0;
  if (parser.parseLess() || parser.parseString(&name) || parser.parseComma() ||
      parser.parseType(elementType))
    return {};
  if (succeeded(parser.parseOptionalComma())) {
    if (succeeded(parser.parseOptionalKeyword("grid"))) {
      SMLoc rankLoc = parser.getCurrentLocation();
      std::string pointSet;
      if (parser.parseInteger(gridRank) || parser.parseKeyword("over") ||
          parser.parseString(&pointSet))
        return {};
      if (gridRank == 0) {
        parser.emitError(rankLoc, "grid rank must be positive");
        return {};
      }
      endpoints.push_back(StringAttr::get(ctx, pointSet));
    } else if (parseStringList(parser, endpoints)) {
      return {};
    }
  }
  if (parser.parseGreater())
    return {};
  return getChecked([&] { return parser.emitError(parser.getNameLoc()); }, ctx,
                    StringAttr::get(ctx, name), elementType, endpoints,
                    gridRank);
}

void SetType::print(AsmPrinter &printer) const {
  printer << "<\"" << getName().getValue() << "\", " << getElementType();
  if (isGrid()) {
    printer << ", grid " << getGridRank() << " over \""
            << getEndpoints().front().getValue() << "\"";
  } else if (!getEndpoints().empty()) {
    printer << ", [";
    llvm::interleaveComma(getEndpoints(), printer, [&](StringAttr endpoint) {
      printer << "\"" << endpoint.getValue() << "\"";
    });
    printer << "]";
  }
  printer << ">";
}

LogicalResult SetType::verify(function_ref<InFlightDiagnostic()> emitError,
                              StringAttr name, Type elementType,
                              ArrayRef<StringAttr> endpoints,
                              unsigned gridRank) {
  if (name.getValue().empty())
    return emitError() << "set name must not be empty";
  if (!isa<ElementType>(elementType))
    return emitError() << "set '" << name.getValue()
                       << "' must have an element type, got " << elementType;
  if (gridRank != 0 && endpoints.size() != 1)
    return emitError() << "grid set '" << name.getValue()
                       << "' must be over exactly one point set";
  for (StringAttr endpoint : endpoints) {
    if (endpoint.getValue().empty())
      return emitError() << "endpoint set names must not be empty";
    if (endpoint == name)
      return emitError() << "set '" << name.getValue()
                         << "' cannot be its own endpoint set";
  }
  return success();
}

bool SetType::isHomogeneous() const {
  return llvm::all_equal(getEndpoints());
}

//===----------------------------------------------------------------------===//
// SystemTensorType
//===----------------------------------------------------------------------===//

Type SystemTensorType::parse(AsmParser &parser) {
  MLIRContext *ctx = parser.getContext();
  SmallVector<Attribute> dims;
  Type blockType;
  auto parseDim = [&]() -> ParseResult {
    std::string setName;
    if (succeeded(parser.parseOptionalString(&setName))) {
      dims.push_back(StringAttr::get(ctx, setName));
      return success();
    }
    int64_t size;
    if (parser.parseInteger(size))
      return failure();
    dims.push_back(IntegerAttr::get(IntegerType::get(ctx, 64), size));
    return success();
  };
  if (parser.parseLess() ||
      parser.parseCommaSeparatedList(AsmParser::Delimiter::Square, parseDim) ||
      parser.parseKeyword("x") || parser.parseType(blockType))
    return {};
  StorageAttr encoding;
  if (succeeded(parser.parseOptionalComma())) {
    SMLoc encodingLoc = parser.getCurrentLocation();
    Attribute attr;
    if (parser.parseAttribute(attr))
      return {};
    encoding = dyn_cast<StorageAttr>(attr);
    if (!encoding) {
      parser.emitError(encodingLoc, "expected a #simit.storage encoding, got ")
          << attr;
      return {};
    }
  }
  if (parser.parseGreater())
    return {};
  return getChecked([&] { return parser.emitError(parser.getNameLoc()); }, ctx,
                    ArrayAttr::get(ctx, dims), blockType, encoding);
}

void SystemTensorType::print(AsmPrinter &printer) const {
  printer << "<[";
  llvm::interleaveComma(getDims(), printer, [&](Attribute dim) {
    if (auto set = dyn_cast<StringAttr>(dim))
      printer << "\"" << set.getValue() << "\"";
    else
      printer << cast<IntegerAttr>(dim).getInt();
  });
  printer << "] x " << getBlockType();
  if (getEncoding())
    printer << ", " << getEncoding();
  printer << ">";
}

/// Checks that `encoding` fits a matrix over (`rows`, `cols`) as far as the
/// set names tell: the sets of a diagonal, a stencil and an incidence.
static LogicalResult
verifyEncodingSets(function_ref<InFlightDiagnostic()> emitError,
                   StorageAttr encoding, StringAttr rows, StringAttr cols) {
  auto mismatch = [&]() {
    return emitError() << "storage '" << encoding.str()
                       << "' does not fit a matrix over (\"" << rows.getValue()
                       << "\", \"" << cols.getValue() << "\")";
  };
  switch (encoding.getKind()) {
  case StorageKind::Diag:
    if (rows != encoding.getSet() || cols != encoding.getSet())
      return mismatch();
    return success();
  case StorageKind::Stencil:
    if (rows != cols)
      return mismatch();
    return success();
  case StorageKind::Incidence:
    if (rows != encoding.getSet() || cols == encoding.getSet())
      return mismatch();
    return success();
  case StorageKind::Transpose:
    return verifyEncodingSets(emitError, encoding.getOperand(), cols, rows);
  case StorageKind::LowRank:
    return verifyEncodingSets(emitError, encoding.getOperand(), rows, cols);
  case StorageKind::Union:
    for (unsigned i = 0, e = encoding.getMembers().size(); i < e; ++i)
      if (failed(verifyEncodingSets(emitError, encoding.getMember(i), rows,
                                    cols)))
        return failure();
    return success();
  default:
    return success();
  }
}

LogicalResult
SystemTensorType::verify(function_ref<InFlightDiagnostic()> emitError,
                         ArrayAttr dims, Type blockType, StorageAttr encoding) {
  if (dims.empty())
    return emitError() << "!simit.tensor needs at least one dimension";
  bool hasSet = false;
  for (Attribute dim : dims) {
    if (auto set = dyn_cast<StringAttr>(dim)) {
      if (set.getValue().empty())
        return emitError() << "set dimension names must not be empty";
      hasSet = true;
      continue;
    }
    auto size = dyn_cast<IntegerAttr>(dim);
    if (!size || !size.getType().isInteger(64))
      return emitError() << "dimension " << dim
                         << " must be a set name or an i64 range size";
    if (size.getInt() <= 0)
      return emitError() << "range dimension must be positive, got "
                         << size.getInt();
  }
  if (encoding) {
    auto rows = dims.size() == 2 ? dyn_cast<StringAttr>(dims[0]) : nullptr;
    auto cols = dims.size() == 2 ? dyn_cast<StringAttr>(dims[1]) : nullptr;
    if (!rows || !cols)
      return emitError() << "a storage encoding needs a matrix over two sets";
    if (failed(verifyEncodingSets(emitError, encoding, rows, cols)))
      return failure();
  }
  if (isScalarType(blockType)) {
    if (!hasSet)
      return emitError() << "a tensor of ranges with a scalar block is a "
                            "builtin tensor; use tensor<...> instead";
    return success();
  }
  if (auto block = dyn_cast<RankedTensorType>(blockType)) {
    if (!block.hasStaticShape() || !isScalarType(block.getElementType()))
      return emitError() << "block " << blockType
                         << " must be a static tensor of scalars";
  } else if (auto block = dyn_cast<SystemTensorType>(blockType)) {
    if (block.isSystem())
      return emitError() << "block " << blockType
                         << " must not have set dimensions";
  } else {
    return emitError() << "block type must be a scalar or a tensor, got "
                       << blockType;
  }
  if (getTensorOrder(blockType) != dims.size())
    return emitError() << "block " << blockType << " must have the order of "
                       << "its container (" << dims.size() << ")";
  return success();
}

bool SystemTensorType::isSystem() const {
  if (llvm::any_of(getDims(), [](Attribute d) { return isa<StringAttr>(d); }))
    return true;
  auto block = dyn_cast<SystemTensorType>(getBlockType());
  return block && block.isSystem();
}

bool SystemTensorType::isSetMatrix() const {
  return getOrder() == 2 && isa<StringAttr>(getDims()[0]) &&
         isa<StringAttr>(getDims()[1]);
}

Type SystemTensorType::getComponentType() const {
  return ::mlir::simit::getComponentType(getBlockType());
}

SmallVector<int64_t> SystemTensorType::getBlockShape() const {
  Type block = getBlockType();
  if (auto tensor = dyn_cast<RankedTensorType>(block))
    return llvm::to_vector(tensor.getShape());
  SmallVector<int64_t> shape;
  if (auto tensor = dyn_cast<SystemTensorType>(block))
    for (Attribute dim : tensor.getDims())
      shape.push_back(cast<IntegerAttr>(dim).getInt());
  return shape;
}

//===----------------------------------------------------------------------===//
// TupleType
//===----------------------------------------------------------------------===//

Type simit::TupleType::parse(AsmParser &parser) {
  SmallVector<StringAttr> names;
  SmallVector<Type> types;
  if (parser.parseLess())
    return {};
  if (succeeded(parser.parseOptionalLBrace())) {
    if (failed(parser.parseOptionalRBrace())) {
      do {
        std::string name;
        Type type;
        if (parser.parseKeywordOrString(&name) || parser.parseColon() ||
            parser.parseType(type))
          return {};
        names.push_back(StringAttr::get(parser.getContext(), name));
        types.push_back(type);
      } while (succeeded(parser.parseOptionalComma()));
      if (parser.parseRBrace())
        return {};
    }
  } else {
    Type type;
    SMLoc countLoc;
    int64_t count;
    if (parser.parseType(type) || parser.parseKeyword("x"))
      return {};
    countLoc = parser.getCurrentLocation();
    if (parser.parseInteger(count))
      return {};
    if (count <= 0) {
      parser.emitError(countLoc, "tuple length must be positive");
      return {};
    }
    types.assign(count, type);
  }
  if (parser.parseGreater())
    return {};
  return getChecked([&] { return parser.emitError(parser.getNameLoc()); },
                    parser.getContext(), types, names);
}

void simit::TupleType::print(AsmPrinter &printer) const {
  printer << "<";
  if (isNamed())
    printNamedTypeList(printer, getNames(), getElementTypes());
  else
    printer << getElementTypes().front() << " x " << size();
  printer << ">";
}

LogicalResult simit::TupleType::verify(function_ref<InFlightDiagnostic()> emitError,
                                ArrayRef<Type> elementTypes,
                                ArrayRef<StringAttr> names) {
  if (elementTypes.empty())
    return emitError() << "tuple must have at least one component";
  for (Type type : elementTypes)
    if (!isa<ElementType>(type))
      return emitError() << "tuple components must be elements, got " << type;
  if (names.empty()) {
    if (!llvm::all_equal(elementTypes))
      return emitError() << "an unnamed tuple must be homogeneous; name the "
                            "components of a heterogeneous tuple";
    return success();
  }
  if (names.size() != elementTypes.size())
    return emitError() << "tuple has " << names.size() << " names for "
                       << elementTypes.size() << " components";
  return verifyUniqueNames(emitError, names, "tuple component");
}

//===----------------------------------------------------------------------===//
// RefType
//===----------------------------------------------------------------------===//

LogicalResult RefType::verify(function_ref<InFlightDiagnostic()> emitError,
                              Type valueType) {
  if (isTensorOrScalarType(valueType) ||
      isa<simit::OpaqueType, StringType>(valueType))
    return success();
  return emitError() << "!simit.ref must hold a scalar, a tensor, an opaque "
                        "handle or a string, got "
                     << valueType;
}
