// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

// Element types print as aliases named after the element.
// CHECK-DAG: !Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
// CHECK-DAG: !Spring = !simit.element<"Spring", {k : f64, l0 : f64, x : tensor<3xf64>}>
// CHECK-DAG: !Cell = !simit.element<"Cell", {}>
// CHECK-DAG: !Wide = !simit.element<"Wide", {w : !simit.tensor<[8] x tensor<3xf32>>, "not an identifier" : i32, c : complex<f64>, b : i1}>
!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64, l0 : f64, x : tensor<3xf64>}>
!Cell = !simit.element<"Cell", {}>
!Wide = !simit.element<"Wide", {w : !simit.tensor<[8] x tensor<3xf32>>, "not an identifier" : i32, c : complex<f64>, b : i1}>

// CHECK-LABEL: func.func @sets
// CHECK-SAME: !simit.set<"points", !Point>
// CHECK-SAME: !simit.set<"springs", !Spring, ["points", "points"]>
// CHECK-SAME: !simit.set<"links", !Spring, ["points", "cells"]>
// CHECK-SAME: !simit.set<"cells", !Cell, grid 2 over "points">
// CHECK-SAME: !simit.set<"faces", !Cell, ["links", "links", "links"]>
func.func @sets(%p : !simit.set<"points", !Point>,
                %s : !simit.set<"springs", !Spring, ["points", "points"]>,
                %l : !simit.set<"links", !Spring, ["points", "cells"]>,
                %g : !simit.set<"cells", !Cell, grid 2 over "points">,
                %f : !simit.set<"faces", !Cell, ["links", "links", "links"]>) {
  return
}

// CHECK-LABEL: func.func @tensors
// CHECK-SAME: !simit.tensor<["points", "points"] x tensor<3x3xf64>>
// CHECK-SAME: !simit.tensor<["points", 3] x f64>
// CHECK-SAME: !simit.tensor<[8] x tensor<3xf64>>
// CHECK-SAME: !simit.tensor<["springs"] x !simit.tensor<[8] x tensor<3xf64>>>
// CHECK-SAME: !simit.tensor<["points"] x complex<f32>>
func.func @tensors(%a : !simit.tensor<["points", "points"] x tensor<3x3xf64>>,
                   %b : !simit.tensor<["points", 3] x f64>,
                   %c : !simit.tensor<[8] x tensor<3xf64>>,
                   %d : !simit.tensor<["springs"] x !simit.tensor<[8] x tensor<3xf64>>>,
                   %e : !simit.tensor<["points"] x complex<f32>>) {
  return
}

// CHECK-LABEL: func.func @tuples
// CHECK-SAME: !simit.tuple<!Point x 2>
// CHECK-SAME: !simit.tuple<{left : !Point, right : !Cell}>
// CHECK-SAME: !simit.tuple<!Point x 1>
func.func @tuples(%a : !simit.tuple<!Point x 2>,
                  %b : !simit.tuple<{left : !Point, right : !Cell}>,
                  %c : !simit.tuple<!Point x 1>) {
  return
}

// CHECK-LABEL: func.func @refs_and_handles
// CHECK-SAME: !simit.ref<f64>
// CHECK-SAME: !simit.ref<tensor<3xf64>>
// CHECK-SAME: !simit.ref<!simit.tensor<["points"] x f64>>
// CHECK-SAME: !simit.ref<!simit.opaque>
// CHECK-SAME: !simit.ref<!simit.string>
// CHECK-SAME: !simit.opaque
// CHECK-SAME: !simit.string
func.func @refs_and_handles(%a : !simit.ref<f64>, %b : !simit.ref<tensor<3xf64>>,
                            %c : !simit.ref<!simit.tensor<["points"] x f64>>,
                            %d : !simit.ref<!simit.opaque>, %e : !simit.ref<!simit.string>,
                            %f : !simit.opaque, %g : !simit.string) {
  return
}

// Sets are identified by name: one element type, two different sets.
// CHECK-LABEL: func.func @set_identity
// CHECK-SAME: !simit.set<"a", !Point>
// CHECK-SAME: !simit.set<"b", !Point>
func.func @set_identity(%a : !simit.set<"a", !Point>, %b : !simit.set<"b", !Point>) {
  return
}

// CHECK-LABEL: func.func @fields
// CHECK-SAME: !Wide
func.func @fields(%w : !Wide) {
  return
}
