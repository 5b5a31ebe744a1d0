// RUN: simit-opt %s --simit-lower-assertions -verify-diagnostics

// A module that declares the runtime's failure function with another type
// is an error at that declaration, not a call of the wrong type.

// expected-error @+1 {{@simit_rt_fail is declared with another type}}
func.func private @simit_rt_fail(i32)

func.func @checked(%ok : i1) {
  cf.assert %ok, "index out of range (prog.sim:2:3)"
  return
}
