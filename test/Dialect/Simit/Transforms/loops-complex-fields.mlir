// RUN: simit-opt %s --split-input-file --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops | FileCheck %s

// A complex field is an array of complex numbers over its set; the host
// binds it as (re, im) pairs of its parts.
!Point = !simit.element<"Point", {z : complex<f64>}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @conj(%p : !Point) {
  %z = simit.elem_read %p["z"] : !Point -> complex<f64>
  %c = complex.conj %z : complex<f64>
  simit.elem_write %c, %p["z"] : complex<f64>, !Point
  return
}

// CHECK-LABEL: func.func @step
// CHECK-SAME: %[[Z:[a-z0-9]+]]: memref<?xcomplex<f64>>
// CHECK: scf.parallel (%[[I:.*]]) =
// CHECK: %[[V:.*]] = memref.load %[[Z]][%[[I]]] : memref<?xcomplex<f64>>
// CHECK: %[[C:.*]] = complex.conj %[[V]]
// CHECK: memref.store %[[C]], %[[Z]][%[[I]]] : memref<?xcomplex<f64>>
func.func @step() attributes {simit.export} {
  %s = simit.get_set @points : !Points
  simit.map @conj() to %s : (!Points) -> ()
  return
}
