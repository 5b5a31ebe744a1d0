// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-fuse-index-expr \
// RUN:   --convert-simit-to-loops --canonicalize --cse | FileCheck %s

// A' * x on a pattern matrix: the loop runs over A's rows i (an scf.for,
// since rows scatter into shared entries of the result), binds j from the
// row's blocks and adds A[k] * x[i] into y[j].

!Point = !simit.element<"Point", {x : f64}>
!Link = !simit.element<"Link", {w : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!V = !simit.tensor<["points"] x f64>
!Points = !simit.set<"points", !Point>
!Links = !simit.set<"links", !Link, ["points", "points"]>
simit.extern @points : !Points
simit.extern @links : !Links

func.func @upper(%l : !Link, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %w = simit.elem_read %l["w"] : !Link -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %w into %A0[%a, %b] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

// CHECK-LABEL: func.func @transposed(
// CHECK-SAME: %{{[^:]*}}: index, %[[NP:[^:]*]]: index, {{.*}}%[[X:[^:]*]]: memref<?xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>)
// CHECK: %[[AV:.*]] = memref.alloc
// CHECK: } {simit.scatter}
// CHECK: %[[Y:.*]] = memref.alloc(%[[NP]]) : memref<?xf64>
// CHECK: memref.store %cst, %[[Y]]
// CHECK: scf.for %[[I:.*]] = %c0 to %[[NP]] step %c1 {
// CHECK:   %[[LO:.*]] = memref.load %[[ROWPTR]][%[[I]]]
// CHECK:   %[[HI:.*]] = memref.load %[[ROWPTR]][%{{.*}}]
// CHECK:   scf.for %[[K:.*]] = %{{.*}} to %{{.*}} step %c1 {
// CHECK:     %[[J32:.*]] = memref.load %[[COLIDX]][%[[K]]]
// CHECK:     %[[J:.*]] = arith.index_cast %[[J32]]
// CHECK:     %[[AK:.*]] = memref.load %[[AV]][%[[K]]]
// CHECK:     %[[XI:.*]] = memref.load %[[X]][%[[I]]]
// CHECK:     %[[P:.*]] = arith.mulf %[[AK]], %[[XI]]
// CHECK:     %[[OLD:.*]] = memref.load %[[Y]][%[[J]]]
// CHECK:     %[[NEW:.*]] = arith.addf %[[OLD]], %[[P]]
// CHECK:     memref.store %[[NEW]], %[[Y]][%[[J]]]
// CHECK: return %[[Y]]
func.func @transposed() -> !V attributes {simit.export} {
  %links = simit.get_set @links : !Links
  %points = simit.get_set @points : !Points
  %A = simit.assemble @upper() to %links reduce <add> : (!Links) -> !A
  %At = simit.transpose %A : !A -> !A
  %x = simit.field_read %points["x"] : !Points -> !V
  %y = simit.matvec %At, %x : !A, !V -> !V
  return %y : !V
}
