// RUN: simit-opt %s --simit-convert-to-llvm --reconcile-unrealized-casts | FileCheck %s
// RUN: simit-opt %s --simit-convert-to-llvm=use-generic-functions --reconcile-unrealized-casts | FileCheck %s --check-prefix=GENERIC

// One conversion takes vector, arith (a ceiling division included), memref,
// cf and func to LLVM: nothing of them, and no cast between them, is left.

// CHECK-LABEL: llvm.func @chunks
// CHECK-NOT: builtin.unrealized_conversion_cast
// CHECK: llvm.udiv
// CHECK: llvm.call @malloc
// CHECK: llvm.extractelement
// CHECK: llvm.cond_br
// CHECK: llvm.call @free
// CHECK-NOT: builtin.unrealized_conversion_cast
// CHECK: llvm.return
// GENERIC-LABEL: llvm.func @chunks
// GENERIC: llvm.call @_mlir_memref_to_llvm_alloc
// GENERIC: llvm.call @_mlir_memref_to_llvm_free
func.func @chunks(%n: index, %v: vector<4xf64>) -> f64 {
  %c64 = arith.constant 64 : index
  %chunks = arith.ceildivui %n, %c64 : index
  %buffer = memref.alloc(%chunks) : memref<?xf64>
  %x = vector.extract %v[2] : f64 from vector<4xf64>
  %c0 = arith.constant 0 : index
  %empty = arith.cmpi eq, %chunks, %c0 : index
  cf.cond_br %empty, ^done(%x : f64), ^store
^store:
  memref.store %x, %buffer[%c0] : memref<?xf64>
  %y = memref.load %buffer[%c0] : memref<?xf64>
  cf.br ^done(%y : f64)
^done(%r: f64):
  memref.dealloc %buffer : memref<?xf64>
  return %r : f64
}

// A 2-D from_elements (a local matrix at the host boundary) is unrolled
// into rows before the conversion, which only knows 1-D vectors.
// CHECK-LABEL: llvm.func @matrix
// CHECK-NOT: vector.from_elements
// CHECK: llvm.insertelement
// CHECK: llvm.insertvalue {{.*}}[1] : !llvm.array<2 x vector<2xf64>>
// CHECK: llvm.return
func.func @matrix(%a: f64, %b: f64) -> vector<2x2xf64> {
  %m = vector.from_elements %a, %b, %b, %a : vector<2x2xf64>
  return %m : vector<2x2xf64>
}
