// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops \
// RUN:   --canonicalize | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64, c : i32}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

// A vertex set writes the diagonal: block [p], no index.
func.func @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %blk = simit.broadcast %m : f64 -> tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%p, %p] : tensor<3x3xf64> into !K, (!Point, !Point)
  return %K1 : !K
}

// CHECK-LABEL: func.func @diagonal(
// CHECK-SAME: %[[N:.*]]: index, %[[M:.*]]: memref<?xf64>, %[[X:.*]]: memref<?x3xf64>) -> memref<?x3xf64>
// CHECK-SAME: simit.bindings = [{kind = "set_size", set = "points"}, {field = "m", kind = "field", set = "points"}, {field = "x", kind = "field", set = "points"}]
// CHECK: %[[OUT:.*]] = memref.alloc(%[[N]]) : memref<?x3x3xf64>
// CHECK: scf.parallel (%[[P:.*]]) = (%{{.*}}) to (%[[N]])
// CHECK: %[[MP:.*]] = memref.load %[[M]][%[[P]]] : memref<?xf64>
// CHECK: %[[OLD:.*]] = memref.load %[[OUT]][%[[P]], %c0, %c0] : memref<?x3x3xf64>
// CHECK: %[[NEW:.*]] = arith.addf %[[OLD]], %[[MP]] : f64
// CHECK: memref.store %[[NEW]], %[[OUT]][%[[P]], %c0, %c0]
// CHECK-NOT: simit.scatter
// CHECK: %[[Y:.*]] = memref.alloc(%[[N]]) : memref<?x3xf64>
// CHECK: return %[[Y]]
func.func @diagonal() -> !F attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %M, %x : !K, !F -> !F
  return %y : !F
}

// Frontend-style results: slots written under a condition.
func.func @springForce(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> (!K, !F) {
  %Kr = simit.alloc : !simit.ref<!K>
  %fr = simit.alloc : !simit.ref<!F>
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %blk = simit.broadcast %k : f64 -> tensor<3x3xf64>
  %c = simit.elem_read %a["c"] : !Point -> i32
  %zero = arith.constant 0 : i32
  %free = arith.cmpi sle, %c, %zero : i32
  scf.if %free {
    %K0 = simit.load %Kr : !simit.ref<!K>
    %K1 = simit.insert %blk into %K0[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
    simit.store %K1, %Kr : !simit.ref<!K>
  }
  %xb = simit.elem_read %b["x"] : !Point -> tensor<3xf64>
  %f0 = simit.load %fr : !simit.ref<!F>
  %f1 = simit.insert %xb into %f0[%a] : tensor<3xf64> into !F, (!Point)
  simit.store %f1, %fr : !simit.ref<!F>
  %K = simit.load %Kr : !simit.ref<!K>
  %f = simit.load %fr : !simit.ref<!F>
  return %K, %f : !K, !F
}

// An edge set stores through its location table: block loc[e][0 * 2 + 1].
// CHECK-LABEL: func.func @edges(
// CHECK-SAME: %[[NP:[^:]*]]: index, %[[NS:[^:]*]]: index, %[[ENDS:[^:]*]]: memref<?x2xi32>, %[[C:[^:]*]]: memref<?xi32>, %[[X:[^:]*]]: memref<?x3xf64>, %[[KF:[^:]*]]: memref<?xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %[[LOC:[^:]*]]: memref<?x4xi32>)
// CHECK-SAME: {kind = "endpoints", set = "springs"}
// CHECK-SAME: {cols = "points", kind = "pattern_locations", rows = "points", set = "springs"}
// CHECK: %[[NNZ32:.*]] = memref.load %[[ROWPTR]][%[[NP]]] : memref<?xi32>
// CHECK: %[[NNZ:.*]] = arith.index_cast %[[NNZ32]]
// CHECK: %[[KV:.*]] = memref.alloc(%[[NNZ]]) : memref<?x3x3xf64>
// CHECK: %[[FV:.*]] = memref.alloc(%[[NP]]) : memref<?x3xf64>
// CHECK: scf.parallel (%[[E:.*]]) = (%{{.*}}) to (%[[NS]])
// CHECK: %[[A32:.*]] = memref.load %[[ENDS]][%[[E]], %c0] : memref<?x2xi32>
// CHECK: %[[A:.*]] = arith.index_cast %[[A32]]
// CHECK: %[[B32:.*]] = memref.load %[[ENDS]][%[[E]], %c1] : memref<?x2xi32>
// CHECK: %[[B:.*]] = arith.index_cast %[[B32]]
// CHECK: memref.load %[[C]][%[[A]]] : memref<?xi32>
// CHECK: scf.if
// CHECK: %[[L32:.*]] = memref.load %[[LOC]][%[[E]], %c1] : memref<?x4xi32>
// CHECK: %[[L:.*]] = arith.index_cast %[[L32]]
// CHECK: memref.load %[[KV]][%[[L]], %c0, %c0]
// CHECK: memref.store %{{.*}}, %[[KV]][%[[L]], %c0, %c0]
// CHECK: memref.load %[[X]][%[[B]], %c0]
// CHECK: memref.load %[[FV]][%[[A]], %c0]
// CHECK: memref.store %{{.*}}, %[[FV]][%[[A]], %c0]
// CHECK: } {simit.scatter}
func.func @edges() -> (!F, !F) attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %K, %f = simit.assemble @springForce() to %springs reduce <add> : (!Springs) -> (!K, !F)
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.matvec %K, %x : !K, !F -> !F
  return %y, %f : !F, !F
}

// A map without results updates fields in place.
func.func @move(%dt : f64, %p : !Point) {
  %x = simit.elem_read %p["x"] : !Point -> tensor<3xf64>
  %s = simit.scale %dt, %x : f64, tensor<3xf64>
  simit.elem_write %s, %p["x"] : tensor<3xf64>, !Point
  return
}

// CHECK-LABEL: func.func @apply(
// CHECK-SAME: %[[DT:.*]]: f64, %[[N:.*]]: index, %[[X:.*]]: memref<?x3xf64>)
// CHECK: scf.parallel (%[[P:.*]]) = (%{{.*}}) to (%[[N]])
// CHECK-DAG: memref.load %[[X]][%[[P]], %c0]
// CHECK-DAG: memref.load %[[X]][%[[P]], %c1]
// CHECK-DAG: memref.load %[[X]][%[[P]], %c2]
// CHECK: %[[S:.*]] = arith.mulf %{{.*}}, %{{.*}} : vector<3xf64>
// CHECK: memref.store %{{.*}}, %[[X]][%[[P]], %c0]
// CHECK-NOT: simit.scatter
func.func @apply(%dt : f64) attributes {simit.export} {
  %points = simit.get_set @points : !Points
  simit.map @move(%dt) to %points : (f64, !Points) -> ()
  return
}

// Element functions and externs are gone.
// CHECK-NOT: simit.
