//===- LoopsTypeConverter.cpp - Types of the loop lowering ----------------===//

#include "simit/Dialect/Simit/Transforms/LoopsTypeConverter.h"

#include "LoopsLowering.h"

#include "mlir/Dialect/LLVMIR/LLVMTypes.h"

using namespace mlir;
using namespace mlir::simit;

/// The numbers a local tensor of `component`s is stored as: complex
/// components are (re, im) pairs of their part type.
static Type storedNumberType(Type component) {
  if (auto complex = dyn_cast<ComplexType>(component))
    return complex.getElementType();
  return component;
}

/// The length of the flat vector or slot that stores a local tensor.
static int64_t storedLength(Type type) {
  return loops::numComponents(type) *
         (isa<ComplexType>(getComponentType(type)) ? 2 : 1);
}

/// The array of a system tensor: a dynamic number of blocks (a set's
/// elements, or a matrix's stored blocks), then the block shape; null
/// where there is no lowering.
static Type systemArrayType(SystemTensorType system) {
  Type component = system.getComponentType();
  SmallVector<int64_t> shape{ShapedType::kDynamic};
  unsigned sets = 0;
  for (Attribute dim : system.getDims()) {
    if (isa<StringAttr>(dim))
      ++sets;
    else if (sets == 0 || system.getOrder() > 1)
      shape.push_back(cast<IntegerAttr>(dim).getInt());
  }
  if (sets > 2 || (sets == 2 && system.getOrder() != 2))
    return nullptr;
  if (hasSetDimension(system.getBlockType()))
    return nullptr;
  llvm::append_range(shape, getLocalShape(system.getBlockType()));
  return MemRefType::get(shape, component);
}

LoopsTypeConverter::LoopsTypeConverter() {
  // Conversions are tried last added first: anything not matched below
  // has no lowering.
  addConversion([](Type) -> Type { return nullptr; });
  addConversion([](Type type) -> std::optional<Type> {
    if (isa<FloatType, IntegerType, IndexType, ComplexType>(type))
      return type;
    if (isa<StringType, OpaqueType>(type))
      return LLVM::LLVMPointerType::get(type.getContext());
    if (isa<SetType, ElementType>(type))
      return IndexType::get(type.getContext());
    return std::nullopt;
  });
  addConversion([](RankedTensorType tensor) -> Type {
    if (tensor.getRank() == 0)
      return tensor.getElementType();
    // Strings are pointers, which vectors do not hold (language.md 4.1:
    // nothing uses tensors of strings).
    if (isa<StringType>(tensor.getElementType()))
      return nullptr;
    return VectorType::get({storedLength(tensor)},
                           storedNumberType(tensor.getElementType()));
  });
  addConversion([](SystemTensorType system) -> Type {
    if (hasSetDimension(system))
      return systemArrayType(system);
    return VectorType::get({storedLength(system)},
                           storedNumberType(system.getComponentType()));
  });
  addConversion([this](RefType ref) -> Type {
    Type value = ref.getValueType();
    if (hasSetDimension(value))
      return convertType(value);
    if (isa<FloatType, IntegerType, IndexType, ComplexType>(value))
      return MemRefType::get({}, value);
    if (isa<StringType>(value))
      return MemRefType::get({},
                             LLVM::LLVMPointerType::get(ref.getContext()));
    if (isa<StringType>(getComponentType(value)))
      return nullptr;
    if (isa<RankedTensorType, SystemTensorType>(value))
      return MemRefType::get({storedLength(value)},
                             storedNumberType(getComponentType(value)));
    return nullptr;
  });
}
