// RUN: simit-opt %s --split-input-file --verify-diagnostics --convert-simit-to-loops | FileCheck %s

// Scalar runtime functions (clock, storeTime) stay calls of their private
// declarations; the JIT binds them to the functions of lib/ABI.

// CHECK-LABEL: func.func @monotonic() -> i1
// CHECK: %[[T0:.*]] = call @simit_rt_clock() : () -> f64
// CHECK: %[[T1:.*]] = call @simit_rt_clock() : () -> f64
// CHECK: %[[D:.*]] = arith.subf %[[T1]], %[[T0]] : f64
// CHECK: call @simit_rt_storeTime(%{{.*}}, %[[D]]) : (i32, f64) -> f64
// CHECK: %[[R:.*]] = arith.cmpf oge, %[[T1]], %[[T0]] : f64
// CHECK: return %[[R]] : i1
// CHECK-DAG: func.func private @simit_rt_clock() -> f64 attributes {simit.runtime_function = "clock"}
// CHECK-DAG: func.func private @simit_rt_storeTime(i32, f64) -> f64 attributes {simit.runtime_function = "storeTime"}
func.func @monotonic() -> i1 attributes {simit.export} {
  %t0 = call @simit_rt_clock() : () -> f64
  %t1 = call @simit_rt_clock() : () -> f64
  %c0 = arith.constant 0 : i32
  %d = arith.subf %t1, %t0 : f64
  %s = call @simit_rt_storeTime(%c0, %d) : (i32, f64) -> f64
  %r = arith.cmpf oge, %t1, %t0 : f64
  return %r : i1
}
func.func private @simit_rt_clock() -> f64 attributes {simit.runtime_function = "clock"}
func.func private @simit_rt_storeTime(i32, f64) -> f64 attributes {simit.runtime_function = "storeTime"}

// -----

// Runtime functions the loop lowering does not know stay errors.
func.func @other(%a : f64) -> f64 attributes {simit.export} {
  // expected-error @below {{'@simit_rt_unknown' is implemented by the host or runtime; calling it is not supported by the loop lowering yet}}
  %x = call @simit_rt_unknown(%a) : (f64) -> f64
  return %x : f64
}
func.func private @simit_rt_unknown(f64) -> f64 attributes {simit.runtime_function = "unknown"}
