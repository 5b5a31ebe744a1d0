//===- LoopsTypeConverter.h - Types of the loop lowering ---------*- C++ -*-===//
//
// The types convert-simit-to-loops gives simit values (docs/lowering.md,
// "Storage of values"), as a TypeConverter that conversion patterns and
// other compilers can share:
//  - scalars stay; strings and opaque handles are !llvm.ptr; sets and
//    elements are index (an element is its position in its set);
//  - a local tensor (builtin, or !simit.tensor of integer dimensions) is a
//    flat vector<N x T> of its components, row-major; N complex components
//    are a vector<2N x T> of (re, im) pairs;
//  - a system tensor is memref<? x block x T>: one dynamic dimension of
//    blocks, however its encoding stores them (a vector's elements, a
//    matrix's diagonal, pattern, incidence, stencil or dense blocks);
//  - a variable (!simit.ref) of a scalar or local tensor is a memref slot
//    (memref<T>, memref<N x T>); of a system tensor, that tensor's array.
// Complex system tensors and tensors over three or more sets have no
// lowering: they are not converted.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_TRANSFORMS_LOOPSTYPECONVERTER_H
#define SIMIT_DIALECT_SIMIT_TRANSFORMS_LOOPSTYPECONVERTER_H

#include "mlir/Transforms/DialectConversion.h"

namespace mlir {
namespace simit {

class LoopsTypeConverter : public TypeConverter {
public:
  LoopsTypeConverter();
};

} // namespace simit
} // namespace mlir

#endif // SIMIT_DIALECT_SIMIT_TRANSFORMS_LOOPSTYPECONVERTER_H
