//===- SimitTypes.td - Types of the simit dialect ----------*- tablegen -*-===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITTYPES_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITTYPES_TD

include "simit/Dialect/Simit/IR/SimitDialect.td"
include "mlir/IR/BuiltinTypeInterfaces.td"

def Simit_ElementType : Simit_Type<"Element", "element"> {
  let summary = "A named record of tensor fields";
  let description = [{
    An element type is a named record. Field types are scalars, builtin
    ranked tensors, or `!simit.tensor` types with integer dimensions only
    (nested local blocks). Field names are unique. Elements of a set are
    values of its element type; they designate members of the set.

    Element types print as aliases named after the element, e.g.

    ```mlir
    !Spring = !simit.element<"Spring", {k : f64, l0 : f64, x : tensor<3xf64>}>
    ```
  }];
  let parameters = (ins
    "::mlir::StringAttr":$name,
    ArrayRefParameter<"::mlir::StringAttr", "field names">:$fieldNames,
    ArrayRefParameter<"::mlir::Type", "field types">:$fieldTypes);
  let hasCustomAssemblyFormat = 1;
  let genVerifyDecl = 1;
  let extraClassDeclaration = [{
    /// The number of fields.
    unsigned getNumFields() const { return getFieldNames().size(); }
    /// The position of the field called `name`, if there is one.
    std::optional<unsigned> getFieldIndex(::llvm::StringRef name) const;
    /// The type of the field called `name`, or null if there is none.
    ::mlir::Type getFieldType(::llvm::StringRef name) const;
  }];
}

def Simit_SetType : Simit_Type<"Set", "set"> {
  let summary = "A set of elements: vertex set, edge set or grid edge set";
  let description = [{
    A set of elements of one element type, identified by its name. A vertex
    set has no endpoints. Every element of an edge set connects one element
    of each of its (ordered) endpoint sets, named by their set names; the
    endpoint sets may differ (heterogeneous edge sets). A grid edge set of
    rank `n` connects neighbouring points of an `n`-dimensional grid laid over
    a vertex set.

    ```mlir
    !simit.set<"points", !Point>
    !simit.set<"springs", !Spring, ["points", "points"]>
    !simit.set<"cells", !Cell, grid 2 over "points">
    ```

    For a grid edge set, `endpoints` holds the single point set and
    `gridRank` the number of grid dimensions; `gridRank` is 0 otherwise.
  }];
  let parameters = (ins
    "::mlir::StringAttr":$name,
    "::mlir::Type":$elementType,
    ArrayRefParameter<"::mlir::StringAttr", "endpoint set names">:$endpoints,
    "unsigned":$gridRank);
  let builders = [
    TypeBuilder<(ins "::llvm::StringRef":$name, "::mlir::Type":$elementType,
                     CArg<"::llvm::ArrayRef<::mlir::StringAttr>", "{}">:$endpoints), [{
      return $_get($_ctxt, ::mlir::StringAttr::get($_ctxt, name), elementType,
                   endpoints, 0);
    }]>
  ];
  let hasCustomAssemblyFormat = 1;
  let genVerifyDecl = 1;
  let extraClassDeclaration = [{
    /// The element type as an ElementType.
    ElementType getElement() const {
      return ::llvm::cast<ElementType>(getElementType());
    }
    /// The number of endpoints of every element: 0 for a vertex set, 2 for a
    /// grid edge set (an edge joins two neighbouring points).
    unsigned getCardinality() const {
      return isGrid() ? 2 : getEndpoints().size();
    }
    /// Whether every endpoint comes from one set (true for vertex sets).
    bool isHomogeneous() const;
    /// Whether this is a grid edge set.
    bool isGrid() const { return getGridRank() != 0; }
    /// The name of the i-th endpoint set.
    ::mlir::StringAttr getEndpoint(unsigned i) const {
      return isGrid() ? getEndpoints().front() : getEndpoints()[i];
    }
  }];
}

