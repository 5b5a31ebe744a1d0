// RUN: simit-opt %s -split-input-file -verify-diagnostics

!P = !simit.element<"P", {}>
// expected-error @+1 {{'simit.extern' op declares a set, a tensor or a scalar, got '!simit.tuple<}}
simit.extern @t : !simit.tuple<!P x 2>

// -----

func.func @f() {
  // expected-error @+1 {{'@nowhere' does not name a simit.extern}}
  %s = simit.get_set @nowhere : !simit.set<"points", !simit.element<"P", {}>>
  return
}

// -----

!P = !simit.element<"P", {}>
simit.extern @points : !simit.set<"points", !P>
func.func @f() {
  // expected-error @+1 {{result type '!simit.set<"nodes", !simit.element<"P", {}>>' differs from the declared type '!simit.set<"points", !simit.element<"P", {}>>' of @points}}
  %s = simit.get_set @points : !simit.set<"nodes", !P>
  return
}

// -----

!P = !simit.element<"P", {}>
simit.extern @points : !simit.set<"points", !P>
func.func @f() {
  // expected-error @+1 {{@points is a set; use simit.get_set to read it}}
  %r = simit.extern_ref @points : !simit.ref<f64>
  return
}

// -----

simit.extern @dt : tensor<2xf64>
func.func @f() {
  // expected-error @+1 {{slot type 'tensor<3xf64>' differs from the declared type 'tensor<2xf64>' of @dt}}
  %r = simit.extern_ref @dt : !simit.ref<tensor<3xf64>>
  return
}

// -----

func.func @f() {
  // expected-error @+1 {{'@g' does not name a simit.extern}}
  %r = simit.extern_ref @g : !simit.ref<f64>
  return
}
func.func @g() {
  return
}

// -----

func.func @f(%r : !simit.ref<f64>, %v : f32) {
  // expected-error @+1 {{'simit.store' op failed to verify that stored value has the slot's value type}}
  "simit.store"(%v, %r) : (f32, !simit.ref<f64>) -> ()
  return
}

// -----

func.func @f(%r : !simit.ref<f64>) {
  // expected-error @+1 {{'simit.load' op failed to verify that result type is the slot's value type}}
  %v = "simit.load"(%r) : (!simit.ref<f64>) -> f32
  return
}
