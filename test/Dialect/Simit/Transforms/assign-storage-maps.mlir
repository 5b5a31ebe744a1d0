// RUN: simit-opt %s --simit-assign-storage | FileCheck %s

// Assembled matrices are stored by where their set can write, read from the
// set type: all assemblies of one set share one storage.

!Point = !simit.element<"Point", {x : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
!Ends = !simit.tuple<!Point x 2>
!K = !simit.tensor<["points", "points"] x f64>
!I = !simit.tensor<["springs", "points"] x f64>
!IT = !simit.tensor<["points", "springs"] x f64>

// CHECK-DAG: #diag_points = #simit.storage<diag("points")>
// CHECK-DAG: #pat_springs = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
// CHECK-DAG: #inc_springs = #simit.storage<incidence("springs", cols [0, 1])>
// CHECK-DAG: #inc_springs_t = #simit.storage<transpose(incidence("springs", cols [0, 1]))>
// CHECK-DAG: #pat_links = #simit.storage<pattern("links", rows [0], cols [1])>
// CHECK-DAG: #pat_links1 = #simit.storage<pattern("links", rows [1], cols [0])>
// CHECK-DAG: #stencil_cells = #simit.storage<stencil("cells", {{\[\[}}0, 0], [1, 0], [2, 1]])>

// Element functions return one element's contributions and keep their types.
// CHECK-LABEL: func.func private @mass(
// CHECK-SAME: -> !simit.tensor<["points", "points"] x f64>
func.func private @mass(%p : !Point) -> !K {
  %m = simit.elem_read %p["x"] : !Point -> f64
  %z = simit.zeros : !K
  %M = simit.insert %m into %z[%p, %p] : f64 into !K, (!Point, !Point)
  return %M : !K
}

func.func private @stiffness(%s : !Spring, %e : !Ends) -> (!K, !I, !IT) {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %a = simit.tuple_get %e[0] : !Ends -> !Point
  %b = simit.tuple_get %e[1] : !Ends -> !Point
  %z = simit.zeros : !K
  %K = simit.insert %k into %z[%a, %b] : f64 into !K, (!Point, !Point)
  %zi = simit.zeros : !I
  %I = simit.insert %k into %zi[%s, %a] : f64 into !I, (!Spring, !Point)
  %zt = simit.zeros : !IT
  %T = simit.insert %k into %zt[%b, %s] : f64 into !IT, (!Point, !Spring)
  return %K, %I, %T : !K, !I, !IT
}

// CHECK-LABEL: func.func @vertex_set
// CHECK: simit.assemble @mass() to %{{.*}} reduce <add> : (!simit.set<"points", !Point>) -> !simit.tensor<["points", "points"] x f64, #diag_points>
// CHECK: simit.map @mass() to %{{.*}} : (!simit.set<"points", !Point>) -> !simit.tensor<["points", "points"] x f64, #diag_points>
func.func @vertex_set(%points : !Points) -> f64 {
  %M = simit.assemble @mass() to %points reduce <add> : (!Points) -> !K
  %N = simit.map @mass() to %points : (!Points) -> !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

// Over the endpoint sets: the pattern of the endpoint positions of the rows
// and columns, whatever the element function writes. Over the edges and
// their endpoints: the incidence, and its transpose.
// CHECK-LABEL: func.func @edge_set
// CHECK: simit.assemble @stiffness() to %{{.*}} reduce <add>
// CHECK-SAME: -> (!simit.tensor<["points", "points"] x f64, #pat_springs>, !simit.tensor<["springs", "points"] x f64, #inc_springs>, !simit.tensor<["points", "springs"] x f64, #inc_springs_t>)
func.func @edge_set(%springs : !Springs) -> f64 {
  %K, %I, %T = simit.assemble @stiffness() to %springs reduce <add>
      : (!Springs) -> (!K, !I, !IT)
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

!Particle = !simit.element<"Particle", {m : f64}>
!Node = !simit.element<"Node", {m : f64}>
!Links = !simit.set<"links", !Spring, ["particles", "nodes"]>
!Link = !simit.tuple<{p : !Particle, n : !Node}>
!H = !simit.tensor<["particles", "nodes"] x f64>
!HT = !simit.tensor<["nodes", "particles"] x f64>

func.func private @couple(%s : !Spring, %e : !Link) -> (!H, !HT) {
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %p = simit.tuple_get %e[0] : !Link -> !Particle
  %n = simit.tuple_get %e[1] : !Link -> !Node
  %z = simit.zeros : !H
  %H = simit.insert %k into %z[%p, %n] : f64 into !H, (!Particle, !Node)
  %zt = simit.zeros : !HT
  %T = simit.insert %k into %zt[%n, %p] : f64 into !HT, (!Node, !Particle)
  return %H, %T : !H, !HT
}

// Heterogeneous endpoints: each set is one position.
// CHECK-LABEL: func.func @heterogeneous
// CHECK: -> (!simit.tensor<["particles", "nodes"] x f64, #pat_links>, !simit.tensor<["nodes", "particles"] x f64, #pat_links1>)
func.func @heterogeneous(%links : !Links) -> f64 {
  %H, %T = simit.assemble @couple() to %links reduce <add> : (!Links) -> (!H, !HT)
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}

!Cell = !simit.element<"Cell", {k : f64}>
!Cells = !simit.set<"cells", !Cell, grid 2 over "points">

// Through a grid: the offsets written, and offset 0.
func.func private @laplace(%p : !Point, %g : !Cells) -> !K {
  %c = arith.constant 1.0 : f64
  %right = simit.grid_point %g, %p [1, 0] : !Cells, !Point
  %far = simit.grid_point %g, %right [1, 1] : !Cells, !Point
  %z = simit.zeros : !K
  %A1 = simit.insert %c into %z[%p, %right] : f64 into !K, (!Point, !Point)
  %A2 = simit.insert %c into %A1[%p, %far] : f64 into !K, (!Point, !Point)
  return %A2 : !K
}

// CHECK-LABEL: func.func @grid
// CHECK: simit.map @laplace() to %{{.*}} through %{{.*}} : {{.*}} -> !simit.tensor<["points", "points"] x f64, #stencil_cells>
func.func @grid(%points : !Points, %cells : !Cells) -> f64 {
  %A = simit.map @laplace() to %points through %cells : (!Points, !Cells) -> !K
  %zero = arith.constant 0.0 : f64
  return %zero : f64
}
