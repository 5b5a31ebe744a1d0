// RUN: simit-opt %s --simit-vectorize-element-loops='vector-bits=512 min-vector-ops=4' | FileCheck %s
// RUN: simit-opt %s --simit-vectorize-element-loops='vector-bits=256 min-vector-ops=4' | FileCheck %s --check-prefix=AVX
// RUN: simit-opt %s --simit-vectorize-element-loops='vector-bits=512 min-vector-ops=1000' | FileCheck %s --check-prefix=SMALL

// An element kernel: gathers through the endpoints, arithmetic on a local
// tensor held in a stack slot, a uniform extern, and a conditional scatter.
// The arithmetic runs on vector<8xf64> (one element per lane); the scatter
// runs for each element in order, reading the kernel's values from stack
// buffers. There is no scalar remainder loop: the last step computes the 8
// elements before the end and scatters only its own.
// CHECK-LABEL: func.func @kernel(
// CHECK-SAME: %[[LB:[^:]*]]: index, %[[UB:[^:]*]]: index
// CHECK-SAME: %[[W1:[^:]*]]: memref<?xf64>, %[[G2:[^:]*]]: memref<?x2xf64>
// Fields of the elements themselves are read from the field, or, for a set
// of fewer than 8 elements, from a zero-padded copy; chosen before the loop.
// CHECK:     %[[WPAD:.*]] = memref.alloca() : memref<8xf64>
// CHECK:     %[[N:.*]] = arith.subi %[[UB]], %[[LB]]
// CHECK:     %[[TINY:.*]] = arith.cmpi slt, %[[N]], %{{.*}} :
// CHECK:     scf.if %[[TINY]] {
// CHECK:       scf.for
// CHECK:         memref.load %[[W1]]
// CHECK:         memref.store %{{.*}}, %[[WPAD]]
// CHECK:     %[[WCAST:.*]] = memref.cast %[[WPAD]]
// CHECK:     %[[WSRC:.*]] = arith.select %[[TINY]], %[[WCAST]], %[[W1]] : memref<?xf64>
// CHECK:     %[[G:.*]] = memref.collapse_shape %[[G2]] {{\[\[}}0, 1]] : memref<?x2xf64> into memref<?xf64>
// CHECK:     %[[GSRC:.*]] = arith.select %{{.*}}, %{{.*}}, %[[G]] : memref<?xf64>
// CHECK:     %[[GAT:.*]] = arith.select
// CHECK:     scf.parallel (%[[START:.*]]) = (%[[LB]]) to (%[[UB]]) step (%[[C8:.*]]) {
// CHECK:       %[[LAST8:.*]] = arith.subi %[[UB]], %[[C8]]
// CHECK:       %[[SHIFTED:.*]] = arith.minsi %[[START]], %[[LAST8]]
// CHECK:       %[[BASE:.*]] = arith.maxsi %[[SHIFTED]], %[[LB]]
// CHECK:       %[[LAST:.*]] = arith.subi %[[UB]], %{{.*}}
// CHECK:       %[[LEFT:.*]] = arith.subi %[[UB]], %[[BASE]]
// CHECK:       %[[OWNED:.*]] = arith.minsi %[[LEFT]], %[[C8]]
// CHECK:       %[[IOTA:.*]] = arith.constant dense<[0, 1, 2, 3, 4, 5, 6, 7]> : vector<8xindex>
// Lanes past the set's last element repeat it.
// CHECK:       %[[E:.*]] = arith.addi %{{.*}}, %[[IOTA]] : vector<8xindex>
// CHECK:       arith.minsi %[[E]], %{{.*}} : vector<8xindex>
// Endpoints are loaded lane by lane, and each lane's index computed as a
// scalar; a float field of the elements themselves is read with one vector
// load of all lanes' blocks.
// CHECK-COUNT-8: memref.load %{{.*}} : memref<?x2xi32>
// CHECK:       vector.from_elements {{.*}} : vector<8xi32>
// CHECK:       arith.index_cast {{.*}} : vector<8xi32> to vector<8xindex>
// The extern is loaded once, as a scalar.
// CHECK:       %[[H:.*]] = memref.load %{{.*}}[] : memref<f64>
// CHECK-COUNT-8: memref.load %{{.*}} : memref<?x3xf64>
// CHECK:       arith.subf {{.*}} : vector<8xf64>
// CHECK:       arith.mulf {{.*}} : vector<8xf64>
// CHECK:       %[[W:.*]] = vector.load %[[WSRC]][%{{.*}}] : memref<?xf64>, vector<8xf64>
// CHECK:       %[[GS:.*]] = vector.load %[[GSRC]][%{{.*}}] : memref<?xf64>, vector<16xf64>
// CHECK:       %[[G1:.*]] = vector.shuffle %[[GS]], %[[GS]] [1, 3, 5, 7, 9, 11, 13, 15]
// CHECK:       arith.mulf %[[W]], %[[G1]] : vector<8xf64>
// CHECK:       arith.cmpf ogt, {{.*}} : vector<8xf64>
// CHECK-NOT:   memref.alloca() : memref<3xf64>
// Values of fewer components than lanes are buffered [component][lane];
// the endpoints' indices share one buffer.
// CHECK-DAG:   %[[BUF:.*]] = memref.alloca() : memref<3x8xf64>
// CHECK-DAG:   vector.store %{{.*}}, %[[BUF]][%{{.*}}, %{{.*}}] : memref<3x8xf64>, vector<8xf64>
// CHECK-DAG:   %[[FLAGS:.*]] = memref.alloca() : memref<1x8xi8>
// CHECK-DAG:   arith.extui %{{.*}} : vector<8xi1> to vector<8xi8>
// CHECK-DAG:   %[[ENDBUF:.*]] = memref.alloca() : memref<2x8xindex>
// The lane phase runs the lanes from the step's start to the end.
// CHECK:       %[[FIRSTLANE:.*]] = arith.subi %[[START]], %[[BASE]]
// CHECK:       scf.for %[[LANE:.*]] = %{{.*}} to %[[C8]] step
// CHECK-DAG:     arith.cmpi slt, %[[LANE]], %[[OWNED]]
// CHECK-DAG:     arith.cmpi sge, %[[LANE]], %[[FIRSTLANE]]
// CHECK:         scf.if
// CHECK:         %[[FLAG:.*]] = memref.load %[[FLAGS]][%{{.*}}, %[[LANE]]] : memref<1x8xi8>
// CHECK:         %[[COND:.*]] = arith.trunci %[[FLAG]] : i8 to i1
// CHECK:         scf.if %[[COND]] {
// Each read of a buffered value is a load next to it.
// CHECK:           %[[A:.*]] = memref.load %[[ENDBUF]][%{{.*}}, %[[LANE]]] : memref<2x8xindex>
// CHECK:           memref.load %{{.*}}[%[[A]], %{{.*}}] : memref<?x3xf64>
// CHECK:           memref.load %[[BUF]][%{{.*}}, %[[LANE]]] : memref<3x8xf64>
// CHECK:           memref.store %{{.*}}[%[[A]], %{{.*}}] : memref<?x3xf64>
// CHECK-NOT:   scf.parallel
// CHECK:       return

