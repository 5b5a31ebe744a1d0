// RUN: simit-opt %s --split-input-file --convert-simit-to-loops | FileCheck %s

// A local matrix result is a flat vector at the host boundary; the function
// records every result's declared shape (empty for scalars) so the host can
// show it as a matrix.

// CHECK-LABEL: func.func @matrix_result
// CHECK-SAME: -> (vector<6xf64>, f64, vector<3xf64>)
// CHECK-SAME: simit.result_shapes = [array<i64: 2, 3>, array<i64>, array<i64: 3>]
func.func @matrix_result(%a: tensor<2x3xf64>, %s: f64, %v: tensor<3xf64>) -> (tensor<2x3xf64>, f64, tensor<3xf64>) attributes {simit.export} {
  return %a, %s, %v : tensor<2x3xf64>, f64, tensor<3xf64>
}

// -----

// Vectors and scalars need no shapes.

// CHECK-LABEL: func.func @vector_result
// CHECK-NOT: simit.result_shapes
// CHECK: return
func.func @vector_result(%v: tensor<3xf64>) -> tensor<3xf64> attributes {simit.export} {
  return %v : tensor<3xf64>
}
