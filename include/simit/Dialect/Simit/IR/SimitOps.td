//===- SimitOps.td - Operations of the simit dialect -------*- tablegen -*-===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITOPS_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITOPS_TD

include "simit/Dialect/Simit/IR/SimitDialect.td"
include "simit/Dialect/Simit/IR/SimitAttrs.td"
include "simit/Dialect/Simit/IR/SimitTypes.td"
include "mlir/IR/SymbolInterfaces.td"
include "mlir/Interfaces/ControlFlowInterfaces.td"
include "mlir/Interfaces/InferTypeOpInterface.td"
include "mlir/Interfaces/SideEffectInterfaces.td"

//===----------------------------------------------------------------------===//
// Globals
//===----------------------------------------------------------------------===//

def Simit_ExternOp : Simit_Op<"extern", [Symbol]> {
  let summary = "Declares a global bound by the host";
  let description = [{
    Declares a global that the host binds by name before running the
    program: a set, or a tensor carrying host parameters. Sets are read with
    `simit.get_set`; the writable slot of a tensor global is
    `simit.extern_ref`.

    ```mlir
    simit.extern @points : !simit.set<"points", !Point>
    simit.extern @dt : tensor<2xf64>
    ```
  }];
  let arguments = (ins SymbolNameAttr:$sym_name, TypeAttr:$type);
  let assemblyFormat = "$sym_name `:` $type attr-dict";
  let hasVerifier = 1;
}

def Simit_GetSetOp : Simit_Op<"get_set",
    [Pure, DeclareOpInterfaceMethods<SymbolUserOpInterface>]> {
  let summary = "The set bound to an extern";
  let description = [{
    Returns the set declared by the `simit.extern` named by the symbol. The
    result type must be the declared set type.

    ```mlir
    %points = simit.get_set @points : !simit.set<"points", !Point>
    ```
  }];
  let arguments = (ins FlatSymbolRefAttr:$global);
  let results = (outs Simit_SetType:$result);
  let assemblyFormat = "$global attr-dict `:` qualified(type($result))";
}

def Simit_ExternRefOp : Simit_Op<"extern_ref",
    [Pure, DeclareOpInterfaceMethods<SymbolUserOpInterface>]> {
  let summary = "The writable slot of an extern tensor";
  let description = [{
    Returns the slot holding the value of a tensor (or scalar) `simit.extern`.
    The slot's value type must be the declared type.

    ```mlir
    %dt = simit.extern_ref @dt : !simit.ref<tensor<2xf64>>
    ```
  }];
  let arguments = (ins FlatSymbolRefAttr:$global);
  let results = (outs Simit_RefType:$result);
  let assemblyFormat = "$global attr-dict `:` qualified(type($result))";
}

//===----------------------------------------------------------------------===//
// Variables
//===----------------------------------------------------------------------===//

def Simit_AllocOp : Simit_Op<"alloc"> {
  let summary = "Creates a zero-initialised mutable slot";
  let description = [{
    Creates a slot for a mutable variable, holding zeros (an empty string for
    `!simit.string`, a null handle for `!simit.opaque`).

    ```mlir
    %x = simit.alloc : !simit.ref<tensor<3xf64>>
    ```
  }];
  let results = (outs Res<Simit_RefType, "the new slot", [MemAlloc]>:$ref);
  let assemblyFormat = "attr-dict `:` qualified(type($ref))";
}

def Simit_LoadOp : Simit_Op<"load", [
    TypesMatchWith<"result type is the slot's value type", "ref", "result",
                   "::llvm::cast<::mlir::simit::RefType>($_self).getValueType()">]> {
  let summary = "Reads the value held by a slot";
  let description = [{
    ```mlir
    %v = simit.load %x : !simit.ref<tensor<3xf64>>
    ```
  }];
  let arguments = (ins Arg<Simit_RefType, "the slot", [MemRead]>:$ref);
  let results = (outs AnyType:$result);
  let assemblyFormat = "$ref attr-dict `:` qualified(type($ref))";
}

