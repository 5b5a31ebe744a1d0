// simit-time-phases brackets assemblies (phase 0) and solves (phase 1) of
// exported functions with the runtime's phase timer; a while loop counts as
// a solve only when it holds no assembly and runs at most once per call (in
// the body, or inside ifs), and its contents are not timed again.
// RUN: simit-translate --import-sim %S/Inputs/time-phases.sim | simit-opt --simit-inline-functions --simit-time-phases | FileCheck %s

// Element functions are not timed.
// CHECK-LABEL: func.func @spring(
// CHECK-NOT: call @simit_rt_phase

// CHECK-LABEL: func.func @step()
// CHECK: %[[ASM:.*]] = arith.constant 0 : i32
// CHECK-NEXT: call @simit_rt_phase_begin(%[[ASM]]) : (i32) -> ()
// CHECK-NEXT: simit.assemble @spring()
// CHECK-NEXT: call @simit_rt_phase_end(%[[ASM]]) : (i32) -> ()
// CHECK: %[[LOOP:.*]] = arith.constant 1 : i32
// CHECK-NEXT: call @simit_rt_phase_begin(%[[LOOP]]) : (i32) -> ()
// CHECK-NEXT: scf.while
// CHECK-NOT: call @simit_rt_phase
// CHECK: scf.yield
// CHECK-NEXT: }
// CHECK-NEXT: call @simit_rt_phase_end(%[[LOOP]]) : (i32) -> ()
// CHECK: %[[SOLVE:.*]] = arith.constant 1 : i32
// CHECK-NEXT: call @simit_rt_phase_begin(%[[SOLVE]]) : (i32) -> ()
// CHECK-NEXT: simit.solve
// CHECK-NEXT: call @simit_rt_phase_end(%[[SOLVE]]) : (i32) -> ()
// CHECK: %[[APPLY:.*]] = arith.constant 0 : i32
// CHECK-NEXT: call @simit_rt_phase_begin(%[[APPLY]]) : (i32) -> ()
// CHECK-NEXT: simit.map @halve()
// CHECK-NEXT: call @simit_rt_phase_end(%[[APPLY]]) : (i32) -> ()

// A loop of assemblies is no solve: only its assembly is timed.
// CHECK-LABEL: func.func @loopOfAssemblies()
// CHECK-NOT: call @simit_rt_phase
// CHECK: scf.while
// CHECK: call @simit_rt_phase_begin(%{{.*}}) : (i32) -> ()
// CHECK-NEXT: simit.assemble @spring()
// CHECK-NEXT: call @simit_rt_phase_end(%{{.*}}) : (i32) -> ()

// A loop inside an if runs at most once per call: it is timed.
// CHECK-LABEL: func.func @loopInBranch()
// CHECK: scf.if
// CHECK: %[[BRANCH:.*]] = arith.constant 1 : i32
// CHECK-NEXT: call @simit_rt_phase_begin(%[[BRANCH]]) : (i32) -> ()
// CHECK-NEXT: scf.while
// CHECK: call @simit_rt_phase_end(%[[BRANCH]]) : (i32) -> ()

// CHECK: func.func private @simit_rt_phase_begin(i32) attributes {simit.runtime_function}
// CHECK: func.func private @simit_rt_phase_end(i32) attributes {simit.runtime_function}
