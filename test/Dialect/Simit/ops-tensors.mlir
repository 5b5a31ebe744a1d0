// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!Point = !simit.element<"Point", {x : tensor<3xf64>, m : f64}>
!Spring = !simit.element<"Spring", {k : f64}>
simit.extern @points : !simit.set<"points", !Point>
simit.extern @springs : !simit.set<"springs", !Spring, ["points", "points"]>

// CHECK-LABEL: func.func @construct
func.func @construct(%s : f64) {
  // CHECK: simit.zeros : tensor<3x3xf64>
  %a = simit.zeros : tensor<3x3xf64>
  // CHECK: simit.zeros : !simit.tensor<["points"] x tensor<3xf64>>
  %b = simit.zeros : !simit.tensor<["points"] x tensor<3xf64>>
  // CHECK: simit.broadcast %{{.*}} : f64 -> tensor<3x3xf64>
  %c = simit.broadcast %s : f64 -> tensor<3x3xf64>
  // CHECK: simit.broadcast %{{.*}} : f64 -> !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  %d = simit.broadcast %s : f64 -> !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  return
}

// CHECK-LABEL: func.func @access
func.func @access(%K : !simit.tensor<["points", "points"] x tensor<3x3xf64>>,
                  %m : tensor<3x3xf64>, %p : !Point, %q : !Point, %i : index) -> f64 {
  // CHECK: %[[B:.*]] = simit.extract %{{.*}}[%{{.*}}, %{{.*}}] : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, (!Point, !Point) -> tensor<3x3xf64>
  %b = simit.extract %K[%p, %q] : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, (!Point, !Point) -> tensor<3x3xf64>
  // CHECK: simit.extract %[[B]][%{{.*}}, %{{.*}}] : tensor<3x3xf64>, (index, index) -> f64
  %c = simit.extract %b[%i, %i] : tensor<3x3xf64>, (index, index) -> f64
  // CHECK: simit.insert %{{.*}} into %{{.*}}[%{{.*}}, %{{.*}}] : tensor<3x3xf64> into !simit.tensor<["points", "points"] x tensor<3x3xf64>>, (!Point, !Point)
  %K2 = simit.insert %m into %K[%q, %p] : tensor<3x3xf64> into !simit.tensor<["points", "points"] x tensor<3x3xf64>>, (!Point, !Point)
  // CHECK: simit.insert %{{.*}} into %{{.*}}[%{{.*}}, %{{.*}}] : f64 into tensor<3x3xf64>, (index, index)
  %m2 = simit.insert %c into %m[%i, %i] : f64 into tensor<3x3xf64>, (index, index)
  return %c : f64
}

// A tensor with a set and a range dimension takes an element and an index.
// CHECK-LABEL: func.func @mixed_dims
func.func @mixed_dims(%t : !simit.tensor<["points", 3] x f64>, %p : !Point, %i : index) -> f64 {
  // CHECK: simit.extract %{{.*}}[%{{.*}}, %{{.*}}] : !simit.tensor<["points", 3] x f64>, (!Point, index) -> f64
  %c = simit.extract %t[%p, %i] : !simit.tensor<["points", 3] x f64>, (!Point, index) -> f64
  return %c : f64
}

// CHECK-LABEL: func.func @slices
func.func @slices(%A : !simit.tensor<["points", "springs"] x f64>, %m : tensor<3x4xf64>,
                  %T : tensor<2x3x4xf64>, %p : !Point, %j : index) {
  // CHECK: simit.slice %{{.*}}[%{{.*}}, :] : !simit.tensor<["points", "springs"] x f64>, (!Point) -> !simit.tensor<["springs"] x f64>
  %row = simit.slice %A[%p, :] : !simit.tensor<["points", "springs"] x f64>, (!Point) -> !simit.tensor<["springs"] x f64>
  // CHECK: simit.slice %{{.*}}[:, %{{.*}}] : tensor<3x4xf64>, (index) -> tensor<3xf64>
  %col = simit.slice %m[:, %j] : tensor<3x4xf64>, (index) -> tensor<3xf64>
  // CHECK: simit.slice %{{.*}}[%{{.*}}, :, :] : tensor<2x3x4xf64>, (index) -> tensor<3x4xf64>
  %mat = simit.slice %T[%j, :, :] : tensor<2x3x4xf64>, (index) -> tensor<3x4xf64>
  return
}
