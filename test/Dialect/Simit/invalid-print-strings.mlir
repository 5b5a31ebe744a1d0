// RUN: simit-opt %s -split-input-file -verify-diagnostics

!P = !simit.element<"P", {}>
func.func @f(%p : !P) {
  // expected-error @+1 {{cannot print a value of type '!simit.element<"P", {}>'}}
  simit.print %p : !P
  return
}

// -----

func.func @f(%s : !simit.set<"points", !simit.element<"P", {}>>) {
  // expected-error @+1 {{cannot print a value of type '!simit.set<"points"}}
  simit.print %s : !simit.set<"points", !simit.element<"P", {}>>
  return
}

// -----

func.func @f(%h : !simit.opaque) {
  // expected-error @+1 {{cannot print a value of type '!simit.opaque'}}
  simit.print %h {newline} : !simit.opaque
  return
}

// -----

func.func @f() {
  // expected-error @+1 {{'simit.print' op needs at least one value}}
  "simit.print"() : () -> ()
  return
}

// -----

func.func @f(%a : !simit.string) {
  // expected-error @+2 {{expected ::mlir::simit::StringPredicate to be one of: eq, ne, lt, le, gt, ge}}
  // expected-error @+1 {{failed to parse Simit_StringPredicateAttr parameter 'value'}}
  %c = simit.string_cmp <less> %a, %a
  return
}
