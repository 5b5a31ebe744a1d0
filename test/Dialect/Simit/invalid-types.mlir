// RUN: simit-opt %s -split-input-file -verify-diagnostics

// expected-error @+1 {{element type name must not be empty}}
func.func @f(%a : !simit.element<"", {x : f64}>)

// -----

// expected-error @+1 {{duplicate field name 'x'}}
func.func @f(%a : !simit.element<"Point", {x : f64, x : tensor<3xf64>}>)

// -----

// expected-error @+1 {{field 'h' must have a scalar or local tensor type, got '!simit.opaque'}}
func.func @f(%a : !simit.element<"Point", {h : !simit.opaque}>)

// -----

// expected-error @+1 {{field 'v' must have a scalar or local tensor type}}
func.func @f(%a : !simit.element<"Point", {v : !simit.tensor<["points"] x f64>}>)

// -----

// expected-error @+1 {{field 'd' must have a scalar or local tensor type}}
func.func @f(%a : !simit.element<"Point", {d : tensor<?xf64>}>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{set name must not be empty}}
func.func @f(%a : !simit.set<"", !P>)

// -----

// expected-error @+1 {{set 'points' must have an element type, got 'f64'}}
func.func @f(%a : !simit.set<"points", f64>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{grid rank must be positive}}
func.func @f(%a : !simit.set<"cells", !P, grid 0 over "points">)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{set 'edges' cannot be its own endpoint set}}
func.func @f(%a : !simit.set<"edges", !P, ["points", "edges"]>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{endpoint set names must not be empty}}
func.func @f(%a : !simit.set<"edges", !P, ["points", ""]>)

// -----

// expected-error @+1 {{!simit.tensor needs at least one dimension}}
func.func @f(%a : !simit.tensor<[] x f64>)

// -----

// expected-error @+1 {{range dimension must be positive, got 0}}
func.func @f(%a : !simit.tensor<["points", 0] x f64>)

// -----

// expected-error @+1 {{range dimension must be positive, got -2}}
func.func @f(%a : !simit.tensor<["points", -2] x f64>)

// -----

// expected-error @+1 {{set dimension names must not be empty}}
func.func @f(%a : !simit.tensor<[""] x f64>)

// -----

// expected-error @+1 {{a tensor of ranges with a scalar block is a builtin tensor}}
func.func @f(%a : !simit.tensor<[3, 3] x f64>)

// -----

// Blocks must have the container's order.
// expected-error @+1 {{block 'tensor<2x2xf64>' must have the order of its container (1)}}
func.func @f(%a : !simit.tensor<["points"] x tensor<2x2xf64>>)

// -----

// expected-error @+1 {{must have the order of its container (2)}}
func.func @f(%a : !simit.tensor<["points", "points"] x !simit.tensor<[8] x tensor<3xf64>>>)

// -----

// expected-error @+1 {{must not have set dimensions}}
func.func @f(%a : !simit.tensor<["points"] x !simit.tensor<["springs"] x f64>>)

// -----

// expected-error @+1 {{block type must be a scalar or a tensor, got '!simit.string'}}
func.func @f(%a : !simit.tensor<["points"] x !simit.string>)

// -----

// expected-error @+1 {{block 'tensor<?xf64>' must be a static tensor of scalars}}
func.func @f(%a : !simit.tensor<["points"] x tensor<?xf64>>)

// -----

// expected-error @+1 {{expected 'x'}}
func.func @f(%a : !simit.tensor<["points"] f64>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{tuple length must be positive}}
func.func @f(%a : !simit.tuple<!P x 0>)

// -----

// expected-error @+1 {{tuple components must be elements, got 'f64'}}
func.func @f(%a : !simit.tuple<f64 x 2>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{duplicate tuple component name 'a'}}
func.func @f(%a : !simit.tuple<{a : !P, a : !P}>)

// -----

// expected-error @+1 {{tuple must have at least one component}}
func.func @f(%a : !simit.tuple<{}>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{!simit.ref must hold a scalar, a tensor, an opaque handle or a string, got '!simit.set<"points"}}
func.func @f(%a : !simit.ref<!simit.set<"points", !P>>)

// -----

!P = !simit.element<"P", {}>
// expected-error @+1 {{!simit.ref must hold a scalar, a tensor, an opaque handle or a string}}
func.func @f(%a : !simit.ref<!P>)

// -----

// expected-error @+1 {{!simit.ref must hold a scalar, a tensor, an opaque handle or a string}}
func.func @f(%a : !simit.ref<index>)
