//===- SimitAttrs.td - Attributes of the simit dialect -----*- tablegen -*-===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITATTRS_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITATTRS_TD

include "simit/Dialect/Simit/IR/SimitDialect.td"
include "mlir/IR/EnumAttr.td"

def Simit_ReductionKind : I32EnumAttr<"ReductionKind",
    "an associative and commutative reduction", [
      I32EnumAttrCase<"Add", 0, "add">,
      I32EnumAttrCase<"Mul", 1, "mul">,
      I32EnumAttrCase<"Min", 2, "min">,
      I32EnumAttrCase<"Max", 3, "max">]> {
  let cppNamespace = "::mlir::simit";
  let genSpecializedAttr = 0;
}

def Simit_ReductionAttr : EnumAttr<Simit_Dialect, Simit_ReductionKind, "reduction"> {
  let summary = "The reduction that combines per-element contributions";
  let description = [{
    The reductions an assembly may use. Each is associative and commutative,
    so the contributions of the elements may be combined in any order.

    ```mlir
    #simit.reduction<add>
    ```
  }];
  let assemblyFormat = "`<` $value `>`";
}

def Simit_StringPredicate : I32EnumAttr<"StringPredicate",
    "a lexicographic string comparison", [
      I32EnumAttrCase<"eq", 0>,
      I32EnumAttrCase<"ne", 1>,
      I32EnumAttrCase<"lt", 2>,
      I32EnumAttrCase<"le", 3>,
      I32EnumAttrCase<"gt", 4>,
      I32EnumAttrCase<"ge", 5>]> {
  let cppNamespace = "::mlir::simit";
  let genSpecializedAttr = 0;
}

def Simit_StringPredicateAttr
    : EnumAttr<Simit_Dialect, Simit_StringPredicate, "string_predicate"> {
  let summary = "A lexicographic string comparison";
  let assemblyFormat = "`<` $value `>`";
}

def Simit_FactorizationKind : I32EnumAttr<"FactorizationKind",
    "a matrix factorisation", [
      I32EnumAttrCase<"LU", 0, "lu">,
      I32EnumAttrCase<"Cholesky", 1, "chol">]> {
  let cppNamespace = "::mlir::simit";
}

//===----------------------------------------------------------------------===//
// Storage of system matrices
//===----------------------------------------------------------------------===//

def Simit_StorageKind : I32EnumAttr<"StorageKind",
    "the kind of a system matrix storage encoding", [
      I32EnumAttrCase<"Dense", 0, "dense">,
      I32EnumAttrCase<"Empty", 1, "empty">,
      I32EnumAttrCase<"Diag", 2, "diag">,
      I32EnumAttrCase<"Pattern", 3, "pattern">,
      I32EnumAttrCase<"Incidence", 4, "incidence">,
      I32EnumAttrCase<"Transpose", 5, "transpose">,
      I32EnumAttrCase<"Stencil", 6, "stencil">,
      I32EnumAttrCase<"Union", 7, "union">,
      I32EnumAttrCase<"Product", 8, "product">,
      I32EnumAttrCase<"LowRank", 9, "lowrank">,
      I32EnumAttrCase<"Host", 10, "host">]> {
  let cppNamespace = "::mlir::simit";
  let genSpecializedAttr = 0;
}

def Simit_StorageAttr : Simit_Attr<"Storage", "storage"> {
  let summary = "Which blocks of a system matrix are stored";
  let description = [{
    The encoding of a `!simit.tensor` over two sets: the blocks (r, c) it
    stores, as a symbolic function of the sets. An encoding covers a superset
    of the structurally nonzero blocks (the others read as zero). The block
    type keeps the in-block layout; the encoding describes the two set
    levels only.

    | kind | blocks (r, c) stored |
    |---|---|
    | `dense` | all |
    | `empty` | none (the storage of `simit.zeros`) |
    | `diag("V")` | (r, r) |
    | `pattern("E", rows [i...], cols [j...])` | (endpoint_i(e), endpoint_j(e)) for e in E, i in rows, j in cols; plus every (r, r) when the rows and columns are one set |
    | `incidence("E", cols [j...])` | over (E, V): (e, endpoint_j(e)) |
    | `transpose(X)` | (c, r) per block (r, c) of X, kept in X's layout |
    | `stencil("G", [[o...], ...])` | (p, p + o) per offset o of grid G, periodic; offset 0 is always present |
    | `union(X, Y, ...)` | any member's |
    | `product(X, Y, ...)` | (r, c) with a path r -> m -> c through X then Y ... |
    | `lowrank(X, k)` | X's, plus k rank-one terms kept as factors |
    | `host("f", n)` | whatever host function `f` returned: the n-th matrix result of the host calls of the function, which carries its own row pointers and column indices |

    ```mlir
    #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
    #simit.storage<transpose(incidence("springs", cols [0, 1]))>
    #simit.storage<union(diag("points"), stencil("cells", [[0, 0], [1, 0]]))>
    #simit.storage<host("matrix_neg", 0)>
    ```

    Equal encodings are one attribute: the builders of `SimitStorage.h`
    canonicalise, and the verifier rejects text that is not canonical.
    Unions are flat, sorted, without duplicates, empty or dense members or
    members contained in another, and hold at most one stencil per grid.
    A `host` encoding contains only itself: two calls may return any two
    patterns.
    `transpose` does not wrap `transpose`, `diag`, `empty` or `lowrank`.
    Products are flat, have no `diag`, `empty` or `lowrank` factor and no
    factor pair `transpose(incidence(E, P))`, `incidence(E, Q)` (that is
    `pattern(E, P, Q)`). `lowrank` does not wrap `lowrank`. Positions and
    offsets are sorted and unique; a stencil holds offset 0. Whether
    positions and grids fit the sets is checked by `simit-assign-storage`,
    which sees the set types.
  }];
  let parameters = (ins
    EnumParameter<Simit_StorageKind>:$kind,
    OptionalParameter<"::mlir::StringAttr", "the set (diag), edge set or grid">:$set,
    OptionalArrayRefParameter<"int64_t", "row endpoint positions (pattern)">:$rows,
    OptionalArrayRefParameter<"int64_t", "column endpoint positions">:$cols,
    OptionalArrayRefParameter<"::mlir::DenseI64ArrayAttr", "stencil offsets">:$offsets,
    OptionalArrayRefParameter<"::mlir::Attribute", "member encodings">:$members,
    DefaultValuedParameter<"int64_t", "0", "rank-one terms (lowrank)">:$rank,
    DefaultValuedParameter<"int64_t", "0",
                           "which matrix result of a host call (host)">:$call);
  let hasCustomAssemblyFormat = 1;
  let genVerifyDecl = 1;
  let extraClassDeclaration = [{
    /// The i-th member of a transpose, union, product or lowrank.
    StorageAttr getMember(unsigned i) const {
      return ::llvm::cast<StorageAttr>(getMembers()[i]);
    }
    /// The encoding transpose, lowrank and a one-member wrapper hold.
    StorageAttr getOperand() const { return getMember(0); }
    /// Prints the encoding without the `#simit.storage<>` wrapper.
    void printBody(::llvm::raw_ostream &os) const;
    /// The body as printed, e.g. `diag("points")`.
    std::string str() const;
  }];
}

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITATTRS_TD
