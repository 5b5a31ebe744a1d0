// RUN: simit-opt %s --split-input-file --simit-fold-scene-constants | FileCheck %s

// A field uniform over its set is read as a constant by the element
// functions mapped over that set (the element and its endpoints), unless
// something writes it.

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64, w : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points {simit.uniform_fields = {m = 2.0 : f64, w = 3.0 : f64}}
simit.extern @springs : !Springs {simit.uniform_fields = {k = 5.0 : f64}}

// CHECK-LABEL: func.func @spring(
// CHECK-NOT: simit.elem_read %{{.*}}["k"]
// CHECK-NOT: simit.elem_read %{{.*}}["m"]
// CHECK: %[[C:.*]] = arith.constant 1.000000e+01 : f64
// CHECK: simit.insert %[[C]]
func.func @spring(%s : !Spring, %p : !simit.tuple<!Point x 2>) -> !V {
  %p0 = simit.tuple_get %p[0] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %m = simit.elem_read %p0["m"] : !Point -> f64
  %km = arith.mulf %k, %m : f64
  %V0 = simit.zeros : !V
  %V1 = simit.insert %km into %V0[%p0] : f64 into !V, (!Point)
  return %V1 : !V
}

// w is written by @scale, so no function reads it as a constant.
// CHECK-LABEL: func.func @scale(
// CHECK: simit.elem_read %{{.*}}["w"]
// CHECK: simit.elem_write
func.func @scale(%p : !Point) {
  %w = simit.elem_read %p["w"] : !Point -> f64
  %w2 = arith.addf %w, %w : f64
  simit.elem_write %w2, %p["w"] : f64, !Point
  return
}

func.func @step() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %f = simit.assemble @spring() to %springs reduce <add> : (!Springs) -> !V
  simit.map @scale() to %points : (!Points) -> ()
  return %f : !V
}

// -----

// An element function mapped over two sets of one element type reads the
// field: it is uniform in one of them only.

!Point = !simit.element<"Point", {m : f64, n : f64}>
!A = !simit.set<"a", !Point>
!B = !simit.set<"b", !Point>
simit.extern @a : !A {simit.uniform_fields = {m = 2.0 : f64}}
simit.extern @b : !B

// CHECK-LABEL: func.func @copy(
// CHECK: simit.elem_read %{{.*}}["m"]
func.func @copy(%p : !Point) {
  %m = simit.elem_read %p["m"] : !Point -> f64
  simit.elem_write %m, %p["n"] : f64, !Point
  return
}

func.func @both() attributes {simit.export} {
  %a = simit.get_set @a : !A
  %b = simit.get_set @b : !B
  simit.map @copy() to %a : (!A) -> ()
  simit.map @copy() to %b : (!B) -> ()
  return
}
