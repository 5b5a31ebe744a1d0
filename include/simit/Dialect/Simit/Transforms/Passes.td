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

#endif // SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_TD
