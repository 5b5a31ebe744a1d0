//===--- HostABI.cpp - Reading simit.bindings back from the IR ------------===//

#include "simit/Engine/HostABI.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/Dialect/LLVMIR/LLVMTypes.h"
#include "mlir/IR/BuiltinAttributes.h"
#include "mlir/IR/BuiltinTypes.h"
#include "mlir/IR/SymbolTable.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/raw_ostream.h"

#include <limits>

using namespace simit;

size_t simit::scalarSize(ScalarKind kind) {
  switch (kind) {
  case ScalarKind::Float64:
  case ScalarKind::Int64:
  case ScalarKind::Index:
  case ScalarKind::String:
    return 8;
  case ScalarKind::Float32:
  case ScalarKind::Int32:
    return 4;
  case ScalarKind::Bool:
    return 1;
  }
  llvm_unreachable("unknown scalar kind");
}

llvm::StringRef simit::scalarKindName(ScalarKind kind) {
  switch (kind) {
  case ScalarKind::Float64:
    return "f64";
  case ScalarKind::Float32:
    return "f32";
  case ScalarKind::Int32:
    return "i32";
  case ScalarKind::Int64:
    return "i64";
  case ScalarKind::Index:
    return "index";
  case ScalarKind::Bool:
    return "i1";
  case ScalarKind::String:
    return "string";
  }
  llvm_unreachable("unknown scalar kind");
}

bool simit::componentTypeFor(ScalarKind kind, ComponentType &type) {
  switch (kind) {
  case ScalarKind::Float64:
    type = ComponentType::Float64;
    return true;
  case ScalarKind::Float32:
    type = ComponentType::Float32;
    return true;
  case ScalarKind::Int32:
    type = ComponentType::Int32;
    return true;
  case ScalarKind::Bool:
    type = ComponentType::Bool;
    return true;
  case ScalarKind::Int64:
  case ScalarKind::Index:
  case ScalarKind::String:
    return false;
  }
  llvm_unreachable("unknown scalar kind");
}

std::string simit::shapeString(llvm::ArrayRef<int64_t> shape) {
  std::string text = "[";
  for (size_t i = 0; i < shape.size(); ++i)
    text += (i ? ", " : "") + (shape[i] == ValueType::kDynamic
                                   ? std::string("?")
                                   : std::to_string(shape[i]));
  return text + "]";
}

std::string simit::shapeString(llvm::ArrayRef<int> shape) {
  return shapeString(llvm::to_vector(
      llvm::map_range(shape, [](int d) { return static_cast<int64_t>(d); })));
}

int64_t ValueType::numComponents() const {
  int64_t n = 1;
  for (int64_t dim : shape)
    n *= dim;
  return n;
}

std::vector<int64_t> ValueType::hostShape() const {
  std::vector<int64_t> result = shape;
  if (isComplex)
    result.push_back(2);
  return result;
}

std::string ValueType::str() const {
  if (!isMemRef && !isVector)
    return isComplex ? "complex<" + scalarKindName(scalar).str() + ">"
                     : scalarKindName(scalar).str();
  std::string text = isVector ? "vector<" : "memref<";
  for (int64_t dim : hostShape())
    text += (dim == kDynamic ? std::string("?") : std::to_string(dim)) + "x";
  return text + scalarKindName(scalar).str() + ">";
}

static llvm::Error typeError(mlir::Type type, llvm::StringRef why) {
  std::string text;
  llvm::raw_string_ostream os(text);
  os << "unsupported host type " << type << ": " << why;
  return llvm::createStringError(text);
}

static bool toScalarKind(mlir::Type type, ScalarKind &kind) {
  if (type.isIndex())
    kind = ScalarKind::Index;
  else if (type.isF64())
    kind = ScalarKind::Float64;
  else if (type.isF32())
    kind = ScalarKind::Float32;
  else if (type.isInteger(64))
    kind = ScalarKind::Int64;
  else if (type.isInteger(32))
    kind = ScalarKind::Int32;
  else if (type.isInteger(1))
    kind = ScalarKind::Bool;
  else
    return false;
  return true;
}

