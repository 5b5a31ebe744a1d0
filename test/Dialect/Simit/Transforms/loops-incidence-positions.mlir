// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// The incidence of a heterogeneous edge set over one of its endpoint sets
// holds a block per endpoint position in that set: links(particles, nodes)
// over (links, nodes) has one, position 1. Its columns are the runtime's
// incidence_endpoints of (links; links, nodes), one per link, and the map
// writes block e * 1 + 0; the product reads them, not the whole endpoint
// array (whose position 0 indexes particles).

!Particle = !simit.element<"Particle", {q : f64}>
!Node = !simit.element<"Node", {x : f64}>
!Link = !simit.element<"Link", {w : f64}>
!D = !simit.tensor<["links", "nodes"] x f64>
!X = !simit.tensor<["nodes"] x f64>
!W = !simit.tensor<["links"] x f64>
!Links = !simit.set<"links", !Link, ["particles", "nodes"]>
!Nodes = !simit.set<"nodes", !Node>
simit.extern @links : !Links
simit.extern @nodes : !Nodes
func.func @weights(%l : !Link, %ends : !simit.tuple<{p : !Particle, n : !Node}>) -> !D {
  %n = simit.tuple_get %ends[1] : !simit.tuple<{p : !Particle, n : !Node}> -> !Node
  %w = simit.elem_read %l["w"] : !Link -> f64
  %D0 = simit.zeros : !D
  %D1 = simit.insert %w into %D0[%l, %n] : f64 into !D, (!Link, !Node)
  return %D1 : !D
}

// CHECK-LABEL: func.func @mixed(
// CHECK-SAME: %[[NL:[^:]*]]: index, %{{[^:]*}}: index, %[[ENDS:[^:]*]]: memref<?x2xi32>, %{{[^:]*}}: memref<?xf64>, %{{[^:]*}}: memref<?xf64>, %[[COLS:[^:]*]]: memref<?x1xi32>)
// CHECK-SAME: {cols = "nodes", kind = "incidence_endpoints", rows = "links", set = "links"}
// CHECK: %[[D:.*]] = memref.alloc(%{{.*}}) : memref<?xf64>
// The map over links writes block e * 1 + 0 (position 1, the first held).
// CHECK: scf.parallel (%[[E:[^)]*]]) = (%{{.*}}) to (%[[NL]])
// CHECK: %[[ZERO:.*]] = arith.constant 0 : index
// CHECK: %[[ONE:.*]] = arith.constant 1 : index
// CHECK: %[[FIRST:.*]] = arith.muli %[[E]], %[[ONE]] : index
// CHECK: %[[AT:.*]] = arith.addi %[[FIRST]], %[[ZERO]] : index
// CHECK: memref.store %{{.*}}, %[[D]][%[[AT]]] : memref<?xf64>
// The product's columns come from the held endpoints.
// CHECK: scf.parallel (%[[ROW:[^)]*]]) =
// CHECK: scf.for %[[K:[^ ]*]] =
// CHECK: memref.load %[[COLS]][%[[ROW]], %[[K]]] : memref<?x1xi32>
// CHECK-NOT: memref.load %[[ENDS]]
func.func @mixed() attributes {simit.export} {
  %links = simit.get_set @links : !Links
  %nodes = simit.get_set @nodes : !Nodes
  %D = simit.assemble @weights() to %links reduce <add> : (!Links) -> !D
  %x = simit.field_read %nodes["x"] : !Nodes -> !X
  %y = simit.matvec %D, %x : !D, !X -> !W
  simit.field_write %y, %links["w"] : !W, !Links
  return
}
