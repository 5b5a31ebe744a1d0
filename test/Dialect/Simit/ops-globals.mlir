// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>

// CHECK: simit.extern @points : !simit.set<"points", !Point>
// CHECK: simit.extern @dt : tensor<2xf64>
// CHECK: simit.extern @steps : i32
// CHECK: simit.extern @K : !simit.tensor<["points", "points"] x f64>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @dt : tensor<2xf64>
simit.extern @steps : i32
simit.extern @K : !simit.tensor<["points", "points"] x f64>

// CHECK-LABEL: func.func @globals
func.func @globals() -> (!simit.set<"points", !Point>, tensor<2xf64>) {
  // CHECK: %[[S:.*]] = simit.get_set @points : !simit.set<"points", !Point>
  %s = simit.get_set @points : !simit.set<"points", !Point>
  // CHECK: %[[R:.*]] = simit.extern_ref @dt : !simit.ref<tensor<2xf64>>
  %r = simit.extern_ref @dt : !simit.ref<tensor<2xf64>>
  // CHECK: %[[V:.*]] = simit.load %[[R]] : !simit.ref<tensor<2xf64>>
  %v = simit.load %r : !simit.ref<tensor<2xf64>>
  // CHECK: return %[[S]], %[[V]]
  return %s, %v : !simit.set<"points", !Point>, tensor<2xf64>
}

// CHECK-LABEL: func.func @variables
func.func @variables(%x : f64) -> f64 {
  // CHECK: %[[A:.*]] = simit.alloc : !simit.ref<f64>
  %a = simit.alloc : !simit.ref<f64>
  // CHECK: simit.store %{{.*}}, %[[A]] : !simit.ref<f64>
  simit.store %x, %a : !simit.ref<f64>
  // CHECK: simit.load %[[A]] : !simit.ref<f64>
  %v = simit.load %a : !simit.ref<f64>
  // CHECK: simit.alloc : !simit.ref<!simit.tensor<["points"] x tensor<3xf64>>>
  %t = simit.alloc : !simit.ref<!simit.tensor<["points"] x tensor<3xf64>>>
  // CHECK: simit.alloc : !simit.ref<!simit.opaque>
  %h = simit.alloc : !simit.ref<!simit.opaque>
  return %v : f64
}
