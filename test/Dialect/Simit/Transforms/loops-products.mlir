// RUN: simit-opt %s --split-input-file --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops | FileCheck %s

// A product of system matrices stays a simit.matmul through
// simit-linalg-to-index-expr and becomes a call of the runtime's numeric
// product on the product's pattern (product_rowptr/colidx bindings, built
// once per binding); a diagonal factor passes layout 1 and empty index
// arrays, and the product keeps the other factor's pattern.

!Point = !simit.element<"Point", {m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Rods = !simit.set<"rods", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
simit.extern @rods : !Rods

func.func @link(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%a, %b] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}

func.func @mass(%p : !Point) -> !A {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %M0 = simit.zeros : !A
  %M1 = simit.insert %m into %M0[%p, %p] : f64 into !A, (!Point, !Point)
  return %M1 : !A
}

// CHECK-LABEL: func.func @products(
// CHECK-SAME: %[[NP:[^:]*]]: index
// CHECK-SAME: %[[SROWPTR:[^:]*]]: memref<?xi32>, %[[SCOLIDX:[^:]*]]: memref<?xi32>, %{{[^:]*}}: memref<?x4xi32>, %[[PROWPTR:[^:]*]]: memref<?xi32>, %[[PCOLIDX:[^:]*]]: memref<?xi32>)
// CHECK-SAME: {cols = "points", kind = "product_rowptr", mid = "points", rows = "points", set = "rods*springs"}, {cols = "points", kind = "product_colidx", mid = "points", rows = "points", set = "rods*springs"}]
// CHECK: %[[EMPTY:.*]] = memref.cast %{{.*}} : memref<0xi32> to memref<?xi32>
// CHECK-NOT: simit.matmul
// CHECK: %[[N:.*]] = memref.load %[[PROWPTR]][%[[NP]]] : memref<?xi32>
// CHECK: %[[NB:.*]] = arith.index_cast %[[N]] : i32 to index
// CHECK: %[[C:.*]] = memref.alloc(%[[NB]]) : memref<?xf64>
// CHECK: call @simit_rt_matmul_bcsr(%c0_i32{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}}, %[[EMPTY]], %{{[^,]*}}, %c0_i32{{[^,]*}}, %[[SROWPTR]], %[[SCOLIDX]], %[[EMPTY]], %{{[^,]*}}, %c0_i32{{[^,]*}}, %[[PROWPTR]], %[[PCOLIDX]], %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}})
// CHECK: %[[D:.*]] = memref.alloc(%{{.*}}) : memref<?xf64>
// CHECK: call @simit_rt_matmul_bcsr(%c1_i32{{[^,]*}}, %[[EMPTY]], %[[EMPTY]], %[[EMPTY]], %{{[^,]*}}, %c0_i32{{[^,]*}}, %[[SROWPTR]], %[[SCOLIDX]], %[[EMPTY]], %{{[^,]*}}, %c0_i32{{[^,]*}}, %[[SROWPTR]], %[[SCOLIDX]], %{{[^,]*}}, %{{[^,]*}}, %{{[^,]*}})
// CHECK: func.func private @simit_rt_matmul_bcsr(i32, memref<?xi32>, memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, i32, memref<?xi32>, memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, i32, memref<?xi32>, memref<?xi32>, memref<?x?x?xf64>, i64, !llvm.ptr) attributes {llvm.emit_c_interface}
func.func @products() -> (f64, f64) attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %rods = simit.get_set @rods : !Rods
  %points = simit.get_set @points : !Points
  %S = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
  %R = simit.assemble @link() to %rods reduce <add> : (!Rods) -> !A
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !A
  %C = simit.matmul %R, %S : !A, !A -> !A
  %D = simit.matmul %M, %S : !A, !A -> !A
  %x = simit.field_read %points["m"] : !Points -> !simit.tensor<["points"] x f64>
  %y = simit.matvec %C, %x : !A, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x f64>
  %z = simit.matvec %D, %x : !A, !simit.tensor<["points"] x f64> -> !simit.tensor<["points"] x f64>
  %ny = simit.norm %y : !simit.tensor<["points"] x f64> -> f64
  %nz = simit.norm %z : !simit.tensor<["points"] x f64> -> f64
  return %ny, %nz : f64, f64
}