// With 256-bit vectors, four f64 lanes.
// AVX-LABEL: func.func @kernel(
// AVX: scf.parallel
// AVX: arith.mulf {{.*}} : vector<4xf64>

// Too few operations: the loop stays as it was.
// SMALL-LABEL: func.func @kernel(
// SMALL-NOT: arith.minsi
// SMALL-NOT: vector<8x
// SMALL: return
func.func @kernel(%lb : index, %ub : index, %ends : memref<?x2xi32>,
                  %x : memref<?x3xf64>, %h : memref<f64>,
                  %f : memref<?x3xf64>, %w : memref<?xf64>,
                  %g : memref<?x2xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %c3 = arith.constant 3 : index
  %zero = arith.constant 0.0 : f64
  scf.parallel (%e) = (%lb) to (%ub) step (%c1) {
    %d = memref.alloca() : memref<3xf64>
    scf.parallel (%i) = (%c0) to (%c3) step (%c1) {
      memref.store %zero, %d[%i] : memref<3xf64>
      scf.reduce
    }
    %a32 = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %a = arith.index_cast %a32 : i32 to index
    %b32 = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %b = arith.index_cast %b32 : i32 to index
    %hv = memref.load %h[] : memref<f64>
    scf.for %k = %c0 to %c3 step %c1 {
      scf.yield
    }
    %xa0 = memref.load %x[%a, %c0] : memref<?x3xf64>
    %xb0 = memref.load %x[%b, %c0] : memref<?x3xf64>
    %d0 = arith.subf %xa0, %xb0 : f64
    %s0 = arith.mulf %d0, %hv : f64
    memref.store %s0, %d[%c0] : memref<3xf64>
    %xa1 = memref.load %x[%a, %c1] : memref<?x3xf64>
    %xb1 = memref.load %x[%b, %c1] : memref<?x3xf64>
    %d1 = arith.subf %xa1, %xb1 : f64
    %we = memref.load %w[%e] : memref<?xf64>
    %ge = memref.load %g[%e, %c1] : memref<?x2xf64>
    %wg = arith.mulf %we, %ge : f64
    %s1 = arith.mulf %d1, %wg : f64
    memref.store %s1, %d[%c1] : memref<3xf64>
    %dv = vector.load %d[%c0] : memref<3xf64>, vector<3xf64>
    %sq = arith.mulf %dv, %dv : vector<3xf64>
    %c = vector.extract %sq[0] : f64 from vector<3xf64>
    %positive = arith.cmpf ogt, %c, %zero : f64
    scf.if %positive {
      %f0 = memref.load %f[%a, %c0] : memref<?x3xf64>
      %g0 = vector.extract %sq[0] : f64 from vector<3xf64>
      %n0 = arith.addf %f0, %g0 : f64
      memref.store %n0, %f[%a, %c0] : memref<?x3xf64>
      %g2 = vector.extract %sq[2] : f64 from vector<3xf64>
      memref.store %g2, %f[%b, %c2] : memref<?x3xf64>
    }
    scf.reduce
  }
  return
}

