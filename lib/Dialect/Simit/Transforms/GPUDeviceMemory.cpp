//===- GPUDeviceMemory.cpp - Host memrefs that kernels use get device copies =//
//
// The host passes its fields, pattern arrays and externs as ordinary host
// memory (docs/lowering.md), so every memref a kernel touches gets a device
// buffer for the time the function runs. The data stays on the device across
// launches; it travels only around host code that touches it and when the
// function ends. docs/gpu.md explains why copies and not unified memory.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/GPU/IR/GPUDialect.h"
#include "mlir/Interfaces/SideEffectInterfaces.h"
#include "mlir/Interfaces/ViewLikeInterface.h"
#include "mlir/Transforms/RegionUtils.h"
#include "llvm/ADT/SetVector.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITGPUDEVICEMEMORY
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;

namespace {
/// `op` may write `memref` (an op without declared effects may do anything).
bool mayWrite(Operation *op, Value memref) {
  auto effects = dyn_cast<MemoryEffectOpInterface>(op);
  if (!effects)
    return !isPure(op);
  SmallVector<MemoryEffects::EffectInstance> instances;
  effects.getEffects(instances);
  return llvm::any_of(instances, [&](const MemoryEffects::EffectInstance &e) {
    return isa<MemoryEffects::Write>(e.getEffect()) &&
           (!e.getValue() || e.getValue() == memref);
  });
}

/// `op` stores the only element of `memref`, so it needs none of the old
/// contents (a reduction's accumulator getting its initial value).
bool overwritesAll(Operation *op, Value memref) {
  auto store = dyn_cast<memref::StoreOp>(op);
  auto type = cast<MemRefType>(memref.getType());
  return store && store.getMemRef() == memref && type.hasStaticShape() &&
         type.getNumElements() == 1;
}

bool insideLaunch(Operation *op) {
  return op->getParentOfType<gpu::LaunchOp>() != nullptr;
}

class FunctionMemory {
public:
  explicit FunctionMemory(func::FuncOp function) : function(function) {}

  LogicalResult run();

private:
  LogicalResult mirror(Value host);
  /// The outermost ancestor of `use` below the memref's defining block that
  /// contains no kernel launch: host code inside it runs without a kernel in
  /// between, so one pair of copies around it suffices.
  Operation *hostRoot(Operation *use, Block *defBlock) const;

