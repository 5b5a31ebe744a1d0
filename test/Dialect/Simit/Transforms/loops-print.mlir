// RUN: simit-opt %s --convert-simit-to-loops | FileCheck %s

// print/println lower to calls of runtime functions; strings are C strings
// (!llvm.ptr), constants global strings, concat/compare runtime calls.

// CHECK-DAG: llvm.mlir.global internal constant @[[NL:simit_str_[0-9A-F]+]]("\0A\00")
// CHECK-DAG: llvm.mlir.global internal constant @[[X:simit_str_[0-9A-F]+]]("x=\00")
// CHECK-DAG: func.func private @simit_rt_print_str(!llvm.ptr)
// CHECK-DAG: func.func private @simit_rt_print_f64(f64)
// CHECK-DAG: func.func private @simit_rt_print_i64(i64)
// CHECK-DAG: func.func private @simit_rt_string_concat(!llvm.ptr, !llvm.ptr) -> !llvm.ptr
// CHECK-DAG: func.func private @simit_rt_string_compare(!llvm.ptr, !llvm.ptr) -> i32

// CHECK-LABEL: func.func @show(
// CHECK-SAME: %[[F:.*]]: f32, %[[N:.*]]: i32, %[[B:.*]]: i1, %[[V:.*]]: vector<2xf64>)
// CHECK: %[[XS:.*]] = llvm.mlir.addressof @[[X]] : !llvm.ptr
// CHECK: call @simit_rt_print_str(%[[XS]])
// CHECK: %[[FE:.*]] = arith.extf %[[F]] : f32 to f64
// CHECK: call @simit_rt_print_f64(%[[FE]])
// CHECK: %[[NE:.*]] = arith.extsi %[[N]] : i32 to i64
// CHECK: call @simit_rt_print_i64(%[[NE]])
// CHECK: %[[BE:.*]] = arith.extui %[[B]] : i1 to i64
// CHECK: call @simit_rt_print_i64(%[[BE]])
// CHECK: %[[V0:.*]] = vector.extract %[[V]][0]
// CHECK: call @simit_rt_print_f64(%[[V0]])
// CHECK: call @simit_rt_print_str(
// CHECK: %[[V1:.*]] = vector.extract %[[V]][1]
// CHECK: call @simit_rt_print_f64(%[[V1]])
// CHECK: %[[NLS:.*]] = llvm.mlir.addressof @[[NL]] : !llvm.ptr
// CHECK: call @simit_rt_print_str(%[[NLS]])
func.func @show(%x : f32, %n : i32, %b : i1, %v : tensor<2xf64>) -> i32
    attributes {simit.export} {
  %s = simit.string_constant "x="
  simit.print %s, %x, %n, %b, %v {newline} : !simit.string, f32, i32, i1, tensor<2xf64>
  return %n : i32
}

// CHECK-LABEL: func.func @less(
// CHECK: %[[A:.*]] = llvm.mlir.addressof
// CHECK: %[[B:.*]] = llvm.mlir.addressof
// CHECK: %[[C:.*]] = call @simit_rt_string_concat(%[[A]], %[[B]]) : (!llvm.ptr, !llvm.ptr) -> !llvm.ptr
// CHECK: %[[O:.*]] = call @simit_rt_string_compare(%[[C]], %[[B]]) : (!llvm.ptr, !llvm.ptr) -> i32
// CHECK: %[[Z:.*]] = arith.constant 0 : i32
// CHECK: %[[R:.*]] = arith.cmpi slt, %[[O]], %[[Z]] : i32
// CHECK: return %[[R]] : i1
func.func @less() -> i1 attributes {simit.export} {
  %a = simit.string_constant "ab"
  %b = simit.string_constant "cd"
  %c = simit.string_concat %a, %b
  %r = simit.string_cmp <lt> %c, %b
  return %r : i1
}