llvm::Expected<ValueType> simit::toValueType(mlir::Type type) {
  ValueType result;
  if (auto memref = llvm::dyn_cast<mlir::MemRefType>(type)) {
    if (!memref.getLayout().isIdentity())
      return typeError(type, "only the identity layout crosses the host boundary");
    mlir::Type element = memref.getElementType();
    // Complex components are (re, im) pairs of their parts at the host.
    if (auto complex = llvm::dyn_cast<mlir::ComplexType>(element)) {
      element = complex.getElementType();
      result.isComplex = true;
    }
    if (!toScalarKind(element, result.scalar) ||
        (result.isComplex && result.scalar != ScalarKind::Float64 &&
         result.scalar != ScalarKind::Float32))
      return typeError(type, "unsupported element type");
    result.isMemRef = true;
    for (int64_t dim : memref.getShape())
      result.shape.push_back(mlir::ShapedType::isDynamic(dim)
                                 ? ValueType::kDynamic
                                 : dim);
    return result;
  }
  if (auto vector = llvm::dyn_cast<mlir::VectorType>(type)) {
    if (vector.isScalable() || !toScalarKind(vector.getElementType(),
                                             result.scalar) ||
        result.scalar == ScalarKind::Bool)
      return typeError(type, "only fixed vectors of numbers are supported");
    result.isVector = true;
    result.shape.assign(vector.getShape().begin(), vector.getShape().end());
    // Local tensors are flat; a second dimension of 2 holds complex pairs.
    if (vector.getRank() == 2 && vector.getShape()[1] == 2 &&
        (result.scalar == ScalarKind::Float64 ||
         result.scalar == ScalarKind::Float32)) {
      result.isComplex = true;
      result.shape.pop_back();
    } else if (vector.getRank() != 1) {
      return typeError(type, "expected a 1-D vector, or N x 2 floats for "
                             "complex components");
    }
    return result;
  }
  if (auto complex = llvm::dyn_cast<mlir::ComplexType>(type)) {
    if (!toScalarKind(complex.getElementType(), result.scalar) ||
        (result.scalar != ScalarKind::Float64 &&
         result.scalar != ScalarKind::Float32))
      return typeError(type, "only complex numbers of f32 or f64 parts are "
                             "supported");
    result.isComplex = true;
    return result;
  }
  if (llvm::isa<mlir::LLVM::LLVMPointerType>(type)) {
    result.scalar = ScalarKind::String;
    return result;
  }
  if (!toScalarKind(type, result.scalar))
    return typeError(type, "expected an index, i1, i32, i64, f32, f64, "
                           "complex, vector or memref");
  return result;
}

std::string ArgumentBinding::describe() const {
  switch (kind) {
  case Kind::SetSize:
    return "size of set '" + set + "'";
  case Kind::GridDims:
    return "extents of grid '" + set + "'";
  case Kind::Field:
    return "field '" + set + "." + field + "'";
  case Kind::Endpoints:
    return "endpoints of set '" + set + "'";
  case Kind::PatternRowPtr:
  case Kind::PatternColIdx:
  case Kind::PatternLocations:
    return "sparsity pattern of set '" + set + "' over ('" + rows + "', '" +
           cols + "')";
  case Kind::IncidenceRowPtr:
  case Kind::IncidenceColIdx:
  case Kind::IncidencePositions:
  case Kind::IncidenceEndpoints:
    return "rows of the incidence of set '" + set + "' over ('" + rows +
           "', '" + cols + "')";
  case Kind::StencilRowPtr:
  case Kind::StencilColIdx:
  case Kind::StencilPositions:
    return "sparsity pattern of the stencil of grid '" + set +
           "' with offsets " + offsets;
  case Kind::UnionRowPtr:
  case Kind::UnionColIdx:
    return "union of the sparsity patterns of '" +
           llvm::join(edgeSets, "', '") + "' over ('" + rows + "', '" + cols +
           "')";
  case Kind::ProductRowPtr:
  case Kind::ProductColIdx:
  {
    std::string text;
    for (const ProductChain &chain : chains) {
      text += text.empty() ? "" : ", united with ";
      text += chain.factorSets.size() == 1
                  ? "the sparsity pattern of "
                  : "the product of the sparsity patterns of ";
      for (size_t i = 0; i < chain.factorSets.size(); ++i) {
        std::string from = i == 0 ? rows : chain.mids[i - 1];
        std::string to =
            i + 1 == chain.factorSets.size() ? cols : chain.mids[i];
        text += (i ? ", '" : "'") + llvm::join(chain.factorSets[i], "', '") +
                "' over ('" + from + "', '" + to + "')";
      }
    }
    return text;
  }
  case Kind::UnionGather:
    return "gather map from the union of the sparsity patterns of '" +
           llvm::join(edgeSets, "', '") + "' over ('" + rows + "', '" + cols +
           "') to the pattern of '" + llvm::join(partSets, "', '") + "'" +
           (partTransposed ? " read transposed" : "");
  case Kind::ElementColours:
    return "element colouring of set '" + set + "' in chunks of " +
           std::to_string(chunk);
  case Kind::Extern:
    return "extern '" + name + "'" +
           (set.empty() ? "" : " (a vector over set '" + set + "')");
  case Kind::Parameter:
    return "parameter " + std::to_string(index);
  }
  llvm_unreachable("unknown binding kind");
}

