// RUN: simit-opt %s -split-input-file -verify-diagnostics

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!SpringSet = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @springs : !SpringSet

func.func @user(%s : !SpringSet) {
  // expected-error @+1 {{'@nowhere' does not name a function}}
  %f = simit.assemble @nowhere() to %s reduce <add> : (!SpringSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !PointSet

func.func @user(%s : !PointSet) {
  // expected-error @+1 {{'@points' does not name a function}}
  %f = simit.assemble @points() to %s reduce <add> : (!PointSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet, %k : f64) {
  // expected-error @+1 {{@f has 1 parameters but the map passes 1 extra arguments and the element}}
  %f = simit.assemble @f(%k) to %s reduce <add> : (f64, !PointSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%k : f32, %p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet, %k : f64) {
  // expected-error @+1 {{passes extra argument #0 of type 'f64' but @f expects 'f32'}}
  %f = simit.assemble @f(%k) to %s reduce <add> : (f64, !PointSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%q : !Point, %p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet, %q : !Point) {
  // expected-error @+1 {{extra argument #0 must be a tensor, a scalar or an opaque handle, got '!simit.element<"Point"}}
  %f = simit.assemble @f(%q) to %s reduce <add> : (!Point, !PointSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Other = !simit.element<"Other", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%p : !Other) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{@f takes '!simit.element<"Other", {x : tensor<3xf64>}>' as its element parameter but set 'points' holds}}
  %f = simit.assemble @f() to %s reduce <add> : (!PointSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!SpringSet = !simit.set<"springs", !Spring, ["points", "points"]>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%s : !Spring, %x : f64) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !SpringSet) {
  // expected-error @+1 {{@f takes 'f64' where the map passes the endpoint tuple}}
  %f = simit.assemble @f() to %s reduce <add> : (!SpringSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!SpringSet = !simit.set<"springs", !Spring, ["points", "points"]>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%s : !Spring, %e : !simit.tuple<!Point x 1>) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !SpringSet) {
  // expected-error @+1 {{endpoint tuple has 1 components but elements of set 'springs' have 2 endpoints}}
  %f = simit.assemble @f() to %s reduce <add> : (!SpringSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Link = !simit.element<"Link", {k : f64}>
!LinkSet = !simit.set<"links", !Link, ["points", "others"]>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%s : !Link, %e : !simit.tuple<!Point x 2>) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !LinkSet) {
  // expected-error @+1 {{set 'links' is heterogeneous; its endpoint tuple must be named}}
  %f = simit.assemble @f() to %s reduce <add> : (!LinkSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Node = !simit.element<"Node", {v : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!SpringSet = !simit.set<"springs", !Spring, ["points", "points"]>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !simit.set<"points", !Point>

func.func @f(%s : !Spring, %e : !simit.tuple<!Node x 2>) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !SpringSet) {
  // expected-error @+1 {{endpoint 0 must be an element of set 'points' ('!simit.element<"Point", {x : tensor<3xf64>}>'), got '!simit.element<"Node"}}
  %f = simit.assemble @f() to %s reduce <add> : (!SpringSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%p : !Point, %extra : f64) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{@f has 2 parameters but the map passes 1}}
  %f = simit.assemble @f() to %s reduce <add> : (!PointSet) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{result types must be the result types of @f}}
  %f = simit.assemble @f() to %s reduce <add> : (!PointSet) -> !simit.tensor<["points"] x f64>
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!G = !simit.tensor<["springs"] x tensor<3xf64>>

func.func @f(%p : !Point) -> !G {
  %z = simit.zeros : !G
  return %z : !G
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{result #0 has dimension 'springs', which is neither the mapped set 'points' nor one of its endpoint sets}}
  %f = simit.assemble @f() to %s reduce <add> : (!PointSet) -> !G
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @f(%p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{assembles at least one result; use simit.map to apply a function without results}}
  simit.assemble @f() to %s reduce <add> : (!PointSet) -> ()
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>

func.func @user(%s : !PointSet) {
  // expected-error @+2 {{expected ::mlir::simit::ReductionKind to be one of: add, mul, min, max}}
  // expected-error @+1 {{failed to parse Simit_ReductionAttr parameter 'value'}}
  %f = simit.assemble @f() to %s reduce <sum> : (!PointSet) -> !F
  return
}

// -----

// The key rule: an element function writes only to locations indexed by its
// own element and endpoints.
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !PointSet

func.func @f(%p : !Point) -> !F {
  %points = simit.get_set @points : !PointSet
  %i = arith.constant 0 : index
  %q = simit.set_element %points[%i] : !PointSet -> !Point
  %v = simit.zeros : tensor<3xf64>
  %z = simit.zeros : !F
  // expected-note @+1 {{see the write here}}
  %w = simit.insert %v into %z[%q] : tensor<3xf64> into !F, (!Point)
  return %w : !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{@f writes result #0 at a set position not indexed by its element or endpoints}}
  %f = simit.assemble @f() to %s reduce <add> : (!PointSet) -> !F
  return
}

// -----

// The endpoints of another edge are not the function's own.
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!SpringSet = !simit.set<"springs", !Spring, ["points", "points"]>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @springs : !SpringSet

func.func @f(%s : !Spring, %e : !simit.tuple<!Point x 2>) -> !F {
  %springs = simit.get_set @springs : !SpringSet
  %i = arith.constant 0 : index
  %other = simit.set_element %springs[%i] : !SpringSet -> !Spring
  %ends = simit.endpoints %springs[%other] : !SpringSet -> !simit.tuple<!Point x 2>
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %v = simit.zeros : tensor<3xf64>
  %z = simit.zeros : !F
  // expected-note @+1 {{see the write here}}
  %w = simit.insert %v into %z[%a] : tensor<3xf64> into !F, (!Point)
  return %w : !F
}
func.func @user(%s : !SpringSet) {
  // expected-error @+1 {{@f writes result #0 at a set position not indexed by its element or endpoints}}
  %f = simit.assemble @f() to %s reduce <add> : (!SpringSet) -> !F
  return
}

// -----

// A bad write reaches the result through a slot.
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !PointSet

func.func @f(%p : !Point) -> !F {
  %g = simit.get_set @points : !PointSet
  %i = arith.constant 1 : index
  %q = simit.set_element %g[%i] : !PointSet -> !Point
  %r = simit.alloc : !simit.ref<!F>
  %v = simit.zeros : tensor<3xf64>
  %z = simit.load %r : !simit.ref<!F>
  // expected-note @+1 {{see the write here}}
  %w = simit.insert %v into %z[%q] : tensor<3xf64> into !F, (!Point)
  simit.store %w, %r : !simit.ref<!F>
  %out = simit.load %r : !simit.ref<!F>
  return %out : !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{'simit.map' op @f writes result #0 at a set position}}
  %f = simit.map @f() to %s : (!PointSet) -> !F
  return
}

// -----

// A bad write reaches the result through a loop and an addition.
!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x tensor<3xf64>>
simit.extern @points : !PointSet

func.func @f(%p : !Point) -> (!F, !F) {
  %points = simit.get_set @points : !PointSet
  %v = simit.zeros : tensor<3xf64>
  %z = simit.zeros : !F
  %good = simit.insert %v into %z[%p] : tensor<3xf64> into !F, (!Point)
  %lb = arith.constant 0 : index
  %ub = arith.constant 4 : index
  %st = arith.constant 1 : index
  %acc = scf.for %i = %lb to %ub step %st iter_args(%a = %z) -> (!F) {
    %q = simit.set_element %points[%i] : !PointSet -> !Point
    // expected-note @+1 {{see the write here}}
    %n = simit.insert %v into %a[%q] : tensor<3xf64> into !F, (!Point)
    scf.yield %n : !F
  }
  %sum = simit.add %good, %acc : !F
  return %good, %sum : !F, !F
}
func.func @user(%s : !PointSet) {
  // expected-error @+1 {{@f writes result #1 at a set position}}
  %f, %g = simit.assemble @f() to %s reduce <add> : (!PointSet) -> (!F, !F)
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Cell = !simit.element<"Cell", {c : f64}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x f64>

func.func @f(%p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet, %g : !simit.set<"edges", !Cell, ["points", "points"]>) {
  // expected-error @+1 {{'through' set 'edges' is not a grid over the mapped set 'points'}}
  %f = simit.map @f() to %s through %g : (!PointSet, !simit.set<"edges", !Cell, ["points", "points"]>) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Cell = !simit.element<"Cell", {c : f64}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x f64>

func.func @f(%p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet, %g : !simit.set<"cells", !Cell, grid 2 over "nodes">) {
  // expected-error @+1 {{'through' set 'cells' is not a grid over the mapped set 'points'}}
  %f = simit.map @f() to %s through %g : (!PointSet, !simit.set<"cells", !Cell, grid 2 over "nodes">) -> !F
  return
}

// -----

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Cell = !simit.element<"Cell", {c : f64}>
!PointSet = !simit.set<"points", !Point>
!F = !simit.tensor<["points"] x f64>

func.func @f(%p : !Point) -> !F {
  %z = simit.zeros : !F
  return %z : !F
}
func.func @user(%s : !PointSet, %g : !simit.set<"cells", !Cell, grid 2 over "points">) {
  // expected-error @+1 {{@f must take the grid '!simit.set<"cells", !simit.element<"Cell", {c : f64}>, grid 2 over "points">' as its last parameter}}
  %f = simit.map @f() to %s through %g : (!PointSet, !simit.set<"cells", !Cell, grid 2 over "points">) -> !F
  return
}
