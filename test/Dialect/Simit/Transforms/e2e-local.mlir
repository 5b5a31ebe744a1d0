// Local (small dense) tensors lowered to flat vectors, run with mlir-runner.
//
// RUN: simit-opt %s --simit-cpu-pipeline > /dev/null
// RUN: simit-opt %s --convert-simit-to-loops | sed '/^}$/d' > %t.mlir
// RUN: cat %S/Inputs/local-driver.mlir >> %t.mlir
// RUN: echo '}' >> %t.mlir
// RUN: simit-opt %t.mlir --simit-cpu-pipeline | mlir-runner -e main \
// RUN:   -entry-point-result=void \
// RUN:   -shared-libs=%mlir_lib_dir/libmlir_runner_utils.so,%mlir_lib_dir/libmlir_c_runner_utils.so \
// RUN:   | FileCheck %s

// m = [2 1 0; 1 3 1; 0 1 4], a = (1, 2, 3), b = (4, 5, 6), by hand:
// det(m) = 2 (12 - 1) - 1 (4 - 0) = 18
// CHECK: 18
// inv(m) = [11 -4 1; -4 8 -2; 1 -2 5] / 18
// CHECK-NEXT: ( 0.611111, -0.222222, 0.0555556, -0.222222, 0.444444, -0.111111, 0.0555556, -0.111111, 0.277778 )
// a x b = (2*6 - 3*5, 3*4 - 1*6, 1*5 - 2*4)
// CHECK-NEXT: ( -3, 6, -3 )
// m \ a = inv(m) a = (6, 6, 12) / 18
// CHECK-NEXT: ( 0.333333, 0.333333, 0.666667 )
// |a| = sqrt(14)
// CHECK-NEXT: 3.74166
// m a
// CHECK-NEXT: ( 4, 10, 14 )
// trace(m), summed in a variable by a loop over extracts
// CHECK-NEXT: 9
// m(:, 1)
// CHECK-NEXT: ( 1, 3, 1 )

func.func @kernel(%m : tensor<3x3xf64>, %a : tensor<3xf64>, %b : tensor<3xf64>)
    -> (f64, tensor<3x3xf64>, tensor<3xf64>, tensor<3xf64>, f64, tensor<3xf64>, f64, tensor<3xf64>)
    attributes {simit.export} {
  %det = simit.det %m : tensor<3x3xf64> -> f64
  %inv = simit.inv %m : tensor<3x3xf64>
  %cross = simit.cross %a, %b : tensor<3xf64>
  %x = simit.solve %m, %a : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  %norm = simit.norm %a : tensor<3xf64> -> f64
  %ma = simit.matvec %m, %a : tensor<3x3xf64>, tensor<3xf64> -> tensor<3xf64>
  %t = simit.alloc : !simit.ref<f64>
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  scf.for %i = %c0 to %c3 step %c1 {
    %mii = simit.extract %m[%i, %i] : tensor<3x3xf64>, (index, index) -> f64
    %old = simit.load %t : !simit.ref<f64>
    %new = arith.addf %old, %mii : f64
    simit.store %new, %t : !simit.ref<f64>
  }
  %trace = simit.load %t : !simit.ref<f64>
  %col = simit.slice %m[:, %c1] : tensor<3x3xf64>, (index) -> tensor<3xf64>
  return %det, %inv, %cross, %x, %norm, %ma, %trace, %col
      : f64, tensor<3x3xf64>, tensor<3xf64>, tensor<3xf64>, f64, tensor<3xf64>, f64, tensor<3xf64>
}
