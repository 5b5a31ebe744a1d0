// RUN: simit-opt %s -cse -canonicalize | FileCheck %s

!P = !simit.element<"P", {m : f64}>
!S = !simit.set<"points", !P>
!V = !simit.tensor<["points"] x f64>
simit.extern @points : !S

// Pure operations are merged by CSE and removed when unused.
// CHECK-LABEL: func.func @pure
// CHECK-COUNT-1: simit.matvec
// CHECK-NOT: simit.dot
// CHECK-NOT: simit.matvec
func.func @pure(%A : !simit.tensor<["points", "points"] x f64>, %x : !V) -> (!V, !V) {
  %y1 = simit.matvec %A, %x : !simit.tensor<["points", "points"] x f64>, !V -> !V
  %y2 = simit.matvec %A, %x : !simit.tensor<["points", "points"] x f64>, !V -> !V
  %unused = simit.dot %x, %x : !V, !V -> f64
  return %y1, %y2 : !V, !V
}

// A field write separates two reads of the field; writes and prints stay.
// CHECK-LABEL: func.func @fields
// CHECK: simit.field_read
// CHECK: simit.field_write
// CHECK: simit.field_read
// CHECK: simit.print
func.func @fields(%v : !V) -> (!V, !V) {
  %s = simit.get_set @points : !S
  %a = simit.field_read %s["m"] : !S -> !V
  simit.field_write %v, %s["m"] : !V, !S
  %b = simit.field_read %s["m"] : !S -> !V
  %unused = simit.field_read %s["m"] : !S -> !V
  simit.print %a {newline} : !V
  return %a, %b : !V, !V
}

// An unused slot is removed; a map is kept for its effects.
// CHECK-LABEL: func.func @slots_and_maps
// CHECK-NOT: simit.alloc
// CHECK: simit.map @touch
func.func @touch(%p : !P) {
  %m = simit.elem_read %p["m"] : !P -> f64
  simit.elem_write %m, %p["m"] : f64, !P
  return
}
func.func @slots_and_maps() {
  %r = simit.alloc : !simit.ref<f64>
  %s = simit.get_set @points : !S
  simit.map @touch() to %s : (!S) -> ()
  return
}

// Each factorisation is a handle of its own, never merged; frees stay.
// CHECK-LABEL: func.func @factorisations
// CHECK-COUNT-2: simit.factorize
// CHECK-COUNT-2: simit.factor_free
func.func @factorisations(%m : tensor<2x2xf64>) {
  %h = simit.factorize lu %m : tensor<2x2xf64>
  %g = simit.factorize lu %m : tensor<2x2xf64>
  simit.factor_free lu %h
  simit.factor_free lu %g
  return
}
