// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>

// CHECK-LABEL: func.func @system
func.func @system(%K : !K, %b : !F, %u : !F, %v : !F) -> !F {
  // CHECK: %[[H:.*]] = simit.factorize chol %{{.*}} : !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  %h = simit.factorize chol %K : !K
  // CHECK: simit.factor_solve chol %[[H]], %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
  %x = simit.factor_solve chol %h, %b : !F -> !F
  // CHECK: simit.factor_free chol %[[H]]
  simit.factor_free chol %h
  // CHECK: simit.triangular_solve %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
  %t = simit.triangular_solve %K, %b : !K, !F -> !F
  // CHECK: simit.woodbury %{{.*}}, %{{.*}}, %{{.*}}, u[%{{.*}}, %{{.*}}], v[%{{.*}}, %{{.*}}], w[%{{.*}}, %{{.*}}] : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x tensor<3xf64>>
  %w = simit.woodbury %K, %b, %x, u[%u, %v], v[%v, %u], w[%t, %x] : !K, !F
  return %w : !F
}

// A matrix over two sets: b and u over its rows, c, v, w and x over its
// columns.
// CHECK-LABEL: func.func @two_sets
func.func @two_sets(%A : !simit.tensor<["q", "v"] x f64>,
                    %b : !simit.tensor<["q"] x f64>,
                    %v : !simit.tensor<["v"] x f64>)
    -> !simit.tensor<["v"] x f64> {
  // CHECK: simit.woodbury %{{.*}}, %{{.*}}, %{{.*}}, u[%{{.*}}], v[%{{.*}}], w[%{{.*}}] : !simit.tensor<["q", "v"] x f64>, !simit.tensor<["q"] x f64> -> !simit.tensor<["v"] x f64>
  %x = simit.woodbury %A, %b, %v, u[%b], v[%v], w[%v]
      : !simit.tensor<["q", "v"] x f64>, !simit.tensor<["q"] x f64>
        -> !simit.tensor<["v"] x f64>
  return %x : !simit.tensor<["v"] x f64>
}

// CHECK-LABEL: func.func @local
func.func @local(%m : tensor<3x3xf64>, %b : tensor<3x2xf64>) -> tensor<3x2xf64> {
  // CHECK: %[[H:.*]] = simit.factorize lu %{{.*}} : tensor<3x3xf64>
  %h = simit.factorize lu %m : tensor<3x3xf64>
  // CHECK: simit.factor_solve lu %[[H]], %{{.*}} : tensor<3x2xf64> -> tensor<3x2xf64>
  %x = simit.factor_solve lu %h, %b : tensor<3x2xf64> -> tensor<3x2xf64>
  // CHECK: simit.factor_free lu %[[H]]
  simit.factor_free lu %h
  return %x : tensor<3x2xf64>
}
