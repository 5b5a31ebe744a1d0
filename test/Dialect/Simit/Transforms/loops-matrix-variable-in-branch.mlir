// RUN: simit-opt %s --simit-linalg-to-index-expr --convert-simit-to-loops | FileCheck %s

// A matrix variable first assigned inside a branch: its array is made,
// zero filled, where it is declared, and the branch copies into it.
!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!A = !simit.tensor<["points", "points"] x f64>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @springs : !Springs
func.func @link(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> !A {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %A0 = simit.zeros : !A
  %A1 = simit.insert %k into %A0[%a, %a] : f64 into !A, (!Point, !Point)
  return %A1 : !A
}
// CHECK-LABEL: func.func @late
// CHECK:         %[[VAR:.*]] = memref.alloc(%{{.*}}) : memref<?xf64>
// CHECK:         memref.store %{{.*}}, %[[VAR]]
// CHECK:         scf.if %arg0 {
// CHECK:           %[[A:.*]] = memref.alloc(%{{.*}}) : memref<?xf64>
// CHECK:           memref.copy %[[A]], %[[VAR]]
func.func @late(%c : i1) attributes {simit.export} {
  %springs = simit.get_set @springs : !Springs
  %var = simit.alloc : !simit.ref<!A>
  scf.if %c {
    %A = simit.assemble @link() to %springs reduce <add> : (!Springs) -> !A
    simit.store %A, %var : !simit.ref<!A>
  }
  return
}
