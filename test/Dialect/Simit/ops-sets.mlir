// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Node = !simit.element<"Node", {v : f64}>
!Link = !simit.element<"Link", {w : f64}>
!Cell = !simit.element<"Cell", {c : f64}>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @springs : !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @nodes : !simit.set<"nodes", !Node>
simit.extern @links : !simit.set<"links", !Link, ["points", "nodes"]>
simit.extern @cells : !simit.set<"cells", !Cell, grid 2 over "points">

// CHECK-LABEL: func.func @fields
func.func @fields(%zero : f64) {
  %points = simit.get_set @points : !simit.set<"points", !Point>
  // CHECK: %[[X:.*]] = simit.field_read %{{.*}}["x"] : !simit.set<"points", !Point> -> !simit.tensor<["points"] x tensor<3xf64>>
  %x = simit.field_read %points["x"] : !simit.set<"points", !Point> -> !simit.tensor<["points"] x tensor<3xf64>>
  // CHECK: simit.field_read %{{.*}}["m"] : !simit.set<"points", !Point> -> !simit.tensor<["points"] x f64>
  %m = simit.field_read %points["m"] : !simit.set<"points", !Point> -> !simit.tensor<["points"] x f64>
  // CHECK: simit.field_write %[[X]], %{{.*}}["x"] : !simit.tensor<["points"] x tensor<3xf64>>, !simit.set<"points", !Point>
  simit.field_write %x, %points["x"] : !simit.tensor<["points"] x tensor<3xf64>>, !simit.set<"points", !Point>
  // CHECK: simit.field_write %{{.*}}, %{{.*}}["x"] : f64, !simit.set<"points", !Point>
  simit.field_write %zero, %points["x"] : f64, !simit.set<"points", !Point>
  return
}

// CHECK-LABEL: func.func @elements
func.func @elements(%p : !Point, %v : tensor<3xf64>, %s : f64) -> tensor<3xf64> {
  // CHECK: simit.elem_read %{{.*}}["x"] : !Point -> tensor<3xf64>
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  // CHECK: simit.elem_write %{{.*}}, %{{.*}}["x"] : tensor<3xf64>, !Point
  simit.elem_write %v, %p["x"] : tensor<3xf64>, !Point
  // CHECK: simit.elem_write %{{.*}}, %{{.*}}["x"] : f64, !Point
  simit.elem_write %s, %p["x"] : f64, !Point
  return %x : tensor<3xf64>
}

// CHECK-LABEL: func.func @iteration
func.func @iteration(%i : index) {
  %springs = simit.get_set @springs : !simit.set<"springs", !Spring, ["points", "points"]>
  // CHECK: simit.set_size %{{.*}} : !simit.set<"springs", !Spring, ["points", "points"]>
  %n = simit.set_size %springs : !simit.set<"springs", !Spring, ["points", "points"]>
  // CHECK: %[[E:.*]] = simit.set_element %{{.*}}[%{{.*}}] : !simit.set<"springs", !Spring, ["points", "points"]> -> !Spring
  %e = simit.set_element %springs[%i] : !simit.set<"springs", !Spring, ["points", "points"]> -> !Spring
  // CHECK: %[[T:.*]] = simit.endpoints %{{.*}}[%[[E]]] : !simit.set<"springs", !Spring, ["points", "points"]> -> !simit.tuple<!Point x 2>
  %ends = simit.endpoints %springs[%e] : !simit.set<"springs", !Spring, ["points", "points"]> -> !simit.tuple<!Point x 2>
  // CHECK: simit.tuple_get %[[T]][1] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  return
}

// A heterogeneous edge set has a named endpoint tuple.
// CHECK-LABEL: func.func @heterogeneous
func.func @heterogeneous(%l : !Link) -> !Node {
  %links = simit.get_set @links : !simit.set<"links", !Link, ["points", "nodes"]>
  // CHECK: simit.endpoints %{{.*}}[%{{.*}}] : !simit.set<"links", !Link, ["points", "nodes"]> -> !simit.tuple<{p : !Point, n : !Node}>
  %ends = simit.endpoints %links[%l] : !simit.set<"links", !Link, ["points", "nodes"]> -> !simit.tuple<{p : !Point, n : !Node}>
  // CHECK: simit.tuple_get %{{.*}}[1] : !simit.tuple<{p : !Point, n : !Node}> -> !Node
  %n = simit.tuple_get %ends[1] : !simit.tuple<{p : !Point, n : !Node}> -> !Node
  return %n : !Node
}

// CHECK-LABEL: func.func @grid
func.func @grid(%p : !Point) -> (!Point, !Cell) {
  %cells = simit.get_set @cells : !simit.set<"cells", !Cell, grid 2 over "points">
  // CHECK: simit.grid_point %{{.*}}, %{{.*}} [1, 0] : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
  %q = simit.grid_point %cells, %p [1, 0] : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
  // CHECK: simit.grid_edge %{{.*}}, %{{.*}} [0, -1] dir [0, 1] : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
  %e = simit.grid_edge %cells, %p [0, -1] dir [0, 1] : !simit.set<"cells", !Cell, grid 2 over "points">, !Point
  return %q, %e : !Point, !Cell
}
