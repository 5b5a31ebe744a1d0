// RUN: simit-opt %s --split-input-file --simit-fold-scene-constants | FileCheck %s

// Loads of externs marked constant become constants, arithmetic on them
// folds, and a branch on a constant flag keeps only the branch taken.

simit.extern @h : f64 {simit.constant = 1.0e-02 : f64}
simit.extern @grav : tensor<3xf64> {simit.constant = dense<[0.0, -9.81, 0.0]> : tensor<3xf64>}
simit.extern @mode : i32 {simit.constant = 0 : i32}
simit.extern @free : f64

// CHECK-LABEL: func.func @step(
// CHECK-NOT: simit.extern_ref @h
// CHECK-NOT: simit.extern_ref @grav
// CHECK-NOT: simit.extern_ref @mode
// CHECK-DAG: %[[HH:.*]] = arith.constant 1.000000e-04 : f64
// CHECK-DAG: %[[G:.*]] = arith.constant dense<[0.000000e+00, -9.810000e+00, 0.000000e+00]> : tensor<3xf64>
// CHECK-DAG: %[[FREE:.*]] = simit.load %{{.*}} : !simit.ref<f64>
// CHECK-NOT: scf.if
// CHECK: %[[R:.*]] = arith.addf %[[FREE]], %[[HH]] : f64
// CHECK: return %[[R]], %[[G]]
func.func @step() -> (f64, tensor<3xf64>) attributes {simit.export} {
  %hr = simit.extern_ref @h : !simit.ref<f64>
  %h = simit.load %hr : !simit.ref<f64>
  %gr = simit.extern_ref @grav : !simit.ref<tensor<3xf64>>
  %g = simit.load %gr : !simit.ref<tensor<3xf64>>
  %mr = simit.extern_ref @mode : !simit.ref<i32>
  %mode = simit.load %mr : !simit.ref<i32>
  %fr = simit.extern_ref @free : !simit.ref<f64>
  %free = simit.load %fr : !simit.ref<f64>
  %zero = arith.constant 0 : i32
  %on = arith.cmpi sgt, %mode, %zero : i32
  %hh = arith.mulf %h, %h : f64
  %r = scf.if %on -> f64 {
    %a = arith.mulf %hh, %free : f64
    scf.yield %a : f64
  } else {
    %b = arith.addf %hh, %free : f64
    scf.yield %b : f64
  }
  return %r, %g : f64, tensor<3xf64>
}

// -----

// An extern the program writes is never folded.

simit.extern @t : f64 {simit.constant = 1.0 : f64}

// CHECK-LABEL: func.func @advance(
// CHECK: %[[T:.*]] = simit.extern_ref @t
// CHECK: simit.load %[[T]]
// CHECK: simit.store %{{.*}}, %[[T]]
func.func @advance() -> f64 attributes {simit.export} {
  %tr = simit.extern_ref @t : !simit.ref<f64>
  %t = simit.load %tr : !simit.ref<f64>
  %t2 = arith.addf %t, %t : f64
  simit.store %t2, %tr : !simit.ref<f64>
  return %t2 : f64
}
