// End to end: a spring system assembled, combined and multiplied, lowered by
// the Simit passes, linked with the host driver of Inputs/springs-driver.mlir
// and run. Expected values by hand (see the comments at @step).
//
// RUN: simit-opt %s --simit-inline-functions --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops > %t.loops.mlir
// RUN: FileCheck %s --check-prefix=ABI < %t.loops.mlir
// RUN: sed '/^}$/d' %t.loops.mlir > %t.mlir
// RUN: cat %S/Inputs/springs-driver.mlir >> %t.mlir
// RUN: echo '}' >> %t.mlir
// RUN: simit-opt %t.mlir --simit-cpu-pipeline | mlir-runner -e main \
// RUN:   -entry-point-result=void \
// RUN:   -shared-libs=%mlir_lib_dir/libmlir_runner_utils.so,%mlir_lib_dir/libmlir_c_runner_utils.so \
// RUN:   | FileCheck %s

// The driver passes the data in this order.
// ABI-LABEL: func.func @step(
// ABI-SAME: simit.bindings = [{kind = "set_size", set = "points"}, {kind = "set_size", set = "springs"}, {kind = "endpoints", set = "springs"}, {field = "m", kind = "field", set = "points"}, {field = "v", kind = "field", set = "points"}, {field = "x", kind = "field", set = "points"}, {field = "k", kind = "field", set = "springs"}, {cols = "points", kind = "pattern_rowptr", rows = "points", set = "springs"}, {cols = "points", kind = "pattern_colidx", rows = "points", set = "springs"}, {cols = "points", kind = "pattern_locations", rows = "points", set = "springs"}, {kind = "extern", name = "h", shape = array<i64>}, {kind = "extern", name = "out", shape = array<i64>}]

// Points x = (0,0,0), (1,0,0), (1,2,0); m = 1, 2, 3; v = e0, e1, e2.
// Springs (0,1) k = 10 and (1,2) k = 20; h = 0.5.
// fm = m v = (1,0,0), (0,2,0), (0,0,3); fe = k (xb - xa) at a, minus at b:
//   (10,0,0), (-10,40,0), (0,-40,0).
// A = M + h K with blocks (multiples of I): A00 = 6, A01 = A10 = -5,
//   A11 = 17, A12 = A21 = -10, A22 = 13.
// A x = (-5,0,0), (7,-20,0), (3,26,0); r = fm + fe - A x =
//   (16,0,0), (-17,62,0), (-3,-66,3); r.r = 8763.
// CHECK: sizes = [3, 3]
// CHECK-NEXT: [16, 0, 0]
// CHECK-NEXT: [-17, 62, 0]
// CHECK-NEXT: [-3, -66, 3]
// CHECK: rank = 0
// CHECK-NEXT: [8763]

!Point = !simit.element<"Point", {x : tensor<3xf64>, v : tensor<3xf64>, m : f64, c : i32}>
!Spring = !simit.element<"Spring", {k : f64, l0 : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
simit.extern @h : f64
simit.extern @out : f64

func.func private @pointMass(%p : !Point) -> (!K, !F) {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %I = arith.constant dense<[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]> : tensor<3x3xf64>
  %blk = simit.scale %m, %I : f64, tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%p, %p] : tensor<3x3xf64> into !K, (!Point, !Point)
  %v = simit.elem_read %p["v"] : !Point -> tensor<3xf64>
  %mv = simit.scale %m, %v : f64, tensor<3xf64>
  %f0 = simit.zeros : !F
  %f1 = simit.insert %mv into %f0[%p] : tensor<3xf64> into !F, (!Point)
  return %K1, %f1 : !K, !F
}

func.func private @springForce(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> (!K, !F) {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %xa = simit.elem_read %a["x"] : !Point -> tensor<3xf64>
  %xb = simit.elem_read %b["x"] : !Point -> tensor<3xf64>
  %d = simit.sub %xb, %xa : tensor<3xf64>
  %f = simit.scale %k, %d : f64, tensor<3xf64>
  %nf = simit.neg %f : tensor<3xf64>
  %I = arith.constant dense<[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]> : tensor<3x3xf64>
  %blk = simit.scale %k, %I : f64, tensor<3x3xf64>
  %nblk = simit.neg %blk : tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K2 = simit.insert %nblk into %K1[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K3 = simit.insert %nblk into %K2[%b, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K4 = simit.insert %blk into %K3[%b, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  %f0 = simit.zeros : !F
  %f1 = simit.insert %f into %f0[%a] : tensor<3xf64> into !F, (!Point)
  %f2 = simit.insert %nf into %f1[%b] : tensor<3xf64> into !F, (!Point)
  return %K4, %f2 : !K, !F
}

func.func @step() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %springs = simit.get_set @springs : !Springs
  %M, %fm = simit.assemble @pointMass() to %points reduce <add> : (!Points) -> (!K, !F)
  %K, %fe = simit.assemble @springForce() to %springs reduce <add> : (!Springs) -> (!K, !F)
  %hr = simit.extern_ref @h : !simit.ref<f64>
  %h = simit.load %hr : !simit.ref<f64>
  %hK = simit.scale %h, %K : f64, !K
  %A = simit.add %M, %hK : !K
  %x = simit.field_read %points["x"] : !Points -> !F
  %Ax = simit.matvec %A, %x : !K, !F -> !F
  %f = simit.add %fm, %fe : !F
  %r = simit.sub %f, %Ax : !F
  %rr = simit.dot %r, %r : !F, !F -> f64
  %outr = simit.extern_ref @out : !simit.ref<f64>
  simit.store %rr, %outr : !simit.ref<f64>
  simit.field_write %r, %points["v"] : !F, !Points
  return
}
