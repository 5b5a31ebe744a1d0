// RUN: simit-opt %s -split-input-file -verify-diagnostics -simit-check-set-names

!P = !simit.element<"P", {}>
!S = !simit.element<"S", {}>
simit.extern @points : !simit.set<"points", !P>
simit.extern @springs : !simit.set<"springs", !S, ["points", "points"]>

// Every name is declared by an extern or a set parameter.
func.func @ok(%nodes : !simit.set<"nodes", !P>,
              %a : !simit.tensor<["points", "nodes"] x f64>) -> !simit.tensor<["springs"] x f64> {
  %z = simit.zeros : !simit.tensor<["springs"] x f64>
  return %z : !simit.tensor<["springs"] x f64>
}

// -----

!P = !simit.element<"P", {}>
simit.extern @points : !simit.set<"points", !P>

func.func @f() {
  // expected-error @+1 {{type '!simit.tensor<["points", "nodes"] x f64>' refers to set 'nodes', which no simit.extern or set parameter declares}}
  %z = simit.zeros : !simit.tensor<["points", "nodes"] x f64>
  return
}

// -----

!P = !simit.element<"P", {}>
!S = !simit.element<"S", {}>
// expected-error @+1 {{refers to set 'vertices'}}
simit.extern @springs : !simit.set<"springs", !S, ["vertices", "vertices"]>

// -----

!P = !simit.element<"P", {}>
!C = !simit.element<"C", {}>
// expected-error @+1 {{refers to set 'grid_points'}}
func.func @f(%g : !simit.set<"cells", !C, grid 2 over "grid_points">) {
  return
}
