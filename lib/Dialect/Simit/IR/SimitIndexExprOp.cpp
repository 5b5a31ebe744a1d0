//===- SimitIndexExprOp.cpp - Tensor index notation -----------------------===//
//
// Syntax:
//   simit.index_expr [i : "points" x 3, k : 3] (i) = (%A(i, k), %x(k))
//       : (T1, T2) -> T attributes {...} { ^bb0(%a: f64, %b: f64): ... }
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/IR/Builders.h"
#include "mlir/IR/OpImplementation.h"
#include "llvm/ADT/StringMap.h"

using namespace mlir;
using namespace mlir::simit;

void IndexExprOp::build(OpBuilder &builder, OperationState &state,
                        Type resultType, ValueRange inputs,
                        ArrayAttr indexVars, ArrayAttr domains,
                        ArrayRef<int64_t> resultIndices,
                        ArrayRef<SmallVector<int64_t>> inputIndices) {
  state.addOperands(inputs);
  state.addTypes(resultType);
  Properties &props = state.getOrAddProperties<Properties>();
  props.setIndexVars(indexVars);
  props.setDomains(domains);
  props.setResultIndices(builder.getDenseI64ArrayAttr(resultIndices));
  SmallVector<Attribute> lists;
  for (ArrayRef<int64_t> list : inputIndices)
    lists.push_back(builder.getDenseI64ArrayAttr(list));
  props.setInputIndices(builder.getArrayAttr(lists));
  // The body takes one component of each input; the caller fills it in.
  Region *body = state.addRegion();
  Block *block = new Block();
  body->push_back(block);
  for (Value input : inputs)
    block->addArgument(getComponentType(input.getType()), state.location);
}

//===----------------------------------------------------------------------===//
// Parsing and printing
//===----------------------------------------------------------------------===//

/// Parses `(name, name, ...)` into positions of declared index variables.
static ParseResult parseIndexList(OpAsmParser &parser,
                                  const llvm::StringMap<int64_t> &positions,
                                  SmallVectorImpl<int64_t> &indices) {
  return parser.parseCommaSeparatedList(
      OpAsmParser::Delimiter::Paren, [&]() -> ParseResult {
        SMLoc loc = parser.getCurrentLocation();
        std::string name;
        if (parser.parseKeywordOrString(&name))
          return failure();
        auto it = positions.find(name);
        if (it == positions.end())
          return parser.emitError(loc, "undeclared index variable '")
                 << name << "'";
        indices.push_back(it->second);
        return success();
      });
}