def Simit_StoreOp : Simit_Op<"store", [
    TypesMatchWith<"stored value has the slot's value type", "ref", "value",
                   "::llvm::cast<::mlir::simit::RefType>($_self).getValueType()">]> {
  let summary = "Replaces the value held by a slot";
  let description = [{
    ```mlir
    simit.store %v, %x : !simit.ref<tensor<3xf64>>
    ```
  }];
  let arguments = (ins AnyType:$value,
                       Arg<Simit_RefType, "the slot", [MemWrite]>:$ref);
  let assemblyFormat = "$value `,` $ref attr-dict `:` qualified(type($ref))";
}

//===----------------------------------------------------------------------===//
// Tensor construction and access
//===----------------------------------------------------------------------===//

def Simit_ZerosOp : Simit_Op<"zeros", [Pure]> {
  let summary = "A tensor of zeros";
  let description = [{
    ```mlir
    %z = simit.zeros : !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = "attr-dict `:` qualified(type($result))";
}

def Simit_BroadcastOp : Simit_Op<"broadcast", [Pure]> {
  let summary = "A tensor with every component set to a scalar";
  let description = [{
    The scalar's type must be the component type of the result.

    ```mlir
    %t = simit.broadcast %s : f64 -> tensor<3x3xf64>
    ```
  }];
  let arguments = (ins Simit_ScalarType:$value);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = "$value attr-dict `:` qualified(type($value)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_ExtractOp : Simit_Op<"extract", [Pure]> {
  let summary = "Reads one block (or component) of a tensor";
  let description = [{
    Takes one index per outer dimension: an `index` for an integer range, an
    element of the dimension's set for a set dimension. The result is the
    block at that position, a scalar when the tensor is unblocked. A system
    matrix component outside its sparsity pattern reads as zero.

    ```mlir
    %b = simit.extract %K[%p, %q]
        : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, (!Point, !Point)
          -> tensor<3x3xf64>
    %c = simit.extract %m[%i, %j] : tensor<3x3xf64>, (index, index) -> f64
    ```
  }];
  let arguments = (ins Simit_TensorLike:$tensor, Variadic<AnyType>:$indices);
  let results = (outs AnyType:$result);
  let assemblyFormat = [{
    $tensor `[` $indices `]` attr-dict `:` qualified(type($tensor)) `,` `(` qualified(type($indices)) `)`
    `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_InsertOp : Simit_Op<"insert",
    [Pure, AllTypesMatch<["tensor", "result"]>]> {
  let summary = "Replaces one block (or component) of a tensor";
  let description = [{
    Returns the tensor with the block at the given position replaced. The
    indices follow the rules of `simit.extract`; the value has the block type.

    ```mlir
    %K2 = simit.insert %k into %K[%p, %q]
        : tensor<3x3xf64> into !simit.tensor<["points", "points"] x tensor<3x3xf64>>,
          (!Point, !Point)
    ```
  }];
  let arguments = (ins AnyType:$value, Simit_TensorLike:$tensor,
                       Variadic<AnyType>:$indices);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $value `into` $tensor `[` $indices `]` attr-dict `:` qualified(type($value)) `into`
    qualified(type($tensor)) `,` `(` qualified(type($indices)) `)`
  }];
  let hasVerifier = 1;
}

def Simit_SliceOp : Simit_Op<"slice", [Pure]> {
  let summary = "Reads a slice of an unblocked tensor";
  let description = [{
    Indexes some outer dimensions (as `simit.extract` does) and keeps the
    dimensions written `:`; the result has the kept dimensions in order.
    Slices of blocked tensors are not supported.

    ```mlir
    %row = simit.slice %A[%p, :]
        : !simit.tensor<["points", "springs"] x f64>, (!Point)
          -> !simit.tensor<["springs"] x f64>
    %col = simit.slice %m[:, %j] : tensor<3x4xf64>, (index) -> tensor<3xf64>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$tensor, Variadic<AnyType>:$indices,
                       DenseBoolArrayAttr:$kept);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $tensor `[` custom<SliceIndices>($indices, $kept) `]` attr-dict `:`
    qualified(type($tensor)) `,` `(` qualified(type($indices)) `)` `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

//===----------------------------------------------------------------------===//
// Sets and elements
//===----------------------------------------------------------------------===//

def Simit_FieldReadOp : Simit_Op<"field_read", [MemoryEffects<[MemRead]>]> {
  let summary = "Reads a field of every element of a set as a global vector";
  let description = [{
    The result is a vector over the set whose blocks are the field values
    (`!simit.tensor<[set] x F>` for field type `F`). Only scalar and vector
    fields can be read this way.

    ```mlir
    %x = simit.field_read %points["x"]
        : !simit.set<"points", !Point> -> !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let arguments = (ins Simit_SetType:$set, StrAttr:$field);
  let results = (outs Simit_SystemTensorType:$result);
  let assemblyFormat = "$set `[` $field `]` attr-dict `:` qualified(type($set)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_FieldWriteOp : Simit_Op<"field_write", [MemoryEffects<[MemWrite]>]> {
  let summary = "Writes a global vector (or a broadcast scalar) to a set field";
  let description = [{
    Writes block `p` of the vector into the field of element `p`. The value
    is a vector of the type `simit.field_read` returns for the field, or a
    scalar of the field's component type, written to every component.

    ```mlir
    simit.field_write %x, %points["x"]
        : !simit.tensor<["points"] x tensor<3xf64>>, !simit.set<"points", !Point>
    simit.field_write %zero, %points["m"] : f64, !simit.set<"points", !Point>
    ```
  }];
  let arguments = (ins AnyType:$value, Simit_SetType:$set, StrAttr:$field);
  let assemblyFormat = [{
    $value `,` $set `[` $field `]` attr-dict `:` qualified(type($value)) `,` qualified(type($set))
  }];
  let hasVerifier = 1;
}

def Simit_ElemReadOp : Simit_Op<"elem_read", [MemoryEffects<[MemRead]>]> {
  let summary = "Reads a field of one element";
  let description = [{
    ```mlir
    %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
    ```
  }];
  let arguments = (ins Simit_ElementType:$element, StrAttr:$field);
  let results = (outs AnyType:$result);
  let assemblyFormat = "$element `[` $field `]` attr-dict `:` qualified(type($element)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_ElemWriteOp : Simit_Op<"elem_write", [MemoryEffects<[MemWrite]>]> {
  let summary = "Writes a field of one element";
  let description = [{
    The value has the field's type, or is a scalar of its component type,
    written to every component.

    ```mlir
    simit.elem_write %v, %p["x"] : tensor<3xf64>, !Point
    ```
  }];
  let arguments = (ins AnyType:$value, Simit_ElementType:$element, StrAttr:$field);
  let assemblyFormat = [{
    $value `,` $element `[` $field `]` attr-dict `:` qualified(type($value)) `,` qualified(type($element))
  }];
  let hasVerifier = 1;
}

def Simit_TupleGetOp : Simit_Op<"tuple_get", [Pure]> {
  let summary = "A component of an endpoint tuple";
  let description = [{
    Returns the component at a constant position (named components are
    addressed by their position too).

    ```mlir
    %b0 = simit.tuple_get %ends[0] : !simit.tuple<!Bead x 2> -> !Bead
    ```
  }];
  let arguments = (ins Simit_TupleType:$tuple,
                       ConfinedAttr<I64Attr, [IntNonNegative]>:$index);
  let results = (outs Simit_ElementType:$result);
  let assemblyFormat = "$tuple `[` $index `]` attr-dict `:` qualified(type($tuple)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_SetSizeOp : Simit_Op<"set_size", [Pure]> {
  let summary = "The number of elements of a set";
  let description = [{
    ```mlir
    %n = simit.set_size %points : !simit.set<"points", !Point>
    ```
  }];
  let arguments = (ins Simit_SetType:$set);
  let results = (outs Index:$result);
  let assemblyFormat = "$set attr-dict `:` qualified(type($set))";
}

def Simit_SetElementOp : Simit_Op<"set_element", [Pure,
    TypesMatchWith<"result is of the set's element type", "set", "result",
                   "::llvm::cast<::mlir::simit::SetType>($_self).getElementType()">]> {
  let summary = "The i-th element of a set";
  let description = [{
    Used by `for p in S` loops, which are `scf.for` loops over
    `0 .. simit.set_size`.

    ```mlir
    %p = simit.set_element %points[%i] : !simit.set<"points", !Point> -> !Point
    ```
  }];
  let arguments = (ins Simit_SetType:$set, Index:$index);
  let results = (outs Simit_ElementType:$result);
  let assemblyFormat = "$set `[` $index `]` attr-dict `:` qualified(type($set)) `->` qualified(type($result))";
}

def Simit_EndpointsOp : Simit_Op<"endpoints", [Pure,
    TypesMatchWith<"element is of the set's element type", "set", "element",
                   "::llvm::cast<::mlir::simit::SetType>($_self).getElementType()">]> {
  let summary = "The endpoint tuple of an edge";
  let description = [{
    The tuple has one component per endpoint; an unnamed tuple requires a
    homogeneous edge set. When an endpoint set is declared by a
    `simit.extern` of the module, the component type must be its element type.

    ```mlir
    %ends = simit.endpoints %springs[%s]
        : !simit.set<"springs", !Spring, ["points", "points"]> -> !simit.tuple<!Point x 2>
    ```
  }];
  let arguments = (ins Simit_SetType:$set, Simit_ElementType:$element);
  let results = (outs Simit_TupleType:$result);
  let assemblyFormat = "$set `[` $element `]` attr-dict `:` qualified(type($set)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_GridPointOp : Simit_Op<"grid_point", [Pure,
    AllTypesMatch<["point", "result"]>]> {
  let summary = "The grid point at an offset from a point";
  let description = [{
    Returns the point at a constant offset (one entry per grid dimension)
    from `point` on the grid. Grids are periodic.

    ```mlir
    %right = simit.grid_point %cells, %p [1, 0]
        : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
    ```
  }];
  let arguments = (ins Simit_SetType:$grid, Simit_ElementType:$point,
                       DenseI64ArrayAttr:$offsets);
  let results = (outs Simit_ElementType:$result);
  let assemblyFormat = "$grid `,` $point $offsets attr-dict `:` qualified(type($grid)) `,` qualified(type($point))";
  let hasVerifier = 1;
}

def Simit_GridEdgeOp : Simit_Op<"grid_edge", [Pure,
    TypesMatchWith<"result is the grid's element type", "grid", "result",
                   "::llvm::cast<::mlir::simit::SetType>($_self).getElementType()">]> {
  let summary = "The grid edge leaving a point in one direction";
  let description = [{
    Returns the edge that leaves the point at `offsets` from `point` in
    direction `dir`, which has exactly one component equal to 1 or -1.

    ```mlir
    %e = simit.grid_edge %cells, %p [0, 0] dir [0, 1]
        : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
    ```
  }];
  let arguments = (ins Simit_SetType:$grid, Simit_ElementType:$point,
                       DenseI64ArrayAttr:$offsets, DenseI64ArrayAttr:$dir);
  let results = (outs Simit_ElementType:$result);
  let assemblyFormat = [{
    $grid `,` $point $offsets `dir` $dir attr-dict `:` qualified(type($grid)) `,` qualified(type($point))
  }];
  let hasVerifier = 1;
}

//===----------------------------------------------------------------------===//
// Map and assembly
//===----------------------------------------------------------------------===//

class Simit_MapLikeOp<string mnemonic, list<Trait> traits = []>
    : Simit_Op<mnemonic, traits # [AttrSizedOperandSegments,
        DeclareOpInterfaceMethods<SymbolUserOpInterface>]> {
  code commonDescription = [{
    The function `@f` is called once per element of the set, in set order,
    with, in order: the extra arguments (evaluated once), the element, the
    endpoint tuple (when the set is an edge set and `@f` has a parameter left
    for it) and, with `through`, the grid. The results have `@f`'s result
    types; each result dimension is the mapped set, one of its endpoint sets
    or an integer range.

    Inside `@f`, every `simit.insert` into a value that flows to a result is
    indexed, on each set dimension, only by the element argument, a component
    of the endpoint tuple argument (`simit.tuple_get`), or a grid point near
    the element (`simit.grid_point`): an element function writes only to
    locations indexed by its own element and endpoints.
  }];
}

def Simit_MapOp : Simit_MapLikeOp<"map", [MemoryEffects<[MemRead, MemWrite]>]> {
  let summary = "Applies a function to every element of a set";
  let description = commonDescription # [{

    Results start at zero and every write stores: the last writer in set
    order wins. Without results this is `apply`, run for the function's
    effects on fields. With `result_inits`, result `i` starts as a copy of
    extra argument `result_inits[i]` of its type instead (-1: zero): the
    frontend's form of an `inout` extra argument, which `@f` writes as a
    result.

    ```mlir
    simit.map @move(%dt) to %points : (f64, !simit.set<"points", !Point>) -> ()
    %w2 = simit.map @clamp(%w) to %points {result_inits = array<i64: 0>}
        : (!simit.tensor<["points"] x f64>, !simit.set<"points", !Point>)
          -> !simit.tensor<["points"] x f64>
    %w = simit.map @weight() to %springs
        : (!simit.set<"springs", !Spring, ["points", "points"]>)
          -> !simit.tensor<["springs"] x f64>
    %A = simit.map @stencil() to %points through %cells
        : (!simit.set<"points", !Point>, !simit.set<"cells", !Cell, grid 2 over "points">)
          -> !simit.tensor<["points", "points"] x f64>
    ```
  }];
  let arguments = (ins FlatSymbolRefAttr:$callee, Variadic<AnyType>:$extras,
                       Simit_SetType:$set, Optional<Simit_SetType>:$grid,
                       OptionalAttr<DenseI64ArrayAttr>:$result_inits);
  let results = (outs Variadic<Simit_TensorOrScalar>:$results);
  let assemblyFormat = [{
    $callee `(` $extras `)` `to` $set (`through` $grid^)? attr-dict `:`
    functional-type(operands, results)
  }];
  let builders = [
    OpBuilder<(ins "TypeRange":$results, "StringRef":$callee,
                   "ValueRange":$extras, "Value":$set, "Value":$grid), [{
      build($_builder, $_state, results, callee, extras, set, grid,
            DenseI64ArrayAttr());
    }]>
  ];
  let hasVerifier = 1;
}

def Simit_AssembleOp : Simit_MapLikeOp<"assemble", [MemoryEffects<[MemRead, MemWrite]>]> {
  let summary = "Assembles global tensors from per-element contributions";
  let description = commonDescription # [{

    Each result starts at zero, and every per-element contribution (every
    write to a result inside `@f`, also repeated writes of one location) is
    combined into it with the reduction, which is associative and
    commutative. The sparsity of an assembled matrix follows the set's
    endpoints (or is diagonal for a vertex set).

    ```mlir
    %K, %f = simit.assemble @springForce(%k) to %springs reduce <add>
        : (f64, !simit.set<"springs", !Spring, ["points", "points"]>)
          -> (!simit.tensor<["points", "points"] x tensor<3x3xf64>>,
              !simit.tensor<["points"] x tensor<3xf64>>)
    ```
  }];
  let arguments = (ins FlatSymbolRefAttr:$callee, Variadic<AnyType>:$extras,
                       Simit_SetType:$set, Optional<Simit_SetType>:$grid,
                       Simit_ReductionAttr:$reduction);
  let results = (outs Variadic<Simit_TensorOrScalar>:$results);
  let assemblyFormat = [{
    $callee `(` $extras `)` `to` $set (`through` $grid^)? `reduce` $reduction
    attr-dict `:` functional-type(operands, results)
  }];
  let hasVerifier = 1;
}

//===----------------------------------------------------------------------===//
// Index expressions
//===----------------------------------------------------------------------===//

def Simit_IndexExprOp : Simit_Op<"index_expr", [RecursiveMemoryEffects]> {
  let summary = "Tensor index notation";
  let description = [{
    Computes a tensor (or scalar) in index notation. Index variables are
    declared with their domains: each ranges over a whole dimension
    hierarchy, written as its levels from the outer dimension inwards, each
    a set name or an integer range (`"points" x 3` for the dimension of
    `!simit.tensor<["points"] x tensor<3xf64>>`). The result lists its free
    variables; every operand lists one variable per dimension. The body sees
    one scalar component of each operand (a block argument of its component
    type) and yields the component of the result; variables that do not
    appear in the result are summed over (add reduction).

    ```mlir
    // C(i, j) = sum_k A(i, k) * B(k, j)
    %C = simit.index_expr [i : "points" x 3, j : "points" x 3, k : "points" x 3]
         (i, j) = (%A(i, k), %B(k, j))
         : (!simit.tensor<["points", "points"] x tensor<3x3xf64>>,
            !simit.tensor<["points", "points"] x tensor<3x3xf64>>)
           -> !simit.tensor<["points", "points"] x tensor<3x3xf64>> {
    ^bb0(%a: f64, %b: f64):
      %p = arith.mulf %a, %b : f64
      simit.yield %p : f64
    }
    ```

    Each variable's domain equals every dimension it indexes; result
    variables appear exactly once in the result, and every variable is used.
  }];
  let arguments = (ins Variadic<Simit_TensorOrScalar>:$inputs,
                       StrArrayAttr:$index_vars, ArrayAttr:$domains,
                       DenseI64ArrayAttr:$result_indices,
                       TypedArrayAttrBase<DenseI64ArrayAttr, "index lists">:$input_indices);
  let results = (outs Simit_TensorOrScalar:$result);
  let regions = (region SizedRegion<1>:$body);
  let hasCustomAssemblyFormat = 1;
  let hasVerifier = 1;
  let hasRegionVerifier = 1;
  let skipDefaultBuilders = 1;
  let builders = [
    OpBuilder<(ins "::mlir::Type":$resultType, "::mlir::ValueRange":$inputs,
                   "::mlir::ArrayAttr":$indexVars, "::mlir::ArrayAttr":$domains,
                   "::llvm::ArrayRef<int64_t>":$resultIndices,
                   "::llvm::ArrayRef<::llvm::SmallVector<int64_t>>":$inputIndices)>
  ];
  let extraClassDeclaration = [{
    /// The index list (variable positions) of input `i`.
    ::llvm::ArrayRef<int64_t> getInputIndexList(unsigned i) {
      return ::llvm::cast<::mlir::DenseI64ArrayAttr>(getInputIndices()[i]).asArrayRef();
    }
    /// The domain hierarchy of variable `v`.
    ::mlir::ArrayAttr getDomain(unsigned v) {
      return ::llvm::cast<::mlir::ArrayAttr>(getDomains()[v]);
    }
  }];
}

def Simit_YieldOp : Simit_Op<"yield", [Pure, Terminator, ReturnLike,
    HasParent<"::mlir::simit::IndexExprOp">]> {
  let summary = "Yields the scalar result component of an index expression";
  let description = [{
    ```mlir
    simit.yield %x : f64
    ```
  }];
  let arguments = (ins Simit_ScalarType:$value);
  let assemblyFormat = "$value attr-dict `:` qualified(type($value))";
}

//===----------------------------------------------------------------------===//
// Linear algebra
//===----------------------------------------------------------------------===//

class Simit_ElementwiseBinaryOp<string mnemonic, string what>
    : Simit_Op<mnemonic, [Pure, SameOperandsAndResultType]> {
  let summary = "Element-wise " # what # " of two tensors";
  let description = [{
    Both operands and the result have one tensor type (a builtin ranked
    tensor or a `!simit.tensor`) with a numeric component type.

    ```mlir
    %c = simit.}] # mnemonic # [{ %a, %b : !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$lhs, Simit_TensorLike:$rhs);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = "$lhs `,` $rhs attr-dict `:` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_AddOp : Simit_ElementwiseBinaryOp<"add", "sum"> {
  let hasFolder = 1;
}
def Simit_SubOp : Simit_ElementwiseBinaryOp<"sub", "difference"> {
  let hasFolder = 1;
}
def Simit_MulOp : Simit_ElementwiseBinaryOp<"mul", "product (`.*`)">;
def Simit_DivOp : Simit_ElementwiseBinaryOp<"div", "quotient (`./`)">;

def Simit_NegOp : Simit_Op<"neg", [Pure, SameOperandsAndResultType]> {
  let summary = "Negates every component of a tensor";
  let description = [{
    ```mlir
    %n = simit.neg %a : tensor<3xf64>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$operand);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = "$operand attr-dict `:` qualified(type($result))";
  let hasVerifier = 1;
  let hasFolder = 1;
}

def Simit_ScaleOp : Simit_Op<"scale", [Pure, AllTypesMatch<["tensor", "result"]>]> {
  let summary = "Multiplies every component of a tensor by a scalar";
  let description = [{
    The scalar's type is the tensor's component type. Scaling by one folds to
    the tensor; scaling by zero canonicalises to `simit.zeros` (assuming
    finite components).

    ```mlir
    %s = simit.scale %h, %v : f64, !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let arguments = (ins Simit_ScalarType:$scalar, Simit_TensorLike:$tensor);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = "$scalar `,` $tensor attr-dict `:` qualified(type($scalar)) `,` qualified(type($tensor))";
  let hasVerifier = 1;
  let hasFolder = 1;
  let hasCanonicalizer = 1;
}

def Simit_MatVecOp : Simit_Op<"matvec", [Pure]> {
  let summary = "Matrix-vector product";
  let description = [{
    `y = A x`: the vector's dimension hierarchy equals the matrix's column
    hierarchy, and the result's equals its row hierarchy.

    ```mlir
    %y = simit.matvec %K, %x
        : !simit.tensor<["points", "points"] x tensor<3x3xf64>>,
          !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$matrix, Simit_TensorLike:$vector);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $matrix `,` $vector attr-dict `:` qualified(type($matrix)) `,` qualified(type($vector)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_MatMulOp : Simit_Op<"matmul", [Pure]> {
  let summary = "Matrix-matrix product";
  let description = [{
    ```mlir
    %C = simit.matmul %A, %B : tensor<2x3xf64>, tensor<3x4xf64> -> tensor<2x4xf64>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$lhs, Simit_TensorLike:$rhs);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $lhs `,` $rhs attr-dict `:` qualified(type($lhs)) `,` qualified(type($rhs)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_TransposeOp : Simit_Op<"transpose", [Pure]> {
  let summary = "Swaps the dimensions of a matrix, blocks included";
  let description = [{
    ```mlir
    %t = simit.transpose %A
        : !simit.tensor<["points", "springs"] x tensor<2x3xf64>>
          -> !simit.tensor<["springs", "points"] x tensor<3x2xf64>>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$operand);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = "$operand attr-dict `:` qualified(type($operand)) `->` qualified(type($result))";
  let hasVerifier = 1;
  let hasFolder = 1;
}

def Simit_DotOp : Simit_Op<"dot", [Pure]> {
  let summary = "Inner product of two vectors";
  let description = [{
    ```mlir
    %d = simit.dot %a, %b : tensor<3xf64>, tensor<3xf64> -> f64
    ```
  }];
  let arguments = (ins Simit_TensorLike:$lhs, Simit_TensorLike:$rhs);
  let results = (outs Simit_ScalarType:$result);
  let assemblyFormat = [{
    $lhs `,` $rhs attr-dict `:` qualified(type($lhs)) `,` qualified(type($rhs)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_OuterOp : Simit_Op<"outer", [Pure]> {
  let summary = "Outer product of two vectors";
  let description = [{
    ```mlir
    %m = simit.outer %a, %b : tensor<3xf64>, tensor<2xf64> -> tensor<3x2xf64>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$lhs, Simit_TensorLike:$rhs);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $lhs `,` $rhs attr-dict `:` qualified(type($lhs)) `,` qualified(type($rhs)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_NormOp : Simit_Op<"norm", [Pure]> {
  let summary = "Euclidean norm of a vector";
  let description = [{
    The result is a float of the vector's precision (the modulus for complex
    components).

    ```mlir
    %n = simit.norm %v : !simit.tensor<["points"] x tensor<3xf64>> -> f64
    ```
  }];
  let arguments = (ins Simit_TensorLike:$operand);
  let results = (outs AnyFloat:$result);
  let assemblyFormat = "$operand attr-dict `:` qualified(type($operand)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_DetOp : Simit_Op<"det", [Pure]> {
  let summary = "Determinant of a dense 2x2, 3x3 or 4x4 float matrix";
  let description = [{
    ```mlir
    %d = simit.det %m : tensor<3x3xf64> -> f64
    ```
  }];
  let arguments = (ins AnyRankedTensor:$operand);
  let results = (outs AnyFloat:$result);
  let assemblyFormat = "$operand attr-dict `:` qualified(type($operand)) `->` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_InvOp : Simit_Op<"inv", [Pure, SameOperandsAndResultType]> {
  let summary = "Inverse of a dense 2x2, 3x3 or 4x4 float matrix";
  let description = [{
    ```mlir
    %i = simit.inv %m : tensor<3x3xf64>
    ```
  }];
  let arguments = (ins AnyRankedTensor:$operand);
  let results = (outs AnyRankedTensor:$result);
  let assemblyFormat = "$operand attr-dict `:` qualified(type($result))";
  let hasVerifier = 1;
}

def Simit_CrossOp : Simit_Op<"cross", [Pure, SameOperandsAndResultType]> {
  let summary = "Cross product of two dense float 3-vectors";
  let description = [{
    ```mlir
    %c = simit.cross %a, %b : tensor<3xf64>
    ```
  }];
  let arguments = (ins AnyRankedTensor:$lhs, AnyRankedTensor:$rhs);
  let results = (outs AnyRankedTensor:$result);
  let assemblyFormat = "$lhs `,` $rhs attr-dict `:` qualified(type($result))";
  let hasVerifier = 1;
}

//===----------------------------------------------------------------------===//
// Printing and strings
//===----------------------------------------------------------------------===//

def Simit_PrintOp : Simit_Op<"print", [MemoryEffects<[MemWrite]>]> {
  let summary = "Prints values, optionally followed by a newline";
  let description = [{
    Prints the values without separators (`print`), then a newline when
    `newline` is set (`println`). Values are scalars, tensors (local or
    system) and strings.

    ```mlir
    simit.print %s, %x {newline} : !simit.string, f64
    ```
  }];
  let arguments = (ins Variadic<AnyType>:$values, UnitAttr:$newline);
  let assemblyFormat = "$values attr-dict `:` qualified(type($values))";
  let hasVerifier = 1;
}

def Simit_StringConstantOp : Simit_Op<"string_constant", [Pure]> {
  let summary = "A string literal";
  let description = [{
    ```mlir
    %s = simit.string_constant "abc"
    ```
  }];
  let arguments = (ins StrAttr:$value);
  let results = (outs Simit_StringType:$result);
  let assemblyFormat = "$value attr-dict";
}

def Simit_StringConcatOp : Simit_Op<"string_concat", [Pure]> {
  let summary = "Concatenates two strings";
  let description = [{
    ```mlir
    %s = simit.string_concat %a, %b
    ```
  }];
  let arguments = (ins Simit_StringType:$lhs, Simit_StringType:$rhs);
  let results = (outs Simit_StringType:$result);
  let assemblyFormat = "$lhs `,` $rhs attr-dict";
}

def Simit_StringCmpOp : Simit_Op<"string_cmp", [Pure]> {
  let summary = "Compares two strings lexicographically";
  let description = [{
    ```mlir
    %lt = simit.string_cmp <lt> %a, %b
    ```
  }];
  let arguments = (ins Simit_StringPredicateAttr:$predicate,
                       Simit_StringType:$lhs, Simit_StringType:$rhs);
  let results = (outs I1:$result);
  let assemblyFormat = "$predicate $lhs `,` $rhs attr-dict";
}

include "simit/Dialect/Simit/IR/SimitFusionOps.td"
include "simit/Dialect/Simit/IR/SimitStorageOps.td"
include "simit/Dialect/Simit/IR/SimitSolverOps.td"

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITOPS_TD
