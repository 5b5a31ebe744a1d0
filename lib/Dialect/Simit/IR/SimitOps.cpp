//===- SimitOps.cpp - Globals, variables, tensor access, sets -------------===//
//
// Verifiers of the operations on globals, slots, tensor blocks, sets and
// elements, and the generated operation definitions. Map and assembly,
// index expressions, linear algebra and folds live in their own files.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

#include "SetChecks.h"
#include "mlir/IR/Builders.h"
#include "mlir/IR/OpImplementation.h"

using namespace mlir;
using namespace mlir::simit;

//===----------------------------------------------------------------------===//
// Custom directives
//===----------------------------------------------------------------------===//

/// Parses slice indices: a comma separated list of operands and `:`
/// wildcards; `kept` is true at the wildcards.
static ParseResult
parseSliceIndices(OpAsmParser &parser,
                  SmallVectorImpl<OpAsmParser::UnresolvedOperand> &indices,
                  DenseBoolArrayAttr &kept) {
  SmallVector<bool> keptDims;
  do {
    if (succeeded(parser.parseOptionalColon())) {
      keptDims.push_back(true);
      continue;
    }
    OpAsmParser::UnresolvedOperand index;
    if (parser.parseOperand(index))
      return failure();
    indices.push_back(index);
    keptDims.push_back(false);
  } while (succeeded(parser.parseOptionalComma()));
  kept = DenseBoolArrayAttr::get(parser.getContext(), keptDims);
  return success();
}

static void printSliceIndices(OpAsmPrinter &printer, SliceOp,
                              OperandRange indices, DenseBoolArrayAttr kept) {
  auto index = indices.begin();
  llvm::interleaveComma(kept.asArrayRef(), printer, [&](bool isKept) {
    if (isKept)
      printer << ":";
    else
      printer << *index++;
  });
}

/// Parses the types of simit.woodbury's vectors: one type, or `row ->
/// column` when A's rows and columns are different sets. b and the k u's
/// are over A's rows; c, the k v's and w's and the result over its
/// columns (k from the parsed u operands).
static ParseResult
parseVectorTypes(OpAsmParser &parser, Type &rhs, Type &solution,
                 SmallVectorImpl<Type> &us, SmallVectorImpl<Type> &vs,
                 SmallVectorImpl<Type> &ws, Type &result,
                 ArrayRef<OpAsmParser::UnresolvedOperand> uOperands) {
  Type row, column;
  if (parser.parseType(row))
    return failure();
  column = row;
  if (succeeded(parser.parseOptionalArrow()) && parser.parseType(column))
    return failure();
  rhs = row;
  solution = result = column;
  us.assign(uOperands.size(), row);
  vs.assign(uOperands.size(), column);
  ws.assign(uOperands.size(), column);
  return success();
}

static void printVectorTypes(OpAsmPrinter &printer, WoodburyOp, Type rhs, Type,
                             TypeRange, TypeRange, TypeRange, Type result,
                             OperandRange) {
  printer << rhs;
  if (result != rhs)
    printer << " -> " << result;
}

#define GET_OP_CLASSES
#include "simit/Dialect/Simit/IR/SimitOps.cpp.inc"

//===----------------------------------------------------------------------===//
// Globals
//===----------------------------------------------------------------------===//

LogicalResult ExternOp::verify() {
  Type type = getType();
  if (isa<SetType>(type) || isTensorOrScalarType(type))
    return success();
  return emitOpError() << "declares a set, a tensor or a scalar, got " << type;
}

/// The simit.extern named by `symbol`, with a diagnostic when there is none.
static FailureOr<ExternOp> lookupExtern(Operation *user,
                                        SymbolTableCollection &symbolTable,
                                        FlatSymbolRefAttr symbol) {
  auto global = symbolTable.lookupNearestSymbolFrom<ExternOp>(user, symbol);
  if (!global)
    return user->emitOpError() << "'" << symbol
                               << "' does not name a simit.extern";
  return global;
}

LogicalResult GetSetOp::verifySymbolUses(SymbolTableCollection &symbolTable) {
  FailureOr<ExternOp> global = lookupExtern(*this, symbolTable, getGlobalAttr());
  if (failed(global))
    return failure();
  if (global->getType() != getType())
    return emitOpError() << "result type " << getType()
                         << " differs from the declared type "
                         << global->getType() << " of " << getGlobalAttr();
  return success();
}

LogicalResult
ExternRefOp::verifySymbolUses(SymbolTableCollection &symbolTable) {
  FailureOr<ExternOp> global = lookupExtern(*this, symbolTable, getGlobalAttr());
  if (failed(global))
    return failure();
  if (isa<SetType>(global->getType()))
    return emitOpError() << getGlobalAttr()
                         << " is a set; use simit.get_set to read it";
  Type valueType = getType().getValueType();
  if (global->getType() != valueType)
    return emitOpError() << "slot type " << valueType
                         << " differs from the declared type "
                         << global->getType() << " of " << getGlobalAttr();
  return success();
}

