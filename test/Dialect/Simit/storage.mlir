// RUN: simit-opt %s | simit-opt | FileCheck %s
// RUN: simit-opt %s --mlir-print-op-generic | simit-opt | FileCheck %s

// Storage encodings print as aliases named after their kind and set.
// CHECK-DAG: #diag_points = #simit.storage<diag("points")>
// CHECK-DAG: #pat_springs = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
// CHECK-DAG: #pat_links = #simit.storage<pattern("links", rows [0], cols [1])>
// CHECK-DAG: #inc_springs = #simit.storage<incidence("springs", cols [0, 1])>
// CHECK-DAG: #inc_springs_t = #simit.storage<transpose(incidence("springs", cols [0, 1]))>
// CHECK-DAG: #stencil_cells = #simit.storage<stencil("cells", {{\[\[}}-1, 0], [0, 0], [1, 0]])>
// CHECK-DAG: #union = #simit.storage<union(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>
// CHECK-DAG: #product = #simit.storage<product(pattern("springs", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>
// CHECK-DAG: #lowrank = #simit.storage<lowrank(diag("points"), 2)>
// CHECK-DAG: #host_neg_1 = #simit.storage<host("neg", 1)>

// CHECK-LABEL: func.func @encodings
// CHECK-SAME: !simit.tensor<["points", "points"] x tensor<3x3xf64>, #diag_points>
// CHECK-SAME: !simit.tensor<["points", "points"] x tensor<3x3xf64>, #pat_springs>
// CHECK-SAME: !simit.tensor<["particles", "nodes"] x f64, #pat_links>
// CHECK-SAME: !simit.tensor<["springs", "points"] x f64, #inc_springs>
// CHECK-SAME: !simit.tensor<["points", "springs"] x f64, #inc_springs_t>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #stencil_cells>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #union>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #product>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #lowrank>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #host_neg_1>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>
// CHECK-SAME: !simit.tensor<["points", "points"] x f64, #simit.storage<empty>>
// CHECK-SAME: !simit.ref<!simit.tensor<["points", "points"] x f64, #diag_points>>
// Without an encoding a tensor prints as before.
// CHECK-SAME: !simit.tensor<["points", "points"] x f64>)
func.func @encodings(
    %d : !simit.tensor<["points", "points"] x tensor<3x3xf64>, #simit.storage<diag("points")>>,
    %p : !simit.tensor<["points", "points"] x tensor<3x3xf64>, #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>>,
    %h : !simit.tensor<["particles", "nodes"] x f64, #simit.storage<pattern("links", rows [0], cols [1])>>,
    %i : !simit.tensor<["springs", "points"] x f64, #simit.storage<incidence("springs", cols [0, 1])>>,
    %t : !simit.tensor<["points", "springs"] x f64, #simit.storage<transpose(incidence("springs", cols [0, 1]))>>,
    %s : !simit.tensor<["points", "points"] x f64, #simit.storage<stencil("cells", [[-1, 0], [0, 0], [1, 0]])>>,
    %u : !simit.tensor<["points", "points"] x f64, #simit.storage<union(pattern("hinges", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>>,
    %m : !simit.tensor<["points", "points"] x f64, #simit.storage<product(pattern("springs", rows [0, 1], cols [0, 1]), pattern("springs", rows [0, 1], cols [0, 1]))>>,
    %l : !simit.tensor<["points", "points"] x f64, #simit.storage<lowrank(diag("points"), 2)>>,
    %host : !simit.tensor<["points", "points"] x f64, #simit.storage<host("neg", 1)>>,
    %full : !simit.tensor<["points", "points"] x f64, #simit.storage<dense>>,
    %none : !simit.tensor<["points", "points"] x f64, #simit.storage<empty>>,
    %slot : !simit.ref<!simit.tensor<["points", "points"] x f64, #simit.storage<diag("points")>>>,
    %plain : !simit.tensor<["points", "points"] x f64>) {
  return
}

// The aliases are accepted as input.
#K = #simit.storage<pattern("springs", rows [0, 1], cols [0, 1])>
#M = #simit.storage<diag("points")>

// CHECK-LABEL: func.func @convert
// CHECK: %[[W:.*]] = simit.convert %{{.*}} : !simit.tensor<["points", "points"] x f64, #diag_points> -> !simit.tensor<["points", "points"] x f64, #pat_springs>
// CHECK: %[[R:.*]] = simit.convert restrict %[[W]] : !simit.tensor<["points", "points"] x f64, #pat_springs> -> !simit.tensor<["points", "points"] x f64, #diag_points>
// CHECK: simit.convert %[[R]] : !simit.tensor<["points", "points"] x f64, #diag_points> -> !simit.tensor<["points", "points"] x f64>
func.func @convert(%d : !simit.tensor<["points", "points"] x f64, #M>)
    -> !simit.tensor<["points", "points"] x f64> {
  %w = simit.convert %d : !simit.tensor<["points", "points"] x f64, #M>
      -> !simit.tensor<["points", "points"] x f64, #K>
  %r = simit.convert restrict %w : !simit.tensor<["points", "points"] x f64, #K>
      -> !simit.tensor<["points", "points"] x f64, #M>
  %f = simit.convert %r : !simit.tensor<["points", "points"] x f64, #M>
      -> !simit.tensor<["points", "points"] x f64>
  return %f : !simit.tensor<["points", "points"] x f64>
}