std::string ArgumentBinding::bufferKey() const {
  return kind == Kind::Parameter ? "#" + std::to_string(index) : name;
}

namespace {
/// The names of a '+'-joined list of sets.
std::vector<std::string> splitSets(llvm::StringRef joined) {
  llvm::SmallVector<llvm::StringRef> names;
  joined.split(names, '+');
  return std::vector<std::string>(names.begin(), names.end());
}

/// Reads one DictionaryAttr of `simit.bindings`.
class BindingReader {
public:
  BindingReader(llvm::StringRef function, unsigned index,
                mlir::DictionaryAttr dict)
      : function(function), index(index), dict(dict) {}

  llvm::Error error(const llvm::Twine &what) const {
    return llvm::createStringError("function '" + function +
                                   "': simit.bindings entry " +
                                   llvm::Twine(index) + ": " + what);
  }

  llvm::Error get(llvm::StringRef key, std::string &value) const {
    auto attr = dict.getAs<mlir::StringAttr>(key);
    if (!attr)
      return error("expected a string '" + key + "'");
    value = attr.getValue().str();
    return llvm::Error::success();
  }

  /// The optional declared `shape` of an extern or parameter.
  llvm::Error getShape(ArgumentBinding &binding) const {
    mlir::Attribute shape = dict.get("shape");
    if (!shape)
      return llvm::Error::success();
    auto dims = llvm::dyn_cast<mlir::DenseI64ArrayAttr>(shape);
    if (!dims)
      return error("expected 'shape' to be an array of integers");
    binding.declaredShape = std::vector<int64_t>(dims.asArrayRef().begin(),
                                                 dims.asArrayRef().end());
    return llvm::Error::success();
  }

  llvm::Error read(ArgumentBinding &binding) const {
    std::string kind;
    if (llvm::Error err = get("kind", kind))
      return err;
    using Kind = ArgumentBinding::Kind;
    std::optional<Kind> parsed = abi::parseBindingKind(kind);
    if (!parsed)
      return error("unknown kind '" + kind + "'");
    binding.kind = *parsed;
    switch (binding.kind) {
    case Kind::SetSize:
    case Kind::GridDims:
    case Kind::Endpoints:
      return get("set", binding.set);
    case Kind::Field:
      if (llvm::Error err = get("set", binding.set))
        return err;
      return get("field", binding.field);
    case Kind::PatternRowPtr:
    case Kind::PatternColIdx:
    case Kind::PatternLocations:
    case Kind::IncidenceRowPtr:
    case Kind::IncidenceColIdx:
    case Kind::IncidencePositions:
    case Kind::IncidenceEndpoints:
      if (llvm::Error err = get("set", binding.set))
        return err;
      if (llvm::Error err = get("rows", binding.rows))
        return err;
      return get("cols", binding.cols);
    case Kind::StencilRowPtr:
    case Kind::StencilColIdx:
    case Kind::StencilPositions:
      if (llvm::Error err = get("set", binding.set))
        return err;
      return get("offsets", binding.offsets);
    case Kind::UnionRowPtr:
    case Kind::UnionColIdx:
    case Kind::UnionGather: {
      std::string joined, part;
      if (llvm::Error err = get("set", joined))
        return err;
      if (llvm::Error err = get("rows", binding.rows))
        return err;
      if (llvm::Error err = get("cols", binding.cols))
        return err;
      binding.edgeSets = splitSets(joined);
      if (binding.kind != Kind::UnionGather)
        return llvm::Error::success();
      if (llvm::Error err = get("part", part))
        return err;
      binding.partTransposed = llvm::StringRef(part).consume_front("~");
      binding.partSets = splitSets(binding.partTransposed ? part.substr(1)
                                                          : part);
      return llvm::Error::success();
    }
    case Kind::ProductRowPtr:
    case Kind::ProductColIdx: {
      std::string factors, joinedMids;
      if (llvm::Error err = get("set", factors))
        return err;
      if (llvm::Error err = get("mid", joinedMids))
        return err;
      llvm::SmallVector<llvm::StringRef> chainFactors, chainMids;
      llvm::StringRef(factors).split(chainFactors, '|');
      llvm::StringRef(joinedMids).split(chainMids, '|');
      bool wellFormed = chainFactors.size() == chainMids.size();
      for (size_t c = 0; wellFormed && c < chainFactors.size(); ++c) {
        llvm::SmallVector<llvm::StringRef> parts, mids;
        chainFactors[c].split(parts, '*');
        if (!chainMids[c].empty())
          chainMids[c].split(mids, ',');
        wellFormed = mids.size() + 1 == parts.size() &&
                     !llvm::is_contained(parts, "") &&
                     !llvm::is_contained(mids, "");
        ArgumentBinding::ProductChain &chain = binding.chains.emplace_back();
        for (llvm::StringRef part : parts)
          chain.factorSets.push_back(splitSets(part));
        chain.mids.assign(mids.begin(), mids.end());
      }
      if (!wellFormed)
        return error("expected 'set' of the form \"A*B*...|C*...\" and "
                     "'mid' naming the sets between the factors of each "
                     "chain, \"M1,...|M2,...\"");
      if (llvm::Error err = get("rows", binding.rows))
        return err;
      return get("cols", binding.cols);
    }
    case Kind::ElementColours: {
      auto chunk = dict.getAs<mlir::IntegerAttr>("chunk");
      if (!chunk || chunk.getInt() < 1 ||
          chunk.getInt() > std::numeric_limits<int32_t>::max())
        return error("expected a positive 32-bit integer 'chunk'");
      binding.chunk = chunk.getInt();
      return get("set", binding.set);
    }
    case Kind::Extern:
      // A vector over a set also names the set.
      if (dict.get("set"))
        if (llvm::Error err = get("set", binding.set))
          return err;
      if (llvm::Error err = getShape(binding))
        return err;
      return get("name", binding.name);
    case Kind::Parameter: {
      auto index = dict.getAs<mlir::IntegerAttr>("index");
      if (!index || index.getInt() < 0)
        return error("expected a non-negative integer 'index'");
      binding.index = index.getInt();
      // A vector over a set names the set, as an extern does.
      if (dict.get("set"))
        if (llvm::Error err = get("set", binding.set))
          return err;
      return getShape(binding);
    }
    }
    llvm_unreachable("unknown binding kind");
  }

private:
  llvm::StringRef function;
  unsigned index;
  mlir::DictionaryAttr dict;
};
} // namespace

