// simit-check-numerics marks the assemblies and solves of exported functions
// whose results hold float system tensors, with the source construct and
// position (from the .sim locations) and the names of the results (the
// element function's result names, "solution" for solves). A solve of an
// inlined function is marked where it was inlined. A map or apply whose
// element function writes float fields of its element is marked with those
// fields (apply shift, which writes p.x); factorisations (an opaque handle)
// and element functions are not marked.
// RUN: simit-translate --import-sim %S/Inputs/check-numerics.sim --print-locations | simit-opt --simit-inline-functions --simit-check-numerics | FileCheck %s

// CHECK-LABEL: func.func @spring(
// CHECK-NOT: simit.check_numerics
// CHECK-LABEL: func.func @shift(
// CHECK-NOT: simit.check_numerics

// CHECK-LABEL: func.func @step()
// CHECK: simit.assemble @spring() to %{{.*}} reduce <add> {simit.check_numerics = {op = "map spring to springs (check-numerics.sim:26:10)", results = ["K", "f"]}}
// CHECK: simit.solve %{{.*}}, %{{.*}} {simit.check_numerics = {op = "solve (check-numerics.sim:22:9)", results = ["solution"]}}
// CHECK-NOT: simit.check_numerics
// CHECK: simit.map @shift() to %{{[^ ]*}} {simit.check_numerics = {fields = ["x"], op = "apply shift to points (check-numerics.sim:28:3)", results = []}} : (
// CHECK-NOT: simit.check_numerics
// CHECK: return

// CHECK-LABEL: func.func @direct()
// CHECK: simit.assemble @spring() to %{{.*}} reduce <add> {simit.check_numerics = {op = "map spring to springs (check-numerics.sim:32:10)", results = ["K", "f"]}}
// CHECK: simit.factorize lu %{{[^ ]*}} :
// CHECK: simit.factor_solve lu %{{.*}} {simit.check_numerics = {op = "lusolve (check-numerics.sim:34:14)", results = ["solution"]}}
// CHECK-NOT: simit.check_numerics
// CHECK: return
