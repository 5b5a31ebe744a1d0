//===- SimitStorageOps.cpp - Changes of storage ---------------------------===//

#include "simit/Dialect/Simit/IR/SimitStorage.h"

using namespace mlir;
using namespace mlir::simit;

LogicalResult ConvertOp::verify() {
  SystemTensorType source = getSource().getType(), result = getType();
  if (!isSameUpToStorage(source, result))
    return emitOpError() << "types must differ only in their storage "
                            "encodings, got "
                         << source << " and " << result;
  StorageAttr from = source.getEncoding(), to = result.getEncoding();
  if (!from) {
    // A host function's matrix result, declared unencoded, gets its
    // pattern known at run time.
    if (to && to.getKind() == StorageKind::Host && !getRestrict())
      return success();
    return emitOpError() << "needs a storage encoding on its source";
  }
  if (!to) {
    if (getRestrict())
      return emitOpError() << "'restrict' needs a storage encoding on its "
                              "result";
    return success();
  }
  if (!getRestrict() && !storage::contains(to, from))
    return emitOpError() << "'" << to.str() << "' does not contain '"
                         << from.str()
                         << "'; 'restrict' drops the blocks it does not store";
  return success();
}

OpFoldResult ConvertOp::fold(FoldAdaptor) {
  if (getSource().getType() == getType())
    return getSource();
  return {};
}
