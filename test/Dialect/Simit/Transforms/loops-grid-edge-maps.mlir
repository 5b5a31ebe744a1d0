// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops --canonicalize | FileCheck %s

// A map over the edges of a grid (no `through`) is a loop over the grid's
// own set, sized by its set_size binding (d edges per point), reading and
// writing its fields.

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Cell = !simit.element<"Cell", {c : f64}>
!Points = !simit.set<"points", !Point>
!Cells = !simit.set<"cells", !Cell, grid 2 over "points">
simit.extern @points : !Points
simit.extern @cells : !Cells

func.func @double(%e : !Cell) {
  %c = simit.elem_read %e["c"] : !Cell -> f64
  %two = arith.addf %c, %c : f64
  simit.elem_write %two, %e["c"] : f64, !Cell
  return
}

// CHECK-LABEL: func.func @grid_edges(
// CHECK-SAME: %[[N:.*]]: index, %[[C:.*]]: memref<?xf64>)
// CHECK-SAME: {kind = "set_size", set = "cells"}
// CHECK-SAME: {field = "c", kind = "field", set = "cells"}
// CHECK: scf.parallel (%[[E:[a-z0-9]+]]) = (%{{.*}}) to (%[[N]])
// CHECK: %[[V:.*]] = memref.load %[[C]][%[[E]]]
// CHECK: %[[W:.*]] = arith.addf %[[V]], %[[V]]
// CHECK: memref.store %[[W]], %[[C]][%[[E]]]
func.func @grid_edges() attributes {simit.export} {
  %cells = simit.get_set @cells : !Cells
  simit.map @double() to %cells : (!Cells) -> ()
  return
}

// The endpoint tuple of a grid edge reads the grid's endpoint array, two
// points per edge.
!Vec = !simit.tensor<["points"] x tensor<3xf64>>

func.func @spread(%e : !Cell, %n : !simit.tuple<!Point x 2>) -> !Vec {
  %c = simit.elem_read %e["c"] : !Cell -> f64
  %v = tensor.from_elements %c, %c, %c : tensor<3xf64>
  %r = simit.alloc : !simit.ref<!Vec>
  %0 = simit.load %r : !simit.ref<!Vec>
  %q = simit.tuple_get %n[1] : !simit.tuple<!Point x 2> -> !Point
  %1 = simit.insert %v into %0[%q] : tensor<3xf64> into !Vec, (!Point)
  simit.store %1, %r : !simit.ref<!Vec>
  %2 = simit.load %r : !simit.ref<!Vec>
  return %2 : !Vec
}

// CHECK-LABEL: func.func @grid_edge_endpoints(
// CHECK-SAME: memref<?x2xi32>
// CHECK-SAME: {kind = "endpoints", set = "cells"}
// CHECK: scf.parallel (%[[E:[a-z0-9]+]]) =
// CHECK: memref.load %{{.*}}[%[[E]], %c1] : memref<?x2xi32>
func.func @grid_edge_endpoints() -> !Vec attributes {simit.export} {
  %cells = simit.get_set @cells : !Cells
  %v = simit.assemble @spread() to %cells reduce <add> : (!Cells) -> !Vec
  return %v : !Vec
}
