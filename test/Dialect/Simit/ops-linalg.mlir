// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>

// CHECK-LABEL: func.func @elementwise
func.func @elementwise(%a : !F, %b : !F, %s : f64, %m : tensor<2x2xi32>) {
  // CHECK: simit.add %{{.*}}, %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>
  %0 = simit.add %a, %b : !F
  // CHECK: simit.sub %{{.*}}, %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>
  %1 = simit.sub %a, %b : !F
  // CHECK: simit.mul %{{.*}}, %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>
  %2 = simit.mul %a, %b : !F
  // CHECK: simit.div %{{.*}}, %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>
  %3 = simit.div %a, %b : !F
  // CHECK: simit.neg %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>
  %4 = simit.neg %a : !F
  // CHECK: simit.scale %{{.*}}, %{{.*}} : f64, !simit.tensor<["points"] x tensor<3xf64>>
  %5 = simit.scale %s, %a : f64, !F
  // CHECK: simit.add %{{.*}}, %{{.*}} : tensor<2x2xi32>
  %6 = simit.add %m, %m : tensor<2x2xi32>
  return
}

// Blocked system operands combine dimension hierarchies.
// CHECK-LABEL: func.func @products
func.func @products(%K : !K, %x : !F, %A : !simit.tensor<["points", "springs"] x tensor<3x2xf64>>,
                    %B : !simit.tensor<["springs", "points"] x tensor<2x3xf64>>) {
  // CHECK: simit.matvec %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
  %y = simit.matvec %K, %x : !K, !F -> !F
  // CHECK: simit.matmul %{{.*}}, %{{.*}} : {{.*}} -> !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  %C = simit.matmul %A, %B : !simit.tensor<["points", "springs"] x tensor<3x2xf64>>, !simit.tensor<["springs", "points"] x tensor<2x3xf64>> -> !K
  // CHECK: simit.transpose %{{.*}} : !simit.tensor<["points", "springs"] x tensor<3x2xf64>> -> !simit.tensor<["springs", "points"] x tensor<2x3xf64>>
  %T = simit.transpose %A : !simit.tensor<["points", "springs"] x tensor<3x2xf64>> -> !simit.tensor<["springs", "points"] x tensor<2x3xf64>>
  // CHECK: simit.dot %{{.*}}, %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>, !simit.tensor<["points"] x tensor<3xf64>> -> f64
  %d = simit.dot %x, %y : !F, !F -> f64
  // CHECK: simit.outer %{{.*}}, %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>>, !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points", "points"] x tensor<3x3xf64>>
  %o = simit.outer %x, %y : !F, !F -> !K
  // CHECK: simit.norm %{{.*}} : !simit.tensor<["points"] x tensor<3xf64>> -> f64
  %n = simit.norm %x : !F -> f64
  // CHECK: simit.solve %{{.*}}, %{{.*}} : !simit.tensor<["points", "points"] x tensor<3x3xf64>>, !simit.tensor<["points"] x tensor<3xf64>> -> !simit.tensor<["points"] x tensor<3xf64>>
  %s = simit.solve %K, %x : !K, !F -> !F
  return
}

// CHECK-LABEL: func.func @local
func.func @local(%m : tensor<3x3xf64>, %v : tensor<3xf64>, %w : tensor<2xf64>,
                 %c : tensor<3xcomplex<f64>>, %m4 : tensor<4x4xf32>) {
  // CHECK: simit.matvec %{{.*}}, %{{.*}} : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  %0 = simit.matvec %m, %v : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  // CHECK: simit.outer %{{.*}}, %{{.*}} : tensor<3xf64>, tensor<2xf64> -> tensor<3x2xf64>
  %1 = simit.outer %v, %w : tensor<3xf64>, tensor<2xf64> -> tensor<3x2xf64>
  // CHECK: simit.matmul %{{.*}}, %{{.*}} : tensor<3x3xf64>, tensor<3x2xf64> -> tensor<3x2xf64>
  %2 = simit.matmul %m, %1 : tensor<3x3xf64>, tensor<3x2xf64> -> tensor<3x2xf64>
  // CHECK: simit.det %{{.*}} : tensor<3x3xf64> -> f64
  %3 = simit.det %m : tensor<3x3xf64> -> f64
  // CHECK: simit.inv %{{.*}} : tensor<4x4xf32>
  %4 = simit.inv %m4 : tensor<4x4xf32>
  // CHECK: simit.cross %{{.*}}, %{{.*}} : tensor<3xf64>
  %5 = simit.cross %v, %v : tensor<3xf64>
  // CHECK: simit.norm %{{.*}} : tensor<3xcomplex<f64>> -> f64
  %6 = simit.norm %c : tensor<3xcomplex<f64>> -> f64
  // CHECK: simit.solve %{{.*}}, %{{.*}} : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  %7 = simit.solve %m, %v : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  return
}
