// RUN: simit-opt %s -split-input-file -verify-diagnostics

!P = !simit.element<"P", {x : tensor<3xf64>, M : tensor<3x3xf64>}>
func.func @f(%s : !simit.set<"points", !P>) {
  // expected-error @+1 {{element 'P' has no field 'y'}}
  %v = simit.field_read %s["y"] : !simit.set<"points", !P> -> !simit.tensor<["points"] x tensor<3xf64>>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>, M : tensor<3x3xf64>}>
func.func @f(%s : !simit.set<"points", !P>) {
  // expected-error @+1 {{field 'M' of type 'tensor<3x3xf64>' is not a scalar or a vector; only those can be accessed as set fields}}
  %v = simit.field_read %s["M"] : !simit.set<"points", !P> -> !simit.tensor<["points"] x tensor<9xf64>>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%s : !simit.set<"points", !P>) {
  // expected-error @+1 {{result type '!simit.tensor<["nodes"] x tensor<3xf64>>' should be '!simit.tensor<["points"] x tensor<3xf64>>'}}
  %v = simit.field_read %s["x"] : !simit.set<"points", !P> -> !simit.tensor<["nodes"] x tensor<3xf64>>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%s : !simit.set<"points", !P>, %v : !simit.tensor<["points"] x f64>) {
  // expected-error @+1 {{value type '!simit.tensor<["points"] x f64>' should be '!simit.tensor<["points"] x tensor<3xf64>>' or the scalar 'f64'}}
  simit.field_write %v, %s["x"] : !simit.tensor<["points"] x f64>, !simit.set<"points", !P>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%s : !simit.set<"points", !P>, %v : f32) {
  // expected-error @+1 {{value type 'f32' should be}}
  simit.field_write %v, %s["x"] : f32, !simit.set<"points", !P>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%s : !simit.set<"points", !P>, %v : f64) {
  // expected-error @+1 {{element 'P' has no field 'q'}}
  simit.field_write %v, %s["q"] : f64, !simit.set<"points", !P>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%p : !P) {
  // expected-error @+1 {{element 'P' has no field 'nosuch'}}
  %v = simit.elem_read %p["nosuch"] : !P -> f64
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%p : !P) {
  // expected-error @+1 {{result type 'tensor<2xf64>' differs from the type 'tensor<3xf64>' of field 'x'}}
  %v = simit.elem_read %p["x"] : !P -> tensor<2xf64>
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%p : !P, %v : tensor<2xf64>) {
  // expected-error @+1 {{value type 'tensor<2xf64>' should be 'tensor<3xf64>' or the scalar 'f64'}}
  simit.elem_write %v, %p["x"] : tensor<2xf64>, !P
  return
}

// -----

!P = !simit.element<"P", {x : tensor<3xf64>}>
func.func @f(%p : !P, %v : f64) {
  // expected-error @+1 {{element 'P' has no field 'y'}}
  simit.elem_write %v, %p["y"] : f64, !P
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%t : !simit.tuple<!P x 2>) {
  // expected-error @+1 {{index 2 is out of range for a tuple of 2 components}}
  %e = simit.tuple_get %t[2] : !simit.tuple<!P x 2> -> !P
  return
}

// -----

!P = !simit.element<"P", {}>
!Q = !simit.element<"Q", {}>
func.func @f(%t : !simit.tuple<{a : !P, b : !Q}>) {
  // expected-error @+1 {{result type '!simit.element<"P", {}>' differs from the component type '!simit.element<"Q", {}>'}}
  %e = simit.tuple_get %t[1] : !simit.tuple<{a : !P, b : !Q}> -> !P
  return
}

// -----

!P = !simit.element<"P", {}>
!Q = !simit.element<"Q", {}>
func.func @f(%s : !simit.set<"points", !P>, %i : index) {
  // expected-error @+1 {{failed to verify that result is of the set's element type}}
  %e = simit.set_element %s[%i] : !simit.set<"points", !P> -> !Q
  return
}

// -----

!P = !simit.element<"P", {}>
func.func @f(%s : !simit.set<"points", !P>, %p : !P) {
  // expected-error @+1 {{set 'points' is a vertex set and has no endpoints}}
  %e = simit.endpoints %s[%p] : !simit.set<"points", !P> -> !simit.tuple<!P x 2>
  return
}

// -----

