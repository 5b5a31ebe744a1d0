// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops \
// RUN:   --canonicalize | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, v : tensor<3xf64>}>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

// x = x + v reads the field arrays in place and, reading x only at the
// position it writes, computes straight into x: no temporary, no copy.
// CHECK-LABEL: func.func @in_place(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[V:[^:]*]]: memref<?x3xf64>, %[[X:[^:]*]]: memref<?x3xf64>)
// CHECK-NOT: memref.alloc
// CHECK-NOT: memref.copy
// CHECK: scf.parallel (%[[P:.*]]) =
// CHECK:   scf.for %[[C:.*]] =
// CHECK:     %[[X0:.*]] = memref.load %[[X]][%[[P]], %[[C]]]
// CHECK:     %[[V0:.*]] = memref.load %[[V]][%[[P]], %[[C]]]
// CHECK:     %[[S:.*]] = arith.addf %[[X0]], %[[V0]]
// CHECK:     memref.store %[[S]], %[[X]][%[[P]], %[[C]]]
// CHECK-NOT: memref.copy
// CHECK: return
func.func @in_place() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !F
  %v = simit.field_read %points["v"] : !Points -> !F
  %y = simit.add %x, %v : !F
  simit.field_write %y, %points["x"] : !F, !Points
  return
}

// The old x is used after x is written: the read copies.
// CHECK-LABEL: func.func @old_value(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[V:[^:]*]]: memref<?x3xf64>, %[[X:[^:]*]]: memref<?x3xf64>)
// CHECK: %[[OLD:.*]] = memref.alloc(%[[N]])
// CHECK: memref.copy %[[X]], %[[OLD]]
// CHECK: memref.copy %[[V]], %[[X]]
// CHECK: memref.copy %[[OLD]], %[[V]]
func.func @old_value() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !F
  %v = simit.field_read %points["v"] : !Points -> !F
  simit.field_write %v, %points["x"] : !F, !Points
  simit.field_write %x, %points["v"] : !F, !Points
  return
}

// A read used in a loop that writes the field sees the old value in every
// iteration: copied.
// CHECK-LABEL: func.func @loop(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[X:[^:]*]]: memref<?x3xf64>)
// CHECK: %[[OLD:.*]] = memref.alloc(%[[N]])
// CHECK: memref.copy %[[X]], %[[OLD]]
// CHECK: scf.for
// CHECK: memref.load %[[OLD]]
// CHECK: memref.store %{{.*}}, %[[X]]
func.func @loop() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !F
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c4 = arith.constant 4 : index
  scf.for %i = %c0 to %c4 step %c1 {
    %y = simit.add %x, %x : !F
    simit.field_write %y, %points["x"] : !F, !Points
  }
  return
}

// `f(p) = ...` on a variable in a loop over the set writes the variable's
// array in place: no copy per element.
// CHECK-LABEL: func.func @host_loop(
// CHECK-SAME: %[[N:[^:]*]]: index, %[[X:[^:]*]]: memref<?x3xf64>)
// CHECK: %[[F:.*]] = memref.alloc(%[[N]]) : memref<?x3xf64>
// CHECK: scf.for %[[P:.*]] = %c0 to %[[N]] step %c1 {
// CHECK-NOT: memref.alloc
// CHECK-NOT: memref.copy
// CHECK:   %[[X0:.*]] = memref.load %[[X]][%[[P]], %c0]
// CHECK:   %[[D:.*]] = arith.addf %{{.*}}, %{{.*}} : vector<3xf64>
// CHECK:   %[[D0:.*]] = vector.extract %[[D]][0]
// CHECK:   memref.store %[[D0]], %[[F]][%[[P]], %c0]
// CHECK: }
// CHECK: memref.copy %[[F]], %[[X]]
func.func @host_loop() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %f = simit.alloc : !simit.ref<!F>
  %x = simit.field_read %points["x"] : !Points -> !F
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %n = simit.set_size %points : !Points
  scf.for %i = %c0 to %n step %c1 {
    %p = simit.set_element %points[%i] : !Points -> !Point
    %xp = simit.extract %x[%p] : !F, (!Point) -> tensor<3xf64>
    %d = simit.add %xp, %xp : tensor<3xf64>
    %old = simit.load %f : !simit.ref<!F>
    %new = simit.insert %d into %old[%p] : tensor<3xf64> into !F, (!Point)
    simit.store %new, %f : !simit.ref<!F>
  }
  %final = simit.load %f : !simit.ref<!F>
  simit.field_write %final, %points["x"] : !F, !Points
  return
}