def Simit_SystemTensorType : Simit_Type<"SystemTensor", "tensor"> {
  let summary = "A tensor whose dimensions are sets or integer ranges, with "
                "a block type";
  let description = [{
    A (typically sparse, global) tensor whose outer dimensions are set names
    or positive integer ranges, and whose components are blocks of the block
    type: a scalar, a builtin ranked tensor, or another `!simit.tensor` with
    integer dimensions (nested blocks). A tensor block has the container's
    order: dimension `i` of the whole tensor is the hierarchy (outer `i`,
    block `i`, ...).

    ```mlir
    !simit.tensor<["points", "points"] x tensor<3x3xf64>>
    !simit.tensor<["points", 3] x f64>
    !simit.tensor<[8] x tensor<3xf64>>
    ```

    A tensor of integer ranges with a scalar block is a builtin tensor
    (`tensor<8xf64>`), so this type requires a set dimension or a tensor block.

    A matrix over two sets may carry a trailing storage encoding
    (`#simit.storage`, assigned by `simit-assign-storage`); without one its
    storage is not assigned yet:

    ```mlir
    !simit.tensor<["points", "points"] x tensor<3x3xf64>,
                  #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>
    ```
  }];
  let parameters = (ins "::mlir::ArrayAttr":$dims, "::mlir::Type":$blockType,
                        OptionalParameter<"StorageAttr", "the storage encoding">:$encoding);
  let skipDefaultBuilders = 1;
  let builders = [
    TypeBuilder<(ins "::mlir::ArrayAttr":$dims, "::mlir::Type":$blockType,
                     CArg<"StorageAttr", "{}">:$encoding), [{
      return $_get($_ctxt, dims, blockType, encoding);
    }]>
  ];
  let hasCustomAssemblyFormat = 1;
  let genVerifyDecl = 1;
  let extraClassDeclaration = [{
    /// The number of outer dimensions.
    unsigned getOrder() const { return getDims().size(); }
    /// Whether some dimension, outer or in a nested block, is a set.
    bool isSystem() const;
    /// The innermost scalar type.
    ::mlir::Type getComponentType() const;
    /// The shape of the block (empty for a scalar block); a nested
    /// `!simit.tensor` block contributes its outer integer dimensions.
    ::llvm::SmallVector<int64_t> getBlockShape() const;
    /// This type with another encoding (null: none).
    SystemTensorType withEncoding(StorageAttr encoding) const {
      return get(getContext(), getDims(), getBlockType(), encoding);
    }
    /// Whether this is a matrix whose two outer dimensions are sets: the
    /// tensors that may carry an encoding.
    bool isSetMatrix() const;
  }];
}

def Simit_TupleType : Simit_Type<"Tuple", "tuple"> {
  let summary = "An endpoint tuple of elements";
  let description = [{
    The tuple of endpoints of an edge. An unnamed tuple holds `n` elements of
    one type; a named tuple names each component and may be heterogeneous.

    ```mlir
    !simit.tuple<!Bead x 2>
    !simit.tuple<{left : !Node, right : !Link}>
    ```
  }];
  let parameters = (ins
    ArrayRefParameter<"::mlir::Type", "component element types">:$elementTypes,
    ArrayRefParameter<"::mlir::StringAttr", "component names (empty when unnamed)">:$names);
  let hasCustomAssemblyFormat = 1;
  let genVerifyDecl = 1;
  let extraClassDeclaration = [{
    unsigned size() const { return getElementTypes().size(); }
    bool isNamed() const { return !getNames().empty(); }
  }];
}

def Simit_RefType : Simit_Type<"Ref", "ref"> {
  let summary = "A mutable slot holding a value";
  let description = [{
    A mutable variable of the program: a slot holding a scalar, a builtin
    tensor, a `!simit.tensor`, a `!simit.opaque` or a `!simit.string`. Slots
    are created by `simit.alloc` or `simit.extern_ref` and accessed with
    `simit.load` and `simit.store`.

    ```mlir
    !simit.ref<tensor<3xf64>>
    ```
  }];
  let parameters = (ins "::mlir::Type":$valueType);
  let assemblyFormat = "`<` $valueType `>`";
  let genVerifyDecl = 1;
}

def Simit_OpaqueType : Simit_Type<"Opaque", "opaque"> {
  let summary = "A host handle";
  let description = [{
    A handle owned by the host or runtime, such as a solver factorisation. It
    can only be stored, assigned and passed.
  }];
}

def Simit_StringType : Simit_Type<"String", "string"> {
  let summary = "An immutable text string";
  let description = [{
    An immutable string value, created by `simit.string_constant`.
  }];
}

//===----------------------------------------------------------------------===//
// Type constraints
//===----------------------------------------------------------------------===//

def Simit_ScalarType : Type<
    CPred<"::mlir::simit::isScalarType($_self)">, "Simit scalar (float, integer or complex)">;

def Simit_TensorLike : Type<
    CPred<"::mlir::simit::isTensorType($_self)">,
    "builtin ranked tensor or !simit.tensor">;

def Simit_TensorOrScalar : Type<
    CPred<"::mlir::simit::isTensorOrScalarType($_self)">,
    "scalar, builtin ranked tensor or !simit.tensor">;

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITTYPES_TD