/// Checks that the argument's machine type fits its kind, so that a lowering
/// that changed the ABI is reported here rather than misread at run time.
static llvm::Error checkKindType(const HostSignature &signature,
                                 const ArgumentBinding &binding) {
  using Kind = ArgumentBinding::Kind;
  const ValueType &type = binding.type;
  auto fail = [&](llvm::StringRef expected) {
    return llvm::createStringError("function '" + signature.function + "': " +
                                   binding.describe() + " has type " +
                                   type.str() + ", expected " + expected);
  };
  switch (binding.kind) {
  case Kind::SetSize:
    if (type.isMemRef || type.isVector ||
        (type.scalar != ScalarKind::Index && type.scalar != ScalarKind::Int64 &&
         type.scalar != ScalarKind::Int32))
      return fail("an integer or index");
    return llvm::Error::success();
  case Kind::Field:
    if (!type.isMemRef || type.rank() < 1)
      return fail("a memref with one dimension per element");
    return llvm::Error::success();
  case Kind::Endpoints:
  case Kind::PatternLocations:
  case Kind::IncidenceEndpoints:
    if (!type.isMemRef || type.rank() != 2 || type.scalar != ScalarKind::Int32)
      return fail("memref<?xNxi32>");
    return llvm::Error::success();
  case Kind::GridDims:
    if (!type.isMemRef || type.rank() != 1 || type.scalar != ScalarKind::Int32 ||
        type.shape[0] == ValueType::kDynamic)
      return fail("memref<Nxi32>");
    return llvm::Error::success();
  case Kind::PatternRowPtr:
  case Kind::PatternColIdx:
  case Kind::UnionRowPtr:
  case Kind::UnionColIdx:
  case Kind::UnionGather:
  case Kind::ProductRowPtr:
  case Kind::ProductColIdx:
  case Kind::IncidenceRowPtr:
  case Kind::IncidenceColIdx:
  case Kind::IncidencePositions:
  case Kind::StencilRowPtr:
  case Kind::StencilColIdx:
  case Kind::StencilPositions:
  case Kind::ElementColours:
    if (!type.isMemRef || type.rank() != 1 || type.scalar != ScalarKind::Int32)
      return fail("memref<?xi32>");
    return llvm::Error::success();
  case Kind::Extern:
  case Kind::Parameter:
    // A vector over a set has one block per element of `set`.
    for (auto [d, dim] : llvm::enumerate(type.shape))
      if (dim == ValueType::kDynamic &&
          (d != 0 || !type.isMemRef || binding.set.empty()))
        return fail(binding.set.empty()
                        ? "a statically shaped memref or a scalar"
                        : "a memref of one dimension per element");
    return llvm::Error::success();
  }
  llvm_unreachable("unknown binding kind");
}

