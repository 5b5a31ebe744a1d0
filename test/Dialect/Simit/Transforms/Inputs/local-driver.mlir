// Driver of e2e-local.mlir: calls the lowered @kernel on constants and
// prints every result.
  func.func @main() {
    %m = arith.constant dense<[2.0, 1.0, 0.0, 1.0, 3.0, 1.0, 0.0, 1.0, 4.0]> : vector<9xf64>
    %a = arith.constant dense<[1.0, 2.0, 3.0]> : vector<3xf64>
    %b = arith.constant dense<[4.0, 5.0, 6.0]> : vector<3xf64>
    %det, %inv, %cross, %x, %norm, %ma, %trace, %col =
        func.call @kernel(%m, %a, %b)
        : (vector<9xf64>, vector<3xf64>, vector<3xf64>)
          -> (f64, vector<9xf64>, vector<3xf64>, vector<3xf64>, f64,
              vector<3xf64>, f64, vector<3xf64>)
    vector.print %det : f64
    vector.print %inv : vector<9xf64>
    vector.print %cross : vector<3xf64>
    vector.print %x : vector<3xf64>
    vector.print %norm : f64
    vector.print %ma : vector<3xf64>
    vector.print %trace : f64
    vector.print %col : vector<3xf64>
    return
  }