//===----------------------------------------------------------------------===//
// Tensor construction and access
//===----------------------------------------------------------------------===//

LogicalResult BroadcastOp::verify() {
  Type component = getComponentType(getType());
  if (getValue().getType() != component)
    return emitOpError() << "scalar type " << getValue().getType()
                         << " differs from the component type " << component
                         << " of the result";
  return success();
}

/// Checks the indices of the outer dimensions of `tensorType` not marked in
/// `kept`: an `index` for a range, an element of the set for a set dimension.
static LogicalResult verifyTensorIndices(Operation *op, Type tensorType,
                                         TypeRange indexTypes,
                                         ArrayRef<bool> kept = {}) {
  unsigned order = getTensorOrder(tensorType);
  unsigned expected = order - llvm::count(kept, true);
  if (indexTypes.size() != expected)
    return op->emitOpError() << "expected " << expected << " indices for "
                             << tensorType << ", got " << indexTypes.size();
  auto indexType = indexTypes.begin();
  for (unsigned dim = 0; dim < order; ++dim) {
    if (!kept.empty() && kept[dim])
      continue;
    Type type = *indexType++;
    Attribute dimAttr =
        isa<SystemTensorType>(tensorType)
            ? cast<SystemTensorType>(tensorType).getDims()[dim]
            : Attribute();
    auto setName = dyn_cast_or_null<StringAttr>(dimAttr);
    if (!setName) {
      if (!type.isIndex())
        return op->emitOpError() << "index of range dimension " << dim
                                 << " must be 'index', got " << type;
      continue;
    }
    if (!isa<ElementType>(type))
      return op->emitOpError() << "index of set dimension " << dim << " ('"
                               << setName.getValue()
                               << "') must be an element, got " << type;
    if (failed(verifyElementOfSet(op, type, setName,
                                  "index of dimension " + Twine(dim))))
      return failure();
  }
  return success();
}

LogicalResult ExtractOp::verify() {
  Type tensorType = getTensor().getType();
  if (failed(verifyTensorIndices(*this, tensorType, getIndices().getTypes())))
    return failure();
  Type block = getBlockType(tensorType);
  if (getType() != block)
    return emitOpError() << "result type " << getType()
                         << " differs from the block type " << block;
  return success();
}

LogicalResult InsertOp::verify() {
  Type tensorType = getTensor().getType();
  if (failed(verifyTensorIndices(*this, tensorType, getIndices().getTypes())))
    return failure();
  Type block = getBlockType(tensorType);
  if (getValue().getType() != block)
    return emitOpError() << "inserted value type " << getValue().getType()
                         << " differs from the block type " << block;
  return success();
}

LogicalResult SliceOp::verify() {
  Type tensorType = getTensor().getType();
  ArrayRef<bool> kept = getKept();
  if (kept.size() != getTensorOrder(tensorType))
    return emitOpError() << "expected " << getTensorOrder(tensorType)
                         << " indices or ':' for " << tensorType << ", got "
                         << kept.size();
  if (llvm::none_of(kept, [](bool k) { return k; }))
    return emitOpError() << "keeps no dimension; use simit.extract";
  if (llvm::all_of(kept, [](bool k) { return k; }))
    return emitOpError() << "indexes no dimension; use the tensor itself";
  Type component = getComponentType(tensorType);
  if (getBlockType(tensorType) != component)
    return emitOpError() << "cannot slice the blocked tensor " << tensorType;
  if (failed(verifyTensorIndices(*this, tensorType, getIndices().getTypes(),
                                 kept)))
    return failure();

  // The kept dimensions, in order, form the result.
  SmallVector<Attribute> keptDims;
  SmallVector<int64_t> keptShape;
  bool keptSet = false;
  for (auto [dim, isKept] : llvm::enumerate(kept)) {
    if (!isKept)
      continue;
    Attribute level = getDimensionHierarchy(tensorType, dim).front();
    keptDims.push_back(level);
    if (auto size = dyn_cast<IntegerAttr>(level))
      keptShape.push_back(size.getInt());
    else
      keptSet = true;
  }
  Type expected =
      keptSet ? Type(SystemTensorType::get(
                    getContext(), ArrayAttr::get(getContext(), keptDims),
                    component))
              : Type(RankedTensorType::get(keptShape, component));
  if (getType() != expected)
    return emitOpError() << "result type " << getType() << " should be "
                         << expected;
  return success();
}

//===----------------------------------------------------------------------===//
// Sets and elements
//===----------------------------------------------------------------------===//

/// The type of `field` of `element`, with a diagnostic when there is none.
static FailureOr<Type> lookupField(Operation *op, ElementType element,
                                   StringRef field) {
  Type type = element.getFieldType(field);
  if (!type)
    return op->emitOpError() << "element '" << element.getName().getValue()
                             << "' has no field '" << field << "'";
  return type;
}

