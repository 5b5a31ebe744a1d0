// The whole CPU pipeline on the frontend's IR of the two target programs:
// LLVM dialect that mlir-translate accepts, with the C interface of every
// exported function.
//
// RUN: simit-opt %S/Inputs/springs-frontend.mlir --simit-cpu-pipeline \
// RUN:   | mlir-translate --mlir-to-llvmir | FileCheck %s --check-prefix=SPRINGS
// RUN: simit-opt %S/Inputs/neo-hookean-frontend.mlir --simit-cpu-pipeline \
// RUN:   | mlir-translate --mlir-to-llvmir | FileCheck %s --check-prefix=FEM
// RUN: simit-opt %s --simit-cpu-pipeline | FileCheck %s --check-prefix=LLVM
// With openmp, the set loops of the springs program run in parallel regions
// of LLVM's OpenMP runtime; without, there is none.
// RUN: simit-opt %S/Inputs/springs-frontend.mlir --simit-cpu-pipeline=openmp=1 \
// RUN:   | mlir-translate --mlir-to-llvmir | FileCheck %s --check-prefix=OMP
// RUN: simit-opt %S/Inputs/springs-frontend.mlir --simit-cpu-pipeline \
// RUN:   | mlir-translate --mlir-to-llvmir | FileCheck %s --check-prefix=SERIAL

// OMP-LABEL: define void @step(
// OMP: call void (ptr, i32, ptr, ...) @__kmpc_fork_call(
// OMP: define internal void @step..omp_par
// OMP: call void @__kmpc_for_static_init_8u(
// SERIAL-NOT: __kmpc

// SPRINGS-DAG: define void @init(
// SPRINGS-DAG: define void @_mlir_ciface_init(
// SPRINGS-DAG: define void @step(
// SPRINGS-DAG: define void @_mlir_ciface_step(
// SPRINGS-DAG: call ptr @malloc(
// SPRINGS-DAG: call void @free(

// FEM-DAG: define void @init(
// FEM-DAG: define void @step(
// FEM-DAG: define void @_mlir_ciface_step(

// Only the LLVM dialect is left, and the bindings, the host type and the
// memref convention stay on the function.
// LLVM-LABEL: llvm.func @scale(
// LLVM-SAME: simit.bindings = [{index = 0 : i64, kind = "param"}, {kind = "set_size", set = "points"}, {field = "x", kind = "field", set = "points"}]
// LLVM-SAME: simit.host_type = (f64, index, memref<?x3xf64>) -> ()
// LLVM-SAME: simit.memref_convention = "descriptor"} {
// LLVM-NOT: simit.
// LLVM-NOT: scf.
// LLVM-NOT: memref.
// LLVM-NOT: vector.{{[a-z_]+}} %
// LLVM: llvm.func @_mlir_ciface_scale(

!Point = !simit.element<"Point", {x : tensor<3xf64>}>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @scale(%s : f64) attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %x = simit.field_read %points["x"] : !Points -> !F
  %y = simit.scale %s, %x : f64, !F
  simit.field_write %y, %points["x"] : !F, !Points
  return
}
