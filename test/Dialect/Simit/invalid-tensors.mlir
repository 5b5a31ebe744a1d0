// RUN: simit-opt %s -split-input-file -verify-diagnostics

func.func @f() {
  // expected-error @+1 {{'simit.zeros' op result #0 must be builtin ranked tensor or !simit.tensor, but got 'f64'}}
  %z = simit.zeros : f64
  return
}

// -----

func.func @f(%s : f32) {
  // expected-error @+1 {{scalar type 'f32' differs from the component type 'f64' of the result}}
  %t = simit.broadcast %s : f32 -> tensor<3xf64>
  return
}

// -----

func.func @f(%m : tensor<3x3xf64>, %i : index) {
  // expected-error @+1 {{expected 2 indices for 'tensor<3x3xf64>', got 1}}
  %c = simit.extract %m[%i] : tensor<3x3xf64>, (index) -> f64
  return
}

// -----

func.func @f(%m : tensor<3x3xf64>, %i : index, %j : i32) {
  // expected-error @+1 {{index of range dimension 1 must be 'index', got 'i32'}}
  %c = simit.extract %m[%i, %j] : tensor<3x3xf64>, (index, i32) -> f64
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%t : !simit.tensor<["points"] x f64>, %i : index) {
  // expected-error @+1 {{index of set dimension 0 ('points') must be an element, got 'index'}}
  %c = simit.extract %t[%i] : !simit.tensor<["points"] x f64>, (index) -> f64
  return
}

// -----

!P = !simit.element<"P", {}>
!Q = !simit.element<"Q", {}>
simit.extern @points : !simit.set<"points", !P>
func.func @f(%t : !simit.tensor<["points"] x f64>, %q : !Q) {
  // expected-error @+1 {{index of dimension 0 must be an element of set 'points' ('!simit.element<"P", {}>'), got '!simit.element<"Q", {}>'}}
  %c = simit.extract %t[%q] : !simit.tensor<["points"] x f64>, (!Q) -> f64
  return
}

// -----

!P = !simit.element<"P", {}>
!Q = !simit.element<"Q", {}>
// A set parameter declares the set too.
func.func @f(%s : !simit.set<"points", !P>, %t : !simit.tensor<["points"] x f64>, %q : !Q) {
  // expected-error @+1 {{index of dimension 0 must be an element of set 'points'}}
  %c = simit.extract %t[%q] : !simit.tensor<["points"] x f64>, (!Q) -> f64
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%t : !simit.tensor<["points"] x tensor<3xf64>>, %p : !P) {
  // expected-error @+1 {{result type 'f64' differs from the block type 'tensor<3xf64>'}}
  %c = simit.extract %t[%p] : !simit.tensor<["points"] x tensor<3xf64>>, (!P) -> f64
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%t : !simit.tensor<["points"] x tensor<3xf64>>, %p : !P, %v : tensor<2xf64>) {
  // expected-error @+1 {{inserted value type 'tensor<2xf64>' differs from the block type 'tensor<3xf64>'}}
  %c = simit.insert %v into %t[%p] : tensor<2xf64> into !simit.tensor<["points"] x tensor<3xf64>>, (!P)
  return
}

// -----

func.func @f(%m : tensor<3x3xf64>, %v : f64) {
  // expected-error @+1 {{expected 2 indices for 'tensor<3x3xf64>', got 0}}
  %c = "simit.insert"(%v, %m) : (f64, tensor<3x3xf64>) -> tensor<3x3xf64>
  return
}

// -----

func.func @f(%m : tensor<3x4xf64>, %j : index) {
  // expected-error @+1 {{result type 'tensor<4xf64>' should be 'tensor<3xf64>'}}
  %c = simit.slice %m[:, %j] : tensor<3x4xf64>, (index) -> tensor<4xf64>
  return
}

// -----

func.func @f(%m : tensor<3x4xf64>, %i : index, %j : index) {
  // expected-error @+1 {{keeps no dimension; use simit.extract}}
  %c = simit.slice %m[%i, %j] : tensor<3x4xf64>, (index, index) -> tensor<4xf64>
  return
}

// -----

func.func @f(%m : tensor<3x4xf64>) {
  // expected-error @+1 {{indexes no dimension; use the tensor itself}}
  %c = "simit.slice"(%m) {kept = array<i1: true, true>} : (tensor<3x4xf64>) -> tensor<3x4xf64>
  return
}

// -----

func.func @f(%m : tensor<3x4xf64>, %i : index) {
  // expected-error @+1 {{expected 2 indices or ':' for 'tensor<3x4xf64>', got 3}}
  %c = simit.slice %m[%i, :, :] : tensor<3x4xf64>, (index) -> tensor<4xf64>
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%K : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, %p : !P) {
  // expected-error @+1 {{cannot slice the blocked tensor}}
  %c = simit.slice %K[%p, :] : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, (!P) -> !simit.tensor<["points"] x tensor<3xf64>>
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%A : !simit.tensor<["points", 4] x f64>, %p : !P) {
  // A slice keeping only range dimensions is a builtin tensor.
  // expected-error @+1 {{result type '!simit.tensor<["points"] x f64>' should be 'tensor<4xf64>'}}
  %c = simit.slice %A[%p, :] : !simit.tensor<["points", 4] x f64>, (!P) -> !simit.tensor<["points"] x f64>
  return
}
