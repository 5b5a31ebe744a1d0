//===- SimitStorageOps.td - Changes of storage -------------*- tablegen -*-===//
//
// Added for simit-assign-storage (lib/Dialect/Simit/Transforms): explicit
// changes of the storage encoding of a system matrix.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITSTORAGEOPS_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITSTORAGEOPS_TD

def Simit_ConvertOp : Simit_Op<"convert", [Pure]> {
  let summary = "Changes the storage encoding of a system matrix";
  let description = [{
    The same matrix in another storage: the types differ only in their
    encodings; the source has one (but see below). Without `restrict` the result's contains
    the source's (widening keeps every value); `restrict` drops the blocks
    the result does not store. A result without an encoding forgets the
    storage (for callees declared on unassigned types, such as `lu`). A
    source without one is the matrix result of a host function (`extern
    func`), declared unencoded: the result's `host` encoding names it.

    ```mlir
    %w = simit.convert %d : !simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>
        -> !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>
    %r = simit.convert restrict %w : !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>
        -> !simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>
    ```
  }];
  let arguments = (ins Simit_SystemTensorType:$source, UnitAttr:$restrict);
  let results = (outs Simit_SystemTensorType:$result);
  let assemblyFormat = [{
    (`restrict` $restrict^)? $source attr-dict `:` qualified(type($source)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
  let hasFolder = 1;
}

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITSTORAGEOPS_TD