ParseResult IndexExprOp::parse(OpAsmParser &parser, OperationState &result) {
  MLIRContext *ctx = parser.getContext();
  Builder &builder = parser.getBuilder();
  SmallVector<Attribute> varNames, domains;
  llvm::StringMap<int64_t> positions;

  // [name : level x level ..., ...]
  auto parseVar = [&]() -> ParseResult {
    SMLoc loc = parser.getCurrentLocation();
    std::string name;
    if (parser.parseKeywordOrString(&name) || parser.parseColon())
      return failure();
    if (!positions.try_emplace(name, varNames.size()).second)
      return parser.emitError(loc, "redefinition of index variable '")
             << name << "'";
    varNames.push_back(StringAttr::get(ctx, name));
    SmallVector<Attribute> levels;
    do {
      std::string setName;
      if (succeeded(parser.parseOptionalString(&setName))) {
        levels.push_back(StringAttr::get(ctx, setName));
        continue;
      }
      int64_t size;
      if (parser.parseInteger(size))
        return failure();
      levels.push_back(builder.getI64IntegerAttr(size));
    } while (succeeded(parser.parseOptionalKeyword("x")));
    domains.push_back(ArrayAttr::get(ctx, levels));
    return success();
  };
  if (parser.parseCommaSeparatedList(OpAsmParser::Delimiter::Square, parseVar))
    return failure();

  // (result vars) = (%input(vars), ...)
  SmallVector<int64_t> resultIndices;
  SmallVector<OpAsmParser::UnresolvedOperand> inputs;
  SmallVector<Attribute> inputIndices;
  if (parseIndexList(parser, positions, resultIndices) || parser.parseEqual() ||
      parser.parseCommaSeparatedList(
          OpAsmParser::Delimiter::Paren, [&]() -> ParseResult {
            OpAsmParser::UnresolvedOperand input;
            SmallVector<int64_t> indices;
            if (parser.parseOperand(input) ||
                parseIndexList(parser, positions, indices))
              return failure();
            inputs.push_back(input);
            inputIndices.push_back(builder.getDenseI64ArrayAttr(indices));
            return success();
          }))
    return failure();

  // : (input types) -> result type
  SmallVector<Type> inputTypes;
  Type resultType;
  SMLoc typesLoc = parser.getCurrentLocation();
  if (parser.parseColon() ||
      parser.parseCommaSeparatedList(OpAsmParser::Delimiter::Paren,
                                     [&]() -> ParseResult {
                                       Type type;
                                       if (parser.parseType(type))
                                         return failure();
                                       inputTypes.push_back(type);
                                       return success();
                                     }) ||
      parser.parseArrow() || parser.parseType(resultType) ||
      parser.resolveOperands(inputs, inputTypes, typesLoc, result.operands) ||
      parser.parseOptionalAttrDictWithKeyword(result.attributes))
    return failure();
  result.addTypes(resultType);

  Properties &props = result.getOrAddProperties<Properties>();
  props.setIndexVars(ArrayAttr::get(ctx, varNames));
  props.setDomains(ArrayAttr::get(ctx, domains));
  props.setResultIndices(builder.getDenseI64ArrayAttr(resultIndices));
  props.setInputIndices(ArrayAttr::get(ctx, inputIndices));
  return parser.parseRegion(*result.addRegion(), /*arguments=*/{});
}

void IndexExprOp::print(OpAsmPrinter &printer) {
  ArrayAttr vars = getIndexVars();
  auto printVar = [&](int64_t position) {
    printer.printKeywordOrString(cast<StringAttr>(vars[position]).getValue());
  };
  printer << " [";
  llvm::interleaveComma(llvm::seq<unsigned>(0, vars.size()), printer,
                        [&](unsigned v) {
                          printVar(v);
                          printer << " : ";
                          llvm::interleave(
                              getDomain(v), printer,
                              [&](Attribute level) {
                                if (auto set = dyn_cast<StringAttr>(level))
                                  printer << "\"" << set.getValue() << "\"";
                                else
                                  printer << cast<IntegerAttr>(level).getInt();
                              },
                              " x ");
                        });
  printer << "] (";
  llvm::interleaveComma(getResultIndices(), printer, printVar);
  printer << ") = (";
  llvm::interleaveComma(llvm::seq<unsigned>(0, getInputs().size()), printer,
                        [&](unsigned i) {
                          printer << getInputs()[i] << "(";
                          llvm::interleaveComma(getInputIndexList(i), printer,
                                                printVar);
                          printer << ")";
                        });
  printer << ") : (" << getInputs().getTypes() << ") -> " << getType();
  printer.printOptionalAttrDictWithKeyword(
      (*this)->getAttrs(),
      {getIndexVarsAttrName(), getDomainsAttrName(), getResultIndicesAttrName(),
       getInputIndicesAttrName()});
  printer << " ";
  printer.printRegion(getBody(), /*printEntryBlockArgs=*/true,
                      /*printBlockTerminators=*/true);
}

//===----------------------------------------------------------------------===//
// Verification
//===----------------------------------------------------------------------===//

