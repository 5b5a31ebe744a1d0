//===--- Accumulation.h - Stores that add to what they read -----*- C++ -*-===//
//
// An accumulation is a store of `load + x` (or `load - x`) to the location
// the load reads. Elements whose shared writes are all accumulations commute
// (up to rounding): simit-parallel-loops runs their loops colour by colour,
// and simit-gpu-scatter-atomics makes them atomic read-modify-writes.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_ACCUMULATION_H
#define SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_ACCUMULATION_H

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/MemRef/IR/MemRef.h"
#include "mlir/Dialect/Vector/IR/VectorOps.h"

#include <optional>

namespace mlir::simit {

/// The memref and indices `op` (a memref or vector load or store) accesses.
inline std::pair<Value, ValueRange> locationOf(Operation *op) {
  if (auto load = dyn_cast<memref::LoadOp>(op))
    return {load.getMemRef(), load.getIndices()};
  if (auto store = dyn_cast<memref::StoreOp>(op))
    return {store.getMemRef(), store.getIndices()};
  if (auto load = dyn_cast<vector::LoadOp>(op))
    return {load.getBase(), load.getIndices()};
  auto store = cast<vector::StoreOp>(op);
  return {store.getBase(), store.getIndices()};
}

struct Accumulation {
  Operation *combine; // the addf/subf/addi/subi
  Operation *load;    // the read of the old value
  Value contribution; // x
  bool negate;        // the combine subtracts x
};

/// The accumulation `store` (a memref or vector store) completes, if any.
inline std::optional<Accumulation> matchAccumulation(Operation *store) {
  Value stored = isa<memref::StoreOp>(store)
                     ? cast<memref::StoreOp>(store).getValueToStore()
                     : cast<vector::StoreOp>(store).getValueToStore();
  Operation *combine = stored.getDefiningOp();
  if (!combine ||
      !isa<arith::AddFOp, arith::SubFOp, arith::AddIOp, arith::SubIOp>(combine))
    return std::nullopt;
  bool subtracts = isa<arith::SubFOp, arith::SubIOp>(combine);
  // `x - old` is not an accumulation of x.
  for (unsigned operand = 0; operand < (subtracts ? 1u : 2u); ++operand) {
    Operation *load = combine->getOperand(operand).getDefiningOp();
    if (load && isa<memref::LoadOp, vector::LoadOp>(load) &&
        locationOf(load).first == locationOf(store).first &&
        llvm::equal(locationOf(load).second, locationOf(store).second))
      return Accumulation{combine, load, combine->getOperand(1 - operand),
                          subtracts};
  }
  return std::nullopt;
}

} // namespace mlir::simit

#endif // SIMIT_LIB_DIALECT_SIMIT_TRANSFORMS_ACCUMULATION_H
