// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

// CHECK-LABEL: func.func @strings
func.func @strings(%x : f64, %v : !simit.tensor<["points"] x f64>) -> i1 {
  // CHECK: %[[A:.*]] = simit.string_constant "abc"
  %a = simit.string_constant "abc"
  // CHECK: %[[B:.*]] = simit.string_constant "line\0A"
  %b = simit.string_constant "line\n"
  // CHECK: %[[C:.*]] = simit.string_concat %[[A]], %[[B]]
  %c = simit.string_concat %a, %b
  // CHECK: simit.string_cmp <lt> %[[A]], %[[C]]
  %lt = simit.string_cmp <lt> %a, %c
  // CHECK: simit.string_cmp <ne> %[[A]], %[[C]]
  %ne = simit.string_cmp <ne> %a, %c
  // CHECK: simit.print %[[A]], %{{.*}} : !simit.string, f64
  simit.print %a, %x : !simit.string, f64
  // CHECK: simit.print %{{.*}} {newline} : !simit.tensor<["points"] x f64>
  simit.print %v {newline} : !simit.tensor<["points"] x f64>
  return %lt : i1
}
