//===- Passes.td - Passes on the simit dialect -------------*- tablegen -*-===//
//
// Every pass on simit IR is declared here (no `let constructor`: tblgen
// generates `create<Name>()`), and registerSimitPasses() registers them all.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_TD
#define SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_TD

include "mlir/Pass/PassBase.td"

def SimitCheckSetNames : Pass<"simit-check-set-names", "::mlir::ModuleOp"> {
  let summary = "Checks that every set named by a type is declared";
  let description = [{
    Types refer to sets by name: the dimensions of `!simit.tensor` and the
    endpoint and point sets of `!simit.set`. A type verifier cannot see the
    module, so this pass checks that every such name is the name of a set
    declared by a `simit.extern` or by a set-typed function parameter of the
    module, and reports each undeclared name at the first operation whose
    types use it.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect"];
}

def SimitInlineFunctions : Pass<"simit-inline-functions", "::mlir::ModuleOp"> {
  let summary = "Inlines every call of a function with a body";
  let description = [{
    Simit has no recursion, so every `func.call` of a function defined in the
    module is inlined (bottom-up through nested calls), after which system
    matrices flow from their assembly to their uses inside one function.
    Functions on simit values that are not exported (`simit.export`) and
    that no operation references any more are erased; element functions
    referenced by `simit.map` / `simit.assemble` stay (the loop lowering
    inlines them into the set loops). The pass registers the dialect's
    inliner interface (registerSimitInlinerInterface).
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect",
                           "::mlir::func::FuncDialect"];
}

def SimitShermanMorrison : Pass<"simit-sherman-morrison", "::mlir::ModuleOp"> {
  let summary = "Solves a sparse matrix plus an outer product by Sherman–Morrison";
  let description = [{
    Rewrites `simit.solve (A + u v^T), b` — a `simit.add` of a system matrix
    A and a `simit.outer` of two system vectors, in either order, or a
    `simit.sub` of A and the outer product, solved as A + (-u) v^T with a
    `simit.neg` of u — into two solves with A and the runtime's last step:

    ```mlir
    %w = simit.solve %A, %u {simit.solve_note = "Sherman-Morrison A^-1 u"}
    %c = simit.solve %A, %b {simit.solve_note = "Sherman-Morrison A^-1 b"}
    %x = func.call @simit_rt_sherman_morrison(%A, %u, %v, %b, %w, %c)
    ```

    so the dense matrix A + u v^T is never formed. With a direct solver
    both solves use one factorisation of A (the SolveSession's cache); the
    last step computes x = c - w (v.c) / (1 + v.w), or, when |1 + v.w| is
    tiny next to |v||w|, solves the bordered system [A u; v^T -1] instead
    of dividing (docs/solvers.md). A that itself holds an outer product (the
    rank-k form A + u1 v1^T + u2 v2^T) is left alone, as are u v^T - A and
    other forms. Run it after simit-inline-functions.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect",
                           "::mlir::func::FuncDialect"];
}

def SimitFoldSceneConstants
    : Pass<"simit-fold-scene-constants", "::mlir::ModuleOp"> {
  let summary = "Folds externs a scene marks constant and uniform fields";
  let description = [{
    The host states what does not change while a scene runs by attributes on
    the `simit.extern`s (docs/scene-specialisation.md):

    ```mlir
    simit.extern @h : f64 {simit.constant = 1.0e-02 : f64}
    simit.extern @points : !Points {simit.uniform_fields = {m = 2.0 : f64}}
    ```

    A `simit.load` of the slot of an extern with `simit.constant` becomes an
    `arith.constant` of the value, unless the module stores to that slot. A
    `simit.elem_read` of a field named in `simit.uniform_fields` becomes a
    constant when the element is the mapped element of its element function,
    or an endpoint of it, and every map and assembly calling the function
    runs over the set holding the field (or sets whose endpoints there are
    that set); a field written anywhere in the module (by `simit.elem_write`
    to an element of the set's element type, or `simit.field_write`) is
    never folded. Then arith folds the constants on, and an `scf.if` whose
    condition became constant keeps only the branch taken. Run it after
    simit-inline-functions.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect",
                           "::mlir::arith::ArithDialect",
                           "::mlir::scf::SCFDialect"];
}

def SimitEliminateDeadAssemblies
    : Pass<"simit-eliminate-dead-assemblies", "::mlir::ModuleOp"> {
  let summary = "Drops the results of maps and assemblies that nothing uses";
  let description = [{
    A `simit.map` or `simit.assemble` result without uses is not computed:
    the op is rebuilt with the used results only, calling a copy of its
    element function that returns only those (named `<f>_live_<i>_<j>...`
    after the kept result positions), so the writes into the dropped results
    and whatever only they needed die with them. A map none of whose results
    is used is erased when its element function writes no field and calls
    nothing (writes into its own local variables do not count); otherwise it
    stays, without results, for its effects. An element function no op
    refers to any more is erased. Run it after simit-inline-functions, when
    the uses of every assembly are in one function.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect",
                           "::mlir::func::FuncDialect"];
}

def SimitAssignStorage : Pass<"simit-assign-storage", "::mlir::ModuleOp"> {
  let summary = "Gives every system matrix its storage encoding";
  let description = [{
    A sparse forward data-flow analysis over the `#simit.storage` lattice
    (docs/storage.md), then a rewrite that puts the encodings into the types
    of results, block arguments and `!simit.ref` slots of matrices over two
    sets, and inserts `simit.convert` where an operand is widened (or, for
    `simit.mul` and `simit.div`, restricted) to the encoding its use needs.
    Assemblies and maps give `diag`, `pattern`, `incidence` or its
    transpose from the set types, and `stencil` from the offsets the element
    function writes through a grid; `add`/`sub` join, `mul` keeps the
    smaller storage, `matmul` composes (`product`), `transpose` is a view,
    `zeros` is `empty`, variables and `scf` values join what reaches them.
    What has no storage (element-wise products of unrelated storages,
    matrices passed to or returned from exported functions, loops whose
    storage keeps growing) is reported once, where it arises, with notes at
    the operations the operands' storage comes from. Element functions are
    left as they are: they return one element's contributions. Run it after
    simit-inline-functions; it is not part of the pipelines yet.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect"];
}

def SimitLinalgToIndexExpr : Pass<"simit-linalg-to-index-expr", "::mlir::ModuleOp"> {
  let summary = "Rewrites linear algebra on system tensors as index expressions";
  let description = [{
    `simit.add`, `sub`, `mul`, `div`, `neg`, `scale`, `matvec`, `matmul`,
    `transpose`, `dot`, `outer` and `norm` whose operands have a set
    dimension become `simit.index_expr` (a norm becomes the index expression
    of the sum of squares, then `math.sqrt`). Operations on local (builtin)
    tensors are left to the loop lowering.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect",
                           "::mlir::arith::ArithDialect",
                           "::mlir::math::MathDialect"];
}

def SimitIndexProductsToMatMul : Pass<"simit-index-products-to-matmul", "::mlir::ModuleOp"> {
  let summary = "Matrix products written in index notation become simit.matmul";
  let description = [{
    In `C(i,j) = A(i,k) * B(k,j) + D(j,i)` on system matrices of scalars,
    the sum over `k` of the product of two matrices each indexed by `k`
    once (a `simit.index_sum` over `k` alone, or the whole body when `k` is
    the expression's one summed variable) becomes an input `P(i,j)` with
    `P = simit.matmul` of the two (each transposed when its index list puts
    `k` on the other side), and `k` leaves the expression. The lowering
    builds the product's pattern from the operands' patterns, which a loop
    over the index variables cannot enumerate.
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect"];
}

def SimitFuseIndexExpr : Pass<"simit-fuse-index-expr", "::mlir::ModuleOp"> {
  let summary = "Fuses chains of index expressions into one loop nest";
  let description = [{
    An index expression whose result is used only as an input of another
    index expression, indexed by that expression's variables, is inlined into
    its consumer: its reduction variables become a `simit.index_sum` inside
    the consumer's body, so `x + A * b` becomes one loop nest with a scalar
    temporary per row and no vector temporary (the paper's Figure 10).
  }];
  let dependentDialects = ["::mlir::simit::SimitDialect"];
}

def ConvertSimitToLoops : Pass<"convert-simit-to-loops", "::mlir::ModuleOp"> {
  let summary = "Lowers the simit dialect to loops over sets and BCSR memrefs";
  let description = [{
    Produces func/scf/arith/math/memref/vector IR. Vectors over sets become
    memref<?x block x T> field-shaped arrays, matrices assembled from an edge
    set become BCSR value arrays over the set's pattern (rowptr, colidx and a
    per-edge location table bound by the host), matrices assembled from a
    vertex set become diagonal block arrays; local tensors become flat
    vectors. Maps and assemblies become scf.parallel loops over the set with
    the element function inlined; index expressions become loop nests that
    follow the matrices' sparsity. Exported functions (`simit.export`) take
    their parameters and then the data they touch, in a canonical order,
    described by their `simit.bindings` attribute (docs/lowering.md); the
    element functions and externs are erased. Unsupported input is reported
    on the operation.

    With `prefetch-scatter-blocks` (the CPU pipeline's setting), an element
    loop that accumulates into blocks of a BCSR matrix prefetches them
    (`memref.prefetch`) at the start of each element, from its location
    table. With `prefetch-matrix-bytes=N` (the CPU pipeline's setting), a
    loop over the blocks of a BCSR row prefetches, at each block, the block
    of each matrix it reads that lies N bytes further on in its value
    array (the row's next blocks, then the next rows'), clamped to the
    array's last block.
  }];
  let options = [
    Option<"prefetchScatterBlocks", "prefetch-scatter-blocks", "bool",
           /*default=*/"false",
           "Prefetch the BCSR blocks an element accumulates into at the "
           "start of the element">,
    Option<"prefetchMatrixBytes", "prefetch-matrix-bytes", "int64_t",
           /*default=*/"0",
           "Loops over a BCSR row's blocks prefetch the matrices they read "
           "this many bytes ahead (0: no prefetch)">,
  ];
  let dependentDialects = ["::mlir::func::FuncDialect",
                           "::mlir::scf::SCFDialect",
                           "::mlir::arith::ArithDialect",
                           "::mlir::cf::ControlFlowDialect",
                           "::mlir::math::MathDialect",
                           "::mlir::memref::MemRefDialect",
                           "::mlir::vector::VectorDialect",
                           "::mlir::complex::ComplexDialect",
                           "::mlir::LLVM::LLVMDialect"];
}

def SimitParallelLoops : Pass<"simit-parallel-loops", "::mlir::ModuleOp"> {
  let summary = "Marks the set loops that may run on all cores, deterministically";
  let description = [{
    Classifies every outermost `scf.parallel` of a function by the memory
    its body touches, and marks those whose iterations may run concurrently
    with `simit.parallel = "<kind>"` (simit-parallel-loops-to-openmp runs
    them on all cores); the results do not depend on the number of threads.
    - owned: every memref the loop writes is indexed, in every access, at
      one position by an induction variable or by a block of the
      iteration's row (`for k = rowptr[i] to rowptr[i + 1]`, from a
      `*_rowptr` binding): the loop is marked as it is.
    - reduction: an owned loop with `scf.reduce` results whose combiners
      are single arith operations with a neutral element becomes an
      `scf.parallel` over chunks of `reduction-chunk` iterations (marked),
      each reducing its iterations in order from the neutral element into a
      partial, then an `scf.for` that combines the loop's initial values
      with the partials in chunk order.
    - scatter: a loop over all elements of a set (`0 to set_size`) whose
      other written memrefs are indexed, in every access, at one position by
      an endpoint of the element (`endpoints[e, k]`) or by the location of a
      block between its endpoints (`pattern_locations[e, k]`) runs colour by
      colour: the function gets an `element_colours` binding of the set
      (chunks of `scatter-chunk` consecutive elements, coloured by the host
      so that no two chunks of a colour share an endpoint), an `scf.for`
      over the colours runs a marked `scf.parallel` over the colour's
      chunks, which runs the original loop on the chunk's elements.
    Every other loop stays as it is and runs sequentially: loops with calls,
    with accesses the pass cannot place, through two views of one buffer,
    with small constant trip counts, or with other combiners. Nested loops
    run inside their outermost loop's iteration. Distinct arguments are
    assumed not to overlap (the host binds distinct arrays).

    With `set-order-only` (for targets that run every `scf.parallel`
    concurrently, the GPU) the pass marks nothing and changes only the
    element loops (`simit.scatter`, no results) that must run in set order
    because their elements read what others write: each becomes a
    one-iteration `scf.parallel` around an `scf.for` over the set.
  }];
  let options = [
    Option<"reductionChunk", "reduction-chunk", "int64_t", /*default=*/"1024",
           "Iterations reduced in order into one partial result">,
    Option<"scatterChunk", "scatter-chunk", "int64_t", /*default=*/"32",
           "Consecutive elements per coloured chunk of a scatter loop">,
    Option<"setOrderOnly", "set-order-only", "bool", /*default=*/"false",
           "Only make the element loops that must run in set order "
           "sequential inside one-iteration parallel loops">,
  ];
  let dependentDialects = ["::mlir::arith::ArithDialect",
                           "::mlir::memref::MemRefDialect",
                           "::mlir::scf::SCFDialect"];
}

def SimitParallelLoopsToOpenMP : Pass<"simit-parallel-loops-to-openmp", "::mlir::ModuleOp"> {
  let summary = "Runs the loops simit-parallel-loops marked on OpenMP threads";
  let description = [{
    Every `scf.parallel` with the `simit.parallel` attribute (and no
    results) becomes an `omp.parallel` region holding an `omp.wsloop` over
    an `omp.loop_nest` with the loop's bounds and body. The static stack
    slots (`memref.alloca`) of the body move to the start of the parallel
    region: each thread reuses one set for its iterations. Other loops are
    left to run sequentially. The number of threads is the OpenMP runtime's
    (the engine sets it, docs/threads.md). A region whose body calls
    `@simit_rt_fail` (simit-lower-assertions) is followed by a call of
    `@simit_rt_raise_parallel_failure()`: inside the region the failure is
    only recorded, since no thread may leave it early, and the call ends
    the run with it once every thread has.

    A loop with too little work to share runs on the calling thread alone:
    an `owned` loop of fewer than `min-iterations` iterations, a
    `reduction` or `scatter` loop over fewer than two chunks. Waking the
    other threads costs microseconds, more than a vector update over a few
    hundred points takes. A loop whose body has at most `max-copied-ops`
    operations (vector updates and dot products, not element functions) is
    copied: `scf.if` runs the region when the work is enough, else the
    copy, an unmarked `scf.parallel` (sequential); a larger one gets the
    region's `if` clause (the region on one thread). The order of the work,
    and so every result, is the same either way.
  }];
  let options = [
    Option<"minIterations", "min-iterations", "int64_t", /*default=*/"2048",
           "Owned loops of fewer iterations run on one thread">,
    Option<"maxCopiedOps", "max-copied-ops", "int64_t", /*default=*/"256",
           "Loops whose body has at most this many operations get a "
           "sequential copy for when they run on one thread">,
  ];
  let dependentDialects = ["::mlir::omp::OpenMPDialect",
                           "::mlir::arith::ArithDialect",
                           "::mlir::func::FuncDialect",
                           "::mlir::memref::MemRefDialect",
                           "::mlir::scf::SCFDialect"];
}

def SimitVectorizeElementLoops : Pass<"simit-vectorize-element-loops", "::mlir::ModuleOp"> {
  let summary = "Runs element kernels on several elements at once, one per vector lane";
  let description = [{
    Every one-dimensional `scf.parallel` without results and with step 1
    that simit-parallel-loops left unmarked (the loop over one chunk of a
    set, or a set loop that runs in order) is split in two: a loop that
    steps `lanes` elements at a time, then the loop as it was for the
    elements after the last whole step. In the first, the body's arithmetic
    (element-wise arith and math ops, vector ops at constant positions,
    loads from memory the loop does not write, and local tensors held in
    stack slots that are only read and written whole or at constant
    positions) runs once on vectors of `lanes` components, one element per
    lane; everything else (stores, scatters, calls, ifs, loops) then runs
    for each element in order, reading what it needs of the vectors from
    stack buffers. `lanes` is `vector-bits` divided by the width of the
    widest floating-point type the kernel computes in. Each lane computes
    what the scalar loop computes, in the same order, so results do not
    change. Loops with fewer than `min-vector-ops` floating-point
    operations (counting components) are left alone. Run it after
    simit-parallel-loops and before simit-parallel-loops-to-openmp.
  }];
  let options = [
    Option<"vectorBits", "vector-bits", "unsigned", /*default=*/"512",
           "Width of the machine's vectors in bits">,
    Option<"minVectorOps", "min-vector-ops", "int64_t", /*default=*/"64",
           "Fewest floating-point operations (counting components) a loop "
           "body needs to be vectorised">,
  ];
  let dependentDialects = ["::mlir::vector::VectorDialect",
                           "::mlir::memref::MemRefDialect",
                           "::mlir::arith::ArithDialect"];
}

def SimitHoistParallelAllocas : Pass<"simit-hoist-parallel-allocas", "::mlir::func::FuncOp"> {
  let summary = "Moves stack slots out of scf.parallel bodies (CPU, sequential)";
  let description = [{
    A `memref.alloca` with a static shape in the body of an `scf.parallel`
    (an automatic allocation scope: one slot per iteration) moves to the
    entry block of the function. On the CPU the pipeline runs `scf.parallel`
    loops sequentially (scf-to-cf), which keeps no per-iteration stack
    scope, so without this every element of a set would add its local
    variables to the stack. One slot for all iterations is only correct when
    the iterations run one after another: slots inside an `omp.parallel`
    region stay there (simit-parallel-loops-to-openmp already put them at
    its start, one set per thread); the GPU backend keeps the slots in the
    loop body.
  }];
  let dependentDialects = ["::mlir::memref::MemRefDialect"];
}

def SimitUnrollLocalTensorLoops : Pass<"simit-unroll-local-tensor-loops", "::mlir::ModuleOp"> {
  let summary = "Fully unrolls small loops that index local tensors";
  let description = [{
    Unrolls every `scf.for` with constant bounds whose induction variable
    decides the position of a `vector.extract` or `vector.insert` in its
    body (a component of a local tensor, LowerLocalTensors.cpp), inner loops
    first, when the unrolled body has at most `max-unrolled-ops` ops. A
    dynamic position forces LLVM to keep the whole vector in memory; after
    unrolling and canonicalization every position is a constant and the
    local tensors of element functions stay in registers. Run it after
    convert-simit-to-loops, followed by canonicalization.
  }];
  let options = [
    Option<"maxUnrolledOps", "max-unrolled-ops", "int64_t",
           /*default=*/"16384",
           "Loops whose trip count times body size exceeds this stay loops">,
  ];
  let dependentDialects = ["::mlir::arith::ArithDialect"];
}

def SimitGuardIntegerDivision : Pass<"simit-guard-integer-division", "::mlir::func::FuncOp"> {
  let summary = "Asserts that integer divisions and mods cannot trap";
  let description = [{
    Before every `arith` integer division or remainder on integers (not
    `index`) whose divisor is not a constant, inserts `cf.assert`s that the
    divisor is not zero and, for signed division, that the quotient does not
    overflow (the minimum integer divided by -1). Both trap on x86 (SIGFPE)
    and are undefined in LLVM, so without the check a program could kill
    the process that runs it. A signed remainder by -1 is 0 and needs no
    error: its divisor becomes 1 instead. The messages name the operation's
    source position. Run it after convert-simit-to-loops.
  }];
  let dependentDialects = ["::mlir::arith::ArithDialect",
                           "::mlir::cf::ControlFlowDialect",
                           "::mlir::vector::VectorDialect"];
}

def SimitRecordHostABI : Pass<"simit-record-host-abi", "::mlir::ModuleOp"> {
  let summary = "Records each exported function's host signature in attributes";
  let description = [{
    Stamps every `func.func` that carries `simit.bindings` with
    `simit.host_type`, its function type as the host sees it (memrefs,
    scalars, vectors), and `simit.memref_convention`, `"descriptor"` or
    `"bare_pointer"` as the conversion to LLVM that follows will pass its
    memrefs. The pipelines run it just before that conversion; the
    attributes stay on the `llvm.func`, where the engine reads the signature
    (simit/ABI/BindingKind.h names them). A function whose bindings do not
    match its arguments in number is an error.
  }];
  let options = [
    Option<"barePointers", "bare-pointers", "bool", /*default=*/"false",
           "Memrefs will be passed as bare pointers to their data">
  ];
}

def SimitConvertToLLVM : Pass<"simit-convert-to-llvm", "::mlir::ModuleOp"> {
  let summary = "Converts vector, ub, arith, index, complex, memref, OpenMP, "
                "func and cf to the LLVM dialect in one conversion";
  let description = [{
    The last step of the CPU pipeline. The upstream passes
    (`convert-vector-to-llvm`, `convert-arith-to-llvm`,
    `finalize-memref-to-llvm`, `convert-func-to-llvm`, ...) each walk the
    whole module and leave casts between them; on the unrolled element
    kernels of a simulation that costs a third of the lowering time. This
    pass first applies the vector lowerings that `convert-vector-to-llvm`
    applies (contractions, shape casts, transposes, masks ...), then runs one
    partial conversion with the patterns of all those dialects on one
    `LLVMTypeConverter` (the module's data layout). `math` is converted
    before (`convert-math-to-llvm`, then `convert-math-to-libm` for what
    LLVM has no intrinsic for); `reconcile-unrealized-casts` follows.
  }];
  let options = [
    Option<"useGenericFunctions", "use-generic-functions", "bool",
           /*default=*/"false",
           "memref.alloc and dealloc call _mlir_memref_to_llvm_alloc/free "
           "(the runtime's allocator) instead of malloc/free">
  ];
  let dependentDialects = ["::mlir::LLVM::LLVMDialect"];
}

def SimitLowerAssertions : Pass<"simit-lower-assertions", "::mlir::ModuleOp"> {
  let summary = "Turns cf.assert into a call of the runtime's simit_rt_fail";
  let description = [{
    `cf.assert %ok, "message"` becomes an `scf.if %ok` around the rest of
    its block, whose other branch calls `@simit_rt_fail(<message>)`
    (declared `func.func private @simit_rt_fail(!llvm.ptr)`) and yields
    zeros (poison for types without one) for the values the rest defines.
    The runtime ends the run of the exported function in progress with the
    message as its error and the host keeps running, where the control-flow
    dialect's own lowering would abort the process. Inside an OpenMP
    parallel region the call returns instead (the failure is raised when the
    region ends, simit-parallel-loops-to-openmp), so the guarded operations
    must not run. The assertions come from the loop lowering (dynamic
    indices into local tensors) and simit-guard-integer-division.
    Assertions inside `gpu` ops (launches, kernels) are left to the GPU
    lowering, which makes them device assertions.
  }];
  let dependentDialects = ["::mlir::scf::SCFDialect",
                           "::mlir::arith::ArithDialect",
                           "::mlir::func::FuncDialect",
                           "::mlir::ub::UBDialect",
                           "::mlir::LLVM::LLVMDialect"];
}

def SimitTimePhases : Pass<"simit-time-phases", "::mlir::ModuleOp"> {
  let summary = "Times the assemblies and solves of exported functions";
  let description = [{
    Brackets work in exported functions with calls of the runtime's phase
    timer (`@simit_rt_phase_begin(i32)` / `@simit_rt_phase_end(i32)`), so
    that a driver can split a time step into assembly and solve:
    - phase 0, assembly: every `simit.map` and `simit.assemble`;
    - phase 1, solve: every `simit.solve`, and every `scf.while` at the top
      level of an exported function that contains no map or assembly (an
      iterative solver written in Simit, after simit-inline-functions).
    Work inside a timed op is not timed again. Run it after
    simit-inline-functions; `simit-cpu-pipeline{time-phases=1}` does.
  }];
  let dependentDialects = ["::mlir::arith::ArithDialect",
                           "::mlir::func::FuncDialect"];
}

def SimitCheckNumerics : Pass<"simit-check-numerics", "::mlir::ModuleOp"> {
  let summary = "Marks the assemblies and solves whose results are checked";
  let description = [{
    Gives every `simit.map` and `simit.assemble` with results, every
    `simit.solve` and every call of a solver runtime function (`lusolve`,
    `lltsolve`, ...) in an exported function, whose results include a
    system tensor of floats, the attribute
    `simit.check_numerics = {op = "<what> (<file>:<line>:<col>)",
    results = ["<name>", ...]}`: the source construct and the name of each
    result (an element function's result name, `solution` for solves).
    A map or apply whose element function writes float fields of its
    element (`inout`) is marked too, with `fields = ["<field>", ...]`.
    convert-simit-to-loops then calls the runtime's scan of each such
    result array and field (`simit_rt_check_numerics_f64`/`_f32`), which
    records the
    first NaN or infinity of a run for the host
    (simit::takeNumericsProblem()). Run it after simit-inline-functions, so
    that the solves of inlined functions are marked;
    `simit-cpu-pipeline{check-numerics=1}` does.
  }];
}

def SimitCpuPipeline : Pass<"simit-cpu-pipeline", "::mlir::ModuleOp"> {
  let summary = "Runs every Simit lowering down to the LLVM dialect";
  let description = [{
    Inlines functions, folds the constants the host marked
    (simit-fold-scene-constants), drops unused map results
    (simit-eliminate-dead-assemblies), solves sparse-plus-outer-product
    systems by Sherman–Morrison, rewrites linear algebra as index expressions, fuses
    them, lowers to loops, unrolls the loops that index local tensors
    (simit-unroll-local-tensor-loops), marks the set loops that may run on all cores and
    makes their results independent of the number of threads
    (simit-parallel-loops), with `element-vector-bits` runs element kernels
    across vector lanes (simit-vectorize-element-loops), frees temporaries,
    with `openmp` runs the marked loops on OpenMP threads
    (simit-parallel-loops-to-openmp), moves the stack slots out of the
    sequential parallel loops, and lowers to the LLVM
    dialect (vector to scf, scf to cf, vector, math, arith, index, memref,
    OpenMP, func and cf to LLVM, reconcile casts). The pipeline is
    buildSimitCpuPipeline(), which the JIT runs as well.
  }];
  let options = [
    Option<"timePhases", "time-phases", "bool", /*default=*/"false",
           "Time assemblies and solves with simit-time-phases">,
    Option<"checkNumerics", "check-numerics", "bool", /*default=*/"false",
           "Scan the results of assemblies and solves for NaN and infinity "
           "(simit-check-numerics)">,
    Option<"runtimeAllocator", "runtime-allocator", "bool",
           /*default=*/"false",
           "Allocate heap memory through the Simit runtime's "
           "_mlir_memref_to_llvm_alloc/free (the JIT's block cache) instead "
           "of malloc/free">,
    Option<"shermanMorrison", "sherman-morrison", "bool", /*default=*/"true",
           "Solve sparse-plus-outer-product systems by Sherman–Morrison "
           "(simit-sherman-morrison)">,
    Option<"openmp", "openmp", "bool", /*default=*/"false",
           "Run the loops simit-parallel-loops marks on OpenMP threads "
           "(simit-parallel-loops-to-openmp); off, they run sequentially in "
           "the same order of chunks and colours">,
    Option<"reductionChunk", "reduction-chunk", "int64_t",
           /*default=*/"1024",
           "simit-parallel-loops: iterations per partial of a reduction">,
    Option<"scatterChunk", "scatter-chunk", "int64_t", /*default=*/"32",
           "simit-parallel-loops: elements per coloured chunk of a scatter "
           "loop">,
    Option<"foldSceneConstants", "fold-scene-constants", "bool",
           /*default=*/"true",
           "Fold the externs and uniform fields the host marked "
           "(simit-fold-scene-constants)">,
    Option<"eliminateDeadAssemblies", "eliminate-dead-assemblies", "bool",
           /*default=*/"true",
           "Drop map and assembly results nothing uses "
           "(simit-eliminate-dead-assemblies)">,
    Option<"prefetchMatrixBytes", "prefetch-matrix-bytes", "int64_t",
           /*default=*/"1024",
           "convert-simit-to-loops: how far ahead, in bytes, loops over a "
           "BCSR row's blocks prefetch the matrices they read (0: no "
           "prefetch)">,
    Option<"elementVectorBits", "element-vector-bits", "unsigned",
           /*default=*/"0",
           "simit-vectorize-element-loops: width of the machine's vectors in "
           "bits (0: element loops are not vectorised)">,
  ];
}

//===----------------------------------------------------------------------===//
// The GPU path: set loops to gpu.launch, NVVM and PTX (docs/gpu.md)
//===----------------------------------------------------------------------===//

def SimitGpuScatterAtomics : Pass<"simit-gpu-scatter-atomics", "::mlir::ModuleOp"> {
  let summary = "Makes accumulations that iterations of a set loop share atomic";
  let description = [{
    In an `scf.parallel` loop, an accumulation `M[i] = M[i] + x` (or `- x`)
    into a memref defined outside the loop becomes `memref.atomic_rmw addf`
    (`addi` for integers) unless the store's indices contain every induction
    variable of the outermost parallel loop, so that no two iterations can
    write one location. This is what makes assembly scatters (through a
    location table or endpoint indices) safe when the iterations run in
    parallel. Thread-private memrefs (allocated inside the loop) are left.
  }];
  let dependentDialects = ["::mlir::memref::MemRefDialect",
                           "::mlir::arith::ArithDialect"];
}

def SimitParallelLoopsToGpu : Pass<"simit-parallel-loops-to-gpu", "::mlir::ModuleOp"> {
  let summary = "Maps outermost scf.parallel loops of host functions to gpu.launch";
  let description = [{
    Every outermost `scf.parallel` in a `func.func` becomes a one-dimensional
    `gpu.launch` of `ceil(trip count / block-size)` blocks of `block-size`
    threads; thread `blockIdx.x * block-size + threadIdx.x` runs the
    iteration of that linear index (multi-dimensional loops are linearised,
    the last dimension fastest) when it is in range. Scalar reductions
    (`scf.reduce` with an `arith.addf` or `arith.addi` combiner) become a
    per-thread partial (the identity for threads out of range), a
    `gpu.all_reduce add` over the block, and one `memref.atomic_rmw` per
    block into a scalar accumulator that starts at the loop's initial value;
    the loop's result is loaded from it after the launch. Other combiners are
    reported as errors. Run `simit-gpu-scatter-atomics` first.
    With fp-contract (the default, like nvcc's -fmad=true), floating-point
    operations in kernels carry the `contract` fast-math flag, so that a
    multiply feeding an add becomes one fused multiply-add.
  }];
  let options = [
    Option<"blockSize", "block-size", "int64_t", /*default=*/"256",
           "Threads per block">,
    Option<"fpContract", "fp-contract", "bool", /*default=*/"true",
           "Let kernels fuse floating-point multiplies and adds">
  ];
  let dependentDialects = ["::mlir::gpu::GPUDialect",
                           "::mlir::memref::MemRefDialect",
                           "::mlir::arith::ArithDialect",
                           "::mlir::scf::SCFDialect"];
}

def SimitGpuDeviceMemory : Pass<"simit-gpu-device-memory", "::mlir::ModuleOp"> {
  let summary = "Gives every host memref that a kernel uses a device copy";
  let description = [{
    For each memref defined outside the `gpu.launch` ops of a function and
    used inside one, the pass allocates a device buffer (`gpu.alloc`) where
    the memref is defined, copies the host contents in (`gpu.memcpy`) unless
    the memref was freshly allocated, and makes the kernels use the device
    buffer. The data stays on the device between launches. Host operations
    that touch the memref are bracketed by copies: device to host before the
    outermost enclosing host-only operation (when a kernel writes the
    memref), host to device after it (when the host may write). Before the
    end of the defining block (a function argument's: the return), data that
    kernels wrote is copied back and the device buffer is freed; a memref
    with `memref.dealloc` frees its device buffer there instead. Memrefs
    with a non-identity layout or a memory space are reported as errors.
  }];
  let dependentDialects = ["::mlir::gpu::GPUDialect",
                           "::mlir::memref::MemRefDialect",
                           "::mlir::arith::ArithDialect"];
}

def SimitGpuPipeline : Pass<"simit-gpu-pipeline", "::mlir::ModuleOp"> {
  let summary = "Lowers loops-level IR to LLVM with kernels compiled to PTX";
  let description = [{
    With lower-simit, first lowers simit IR to loops as simit-cpu-pipeline
    does (inlining, index expressions, fusion, convert-simit-to-loops) and
    frees temporaries (buffer deallocation). Then it runs
    simit-gpu-scatter-atomics, simit-parallel-loops-to-gpu,
    simit-gpu-device-memory, gpu-launch-sink-index-computations,
    gpu-kernel-outlining and gpu-async-region, then MLIR's NVVM pipeline
    (gpu-lower-to-nvvm-pipeline): host code to the LLVM dialect with GPU
    runtime calls (mgpu*), kernels to NVVM, and `gpu-module-to-binary`, which
    with format=isa embeds PTX text and needs no CUDA installation.
  }];
  let options = [
    Option<"chip", "chip", "std::string", /*default=*/"\"sm_90\"",
           "NVIDIA GPU architecture of the kernels">,
    Option<"features", "features", "std::string", /*default=*/"\"+ptx80\"",
           "PTX ISA version feature">,
    Option<"format", "format", "std::string", /*default=*/"\"isa\"",
           "gpu-module-to-binary format: isa (PTX text), bin or fatbin "
           "(these two need CUDA's ptxas)">,
    Option<"optLevel", "opt-level", "int", /*default=*/"3",
           "Optimisation level of the kernel compilation">,
    Option<"blockSize", "block-size", "int64_t", /*default=*/"256",
           "Threads per block">,
    Option<"fpContract", "fp-contract", "bool", /*default=*/"true",
           "Let kernels fuse floating-point multiplies and adds">,
    Option<"lowerSimit", "lower-simit", "bool", /*default=*/"false",
           "Start from simit IR: first run the passes of the CPU pipeline "
           "up to convert-simit-to-loops, then buffer deallocation">
  ];
}

#endif // SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_TD
