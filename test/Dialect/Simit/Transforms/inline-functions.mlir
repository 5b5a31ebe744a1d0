// RUN: simit-opt %s --simit-inline-functions --split-input-file --verify-diagnostics | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @scaled(%s : f64, %v : tensor<3xf64>) -> tensor<3xf64> {
  %r = simit.scale %s, %v : f64, tensor<3xf64>
  return %r : tensor<3xf64>
}

// Calls of calls are inlined bottom-up.
func.func @twice(%s : f64, %v : tensor<3xf64>) -> tensor<3xf64> {
  %a = func.call @scaled(%s, %v) : (f64, tensor<3xf64>) -> tensor<3xf64>
  %b = func.call @scaled(%s, %a) : (f64, tensor<3xf64>) -> tensor<3xf64>
  return %b : tensor<3xf64>
}

// The element function stays (a map refers to it); its calls are inlined.
// CHECK-LABEL: func.func @force
// CHECK-NOT: call
// CHECK: simit.scale
// CHECK: simit.scale
// CHECK: simit.insert
func.func @force(%p : !Point) -> !F {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  %f = func.call @twice(%m, %x) : (f64, tensor<3xf64>) -> tensor<3xf64>
  %z = simit.zeros : !F
  %r = simit.insert %f into %z[%p] : tensor<3xf64> into !F, (!Point)
  return %r : !F
}

func.func @total(%v : !F) -> f64 {
  %d = simit.dot %v, %v : !F, !F -> f64
  return %d : f64
}

// CHECK-LABEL: func.func @step
// CHECK-SAME: attributes {simit.export}
// CHECK: simit.assemble @force
// CHECK-NEXT: simit.dot
// CHECK-NOT: call
// CHECK: return
func.func @step() -> f64 attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %f = simit.assemble @force() to %points reduce <add> : (!Points) -> !F
  %t = func.call @total(%f) : (!F) -> f64
  return %t : f64
}

// Helpers nothing refers to any more are erased; host code without simit
// is kept.
// CHECK-NOT: func.func @scaled
// CHECK-NOT: func.func @twice
// CHECK-NOT: func.func @total
// CHECK-LABEL: func.func @host
func.func @host(%a : f64) -> f64 {
  %b = arith.addf %a, %a : f64
  return %b : f64
}

// -----

// A function that is no longer exported (the engine's entry functions,
// docs/scene-specialisation.md) is erased, and then the element function
// only its map referred to.

!Point = !simit.element<"Point", {m : f64}>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// CHECK-NOT: func.func @mass
// CHECK-NOT: func.func @uncalled
// CHECK-LABEL: func.func @called
func.func @mass(%p : !Point) -> !V {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %z = simit.zeros : !V
  %r = simit.insert %m into %z[%p] : f64 into !V, (!Point)
  return %r : !V
}

func.func @uncalled() {
  %points = simit.get_set @points : !Points
  %m = simit.assemble @mass() to %points reduce <add> : (!Points) -> !V
  simit.field_write %m, %points["m"] : !V, !Points
  return
}

func.func @called() attributes {simit.export} {
  return
}

// -----

// expected-error @below {{recursive calls cannot be inlined (Simit has no recursion)}}
module {
  func.func @f(%a : f64) -> f64 {
    %b = func.call @f(%a) : (f64) -> f64
    return %b : f64
  }
}
