// RUN: simit-opt %s --simit-gpu-scatter-atomics --simit-parallel-loops-to-gpu \
// RUN:   --simit-gpu-device-memory | FileCheck %s --check-prefix=LAUNCH
// RUN: simit-opt %s --simit-gpu-pipeline | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' \
// RUN:   | FileCheck %s --check-prefix=PTX
// RUN: simit-opt %s --simit-gpu-pipeline="chip=sm_80 features=+ptx75 block-size=128 fp-contract=false" \
// RUN:   | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' | FileCheck %s --check-prefix=SM80
// RUN: %if ptxas %{ simit-opt %s --simit-gpu-pipeline=format=bin \
// RUN:   | FileCheck %s --check-prefix=CUBIN %}

// x is updated where it lives: iteration i owns x[i], so no atomics; the
// extern h is copied to the device like any other memref and only x comes
// back.

// LAUNCH-LABEL: func.func @step
// LAUNCH-SAME:    (%{{.*}}: index, %[[X:.*]]: memref<?x3xf64>, %[[V:.*]]: memref<?x3xf64>, %[[H:.*]]: memref<f64>)
// LAUNCH-DAG:     %[[DH:.*]] = gpu.alloc () : memref<f64>
// LAUNCH-DAG:     gpu.memcpy %[[DH]], %[[H]]
// LAUNCH-DAG:     %[[DX:.*]] = gpu.alloc (%{{.*}}) : memref<?x3xf64>
// LAUNCH-DAG:     gpu.memcpy %[[DX]], %[[X]]
// LAUNCH-DAG:     %[[DV:.*]] = gpu.alloc (%{{.*}}) : memref<?x3xf64>
// LAUNCH-DAG:     gpu.memcpy %[[DV]], %[[V]]
// LAUNCH:         gpu.launch
// LAUNCH:           %[[I:.*]] = arith.addi
// LAUNCH:           scf.if
// LAUNCH:             %[[HS:.*]] = memref.load %[[DH]][]
// LAUNCH:             scf.for %[[K:.*]] =
// LAUNCH:               %[[XI:.*]] = memref.load %[[DX]][%[[I]], %[[K]]]
// LAUNCH:               %[[VI:.*]] = memref.load %[[DV]][%[[I]], %[[K]]]
// LAUNCH:               %[[HV:.*]] = arith.mulf %[[HS]], %[[VI]] fastmath<contract>
// LAUNCH:               %[[NEW:.*]] = arith.addf %[[XI]], %[[HV]] fastmath<contract>
// LAUNCH:               memref.store %[[NEW]], %[[DX]][%[[I]], %[[K]]]
// LAUNCH-NOT:     memref.atomic_rmw
// LAUNCH:         gpu.terminator
// LAUNCH-NOT:     gpu.memcpy %[[H]],
// LAUNCH-NOT:     gpu.memcpy %[[V]],
// LAUNCH:         gpu.memcpy %[[X]], %[[DX]]
// LAUNCH-NOT:     gpu.memcpy
// LAUNCH:         return

// PTX:     .target sm_90
// PTX:     .visible .entry step_kernel(
// PTX:     .maxntid 256, 1, 1
// PTX-COUNT-3: fma.rn.f64
// PTX-NOT: atom.
// PTX:     ret;

// Another chip and PTX version, smaller blocks, and no contraction: the
// multiply and the add stay two roundings.
// SM80:     .version 7.5
// SM80:     .target sm_80
// SM80:     .maxntid 128, 1, 1
// SM80-NOT: fma.rn.f64
// SM80:     mul.rn.f64
// SM80:     add.rn.f64
// SM80-NOT: fma.rn.f64
// SM80:     ret;

// The field update x += h * v over a vertex set, with the time step an
// extern bound by the host as memref<f64>.
func.func @step(%n: index, %x: memref<?x3xf64>, %v: memref<?x3xf64>,
                %h: memref<f64>) attributes {llvm.emit_c_interface} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  scf.parallel (%i) = (%c0) to (%n) step (%c1) {
    %hs = memref.load %h[] : memref<f64>
    scf.for %k = %c0 to %c3 step %c1 {
      %xi = memref.load %x[%i, %k] : memref<?x3xf64>
      %vi = memref.load %v[%i, %k] : memref<?x3xf64>
      %hv = arith.mulf %hs, %vi : f64
      %sum = arith.addf %xi, %hv : f64
      memref.store %sum, %x[%i, %k] : memref<?x3xf64>
    }
    scf.reduce
  }
  return
}

// ptxas accepts the generated assembly and makes an sm_90 ELF cubin.
// CUBIN: gpu.binary @step_kernel [#gpu.object<#nvvm.target<O = 3, chip = "sm_90", features = "+ptx80">, properties = {{.*}}, bin = "\7FELF
