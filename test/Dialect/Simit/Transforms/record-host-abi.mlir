// RUN: simit-opt %s --split-input-file --verify-diagnostics --simit-record-host-abi | FileCheck %s
// RUN: simit-opt %s --split-input-file --verify-diagnostics --simit-record-host-abi=bare-pointers=true | FileCheck %s --check-prefix=BARE

// A function with bindings keeps its host type and the convention of its
// memrefs; the conversion to LLVM keeps both on the llvm.func.
// CHECK-LABEL: func.func @step(
// CHECK-SAME: simit.host_type = (index, memref<?x3xf64>) -> f64
// CHECK-SAME: simit.memref_convention = "descriptor"
// BARE-LABEL: func.func @step(
// BARE-SAME: simit.memref_convention = "bare_pointer"
func.func @step(%n : index, %x : memref<?x3xf64>) -> f64
    attributes {simit.bindings = [{kind = "set_size", set = "points"},
                                  {kind = "field", set = "points", field = "x"}]} {
  %c = arith.constant 0.0 : f64
  return %c : f64
}

// Functions without bindings (runtime declarations, helpers) are left alone.
// CHECK-LABEL: func.func private @helper(
// CHECK-NOT: simit.host_type
func.func private @helper(memref<?xf64>)

// -----

// expected-error @below {{has 1 simit.bindings entries for 2 arguments}}
func.func @bad(%n : index, %m : index)
    attributes {simit.bindings = [{kind = "set_size", set = "points"}]} {
  return
}
