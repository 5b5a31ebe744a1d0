// RUN: simit-opt %s --simit-linalg-to-index-expr --simit-assign-storage --convert-simit-to-loops --canonicalize | FileCheck %s

// Patterns known only at run time: a product with a host function's matrix
// gets its pattern from the runtime where it is computed
// (simit_rt_product_pattern), a stored sum or transpose of one where it is
// first needed (simit_rt_union_pattern, a diagonal member through the
// BCSR pattern of its layout, one block a row; simit_rt_transpose_pattern);
// simit_rt_pattern_take copies each into fresh arrays, which the product
// and the reads then use.

!Point = !simit.element<"Point", {x : f64, y : f64, m : f64}>
!Points = !simit.set<"points", !Point>
!K = !simit.tensor<["points", "points"] x f64>
!X = !simit.tensor<["points"] x f64>
simit.extern @points : !Points
func.func private @tridiagonal() -> !K attributes {simit.extern_function = "tridiagonal"}
func.func private @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["m"] : !Point -> f64
  %z = simit.zeros : !K
  %M = simit.insert %m into %z[%p, %p] : f64 into !K, (!Point, !Point)
  return %M : !K
}

// CHECK-LABEL: func.func @product(
// CHECK: call @simit_host.simit_rt_host_matrix_adopt(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %[[RP:[^,]*]], %[[CI:[^,]*]], %{{.*}})
// CHECK: %[[H:.*]] = call @simit_rt_product_pattern(%[[RP]], %[[CI]], %[[RP]], %[[CI]], %{{.*}}) : (memref<?xi32>, memref<?xi32>, memref<?xi32>, memref<?xi32>, i64) -> !llvm.ptr
// CHECK: %[[NB:.*]] = call @simit_rt_pattern_blocks(%[[H]])
// CHECK: %[[PRP:.*]] = memref.alloc(%{{.*}}) : memref<?xi32>
// CHECK: %[[PCI:.*]] = memref.alloc(%{{.*}}) : memref<?xi32>
// CHECK: call @simit_rt_pattern_take(%[[H]], %[[PRP]], %[[PCI]])
// CHECK: call @simit_rt_matmul_bcsr(%c0_i32, %[[RP]], %[[CI]], %{{.*}}, %{{.*}}, %c0_i32, %[[RP]], %[[CI]], %{{.*}}, %{{.*}}, %c0_i32, %[[PRP]], %[[PCI]],
// CHECK: scf.parallel
// CHECK: memref.load %[[PRP]]
func.func @product() attributes {simit.export} {
  %T = func.call @tridiagonal() : () -> !K
  %S = simit.matmul %T, %T : !K, !K -> !K
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !X
  %y = simit.matvec %S, %x : !K, !X -> !X
  simit.field_write %y, %points["y"] : !X, !Points
  return
}

// CHECK-LABEL: func.func @sum(
// CHECK: call @simit_host.simit_rt_host_matrix_adopt(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %[[RP:[^,]*]], %[[CI:[^,]*]], %{{.*}})
// CHECK: %[[DRP:.*]] = memref.alloc(%{{.*}}) : memref<?xi32>
// CHECK: %[[DCI:.*]] = memref.alloc(%{{.*}}) : memref<?xi32>
// CHECK: scf.for %[[R:[^ ]*]] =
// CHECK: memref.store %{{.*}}, %[[DRP]][%[[R]]]
// CHECK: memref.store %{{.*}}, %[[DCI]][%[[R]]]
// CHECK: %[[H:.*]] = call @simit_rt_union_pattern(%[[DRP]], %[[DCI]], %[[RP]], %[[CI]], %{{.*}}) : (memref<?xi32>, memref<?xi32>, memref<?xi32>, memref<?xi32>, i64) -> !llvm.ptr
// CHECK: call @simit_rt_pattern_blocks(%[[H]])
// CHECK: call @simit_rt_pattern_take(%[[H]], %[[URP:[^,]*]], %[[UCI:[^)]*]])
// CHECK: scf.parallel
// CHECK: memref.load %[[URP]]
func.func @sum() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %T = func.call @tridiagonal() : () -> !K
  %B = simit.add %T, %M : !K
  %x = simit.field_read %points["x"] : !Points -> !X
  %y = simit.matvec %B, %x : !K, !X -> !X
  %z = simit.matvec %B, %y : !K, !X -> !X
  simit.field_write %z, %points["y"] : !X, !Points
  return
}

// CHECK-LABEL: func.func @transposed(
// CHECK: call @simit_host.simit_rt_host_matrix_adopt(%{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %{{.*}}, %[[RP:[^,]*]], %[[CI:[^,]*]], %{{.*}})
// CHECK: %[[H:.*]] = call @simit_rt_transpose_pattern(%[[RP]], %[[CI]], %{{.*}}) : (memref<?xi32>, memref<?xi32>, i64) -> !llvm.ptr
// CHECK: call @simit_rt_pattern_blocks(%[[H]])
// CHECK: call @simit_rt_pattern_take(%[[H]], %[[TRP:[^,]*]], %[[TCI:[^)]*]])
// CHECK: scf.parallel
// CHECK: memref.load %[[TRP]]
func.func @transposed() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %T = func.call @tridiagonal() : () -> !K
  %B = simit.transpose %T : !K -> !K
  %x = simit.field_read %points["x"] : !Points -> !X
  %y = simit.matvec %B, %x : !K, !X -> !X
  %z = simit.matvec %B, %y : !K, !X -> !X
  simit.field_write %z, %points["y"] : !X, !Points
  return
}
