//===- HoistParallelAllocas.cpp - Stack slots out of parallel loops -------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITHOISTPARALLELALLOCAS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
struct HoistParallelAllocas
    : public simit::impl::SimitHoistParallelAllocasBase<HoistParallelAllocas> {
  void runOnOperation() override {
    func::FuncOp function = getOperation();
    if (function.isExternal())
      return;
    Block &entry = function.front();
    SmallVector<memref::AllocaOp> slots;
    function.walk([&](memref::AllocaOp alloca) {
      if (alloca->getParentOfType<scf::ParallelOp>() &&
          !alloca->getParentOfType<omp::ParallelOp>() &&
          alloca.getType().hasStaticShape() && alloca->getNumOperands() == 0)
        slots.push_back(alloca);
    });
    for (memref::AllocaOp alloca : slots)
      alloca->moveBefore(&entry, entry.begin());
  }
};
} // namespace