!P = !simit.element<"P", {}>
!S = !simit.element<"S", {}>
func.func @f(%s : !simit.set<"springs", !S, ["points", "points"]>, %e : !S) {
  // expected-error @+1 {{endpoint tuple has 3 components but elements of set 'springs' have 2 endpoints}}
  %t = simit.endpoints %s[%e] : !simit.set<"springs", !S, ["points", "points"]> -> !simit.tuple<!P x 3>
  return
}

// -----

!P = !simit.element<"P", {}>
!S = !simit.element<"S", {}>
func.func @f(%s : !simit.set<"links", !S, ["points", "nodes"]>, %e : !S) {
  // expected-error @+1 {{set 'links' is heterogeneous; its endpoint tuple must be named}}
  %t = simit.endpoints %s[%e] : !simit.set<"links", !S, ["points", "nodes"]> -> !simit.tuple<!P x 2>
  return
}

// -----

!P = !simit.element<"P", {}>
!N = !simit.element<"N", {}>
!S = !simit.element<"S", {}>
simit.extern @nodes : !simit.set<"nodes", !N>
func.func @f(%s : !simit.set<"links", !S, ["points", "nodes"]>, %e : !S) {
  // expected-error @+1 {{endpoint 1 must be an element of set 'nodes' ('!simit.element<"N", {}>'), got '!simit.element<"P", {}>'}}
  %t = simit.endpoints %s[%e] : !simit.set<"links", !S, ["points", "nodes"]> -> !simit.tuple<{a : !P, b : !P}>
  return
}

// -----

!P = !simit.element<"P", {}>
!S = !simit.element<"S", {}>
func.func @f(%s : !simit.set<"springs", !S, ["points", "points"]>, %p : !P) {
  // expected-error @+1 {{failed to verify that element is of the set's element type}}
  %t = "simit.endpoints"(%s, %p) : (!simit.set<"springs", !S, ["points", "points"]>, !P) -> !simit.tuple<!P x 2>
  return
}

// -----

!P = !simit.element<"P", {}>
!S = !simit.element<"S", {}>
func.func @f(%g : !simit.set<"springs", !S, ["points", "points"]>, %p : !P) {
  // expected-error @+1 {{set 'springs' is not a grid}}
  %q = simit.grid_point %g, %p [1, 0] : !simit.set<"springs", !S, ["points", "points"]>, !P
  return
}

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %p : !P) {
  // expected-error @+1 {{expected 2 offsets for a grid of rank 2, got 3}}
  %q = simit.grid_point %g, %p [1, 0, 0] : !simit.set<"cells", !C, grid 2 over "points">, !P
  return
}

// -----

!P = !simit.element<"P", {}>
!Q = !simit.element<"Q", {}>
!C = !simit.element<"C", {}>
simit.extern @points : !simit.set<"points", !P>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %q : !Q) {
  // expected-error @+1 {{point must be an element of set 'points'}}
  %r = simit.grid_point %g, %q [1, 0] : !simit.set<"cells", !C, grid 2 over "points">, !Q
  return
}

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %p : !P) {
  // expected-error @+1 {{expected 2 offsets for a grid of rank 2, got 1}}
  %e = simit.grid_edge %g, %p [0] dir [0, 1] : !simit.set<"cells", !C, grid 2 over "points">, !P
  return
}

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %p : !P) {
  // expected-error @+1 {{expected a direction of 2 components, got 3}}
  %e = simit.grid_edge %g, %p [0, 0] dir [0, 1, 0] : !simit.set<"cells", !C, grid 2 over "points">, !P
  return
}

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %p : !P) {
  // expected-error @+1 {{direction must have exactly one component equal to 1 or -1 and zeros elsewhere}}
  %e = simit.grid_edge %g, %p [0, 0] dir [1, 1] : !simit.set<"cells", !C, grid 2 over "points">, !P
  return
}

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %p : !P) {
  // expected-error @+1 {{direction must have exactly one component equal to 1 or -1 and zeros elsewhere}}
  %e = simit.grid_edge %g, %p [0, 0] dir [0, 2] : !simit.set<"cells", !C, grid 2 over "points">, !P
  return
}

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "points">, %p : !P) {
  // expected-error @+1 {{direction must have exactly one component equal to 1 or -1 and zeros elsewhere}}
  %e = simit.grid_edge %g, %p [0, 0] dir [0, 0] : !simit.set<"cells", !C, grid 2 over "points">, !P
  return
}
