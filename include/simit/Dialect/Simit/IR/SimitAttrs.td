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

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITATTRS_TD