// A value of at least as many components as lanes (a 3x3 block) is
// transposed in registers (butterfly shuffles) and buffered
// [lane][component], so that a lane's scatter reads the components of its
// block side by side; the scalars the lane phase reads share one buffer, in
// the order it reads them. Each read loads only the components it uses.
// CHECK-LABEL: func.func @block_scatter(
// CHECK:       scf.parallel
// CHECK:         arith.mulf {{.*}} : vector<8xf64>
// CHECK:         %[[BLOCKS:.*]] = memref.alloca() : memref<8x16xf64>
// CHECK-COUNT-24: vector.shuffle {{.*}} : vector<8xf64>, vector<8xf64>
// CHECK-COUNT-8: vector.store %{{.*}}, %[[BLOCKS]][%{{.*}}, %{{.*}}] : memref<8x16xf64>, vector<8xf64>
// CHECK-COUNT-24: vector.shuffle {{.*}} : vector<8xf64>, vector<8xf64>
// CHECK-COUNT-8: vector.store %{{.*}}, %[[BLOCKS]][%{{.*}}, %{{.*}}] : memref<8x16xf64>, vector<8xf64>
// CHECK:         %[[SCALARS:.*]] = memref.alloca() : memref<2x8xf64>
// CHECK:         scf.for %[[LANE:.*]] =
// CHECK:           scf.if
// CHECK:           scf.if
// CHECK:             %[[FIRST:.*]] = arith.constant 0 : index
// CHECK:             %[[K0:.*]] = memref.load %[[SCALARS]][%[[FIRST]], %[[LANE]]] : memref<2x8xf64>
// CHECK:             memref.store %[[K0]]
// CHECK:             %[[SECOND:.*]] = arith.constant 1 : index
// CHECK:             %[[K4:.*]] = memref.load %[[SCALARS]][%[[SECOND]], %[[LANE]]] : memref<2x8xf64>
// CHECK:             memref.store %[[K4]]
// CHECK:             %[[C4:.*]] = arith.constant 4 : index
// CHECK:             %[[MIDDLE:.*]] = memref.load %[[BLOCKS]][%[[LANE]], %[[C4]]] : memref<8x16xf64>
// CHECK:             memref.store %[[MIDDLE]]
// AVX-LABEL: func.func @block_scatter(
// AVX: memref.alloca() : memref<4x12xf64>
func.func @block_scatter(%lb : index, %ub : index, %x : memref<?x9xf64>,
                         %k : memref<?x9xf64>, %h : memref<f64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %hv = memref.load %h[] : memref<f64>
  scf.parallel (%e) = (%lb) to (%ub) step (%c1) {
    %x0 = memref.load %x[%e, %c0] : memref<?x9xf64>
    %xe = vector.broadcast %x0 : f64 to vector<9xf64>
    %hs = vector.broadcast %hv : f64 to vector<9xf64>
    %ke = arith.mulf %xe, %hs : vector<9xf64>
    %k4 = vector.extract %ke[4] : f64 from vector<9xf64>
    %k0 = vector.extract %ke[0] : f64 from vector<9xf64>
    %positive = arith.cmpf ogt, %k4, %k0 : f64
    scf.if %positive {
      memref.store %k0, %k[%e, %c0] : memref<?x9xf64>
      memref.store %k4, %k[%e, %c1] : memref<?x9xf64>
      %middle = vector.extract %ke[4] : f64 from vector<9xf64>
      %c2 = arith.constant 2 : index
      memref.store %middle, %k[%e, %c2] : memref<?x9xf64>
    }
    scf.reduce
  }
  return
}

// An element loop inside another loop (a map in a `while`): the padded copy
// of a small set's field is a slot at the function's entry, not one more
// stack slot in every iteration of the outer loop.
// CHECK-LABEL: func.func @repeated(
// CHECK-NEXT:    memref.alloca() : memref<8xf64>
// CHECK:         scf.for
// CHECK-NOT:       memref.alloca() : memref<8xf64>
// CHECK:           scf.parallel
func.func @repeated(%n : index, %w : memref<?xf64>, %out : memref<?xf64>) {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c10 = arith.constant 10 : index
  scf.for %t = %c0 to %c10 step %c1 {
    scf.parallel (%e) = (%c0) to (%n) step (%c1) {
      %we = memref.load %w[%e] : memref<?xf64>
      %a = arith.mulf %we, %we : f64
      %b = arith.mulf %a, %we : f64
      %c = arith.mulf %b, %a : f64
      %d = arith.addf %c, %b : f64
      memref.store %d, %out[%e] : memref<?xf64>
      scf.reduce
    }
  }
  return
}
