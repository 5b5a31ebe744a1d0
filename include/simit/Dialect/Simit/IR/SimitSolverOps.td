//===- SimitSolverOps.td - Solves and factorisations -------*- tablegen -*-===//
//
// Linear solves of the language (`\`, lu/chol and their solves,
// triangularSolve) and the last step of simit-sherman-morrison, as ops:
// passes match them by kind, never calls by name, and their verifiers check
// operand shapes where the program is written.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITSOLVEROPS_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITSOLVEROPS_TD

def Simit_SolveOp : Simit_Op<"solve", [Pure]> {
  let summary = "Solves a linear system (`A \\ b`)";
  let description = [{
    Returns `x` with `A x = b`: `b` is over `A`'s row hierarchy and `x` over
    its column hierarchy. Works on system and local tensors.

    ```mlir
    %x = simit.solve %K, %f
        : !simit.tensor<["points", "points"] x tensor<3x3xf64>>,
          !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$matrix, Simit_TensorLike:$rhs);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $matrix `,` $rhs attr-dict `:` qualified(type($matrix)) `,` qualified(type($rhs)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_TriangularSolveOp : Simit_Op<"triangular_solve", [Pure]> {
  let summary = "Solves with a matrix's lower triangle (`triangularSolve`)";
  let description = [{
    Returns `x` with `L x = b`, where `L` is the lower triangle of the
    matrix (its entries above the diagonal are not read): forward
    substitution. Shapes as for `simit.solve`.

    ```mlir
    %x = simit.triangular_solve %L, %b : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
    ```
  }];
  let arguments = (ins Simit_TensorLike:$matrix, Simit_TensorLike:$rhs);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $matrix `,` $rhs attr-dict `:` qualified(type($matrix)) `,` qualified(type($rhs)) `->` qualified(type($result))
  }];
  let hasVerifier = 1;
}

def Simit_FactorizeOp : Simit_Op<"factorize",
    [MemoryEffects<[MemAlloc<DefaultResource>]>]> {
  let summary = "Factorises a square matrix (`lu`, `chol`)";
  let description = [{
    A handle to the LU (partial pivoting) or Cholesky (LL^T) factorisation of
    a square float matrix, local or over two sets, for `simit.factor_solve`.
    The handle holds runtime memory until `simit.factor_free`. A singular or
    (for `chol`) not positive definite matrix stops the program with the
    op's source position.

    ```mlir
    %h = simit.factorize chol %K : !simit.tensor<["points", "points"] x tensor<3x3xf64>>
    ```
  }];
  let arguments = (ins Simit_FactorizationKind:$kind,
                       Simit_TensorLike:$matrix);
  let results = (outs Simit_OpaqueType:$factorization);
  let assemblyFormat = [{
    $kind $matrix attr-dict `:` qualified(type($matrix))
  }];
  let hasVerifier = 1;
}

def Simit_FactorSolveOp : Simit_Op<"factor_solve",
    [MemoryEffects<[MemRead<DefaultResource>]>]> {
  let summary = "Solves with a factorisation (`lusolve`, `lumatsolve`, ...)";
  let description = [{
    Returns `x` with `A x = b` for the matrix `A` that `simit.factorize` of
    the same kind factorised: a vector right-hand side (`lusolve`,
    `lltsolve`) or a matrix one, solved column by column (`lumatsolve`,
    `lltmatsolve`).

    ```mlir
    %x = simit.factor_solve chol %h, %b : !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
    ```
  }];
  let arguments = (ins Simit_FactorizationKind:$kind,
                       Simit_OpaqueType:$factorization,
                       Simit_TensorLike:$rhs);
  let results = (outs Simit_TensorLike:$result);
  let assemblyFormat = [{
    $kind $factorization `,` $rhs attr-dict `:` qualified(type($rhs)) `->` qualified(type($result))
  }];
  let extraClassDeclaration = [{
    /// The language's name of this solve: lusolve, lltsolve, lumatsolve or
    /// lltmatsolve.
    ::llvm::StringRef getIntrinsicName();
  }];
  let hasVerifier = 1;
}

def Simit_FactorFreeOp : Simit_Op<"factor_free",
    [MemoryEffects<[MemFree<DefaultResource>]>]> {
  let summary = "Releases a factorisation (`lufree`, `cholfree`)";
  let description = [{
    ```mlir
    simit.factor_free chol %h
    ```
  }];
  let arguments = (ins Simit_FactorizationKind:$kind,
                       Simit_OpaqueType:$factorization);
  let assemblyFormat = "$kind $factorization attr-dict";
}

def Simit_WoodburyOp : Simit_Op<"woodbury", [Pure, AttrSizedOperandSegments]> {
  let summary = "The last step of a solve of A plus k outer products";
  let description = [{
    `x` with `(A + sum_i u_i v_i^T) x = b`, given the solutions `w_i` of
    `A w_i = u_i` and `c` of `A c = b` (simit-sherman-morrison):
    `x = c - W (I + V^T W)^-1 V^T c` (Sherman-Morrison for k = 1, Woodbury
    otherwise). When the k x k system is near singular relative to its
    terms, the runtime solves the bordered system `[A U; V^T -I]` instead,
    which is why `A` is an operand. `b` and the `u_i` are over A's rows;
    `c`, the `v_i`, the `w_i` and `x` over its columns. Their types are
    written once when they are one (A's rows and columns are one set),
    else as `rows -> columns`.

    ```mlir
    %x = simit.woodbury %A, %b, %c, u[%u], v[%v], w[%w]
        : !simit.tensor<["p", "p"] x f64>, !simit.tensor<["p"] x f64>
    ```
  }];
  let arguments = (ins Simit_SystemTensorType:$matrix,
                       Simit_SystemTensorType:$rhs,
                       Simit_SystemTensorType:$solution,
                       Variadic<Simit_SystemTensorType>:$us,
                       Variadic<Simit_SystemTensorType>:$vs,
                       Variadic<Simit_SystemTensorType>:$ws);
  let results = (outs Simit_SystemTensorType:$result);
  let assemblyFormat = [{
    $matrix `,` $rhs `,` $solution `,` `u` `[` $us `]` `,` `v` `[` $vs `]` `,`
    `w` `[` $ws `]` attr-dict `:` qualified(type($matrix)) `,`
    custom<VectorTypes>(type($rhs), type($solution), type($us), type($vs),
                        type($ws), type($result), ref($us))
  }];
  let extraClassDeclaration = [{
    /// k: the number of outer products.
    unsigned getRank() { return getUs().size(); }
    /// The largest k the runtime solves (simit_rt_woodbury<k>_bcsr).
    static constexpr unsigned kMaxRank = 4;
  }];
  let hasVerifier = 1;
}

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITSOLVEROPS_TD