LogicalResult IndexExprOp::verify() {
  ArrayAttr vars = getIndexVars();
  unsigned numVars = vars.size();
  if (getDomains().size() != numVars)
    return emitOpError() << "has " << numVars << " index variables but "
                         << getDomains().size() << " domains";
  llvm::StringMap<unsigned> seen;
  for (auto [v, name] : llvm::enumerate(vars.getAsValueRange<StringAttr>()))
    if (!seen.try_emplace(name, v).second)
      return emitOpError() << "declares index variable '" << name << "' twice";
  for (unsigned v = 0; v < numVars; ++v) {
    auto levels = dyn_cast<ArrayAttr>(getDomains()[v]);
    if (!levels || levels.empty())
      return emitOpError() << "domain of index variable '"
                           << cast<StringAttr>(vars[v]).getValue()
                           << "' must be a non-empty list of levels";
    for (Attribute level : levels) {
      auto size = dyn_cast<IntegerAttr>(level);
      bool validRange = size && size.getType().isInteger(64) && size.getInt() > 0;
      if (!validRange && !isa<StringAttr>(level))
        return emitOpError() << "domain level " << level
                             << " must be a set name or a positive range";
    }
  }

  SmallVector<unsigned> uses(numVars, 0);
  auto varName = [&](int64_t v) { return cast<StringAttr>(vars[v]).getValue(); };
  // Checks one access list against the dimensions of `type`.
  auto verifyAccess = [&](Type type, ArrayRef<int64_t> indices,
                          const Twine &what) -> LogicalResult {
    if (indices.size() != getTensorOrder(type))
      return emitOpError() << what << " of type " << type << " needs "
                           << getTensorOrder(type) << " index variables, got "
                           << indices.size();
    for (auto [dim, v] : llvm::enumerate(indices)) {
      if (v < 0 || v >= numVars)
        return emitOpError() << what << " uses index variable #" << v
                             << ", which is not declared";
      ++uses[v];
      ArrayAttr dimension = ArrayAttr::get(
          getContext(), getDimensionHierarchy(type, dim));
      if (dimension != getDomain(v))
        return emitOpError() << "index variable '" << varName(v)
                             << "' has domain " << getDomain(v)
                             << " but indexes dimension " << dim << " "
                             << dimension << " of " << what;
    }
    return success();
  };

  if (failed(verifyAccess(getType(), getResultIndices(), "the result")))
    return failure();
  for (auto [v, count] : llvm::enumerate(uses))
    if (count > 1)
      return emitOpError() << "result index variable '" << varName(v)
                           << "' appears more than once";
  if (getInputIndices().size() != getInputs().size())
    return emitOpError() << "has " << getInputs().size() << " inputs but "
                         << getInputIndices().size() << " index lists";
  for (auto [i, input] : llvm::enumerate(getInputs()))
    if (failed(verifyAccess(input.getType(), getInputIndexList(i),
                            "input #" + Twine(i))))
      return failure();
  for (auto [v, count] : llvm::enumerate(uses))
    if (count == 0)
      return emitOpError() << "index variable '" << varName(v)
                           << "' is not used";
  return success();
}

LogicalResult IndexExprOp::verifyRegions() {
  Block &body = getBody().front();
  if (body.getNumArguments() != getInputs().size())
    return emitOpError() << "body must take one argument per input ("
                         << getInputs().size() << "), got "
                         << body.getNumArguments();
  for (auto [i, input, argument] :
       llvm::enumerate(getInputs(), body.getArguments())) {
    Type component = getComponentType(input.getType());
    if (argument.getType() != component)
      return emitOpError() << "body argument #" << i << " must have the "
                           << "component type " << component << " of input #"
                           << i << ", got " << argument.getType();
  }
  auto yield = body.empty() ? YieldOp() : dyn_cast<YieldOp>(body.back());
  if (!yield)
    return emitOpError() << "body must end with simit.yield";
  Type component = getComponentType(getType());
  if (yield.getValue().getType() != component)
    return emitOpError() << "body yields " << yield.getValue().getType()
                         << " but the result component type is " << component;
  return success();
}
