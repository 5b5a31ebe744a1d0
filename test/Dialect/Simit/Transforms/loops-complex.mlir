// RUN: simit-opt %s --convert-simit-to-loops | FileCheck %s
// RUN: simit-opt %s --convert-simit-to-loops --convert-complex-to-standard \
// RUN:   | FileCheck %s --check-prefix=STD

// A complex multiply. convert-simit-to-loops keeps complex scalars and the
// complex dialect op; convert-complex-to-standard (in the CPU pipeline)
// then expands it on the parts:
// (a + bi)(c + di) = (ac - bd) + (bc + ad)i.

// CHECK-LABEL: func.func @mul(
// CHECK-SAME: %[[A:.*]]: complex<f64>, %[[B:.*]]: complex<f64>) -> complex<f64>
// CHECK: %[[C:.*]] = complex.mul %[[A]], %[[B]] : complex<f64>
// CHECK: return %[[C]] : complex<f64>

// STD-LABEL: func.func @mul(
// STD-SAME: %[[A:.*]]: complex<f64>, %[[B:.*]]: complex<f64>) -> complex<f64>
// STD-DAG: %[[AR:.*]] = complex.re %[[A]] : complex<f64>
// STD-DAG: %[[AI:.*]] = complex.im %[[A]] : complex<f64>
// STD-DAG: %[[BR:.*]] = complex.re %[[B]] : complex<f64>
// STD-DAG: %[[BI:.*]] = complex.im %[[B]] : complex<f64>
// STD-DAG: %[[ACBD0:.*]] = arith.mulf %[[AR]], %[[BR]] : f64
// STD-DAG: %[[ACBD1:.*]] = arith.mulf %[[AI]], %[[BI]] : f64
// STD-DAG: %[[RE:.*]] = arith.subf %[[ACBD0]], %[[ACBD1]] : f64
// STD-DAG: %[[BCAD0:.*]] = arith.mulf %[[AI]], %[[BR]] : f64
// STD-DAG: %[[BCAD1:.*]] = arith.mulf %[[AR]], %[[BI]] : f64
// STD-DAG: %[[IM:.*]] = arith.addf %[[BCAD0]], %[[BCAD1]] : f64
// STD: %[[C:.*]] = complex.create %[[RE]], %[[IM]] : complex<f64>
// STD: return %[[C]] : complex<f64>
// STD-NOT: complex.mul
func.func @mul(%a : complex<f64>, %b : complex<f64>) -> complex<f64>
    attributes {simit.export} {
  %c = complex.mul %a, %b : complex<f64>
  return %c : complex<f64>
}

// A complex local tensor is a flat vector of (re, im) pairs; at the host
// boundary it is vector<N x 2 x T>. Scaling multiplies component by
// component.
// CHECK-LABEL: func.func @scale(
// CHECK-SAME: %[[S:.*]]: complex<f64>, %[[V:.*]]: vector<2x2xf64>) -> vector<2x2xf64>
// CHECK: %[[F:.*]] = vector.shape_cast %[[V]] : vector<2x2xf64> to vector<4xf64>
// CHECK-DAG: %[[R0:.*]] = vector.extract %[[F]][0] : f64 from vector<4xf64>
// CHECK-DAG: %[[I0:.*]] = vector.extract %[[F]][1] : f64 from vector<4xf64>
// CHECK-DAG: %[[C0:.*]] = complex.create %[[R0]], %[[I0]] : complex<f64>
// CHECK-DAG: %[[R1:.*]] = vector.extract %[[F]][2] : f64 from vector<4xf64>
// CHECK-DAG: %[[I1:.*]] = vector.extract %[[F]][3] : f64 from vector<4xf64>
// CHECK-DAG: %[[C1:.*]] = complex.create %[[R1]], %[[I1]] : complex<f64>
// CHECK-DAG: %[[P0:.*]] = complex.mul %[[S]], %[[C0]] : complex<f64>
// CHECK-DAG: %[[P1:.*]] = complex.mul %[[S]], %[[C1]] : complex<f64>
// CHECK-DAG: %[[P0R:.*]] = complex.re %[[P0]]
// CHECK-DAG: %[[P0I:.*]] = complex.im %[[P0]]
// CHECK-DAG: %[[P1R:.*]] = complex.re %[[P1]]
// CHECK-DAG: %[[P1I:.*]] = complex.im %[[P1]]
// CHECK: %[[FR:.*]] = vector.from_elements %[[P0R]], %[[P0I]], %[[P1R]], %[[P1I]] : vector<4xf64>
// CHECK: %[[R:.*]] = vector.shape_cast %[[FR]] : vector<4xf64> to vector<2x2xf64>
// CHECK: return %[[R]] : vector<2x2xf64>
func.func @scale(%s : complex<f64>, %v : tensor<2xcomplex<f64>>)
    -> tensor<2xcomplex<f64>> attributes {simit.export} {
  %r = simit.scale %s, %v : complex<f64>, tensor<2xcomplex<f64>>
  return %r : tensor<2xcomplex<f64>>
}

// A complex literal tensor is a constant of its parts; a complex variable a
// memref<complex<T>> that starts at zero.
// CHECK-LABEL: func.func @literal(
// CHECK-SAME: ) -> (vector<2x2xf64>, complex<f64>)
// CHECK-DAG: %[[SLOT:.*]] = memref.alloca() : memref<complex<f64>>
// CHECK-DAG: %[[K:.*]] = arith.constant dense<[1.000000e+00, 2.000000e+00, 0.000000e+00, -1.000000e+00]> : vector<4xf64>
// CHECK-DAG: %[[Z:.*]] = complex.constant [0.000000e+00, 0.000000e+00] : complex<f64>
// CHECK: memref.store %[[Z]], %[[SLOT]][] : memref<complex<f64>>
// CHECK: %[[L:.*]] = memref.load %[[SLOT]][] : memref<complex<f64>>
// CHECK: vector.shape_cast %[[K]] : vector<4xf64> to vector<2x2xf64>
func.func @literal() -> (tensor<2xcomplex<f64>>, complex<f64>)
    attributes {simit.export} {
  %k = arith.constant dense<[(1.0, 2.0), (0.0, -1.0)]> : tensor<2xcomplex<f64>>
  %slot = simit.alloc : !simit.ref<complex<f64>>
  %z = simit.load %slot : !simit.ref<complex<f64>>
  return %k, %z : tensor<2xcomplex<f64>>, complex<f64>
}
