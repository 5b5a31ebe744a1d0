// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops \
// RUN:   --canonicalize --cse | FileCheck %s

// A variable holding an assembled matrix takes the matrix's array (a fresh
// matrix stored once). A(q,q) = 1 + A(q,q) in a loop finds block (q, q) by
// a scan of row q's columns, reads it (zero when absent) and writes it in
// place after asserting it exists; the write reuses the read's scan.

!Point = !simit.element<"Point", {x : f64}>
!V = !simit.tensor<["points"] x f64>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @link(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%a, %b] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

// CHECK-LABEL: func.func @diagonal(
// CHECK-SAME: %[[NP:[^:]*]]: index, {{.*}}%[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>)
// CHECK: %[[AV:.*]] = memref.alloc
// CHECK: } {simit.scatter}
// CHECK-NOT: memref.copy
// CHECK: scf.for %[[Q:.*]] = %c0 to %[[NP]] step %c1 {
// CHECK:   %[[POS:.*]] = scf.for %[[K:.*]] = %{{.*}} to %{{.*}} step %c1 iter_args(%[[FOUND:.*]] = %c-1) -> (index) {
// CHECK:     %[[C32:.*]] = memref.load %[[COLIDX]][%[[K]]]
// CHECK:     %[[C:.*]] = arith.index_cast %[[C32]]
// CHECK:     %[[MATCH:.*]] = arith.cmpi eq, %[[C]], %[[Q]]
// CHECK:     %[[SEL:.*]] = arith.select %[[MATCH]], %[[K]], %[[FOUND]]
// CHECK:     scf.yield %[[SEL]]
// CHECK:   %[[HAS:.*]] = arith.cmpi sge, %[[POS]], %c0
// CHECK:   %[[OLD:.*]] = scf.if %[[HAS]] -> (f64) {
// CHECK:     %[[V:.*]] = memref.load %[[AV]][%[[POS]]]
// CHECK:     scf.yield %[[V]]
// CHECK:   } else {
// CHECK:     scf.yield %{{.*}}
// CHECK:   %[[NEW:.*]] = arith.addf %[[OLD]], %{{.*}}
// The write reuses the read's scan.
// CHECK-NOT: scf.for
// CHECK:   cf.assert %[[HAS]], "writing a block outside the storage of the matrix, pattern of 'springs' over ('points', 'points')
// CHECK:   memref.store %[[NEW]], %[[AV]][%[[POS]]]
// The matrix product reads the variable's array.
// CHECK: memref.load %[[AV]]
func.func @diagonal() -> !V attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %var = simit.alloc : !simit.ref<!A>
  simit.store %A, %var : !simit.ref<!A>
  %n = simit.set_size %points : !Points
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %one = arith.constant 1.0 : f64
  scf.for %i = %c0 to %n step %c1 {
    %q = simit.set_element %points[%i] : !Points -> !Point
    %A1 = simit.load %var : !simit.ref<!A>
    %old = simit.extract %A1[%q, %q] : !A, (!Point, !Point) -> f64
    %new = arith.addf %old, %one : f64
    %A2 = simit.insert %new into %A1[%q, %q] : f64 into !A, (!Point, !Point)
    simit.store %A2, %var : !simit.ref<!A>
  }
  %result = simit.load %var : !simit.ref<!A>
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %result, %x : !A, !V -> !V
  return %y : !V
}