/// The global vector type of a set field, `!simit.tensor<[set] x F>`, with a
/// diagnostic unless F is a scalar or a vector.
static FailureOr<SystemTensorType>
getFieldVectorType(Operation *op, SetType set, StringRef field) {
  FailureOr<Type> fieldType = lookupField(op, set.getElement(), field);
  if (failed(fieldType))
    return failure();
  if (getTensorOrder(*fieldType) > 1)
    return op->emitOpError() << "field '" << field << "' of type "
                             << *fieldType
                             << " is not a scalar or a vector; only those "
                                "can be accessed as set fields";
  MLIRContext *ctx = op->getContext();
  return SystemTensorType::get(ctx, ArrayAttr::get(ctx, {set.getName()}),
                               *fieldType);
}

LogicalResult FieldReadOp::verify() {
  FailureOr<SystemTensorType> expected =
      getFieldVectorType(*this, getSet().getType(), getField());
  if (failed(expected))
    return failure();
  if (getType() != *expected)
    return emitOpError() << "result type " << getType() << " should be "
                         << *expected;
  return success();
}

LogicalResult FieldWriteOp::verify() {
  FailureOr<SystemTensorType> expected =
      getFieldVectorType(*this, getSet().getType(), getField());
  if (failed(expected))
    return failure();
  Type valueType = getValue().getType();
  if (valueType != *expected && valueType != expected->getComponentType())
    return emitOpError() << "value type " << valueType << " should be "
                         << *expected << " or the scalar "
                         << expected->getComponentType();
  return success();
}

LogicalResult ElemReadOp::verify() {
  FailureOr<Type> fieldType =
      lookupField(*this, getElement().getType(), getField());
  if (failed(fieldType))
    return failure();
  if (getType() != *fieldType)
    return emitOpError() << "result type " << getType()
                         << " differs from the type " << *fieldType
                         << " of field '" << getField() << "'";
  return success();
}

LogicalResult ElemWriteOp::verify() {
  FailureOr<Type> fieldType =
      lookupField(*this, getElement().getType(), getField());
  if (failed(fieldType))
    return failure();
  Type valueType = getValue().getType();
  if (valueType != *fieldType && valueType != getComponentType(*fieldType))
    return emitOpError() << "value type " << valueType << " should be "
                         << *fieldType << " or the scalar "
                         << getComponentType(*fieldType);
  return success();
}

LogicalResult TupleGetOp::verify() {
  simit::TupleType tuple = getTuple().getType();
  uint64_t index = getIndex();
  if (index >= tuple.size())
    return emitOpError() << "index " << index << " is out of range for a "
                         << "tuple of " << tuple.size() << " components";
  if (getType() != tuple.getElementTypes()[index])
    return emitOpError() << "result type " << getType()
                         << " differs from the component type "
                         << tuple.getElementTypes()[index];
  return success();
}

LogicalResult EndpointsOp::verify() {
  return verifyEndpointTuple(*this, getSet().getType(), getType());
}

/// Checks a grid operand and the offsets into it.
static LogicalResult verifyGridAccess(Operation *op, SetType grid, Type point,
                                      ArrayRef<int64_t> offsets) {
  if (!grid.isGrid())
    return op->emitOpError() << "set '" << grid.getName().getValue()
                             << "' is not a grid";
  if (offsets.size() != grid.getGridRank())
    return op->emitOpError() << "expected " << grid.getGridRank()
                             << " offsets for a grid of rank "
                             << grid.getGridRank() << ", got "
                             << offsets.size();
  return verifyElementOfSet(op, point, grid.getEndpoint(0), "point");
}

LogicalResult GridPointOp::verify() {
  return verifyGridAccess(*this, getGrid().getType(), getPoint().getType(),
                          getOffsets());
}

LogicalResult GridEdgeOp::verify() {
  SetType grid = getGrid().getType();
  if (failed(verifyGridAccess(*this, grid, getPoint().getType(), getOffsets())))
    return failure();
  ArrayRef<int64_t> dir = getDir();
  if (dir.size() != grid.getGridRank())
    return emitOpError() << "expected a direction of " << grid.getGridRank()
                         << " components, got " << dir.size();
  unsigned unitSteps = llvm::count_if(dir, [](int64_t d) { return d != 0; });
  bool unit = llvm::all_of(dir, [](int64_t d) { return d >= -1 && d <= 1; });
  if (unitSteps != 1 || !unit)
    return emitOpError() << "direction must have exactly one component equal "
                            "to 1 or -1 and zeros elsewhere";
  return success();
}

//===----------------------------------------------------------------------===//
// Printing
//===----------------------------------------------------------------------===//

LogicalResult PrintOp::verify() {
  if (getValues().empty())
    return emitOpError() << "needs at least one value";
  for (Type type : getValues().getTypes())
    if (!isTensorOrScalarType(type) && !isa<StringType>(type))
      return emitOpError() << "cannot print a value of type " << type;
  return success();
}
