// Linear algebra on blocked local tensors, unrolled over the hierarchy of
// dimensions (outer x block, blocks contiguous in the flat vector).
// RUN: simit-opt %s --convert-simit-to-loops --canonicalize | FileCheck %s

// Transpose swaps the outer dimensions and transposes each block:
// T(0,1) = K(1,0)', K(1,0) being components 8..11.
// CHECK-LABEL: func.func @transpose
// CHECK: %[[K0:.*]] = vector.extract %arg0[0]
// CHECK: %[[K1:.*]] = vector.extract %arg0[1]
// CHECK: %[[K2:.*]] = vector.extract %arg0[2]
// CHECK: %[[K3:.*]] = vector.extract %arg0[3]
// CHECK: %[[K4:.*]] = vector.extract %arg0[4]
// CHECK: %[[K5:.*]] = vector.extract %arg0[5]
// CHECK: %[[K6:.*]] = vector.extract %arg0[6]
// CHECK: %[[K7:.*]] = vector.extract %arg0[7]
// CHECK: %[[K8:.*]] = vector.extract %arg0[8]
// CHECK: %[[K9:.*]] = vector.extract %arg0[9]
// CHECK: %[[K10:.*]] = vector.extract %arg0[10]
// CHECK: %[[K11:.*]] = vector.extract %arg0[11]
// CHECK: %[[K12:.*]] = vector.extract %arg0[12]
// CHECK: %[[K13:.*]] = vector.extract %arg0[13]
// CHECK: %[[K14:.*]] = vector.extract %arg0[14]
// CHECK: %[[K15:.*]] = vector.extract %arg0[15]
// CHECK: vector.from_elements %[[K0]], %[[K2]], %[[K1]], %[[K3]], %[[K8]], %[[K10]], %[[K9]], %[[K11]], %[[K4]], %[[K6]], %[[K5]], %[[K7]], %[[K12]], %[[K14]], %[[K13]], %[[K15]] : vector<16xf64>
func.func @transpose(%k : !simit.tensor<[2, 2] x tensor<2x2xf64>>) -> !simit.tensor<[2, 2] x tensor<2x2xf64>> attributes {simit.export} {
  %t = simit.transpose %k : !simit.tensor<[2, 2] x tensor<2x2xf64>> -> !simit.tensor<[2, 2] x tensor<2x2xf64>>
  return %t : !simit.tensor<[2, 2] x tensor<2x2xf64>>
}

// Row 0 of K x: K(0,0) row 0 (components 0, 1) times x(0), plus K(0,1) row 0
// (components 4, 5) times x(1).
// CHECK-LABEL: func.func @matvec
// CHECK-DAG: %[[K0:.*]] = vector.extract %arg0[0]
// CHECK-DAG: %[[K1:.*]] = vector.extract %arg0[1]
// CHECK-DAG: %[[K4:.*]] = vector.extract %arg0[4]
// CHECK-DAG: %[[K5:.*]] = vector.extract %arg0[5]
// CHECK-DAG: %[[X0:.*]] = vector.extract %arg1[0]
// CHECK-DAG: %[[X1:.*]] = vector.extract %arg1[1]
// CHECK-DAG: %[[X2:.*]] = vector.extract %arg1[2]
// CHECK-DAG: %[[X3:.*]] = vector.extract %arg1[3]
// CHECK: %[[P0:.*]] = arith.mulf %[[K0]], %[[X0]]
// CHECK: %[[P1:.*]] = arith.mulf %[[K1]], %[[X1]]
// CHECK: %[[S1:.*]] = arith.addf %[[P0]], %[[P1]]
// CHECK: %[[P2:.*]] = arith.mulf %[[K4]], %[[X2]]
// CHECK: %[[S2:.*]] = arith.addf %[[S1]], %[[P2]]
// CHECK: %[[P3:.*]] = arith.mulf %[[K5]], %[[X3]]
// CHECK: %[[R0:.*]] = arith.addf %[[S2]], %[[P3]]
// CHECK: vector.from_elements %[[R0]], %{{.*}}, %{{.*}}, %{{.*}} : vector<4xf64>
func.func @matvec(%k : !simit.tensor<[2, 2] x tensor<2x2xf64>>, %x : !simit.tensor<[2] x tensor<2xf64>>) -> !simit.tensor<[2] x tensor<2xf64>> attributes {simit.export} {
  %y = simit.matvec %k, %x : !simit.tensor<[2, 2] x tensor<2x2xf64>>, !simit.tensor<[2] x tensor<2xf64>> -> !simit.tensor<[2] x tensor<2xf64>>
  return %y : !simit.tensor<[2] x tensor<2xf64>>
}

// Matmul: S(0,0) row 0, column 0 sums over the 4 hierarchical inner indices.
// CHECK-LABEL: func.func @matmul
// CHECK-COUNT-64: arith.mulf
// CHECK: vector.from_elements {{.*}} : vector<16xf64>
func.func @matmul(%k : !simit.tensor<[2, 2] x tensor<2x2xf64>>) -> !simit.tensor<[2, 2] x tensor<2x2xf64>> attributes {simit.export} {
  %s = simit.matmul %k, %k : !simit.tensor<[2, 2] x tensor<2x2xf64>>, !simit.tensor<[2, 2] x tensor<2x2xf64>> -> !simit.tensor<[2, 2] x tensor<2x2xf64>>
  return %s : !simit.tensor<[2, 2] x tensor<2x2xf64>>
}

// Dot and norm pair up all components in storage order.
// CHECK-LABEL: func.func @norm
// CHECK-COUNT-4: arith.mulf
// CHECK: math.sqrt
func.func @norm(%x : !simit.tensor<[2] x tensor<2xf64>>) -> f64 attributes {simit.export} {
  %n = simit.norm %x : !simit.tensor<[2] x tensor<2xf64>> -> f64
  return %n : f64
}