  func::FuncOp function;
  llvm::DenseSet<Operation *> holdsLaunch;
  /// The last operation this pass put at the start of a block for a block
  /// argument, so that later mirrors go after earlier ones.
  llvm::DenseMap<Block *, Operation *> lastAtBlockStart;
};

LogicalResult FunctionMemory::run() {
  llvm::SetVector<Value> captured;
  function.walk([&](gpu::LaunchOp launch) {
    for (Operation *op = launch; op != function; op = op->getParentOp())
      holdsLaunch.insert(op);
    llvm::SetVector<Value> used;
    getUsedValuesDefinedAbove(launch.getBody(), used);
    for (Value value : used)
      if (isa<BaseMemRefType>(value.getType()))
        captured.insert(value);
  });
  for (Value host : captured)
    if (failed(mirror(host)))
      return failure();
  return success();
}

Operation *FunctionMemory::hostRoot(Operation *use, Block *defBlock) const {
  Operation *root = use;
  while (root->getBlock() != defBlock &&
         !holdsLaunch.contains(root->getParentOp()))
    root = root->getParentOp();
  return root;
}

LogicalResult FunctionMemory::mirror(Value host) {
  Location loc = host.getLoc();
  auto type = dyn_cast<MemRefType>(host.getType());
  if (!type || !type.getLayout().isIdentity() || type.getMemorySpace())
    return emitError(loc) << "a kernel uses " << host.getType()
                          << ", but the GPU path copies only ranked memrefs "
                             "with the identity layout in the default memory "
                             "space";
  Operation *def = host.getDefiningOp();
  if (def && isa<ViewLikeOpInterface>(def))
    return emitError(loc) << "a kernel uses a view of another memref; the GPU "
                             "path copies whole memrefs and cannot keep "
                             "aliases consistent";
  Block *defBlock = def ? def->getBlock() : cast<BlockArgument>(host).getOwner();
  if (!defBlock->getParent()->hasOneBlock())
    return emitError(loc) << "a kernel uses a memref defined in a region with "
                             "several blocks, which the GPU path does not "
                             "support";

  OpBuilder b(function.getContext());
  if (def)
    b.setInsertionPointAfter(def);
  else if (Operation *last = lastAtBlockStart.lookup(defBlock))
    b.setInsertionPointAfter(last);
  else
    b.setInsertionPointToStart(defBlock);
  SmallPtrSet<Operation *, 8> created;
  SmallVector<Value> sizes;
  for (int64_t dim = 0; dim < type.getRank(); ++dim) {
    if (!type.isDynamicDim(dim))
      continue;
    auto size = memref::DimOp::create(b, loc, host, dim);
    created.insert(size);
    sizes.push_back(size);
  }
  auto alloc = gpu::AllocOp::create(b, loc, type, /*asyncToken=*/Type(),
                                    ValueRange(), sizes, ValueRange());
  Value device = alloc.getMemref();
  // A fresh allocation has no contents to copy yet.
  bool fresh = isa_and_nonnull<memref::AllocOp, memref::AllocaOp>(def);
  if (!fresh)
    created.insert(gpu::MemcpyOp::create(b, loc, Type(), ValueRange(), device,
                                         host));
  if (!def)
    lastAtBlockStart[defBlock] = &*std::prev(b.getInsertionPoint());

  host.replaceUsesWithIf(device, [](OpOperand &use) {
    return insideLaunch(use.getOwner());
  });
  bool kernelWrites = llvm::any_of(device.getUsers(), [&](Operation *user) {
    return insideLaunch(user) && mayWrite(user, device);
  });

  llvm::SetVector<Operation *> readRoots, writeRoots;
  SmallVector<memref::DeallocOp> deallocs;
  for (Operation *user : host.getUsers()) {
    if (created.contains(user) || isa<memref::DimOp>(user) ||
        user == defBlock->getTerminator())
      continue;
    if (auto dealloc = dyn_cast<memref::DeallocOp>(user)) {
      deallocs.push_back(dealloc);
      continue;
    }
    Operation *root = hostRoot(user, defBlock);
    if (root->hasTrait<OpTrait::IsTerminator>())
      return user->emitOpError()
             << "passes on a memref that a kernel uses; the GPU path cannot "
                "follow it through control flow";
    // Only an unconditional overwrite may skip the copy back: inside a
    // larger host region the store might not run.
    if (root != user || !overwritesAll(user, host))
      readRoots.insert(root);
    if (mayWrite(user, host))
      writeRoots.insert(root);
  }
  if (kernelWrites)
    for (Operation *root : readRoots) {
      b.setInsertionPoint(root);
      gpu::MemcpyOp::create(b, loc, Type(), ValueRange(), host, device);
    }
  for (Operation *root : writeRoots) {
    b.setInsertionPointAfter(root);
    gpu::MemcpyOp::create(b, loc, Type(), ValueRange(), device, host);
  }

  if (!deallocs.empty()) {
    for (memref::DeallocOp dealloc : deallocs) {
      b.setInsertionPoint(dealloc);
      gpu::DeallocOp::create(b, loc, Type(), ValueRange(), device);
    }
    return success();
  }
  // Host code in the block has its copies already; only a memref that
  // outlives the block (an argument, or one the terminator passes on) needs
  // the kernels' results back.
  Operation *terminator = defBlock->getTerminator();
  bool outlivesBlock =
      !def || llvm::is_contained(terminator->getOperands(), host);
  b.setInsertionPoint(terminator);
  if (kernelWrites && outlivesBlock)
    gpu::MemcpyOp::create(b, loc, Type(), ValueRange(), host, device);
  gpu::DeallocOp::create(b, loc, Type(), ValueRange(), device);
  return success();
}

struct GpuDeviceMemory
    : public simit::impl::SimitGpuDeviceMemoryBase<GpuDeviceMemory> {
  void runOnOperation() override {
    for (auto function : getOperation().getOps<func::FuncOp>())
      if (failed(FunctionMemory(function).run()))
        return signalPassFailure();
  }
};
} // namespace