llvm::Expected<HostSignature>
simit::readHostSignature(mlir::Operation *function) {
  HostSignature signature;
  signature.function = mlir::SymbolTable::getSymbolName(function).str();
  mlir::FunctionType type;
  if (auto hostType = function->getAttrOfType<mlir::TypeAttr>(
          llvm::StringRef(abi::kHostTypeAttr)))
    type = llvm::dyn_cast<mlir::FunctionType>(hostType.getValue());
  else if (auto func = llvm::dyn_cast<mlir::func::FuncOp>(function))
    type = func.getFunctionType();
  if (!type)
    return llvm::createStringError(
        "function '" + signature.function + "' has no function type in " +
        llvm::StringRef(abi::kHostTypeAttr) + " (simit-record-host-abi)");
  auto bindings = function->getAttrOfType<mlir::ArrayAttr>(
      llvm::StringRef(abi::kBindingsAttr));
  if (!bindings)
    return llvm::createStringError("function '" + signature.function +
                                   "' has no simit.bindings attribute");
  if (bindings.size() != type.getNumInputs())
    return llvm::createStringError(
        "function '" + signature.function + "': simit.bindings has " +
        llvm::Twine(bindings.size()) + " entries for " +
        llvm::Twine(type.getNumInputs()) + " arguments");

  for (unsigned i = 0, e = type.getNumInputs(); i < e; ++i) {
    ArgumentBinding binding;
    auto dict = llvm::dyn_cast<mlir::DictionaryAttr>(bindings[i]);
    BindingReader reader(signature.function, i, dict);
    if (!dict)
      return reader.error("expected a dictionary");
    if (llvm::Error err = reader.read(binding))
      return err;
    llvm::Expected<ValueType> valueType = toValueType(type.getInput(i));
    if (!valueType)
      return llvm::createStringError("function '" + signature.function +
                                     "': " + binding.describe() + ": " +
                                     llvm::toString(valueType.takeError()));
    binding.type = std::move(*valueType);
    if (llvm::Error err = checkKindType(signature, binding))
      return err;
    signature.arguments.push_back(std::move(binding));
  }
  // Parameters are numbered 0..k-1, each once, so callers can bind them by
  // position.
  std::vector<bool> seen;
  for (const ArgumentBinding &arg : signature.arguments)
    if (arg.kind == ArgumentBinding::Kind::Parameter) {
      if (static_cast<size_t>(arg.index) >= seen.size())
        seen.resize(arg.index + 1, false);
      if (seen[arg.index])
        return llvm::createStringError("function '" + signature.function +
                                       "': parameter " +
                                       llvm::Twine(arg.index) +
                                       " is bound twice");
      seen[arg.index] = true;
    }
  if (llvm::is_contained(seen, false))
    return llvm::createStringError("function '" + signature.function +
                                   "': its parameter indices have a gap");
  for (mlir::Type result : type.getResults()) {
    llvm::Expected<ValueType> valueType = toValueType(result);
    if (!valueType)
      return llvm::createStringError("function '" + signature.function +
                                     "': result: " +
                                     llvm::toString(valueType.takeError()));
    signature.results.push_back(std::move(*valueType));
  }
  // A local matrix result travels as a flat vector; the host shows it
  // with its declared shape.
  if (auto shapes = function->getAttrOfType<mlir::ArrayAttr>(
          llvm::StringRef(abi::kResultShapesAttr))) {
    if (shapes.size() != signature.results.size())
      return llvm::createStringError(
          "function '" + signature.function +
          "': " + llvm::StringRef(abi::kResultShapesAttr) + " has " +
          llvm::Twine(shapes.size()) + " entries for " +
          llvm::Twine(signature.results.size()) + " results");
    for (auto [shape, result] : llvm::zip(shapes, signature.results)) {
      auto dims = llvm::dyn_cast<mlir::DenseI64ArrayAttr>(shape);
      if (!dims)
        return llvm::createStringError(
            "function '" + signature.function +
            "': " + llvm::StringRef(abi::kResultShapesAttr) +
            " entries must be arrays of integers");
      int64_t count = 1;
      for (int64_t dim : dims.asArrayRef())
        count *= dim;
      if (result.isVector && dims.size() > 1 && count == result.numComponents())
        result.shape.assign(dims.asArrayRef().begin(), dims.asArrayRef().end());
    }
  }
  return signature;
}
