//===- SimitDialect.td - The simit dialect -----------------*- tablegen -*-===//
//
// The dialect definition and the base classes of its types, attributes and
// operations.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_DIALECT_SIMIT_IR_SIMITDIALECT_TD
#define SIMIT_DIALECT_SIMIT_IR_SIMITDIALECT_TD

include "mlir/IR/OpBase.td"
include "mlir/IR/AttrTypeBase.td"

def Simit_Dialect : Dialect {
  let name = "simit";
  let cppNamespace = "::mlir::simit";
  let summary = "Hypergraph sets, system tensors, maps and index expressions "
                "of the Simit language";
  let description = [{
    The `simit` dialect is the high-level IR of the Simit physical-simulation
    language. A program describes a physical system as a hypergraph: sets of
    elements (records of tensor fields), where every element of an edge set
    connects a fixed number of elements of its endpoint sets. Local functions
    on elements are mapped over sets to update fields or to assemble global
    sparse vectors and matrices, which are then combined with linear algebra.

    The dialect has value semantics: every tensor-valued operation takes and
    returns SSA values, and mutable variables are explicit `!simit.ref<T>`
    slots. Scalars are builtin types (`f64` or `f32`, `i32`, `i1`,
    `complex<f64>`), and local dense tensors are builtin ranked tensors
    (`tensor<3x3xf64>`). Tensors with set dimensions (system tensors) and
    blocked tensors are `!simit.tensor`, whose dimensions are set names or
    integer ranges and whose block type makes blocking part of the type.

    Sets are identified by name: two sets with one element type are different
    sets, and the dimensions of system tensors refer to sets by name.
  }];
  let useDefaultTypePrinterParser = 1;
  let useDefaultAttributePrinterParser = 1;
  let extraClassDeclaration = [{
  private:
    void registerTypes();
    void registerAttributes();
    void registerInterfaces();
  }];
}

class Simit_Type<string name, string typeMnemonic, list<Trait> traits = []>
    : TypeDef<Simit_Dialect, name, traits> {
  let mnemonic = typeMnemonic;
}

class Simit_Attr<string name, string attrMnemonic, list<Trait> traits = []>
    : AttrDef<Simit_Dialect, name, traits> {
  let mnemonic = attrMnemonic;
}

class Simit_Op<string mnemonic, list<Trait> traits = []>
    : Op<Simit_Dialect, mnemonic, traits>;

#endif // SIMIT_DIALECT_SIMIT_IR_SIMITDIALECT_TD
