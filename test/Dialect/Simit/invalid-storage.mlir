// RUN: simit-opt %s -split-input-file -verify-diagnostics

// Encodings whose text is not canonical are rejected (the unit tests of
// StorageTest.cpp cover every rule); these check the diagnostics reach
// the source.

// expected-error @+1 {{'transpose(diag("points"))' is not canonical}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<transpose(diag("points"))>>)

// -----

// The transpose of a product is the product of the transposed factors.
// expected-error @+1 {{'transpose(product(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1])))' is not canonical}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<transpose(product(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1])))>>)

// -----

// expected-error @+1 {{union member 'diag("points")' is contained in 'pattern("springs", rows [0, 1], cols [0, 1])'}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<union(diag("points"), pattern("springs", rows [0, 1], cols [0, 1]))>>)

// -----

// expected-error @+1 {{unknown storage kind 'csr'}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<csr>>)

// -----

// expected-error @+1 {{expected a #simit.storage encoding, got unit}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, unit>)

// -----

// expected-error @+1 {{a storage encoding needs a matrix over two sets}}
func.func @f(%a : !simit.tensor<["points"] x f64, #simit.storage<diag("points")>>)

// -----

// expected-error @+1 {{a storage encoding needs a matrix over two sets}}
func.func @f(%a : !simit.tensor<["points", 3] x f64, #simit.storage<dense>>)

// -----

// expected-error @+1 {{storage 'diag("points")' does not fit a matrix over ("points", "nodes")}}
func.func @f(%a : !simit.tensor<["points", "nodes"] x f64, #simit.storage<diag("points")>>)

// -----

// expected-error @+1 {{storage 'incidence("springs", cols [0, 1])' does not fit a matrix over ("points", "springs")}}
func.func @f(%a : !simit.tensor<["points", "springs"] x f64, #simit.storage<incidence("springs", cols [0, 1])>>)

// -----

// The transpose of an incidence is over (endpoints, edges).
// expected-error @+1 {{storage 'incidence("springs", cols [0])' does not fit a matrix over ("springs", "springs")}}
func.func @f(%a : !simit.tensor<["springs", "springs"] x f64, #simit.storage<transpose(incidence("springs", cols [0]))>>)

// -----

// expected-error @+1 {{storage 'stencil("cells", [[0]])' does not fit a matrix over ("points", "nodes")}}
func.func @f(%a : !simit.tensor<["points", "nodes"] x f64, #simit.storage<stencil("cells", [[0]])>>)

// -----

func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>) {
  // expected-error @+1 {{'pattern("hinges", rows [0, 1], cols [0, 1])' does not contain 'pattern("springs", rows [0, 1], cols [0, 1])'; 'restrict' drops the blocks it does not store}}
  %b = simit.convert %a : !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>
      -> !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("hinges", rows [0, 1], cols [0, 1])>>
  return
}

// -----

func.func @f(%a : !simit.tensor<["points", "points"] x f64>) {
  // expected-error @+1 {{needs a storage encoding on its source}}
  %b = simit.convert %a : !simit.tensor<["points", "points"] x f64>
      -> !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>
  return
}

// -----

func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>) {
  // expected-error @+1 {{'restrict' needs a storage encoding on its result}}
  %b = simit.convert restrict %a : !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>
      -> !simit.tensor<["points", "points"] x f64>
  return
}

// -----

func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>) {
  // expected-error @+1 {{types must differ only in their storage encodings}}
  %b = simit.convert %a : !simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>
      -> !simit.tensor<["points", "points"] x f32, #simit.storage<diag("points")>>
  return
}

// -----

func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>,
             %b : !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>) {
  // Element-wise ops keep one type: operands of another storage are converted.
  // expected-error @+1 {{requires the same type for all operands and results}}
  %c = "simit.add"(%a, %b) : (!simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>,
                              !simit.tensor<["points", "points"] x f64, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>)
      -> !simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>
  return
}

// -----

// A host function's matrix is named after the function.
// expected-error @+1 {{'host' needs a set name}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<host("", 0)>>)

// -----

// expected-error @+1 {{'host' needs a non-negative call number}}
func.func @f(%a : !simit.tensor<["points", "points"] x f64, #simit.storage<host("neg", -1)>>)
