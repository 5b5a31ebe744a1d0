// RUN: simit-opt %s --split-input-file --simit-eliminate-dead-assemblies | FileCheck %s

// An assembly whose second result nothing uses calls a copy of its element
// function that returns the first only; the original function is erased.

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

// CHECK-NOT: func.func @force(
// CHECK-LABEL: func.func @force_live_1(
// CHECK-SAME: -> !simit.tensor<["points"] x tensor<3xf64>>
// CHECK: return %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>
func.func @force(%s : !Spring, %p : !simit.tuple<!Point x 2>) -> (!A, !V) {
  %p0 = simit.tuple_get %p[0] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %kb = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %A0 = simit.zeros : !A
  %A1 = simit.insert %kb into %A0[%p0, %p0] : tensor<3x3xf64> into !A, (!Point, !Point)
  %f = simit.broadcast %k : f64 -> tensor<3xf64>
  %V0 = simit.zeros : !V
  %V1 = simit.insert %f into %V0[%p0] : tensor<3xf64> into !V, (!Point)
  return %A1, %V1 : !A, !V
}

// CHECK-LABEL: func.func @step(
// CHECK: %[[F:.*]] = simit.assemble @force_live_1() to %{{.*}} reduce <add> : (!simit.set<"springs", {{.*}}>) -> !simit.tensor<["points"] x tensor<3xf64>>
// CHECK: simit.field_write %[[F]]
func.func @step() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K, %f = simit.assemble @force() to %springs reduce <add> : (!Springs) -> (!A, !V)
  simit.field_write %f, %points["x"] : !V, !Points
  return
}

// -----

// A map none of whose results is used, over a function without effects,
// is erased with the function.

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// CHECK-NOT: func.func @weight
func.func @weight(%p : !Point) -> !V {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %b = simit.broadcast %m : f64 -> tensor<3xf64>
  %V0 = simit.zeros : !V
  %V1 = simit.insert %b into %V0[%p] : tensor<3xf64> into !V, (!Point)
  return %V1 : !V
}

// CHECK-LABEL: func.func @unused(
// CHECK-NOT: simit.assemble
// CHECK: return
func.func @unused() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %w = simit.assemble @weight() to %points reduce <add> : (!Points) -> !V
  return
}

// -----

// A map whose element function writes a field stays for that effect,
// without results.

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// CHECK-LABEL: func.func @move_live(
// CHECK-SAME: %{{.*}}: !Point) {
// CHECK: simit.elem_write
// CHECK: return
// CHECK-NOT: func.func @move(
func.func @move(%p : !Point) -> !V {
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  simit.elem_write %x, %p["x"] : tensor<3xf64>, !Point
  %V0 = simit.zeros : !V
  %V1 = simit.insert %x into %V0[%p] : tensor<3xf64> into !V, (!Point)
  return %V1 : !V
}

// CHECK-LABEL: func.func @apply(
// CHECK: simit.map @move_live() to %{{.*}} : (!simit.set<"points", {{.*}}>) -> ()
func.func @apply() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %v = simit.map @move() to %points : (!Points) -> !V
  return
}

// -----

// Every result used: nothing changes.

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// CHECK-LABEL: func.func @weight(
func.func @weight(%p : !Point) -> !V {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %b = simit.broadcast %m : f64 -> tensor<3xf64>
  %V0 = simit.zeros : !V
  %V1 = simit.insert %b into %V0[%p] : tensor<3xf64> into !V, (!Point)
  return %V1 : !V
}

// CHECK-LABEL: func.func @used(
// CHECK: simit.assemble @weight()
func.func @used() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %w = simit.assemble @weight() to %points reduce <add> : (!Points) -> !V
  simit.field_write %w, %points["x"] : !V, !Points
  return
}

// -----

// Results written through variables (the frontend's form of `K(p, p) = ...`
// in a branch): the dropped result's variable and the values stored to it
// are erased with it.

!Point = !simit.element<"Point", {x : tensor<3xf64>, c : i32}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// CHECK-LABEL: func.func @force_live_1(
// CHECK-NOT: !simit.ref<!simit.tensor<["points", "points"]
// CHECK-NOT: simit.outer
// CHECK: simit.alloc : !simit.ref<!simit.tensor<["points"] x tensor<3xf64>>>
// CHECK: scf.if
// CHECK: simit.insert %{{.*}}[%{{.*}}] : tensor<3xf64>
// CHECK-NOT: simit.outer
// CHECK: return
func.func @force(%p : !Point) -> (!A, !V) {
  %K = simit.alloc : !simit.ref<!A>
  %f = simit.alloc : !simit.ref<!V>
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  %xx = simit.outer %x, %x : tensor<3xf64>, tensor<3xf64> -> tensor<3x3xf64>
  %c = simit.elem_read %p["c"] : !Point -> i32
  %zero = arith.constant 0 : i32
  %free = arith.cmpi sle, %c, %zero : i32
  scf.if %free {
    %f0 = simit.load %f : !simit.ref<!V>
    %f1 = simit.insert %x into %f0[%p] : tensor<3xf64> into !V, (!Point)
    simit.store %f1, %f : !simit.ref<!V>
    %K0 = simit.load %K : !simit.ref<!A>
    %K1 = simit.insert %xx into %K0[%p, %p] : tensor<3x3xf64> into !A, (!Point, !Point)
    simit.store %K1, %K : !simit.ref<!A>
  }
  %Kr = simit.load %K : !simit.ref<!A>
  %fr = simit.load %f : !simit.ref<!V>
  return %Kr, %fr : !A, !V
}

// CHECK-LABEL: func.func @step(
// CHECK: simit.assemble @force_live_1()
func.func @step() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %K, %f = simit.assemble @force() to %points reduce <add> : (!Points) -> (!A, !V)
  simit.field_write %f, %points["x"] : !V, !Points
  return
}

// -----

// An assembly none of whose results is used, over a function that writes a
// field, becomes a map run for that effect.

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @touch(%p : !Point) -> !V {
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  simit.elem_write %x, %p["x"] : tensor<3xf64>, !Point
  %V0 = simit.zeros : !V
  %V1 = simit.insert %x into %V0[%p] : tensor<3xf64> into !V, (!Point)
  return %V1 : !V
}

// CHECK-LABEL: func.func @apply(
// CHECK-NOT: simit.assemble
// CHECK: simit.map @touch_live() to %{{.*}} : (!simit.set<"points", {{.*}}>) -> ()
// CHECK-NOT: reduce
func.func @apply() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %v = simit.assemble @touch() to %points reduce <add> : (!Points) -> !V
  return
}