// A string variable is a memref<!llvm.ptr> slot that starts as "".
// CHECK-LABEL: func.func @repeat(
// CHECK-SAME: %[[S:.*]]: !llvm.ptr, %[[N:.*]]: i32) -> !llvm.ptr
// CHECK: %[[SLOT:.*]] = memref.alloca() : memref<!llvm.ptr>
// CHECK: %[[EMPTY:.*]] = llvm.mlir.addressof @{{simit_str_[0-9A-F]+}} : !llvm.ptr
// CHECK: memref.store %[[EMPTY]], %[[SLOT]][] : memref<!llvm.ptr>
// CHECK: scf.for
// CHECK:   %[[OLD:.*]] = memref.load %[[SLOT]][] : memref<!llvm.ptr>
// CHECK:   %[[NEW:.*]] = func.call @simit_rt_string_concat(%[[OLD]], %[[S]])
// CHECK:   memref.store %[[NEW]], %[[SLOT]][] : memref<!llvm.ptr>
// CHECK: %[[R:.*]] = memref.load %[[SLOT]][] : memref<!llvm.ptr>
// CHECK: return %[[R]] : !llvm.ptr
func.func @repeat(%s : !simit.string, %n : i32) -> !simit.string
    attributes {simit.export} {
  %acc = simit.alloc : !simit.ref<!simit.string>
  %c0 = arith.constant 0 : index
  %end = arith.index_cast %n : i32 to index
  %c1 = arith.constant 1 : index
  scf.for %i = %c0 to %end step %c1 {
    %old = simit.load %acc : !simit.ref<!simit.string>
    %new = simit.string_concat %old, %s
    simit.store %new, %acc : !simit.ref<!simit.string>
  }
  %r = simit.load %acc : !simit.ref<!simit.string>
  return %r : !simit.string
}

// A system vector prints its elements in set order: a loop over the set,
// a separator before every element but the first (a space for scalar
// elements, a newline for blocks), a block's components separated by
// spaces.
!Point = !simit.element<"Point", {x : f64, v : tensor<2xf64>}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points
// CHECK-LABEL: func.func @fields(
// CHECK-SAME: %[[V:[^:]*]]: memref<?x2xf64>, %[[X:[^:]*]]: memref<?xf64>)
// CHECK: %[[N:.*]] = memref.dim %[[X]], %{{.*}}
// CHECK: scf.for %[[I:.*]] = %{{.*}} to %[[N]]
// CHECK:   %[[LATER:.*]] = arith.cmpi ne, %[[I]], %{{.*}}
// CHECK:   scf.if %[[LATER]] {
// CHECK:     %[[SP:.*]] = llvm.mlir.addressof @{{simit_str_[0-9A-F]+}}
// CHECK:     func.call @simit_rt_print_str(%[[SP]])
// CHECK:   %[[XI:.*]] = memref.load %[[X]][%[[I]]]
// CHECK:   func.call @simit_rt_print_f64(%[[XI]])
// CHECK: scf.for %[[I:.*]] = %{{.*}} to %{{.*}}
// CHECK:   scf.if
// CHECK:     %[[NLS:.*]] = llvm.mlir.addressof @[[NL]]
// CHECK:     func.call @simit_rt_print_str(%[[NLS]])
// CHECK:   %[[V0:.*]] = memref.load %[[V]][%[[I]], %{{.*}}]
// CHECK:   func.call @simit_rt_print_f64(%[[V0]])
// CHECK:   func.call @simit_rt_print_str(
// CHECK:   %[[V1:.*]] = memref.load %[[V]][%[[I]], %{{.*}}]
// CHECK:   func.call @simit_rt_print_f64(%[[V1]])
func.func @fields() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !simit.tensor<["points"] x f64>
  %v = simit.field_read %points["v"] : !Points -> !simit.tensor<["points"] x tensor<2xf64>>
  simit.print %x, %v : !simit.tensor<["points"] x f64>, !simit.tensor<["points"] x tensor<2xf64>>
  return
}
