// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops \
// RUN:   --canonicalize | FileCheck %s

!Node = !simit.element<"Node", {x : f64}>
!Link = !simit.element<"Link", {k : f64}>
!Nodes = !simit.set<"nodes", !Node>
!Links = !simit.set<"links", !Link, grid 1 over "nodes">
!A = !simit.tensor<["nodes", "nodes"] x f64>
!V = !simit.tensor<["nodes"] x f64>
simit.extern @nodes : !Nodes
simit.extern @links : !Links

// A(p, p) = k of the link arriving at p; A(p, p - 1) = -that k.
func.func @conduct(%p : !Node, %g : !Links) -> !A {
  %e = simit.grid_edge %g, %p [0] dir [-1] : !Links, !Node
  %k = simit.elem_read %e["k"] : !Link -> f64
  %left = simit.grid_point %g, %p [-1] : !Links, !Node
  %nk = arith.negf %k : f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%p, %p] : f64 into !A, (!Node, !Node)
  %A2 = simit.insert %nk into %A1[%p, %left] : f64 into !A, (!Node, !Node)
  return %A2 : !A
}

// The grid's extents are the only grid binding; no index arrays.
// CHECK-LABEL: func.func @apply(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[DIMS:[^:]*]]: memref<1xi32>, %[[K:[^:]*]]: memref<?xf64>, %[[X:[^:]*]]: memref<?xf64>)
// CHECK-SAME: simit.bindings = [{kind = "set_size", set = "nodes"}, {kind = "grid_dims", set = "links"}, {field = "k", kind = "field", set = "links"}, {field = "x", kind = "field", set = "nodes"}]
// CHECK: %[[TABLE:.*]] = arith.constant dense<[-1, 0]> : vector<2xi64>
// Offsets [-1] and [0]: two arrays of |nodes| blocks.
// CHECK: %[[SIZE:.*]] = arith.muli %[[N]], %c2 : index
// CHECK: %[[VALS:.*]] = memref.alloc(%[[SIZE]]) : memref<?xf64>
// CHECK: scf.parallel (%[[P:.*]]) = (%c0) to (%[[N]])
// The arriving edge is edge (p - 1 mod n) * 1 + 0.
// CHECK: %[[N32:.*]] = memref.load %[[DIMS]][%c0] : memref<1xi32>
// CHECK: %[[EXT:.*]] = arith.index_cast %[[N32]] : i32 to index
// CHECK: %[[C:.*]] = arith.remui %[[P]], %[[EXT]] : index
// CHECK: %[[M1:.*]] = arith.addi %[[C]], %c-1 : index
// CHECK: %[[R1:.*]] = arith.remsi %[[M1]], %[[EXT]] : index
// CHECK: %[[R2:.*]] = arith.addi %[[R1]], %[[EXT]] : index
// CHECK: %[[LEFT:.*]] = arith.remsi %[[R2]], %[[EXT]] : index
// CHECK: %[[KL:.*]] = memref.load %[[K]][%[[LEFT]]] : memref<?xf64>
// CHECK: %[[NEG:.*]] = arith.negf %[[KL]] : f64
// The diagonal is offset 1 (after [-1]), unless [-1] names p itself
// (n divides 1): then it goes to offset 0.
// CHECK: %[[ALIAS:.*]] = arith.cmpi eq, %{{.*}}, %c0 : index
// CHECK: %[[DIAG:.*]] = arith.select %[[ALIAS]], %c0, %c1 : index
// CHECK: %[[DOFF:.*]] = arith.muli %[[DIAG]], %[[N]] : index
// CHECK: %[[DPOS:.*]] = arith.addi %[[DOFF]], %[[P]] : index
// CHECK: memref.store %[[KL]], %[[VALS]][%[[DPOS]]] : memref<?xf64>
// Offset [-1] is the first: block 0 * n + p.
// CHECK: memref.store %[[NEG]], %[[VALS]][%[[P]]] : memref<?xf64>
// CHECK-NOT: simit.scatter
// y = A x: for each row, a loop over the two offsets; the column is the
// neighbour at the offset read from a constant table.
// CHECK: scf.parallel (%[[R:.*]]) = (%c0) to (%[[N]])
// CHECK: scf.for %[[O:.*]] = %c0 to %c2 step %c1
// CHECK: %[[OFF64:.*]] = vector.extract %[[TABLE]][%[[O]]] : i64 from vector<2xi64>
// CHECK: %[[OFF:.*]] = arith.index_cast %[[OFF64]] : i64 to index
// CHECK: %[[E2:.*]] = arith.index_cast %{{.*}} : i32 to index
// CHECK: %[[C2:.*]] = arith.remui %[[R]], %[[E2]] : index
// CHECK: %[[S2:.*]] = arith.addi %[[C2]], %[[OFF]] : index
// CHECK: %[[T2:.*]] = arith.remsi %[[S2]], %[[E2]] : index
// CHECK: %[[U2:.*]] = arith.addi %[[T2]], %[[E2]] : index
// CHECK: %[[COL:.*]] = arith.remsi %[[U2]], %[[E2]] : index
// CHECK: %[[BOFF:.*]] = arith.muli %[[O]], %[[N]] : index
// CHECK: %[[BLK:.*]] = arith.addi %[[BOFF]], %[[R]] : index
// CHECK: memref.load %[[VALS]][%[[BLK]]] : memref<?xf64>
// CHECK: memref.load %[[X]][%[[COL]]] : memref<?xf64>
func.func @apply() -> !V attributes {simit.export} {
  %nodes = simit.get_set @nodes : !Nodes
  %links = simit.get_set @links : !Links
  %A = simit.map @conduct() to %nodes through %links : (!Nodes, !Links) -> !A
  %x = simit.field_read %nodes["x"] : !Nodes -> !V
  %y = simit.matvec %A, %x : !A, !V -> !V
  return %y : !V
}
