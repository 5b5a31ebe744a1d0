// RUN: simit-opt %s --simit-gpu-pipeline=lower-simit=true \
// RUN:   | sed -e 's/\\0A/\n/g' -e 's/\\09/ /g' | FileCheck %s

// Complex arithmetic inside a set loop: convert-complex-to-standard runs
// before the kernels are outlined, so the kernel is plain f64 arithmetic
// (without it, the complex values of the kernel cannot be translated to
// LLVM IR). x := |(x + 0i)(0 + 2i)| = |2x i| = 2|x|; complex.abs is the
// overflow-safe max * sqrt(1 + (min/max)^2).

// CHECK: .visible .entry step_kernel(
// CHECK: ld.global.b64
// CHECK: {{sqrt.rn.f64|__nv_sqrt}}
// CHECK: st.global.b64

!Point = !simit.element<"Point", {x : f64}>
!Points = !simit.set<"points", !Point>
simit.extern @points : !Points

func.func @modulus(%p : !Point) {
  %x = simit.elem_read %p["x"] : !Point -> f64
  %zero = arith.constant 0.0 : f64
  %c = complex.create %x, %zero : complex<f64>
  %i = complex.constant [0.0, 2.0] : complex<f64>
  %m = complex.mul %c, %i : complex<f64>
  %a = complex.abs %m : complex<f64>
  simit.elem_write %a, %p["x"] : f64, !Point
  return
}

func.func @step() attributes {simit.export} {
  %s = simit.get_set @points : !Points
  simit.map @modulus() to %s : (!Points) -> ()
  return
}
