// RUN: simit-opt %s --simit-inline-functions --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops --simit-gpu-scatter-atomics \
// RUN:   --simit-parallel-loops-to-gpu --simit-gpu-device-memory \
// RUN:   | FileCheck %s --check-prefix=LAUNCH
// RUN: simit-opt %s --simit-inline-functions --simit-linalg-to-index-expr \
// RUN:   --convert-simit-to-loops --simit-gpu-pipeline \
// RUN:   | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' | FileCheck %s --check-prefix=PTX
// RUN: simit-opt %s --simit-gpu-pipeline=lower-simit=true \
// RUN:   | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' | FileCheck %s --check-prefix=PTX
// RUN: simit-opt %s --simit-gpu-pipeline=lower-simit=true \
// RUN:   | FileCheck %s --check-prefix=FREED

// The GPU path on what the CPU lowering makes of a Simit program: spring
// forces and stiffness assembled over the springs (scatters into the points
// and into the BCSR blocks through the location table), a matrix-vector
// product over the pattern, and a dot product.

!Point = !simit.element<"Point", {x : tensor<3xf64>, v : tensor<3xf64>}>
!Spring = !simit.element<"Spring", {k : f64}>
!K = !simit.tensor<["points", "points"] x tensor<3x3xf64>>
!F = !simit.tensor<["points"] x tensor<3xf64>>
!Points = !simit.set<"points", !Point>
!Springs = !simit.set<"springs", !Spring, ["points", "points"]>
simit.extern @points : !Points
simit.extern @springs : !Springs
simit.extern @out : f64

func.func private @springForce(%s : !Spring, %ends : !simit.tuple<!Point x 2>) -> (!K, !F) {
  %a = simit.tuple_get %ends[0] : !simit.tuple<!Point x 2> -> !Point
  %b = simit.tuple_get %ends[1] : !simit.tuple<!Point x 2> -> !Point
  %k = simit.elem_read %s["k"] : !Spring -> f64
  %xa = simit.elem_read %a["x"] : !Point -> tensor<3xf64>
  %xb = simit.elem_read %b["x"] : !Point -> tensor<3xf64>
  %d = simit.sub %xb, %xa : tensor<3xf64>
  %f = simit.scale %k, %d : f64, tensor<3xf64>
  %nf = simit.neg %f : tensor<3xf64>
  %I = arith.constant dense<[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]> : tensor<3x3xf64>
  %blk = simit.scale %k, %I : f64, tensor<3x3xf64>
  %nblk = simit.neg %blk : tensor<3x3xf64>
  %K0 = simit.zeros : !K
  %K1 = simit.insert %blk into %K0[%a, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K2 = simit.insert %nblk into %K1[%a, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K3 = simit.insert %nblk into %K2[%b, %a] : tensor<3x3xf64> into !K, (!Point, !Point)
  %K4 = simit.insert %blk into %K3[%b, %b] : tensor<3x3xf64> into !K, (!Point, !Point)
  %f0 = simit.zeros : !F
  %f1 = simit.insert %f into %f0[%a] : tensor<3xf64> into !F, (!Point)
  %f2 = simit.insert %nf into %f1[%b] : tensor<3xf64> into !F, (!Point)
  return %K4, %f2 : !K, !F
}

// LAUNCH-LABEL: func.func @step
// The assembly kernel scatters into the BCSR values and the forces.
// LAUNCH:         gpu.launch
// LAUNCH:           memref.atomic_rmw addf %{{.*}}, %{{.*}}[%{{.*}}, %{{.*}}, %{{.*}}] : (f64, memref<?x3x3xf64>) -> f64
// LAUNCH:           memref.atomic_rmw addf %{{.*}}, %{{.*}}[%{{.*}}, %{{.*}}] : (f64, memref<?x3xf64>) -> f64
// LAUNCH:           gpu.terminator
// The dot product reduces per block, then atomically.
// LAUNCH:         gpu.launch
// LAUNCH:           gpu.all_reduce add
// LAUNCH:           memref.atomic_rmw addf %{{.*}}, %{{.*}}[] : (f64, memref<f64>) -> f64
// LAUNCH:           gpu.terminator
// LAUNCH-NOT:     scf.parallel
// LAUNCH:         return

// With lower-simit the temporaries are freed (convert-simit-to-loops alone
// leaves that to the buffer-deallocation pipeline), on the host and on the
// device.
// FREED-LABEL: llvm.func @step(
// FREED:       llvm.call @malloc
// FREED:       llvm.call @mgpuMemFree
// FREED:       llvm.call @free
// FREED-LABEL: llvm.func @_mlir_ciface_step(

// PTX: .visible .entry step_kernel(
// PTX: atom.global.add.f64
// PTX: .visible .entry step_kernel(
// PTX: fma.rn.f64
// PTX: .visible .entry step_kernel(
// PTX: bar.sync 0;
// PTX: atom.global.add.f64
func.func @step() attributes {simit.export} {
  %points = simit.get_set @points : !Points
  %springs = simit.get_set @springs : !Springs
  %K, %fe = simit.assemble @springForce() to %springs reduce <add> : (!Springs) -> (!K, !F)
  %x = simit.field_read %points["x"] : !Points -> !F
  %Kx = simit.matvec %K, %x : !K, !F -> !F
  %r = simit.sub %fe, %Kx : !F
  %rr = simit.dot %r, %r : !F, !F -> f64
  %outr = simit.extern_ref @out : !simit.ref<f64>
  simit.store %rr, %outr : !simit.ref<f64>
  simit.field_write %r, %points["v"] : !F, !Points
  return
}
