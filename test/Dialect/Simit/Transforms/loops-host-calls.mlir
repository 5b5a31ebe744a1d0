// RUN: simit-opt %s --convert-simit-to-loops --canonicalize | FileCheck %s

// A host function (extern func) is called through a private shim whose
// memref parameters keep the arrays alive up to the call, and which passes
// them as pointers to the C symbol: the name with the precision's prefix,
// parameters then results, local tensors as (n, pointer), scalar results by
// pointer, an int status that must be 0. Their stack slots are made at
// the function's entry (once, however often the call runs), each new one
// first.
// CHECK-LABEL: func.func @scale(
// CHECK-SAME: %[[A:[^:]*]]: f64, %[[V:[^:]*]]: vector<3xf64>)
// CHECK: %[[SUM:.*]] = memref.alloca() : memref<1xf64>
// CHECK-NEXT: %[[OUT:.*]] = memref.alloca() : memref<3xf64>
// CHECK-NEXT: %[[IN:.*]] = memref.alloca() : memref<3xf64>
// CHECK-NEXT: vector.store %[[V]], %[[IN]]
// CHECK-NEXT: %[[INP:.*]] = memref.cast %[[IN]] : memref<3xf64> to memref<?xf64>
// CHECK-NEXT: %[[OUTP:.*]] = memref.cast %[[OUT]]
// CHECK-NEXT: %[[SUMP:.*]] = memref.cast %[[SUM]]
// CHECK: %[[STATUS:.*]] = call @simit_host.dscaled(%[[A]], %c3_i32, %[[INP]], %c3_i32, %[[OUTP]], %[[SUMP]])
// CHECK: %[[OK:.*]] = arith.cmpi eq, %[[STATUS]], %c0_i32
// CHECK: cf.assert %[[OK]], "extern func 'scaled' (host symbol 'dscaled') returned a non-zero status (h.sim:5:3)"
// CHECK: vector.load %[[OUT]]
// CHECK: memref.load %[[SUM]]
// No float crosses: the symbol is the name itself.
// CHECK: call @simit_host.count_calls(
// CHECK: func.func private @dscaled(f64, i32, !llvm.ptr, i32, !llvm.ptr, !llvm.ptr) -> i32
// CHECK-LABEL: func.func private @simit_host.dscaled(
// CHECK: memref.extract_aligned_pointer_as_index
// CHECK: llvm.inttoptr
// CHECK: call @dscaled(
// CHECK: func.func private @count_calls(!llvm.ptr) -> i32
// The Simit declarations are gone.
// CHECK-NOT: simit.extern_function
func.func private @scaled(f64, tensor<3xf64>) -> (tensor<3xf64>, f64) attributes {simit.extern_function = "scaled"}
func.func private @count_calls() -> i32 attributes {simit.extern_function = "count_calls"}
func.func @scale(%a : f64, %v : tensor<3xf64>) -> (tensor<3xf64>, f64, i32) attributes {simit.export} {
  %w, %s = func.call @scaled(%a, %v) : (f64, tensor<3xf64>) -> (tensor<3xf64>, f64) loc("h.sim":5:3)
  %n = func.call @count_calls() : () -> i32
  return %w, %s, %n : tensor<3xf64>, f64, i32
}
