// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// An incidence D over (springs, points) times a matrix K assembled from the
// springs is stored on the bind-time pattern of the product (the pattern of
// "springs" over (springs, points) is the incidence's); the runtime's
// product reads D row by row through the incidence_* bindings (layout 2:
// row pointers, columns and value positions), and D' (over (points,
// springs)) through the same edge set's transposed rows.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64, y : f64}>
!D = !simit.tensor<["springs", "points"] x f64>
!DT = !simit.tensor<["points", "springs"] x f64>
!K = !simit.tensor<["points", "points"] x f64>
!DK = !simit.tensor<["springs", "points"] x f64>
!DD = !simit.tensor<["springs", "springs"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs

func.func @incidence(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !D {
  %one = arith.constant 1.0 : f64
  %p = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %q = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %z = simit.zeros : !D
  %d0 = simit.insert %one into %z[%s, %p] : f64 into !D, (!Spring, !Point)
  %d1 = simit.insert %one into %d0[%s, %q] : f64 into !D, (!Spring, !Point)
  return %d1 : !D
}

func.func @stiffness(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !K {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %p = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %q = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %z = simit.zeros : !K
  %a = simit.insert %k into %z[%p, %q] : f64 into !K, (!Point, !Point)
  return %a : !K
}

// CHECK-LABEL: func.func @incidence_times_pattern(
// CHECK-SAME: memref<?x4xi32>, %[[DROWS:[^:]*]]: memref<?xi32>, %[[DCOLS:[^:]*]]: memref<?xi32>, %[[DPOS:[^:]*]]: memref<?xi32>
// CHECK-SAME: {cols = "points", kind = "incidence_rowptr", rows = "springs", set = "springs"}
// CHECK-SAME: {cols = "points", kind = "incidence_colidx", rows = "springs", set = "springs"}
// CHECK-SAME: {cols = "points", kind = "incidence_positions", rows = "springs", set = "springs"}
// CHECK-SAME: {cols = "points", kind = "product_rowptr", mid = "points", rows = "springs", set = "springs*springs"}
// CHECK: %[[INCIDENCE:.*]] = arith.constant 2 : i32
// CHECK: call @simit_rt_matmul_bcsr(%[[INCIDENCE]], %[[DROWS]], %[[DCOLS]], %[[DPOS]], %{{[^,]*}}, %[[BCSR:[^,]*]],
func.func @incidence_times_pattern() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %points = simit.get_set @points : !Points
  %d = simit.assemble @incidence() to %springs reduce <add> : (!Springs) -> !D
  %k = simit.assemble @stiffness() to %springs reduce <add> : (!Springs) -> !K
  %dk = simit.matmul %d, %k : !D, !K -> !DK
  %x = simit.field_read %points["x"] : !Points -> !simit.tensor<["points"] x f64>
  %y = simit.matvec %dk, %x : !DK, !simit.tensor<["points"] x f64> -> !simit.tensor<["springs"] x f64>
  simit.field_write %y, %springs["y"] : !simit.tensor<["springs"] x f64>, !Springs
  return
}

// D D' over (springs, springs): D' is read through the transposed rows of
// the same edge set (rows "points", cols "springs").
// CHECK-LABEL: func.func @incidence_times_its_transpose(
// CHECK-SAME: {cols = "springs", kind = "incidence_rowptr", rows = "points", set = "springs"}
// CHECK-SAME: {cols = "points", kind = "incidence_rowptr", rows = "springs", set = "springs"}
// CHECK-SAME: {cols = "springs", kind = "product_rowptr", mid = "points", rows = "springs", set = "springs*springs"}
// CHECK: %[[LEFT:.*]] = arith.constant 2 : i32
// CHECK: %[[RIGHT:.*]] = arith.constant 2 : i32
// CHECK: call @simit_rt_matmul_bcsr(%[[LEFT]], %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}}, %[[RIGHT]],
func.func @incidence_times_its_transpose() attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %d = simit.assemble @incidence() to %springs reduce <add> : (!Springs) -> !D
  %dt = simit.transpose %d : !D -> !DT
  %dd = simit.matmul %d, %dt : !D, !DT -> !DD
  %k = simit.field_read %springs["k"] : !Springs -> !simit.tensor<["springs"] x f64>
  %y = simit.matvec %dd, %k : !DD, !simit.tensor<["springs"] x f64> -> !simit.tensor<["springs"] x f64>
  simit.field_write %y, %springs["y"] : !simit.tensor<["springs"] x f64>, !Springs
  return
}
