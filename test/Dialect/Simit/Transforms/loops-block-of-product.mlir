// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-fuse-index-expr \
// RUN:   --convert-simit-to-loops --canonicalize --cse | FileCheck %s

// A block of a product read right after it and nowhere else, (A x)(p) (the
// frontend's A(p,:) * x of a blocked A), is computed alone: row p's blocks
// summed in loop-carried values, no loop over the rows, no vector y.

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!Link = !simit.element<"Link", {w : f64}>
!A = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!V = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Links = !simit.set<"links", !Link, ["points", "points"]>
simit.extern @points : !Points
simit.extern @links : !Links

func.func @upper(%l : !Link, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %w = simit.elem_read %l["w"] : !Link -> f64
  %B = arith.constant dense<[[1.0, 2.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 3.0]]> : tensor<3x3xf64>
  %block = simit.scale %w, %B : f64, tensor<3x3xf64>
  %A0 = simit.zeros : !A
  %A1 = simit.insert %block into %A0[%a, %b] : tensor<3x3xf64> into !A, (!Point, !Point)
  return %A1 : !A
}

// CHECK-LABEL: func.func @row(
// CHECK-SAME: %[[I:[^:]*]]: index, {{.*}}%[[X:[^:]*]]: memref<?x3xf64>, %[[ROWPTR:[^:]*]]: memref<?xi32>, %[[COLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>)
// CHECK: %[[AV:.*]] = memref.alloc
// CHECK: } {simit.scatter}
// CHECK-NOT: scf.parallel
// CHECK-NOT: memref.alloc
// CHECK: %[[LO:.*]] = memref.load %[[ROWPTR]][%[[I]]]
// CHECK: %[[HI:.*]] = memref.load %[[ROWPTR]][%{{.*}}]
// CHECK: %[[SUMS:.*]]:3 = scf.for %[[K:.*]] = %{{.*}} to %{{.*}} step %c1 iter_args({{.*}}) -> (vector<4xf64>, vector<4xf64>, f64) {
// CHECK:   memref.load %[[COLIDX]][%[[K]]]
// CHECK:   memref.load %[[AV]][%[[K]], %c0, %c0]
// CHECK:   memref.load %[[X]]
// CHECK:   vector.from_elements {{.*}} : vector<4xf64>
// CHECK:   scf.yield
// CHECK: vector.extract %[[SUMS]]#0[0]
// CHECK: vector.from_elements {{.*}} : vector<3xf64>
func.func @row(%i : index) -> tensor<3xf64> attributes {simit.export} {
  %links = simit.get_set @links : !Links
  %points = simit.get_set @points : !Points
  %A = simit.assemble @upper() to %links reduce <add> : (!Links) -> !A
  %x = simit.field_read %points["x"] : !Points -> !V
  %p = simit.set_element %points[%i] : !Points -> !Point
  %y = simit.matvec %A, %x : !A, !V -> !V
  %b = simit.extract %y[%p] : !V, (!Point) -> tensor<3xf64>
  return %b : tensor<3xf64>
}

// A' x has no row sums: the whole product, then its block.
// CHECK-LABEL: func.func @column(
// CHECK: %[[Y:.*]] = memref.alloc(%{{.*}}) : memref<?x3xf64>
// CHECK: scf.for
// CHECK: memref.load %[[Y]][%{{.*}}, %c0]
func.func @column(%i : index) -> tensor<3xf64> attributes {simit.export} {
  %links = simit.get_set @links : !Links
  %points = simit.get_set @points : !Points
  %A = simit.assemble @upper() to %links reduce <add> : (!Links) -> !A
  %At = simit.transpose %A : !A -> !A
  %x = simit.field_read %points["x"] : !Points -> !V
  %p = simit.set_element %points[%i] : !Points -> !Point
  %y = simit.matvec %At, %x : !A, !V -> !V
  %b = simit.extract %y[%p] : !V, (!Point) -> tensor<3xf64>
  return %b : tensor<3xf64>
}
