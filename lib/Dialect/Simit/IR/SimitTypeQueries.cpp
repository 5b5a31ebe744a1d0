//===- SimitTypeQueries.cpp - Queries shared by the verifiers -------------===//
//
// Scalars are builtin types and local tensors builtin ranked tensors, so the
// questions the verifiers ask ("what is the block?", "what is dimension i?")
// are answered here for builtin tensors and !simit.tensor alike.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"

using namespace mlir;
using namespace mlir::simit;

bool mlir::simit::isScalarType(Type type) {
  if (auto complex = dyn_cast<ComplexType>(type))
    return isa<FloatType>(complex.getElementType());
  return isa<FloatType, IntegerType>(type);
}

bool mlir::simit::isTensorType(Type type) {
  return isa<RankedTensorType, SystemTensorType>(type);
}

bool mlir::simit::isTensorOrScalarType(Type type) {
  return isScalarType(type) || isTensorType(type);
}

unsigned mlir::simit::getTensorOrder(Type type) {
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return tensor.getRank();
  if (auto tensor = dyn_cast<SystemTensorType>(type))
    return tensor.getOrder();
  return 0;
}

Type mlir::simit::getComponentType(Type type) {
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return tensor.getElementType();
  if (auto tensor = dyn_cast<SystemTensorType>(type))
    return tensor.getComponentType();
  return type;
}

SmallVector<int64_t> mlir::simit::getLocalShape(Type type) {
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return SmallVector<int64_t>(tensor.getShape());
  SmallVector<int64_t> shape;
  if (auto system = dyn_cast<SystemTensorType>(type)) {
    for (Attribute dim : system.getDims())
      shape.push_back(cast<IntegerAttr>(dim).getInt());
    llvm::append_range(shape, getLocalShape(system.getBlockType()));
  }
  return shape;
}

Type mlir::simit::getBlockType(Type type) {
  if (auto tensor = dyn_cast<RankedTensorType>(type))
    return tensor.getElementType();
  if (auto tensor = dyn_cast<SystemTensorType>(type))
    return tensor.getBlockType();
  return type;
}

SmallVector<Attribute> mlir::simit::getDimensionHierarchy(Type type,
                                                          unsigned dim) {
  SmallVector<Attribute> levels;
  MLIRContext *ctx = type.getContext();
  while (dim < getTensorOrder(type)) {
    if (auto tensor = dyn_cast<RankedTensorType>(type)) {
      levels.push_back(IntegerAttr::get(IntegerType::get(ctx, 64),
                                        tensor.getDimSize(dim)));
      break;
    }
    auto system = cast<SystemTensorType>(type);
    levels.push_back(system.getDims()[dim]);
    type = system.getBlockType();
  }
  return levels;
}

bool mlir::simit::hasSetDimension(Type type) {
  auto system = dyn_cast<SystemTensorType>(type);
  return system && system.isSystem();
}
