//===- SimitFusionOps.td - Nested sums of fused index exprs -*- tablegen -*-===//
//
// Added for simit-fuse-index-expr (lib/Dialect/Simit/Transforms): a fused
// index expression sums some variables inside its body, not around it.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITFUSIONOPS_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITFUSIONOPS_TD

def Simit_IndexSumOp : Simit_Op<"index_sum", [RecursiveMemoryEffects,
    ParentOneOf<["::mlir::simit::IndexExprOp", "::mlir::simit::IndexSumOp"]>]> {
  let summary = "Sums a scalar over index variables inside an index expression";
  let description = [{
    Inside the body of a `simit.index_expr`, sums the value its region yields
    over every value of the listed index variables (positions in the
    enclosing expression's variable list), with the other variables fixed.
    Block arguments of inputs indexed by a listed variable may only be used
    inside the region. The listed variables are not summed around the whole
    body. This is how fusion writes `y(i) = x(i) + sum_j A(i, j) b(j)` as one
    index expression, one loop nest and a scalar temporary per row:

    ```mlir
    %y = simit.index_expr [i : "points" x 3, j : "points" x 3]
         (i) = (%x(i), %A(i, j), %b(j)) : (!F, !K, !F) -> !F {
    ^bb0(%xi: f64, %aij: f64, %bj: f64):
      %s = simit.index_sum vars [1] : f64 {
        %p = arith.mulf %aij, %bj : f64
        simit.index_sum_yield %p : f64
      }
      %r = arith.addf %xi, %s : f64
      simit.yield %r : f64
    }
    ```
  }];
  let arguments = (ins DenseI64ArrayAttr:$vars);
  let results = (outs Simit_ScalarType:$result);
  let regions = (region SizedRegion<1>:$body);
  let assemblyFormat = "`vars` $vars attr-dict `:` type($result) $body";
}

def Simit_IndexSumYieldOp : Simit_Op<"index_sum_yield", [Pure, Terminator,
    ReturnLike, HasParent<"::mlir::simit::IndexSumOp">]> {
  let summary = "Yields the summand of a simit.index_sum";
  let arguments = (ins Simit_ScalarType:$value);
  let assemblyFormat = "$value attr-dict `:` type($value)";
}

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITFUSIONOPS_TD
