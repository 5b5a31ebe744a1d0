//===- InlineFunctions.cpp - Inline every call of a defined function ------===//
//
// Simit has no recursion, so inlining bottom-up terminates: a call is inlined
// once its callee no longer contains calls of defined functions.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/Dialect/Func/Extensions/InlinerExtension.h"
#include "mlir/IR/SymbolTable.h"
#include "mlir/Transforms/InliningUtils.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITINLINEFUNCTIONS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// Every simit operation can be inlined: the dialect has value semantics and
/// its only symbol references name module-level externs and functions.
struct SimitInlinerInterface : public DialectInlinerInterface {
  using DialectInlinerInterface::DialectInlinerInterface;

  bool isLegalToInline(Operation *, Operation *, bool) const final {
    return true;
  }
  bool isLegalToInline(Region *, Region *, bool, IRMapping &) const final {
    return true;
  }
  bool isLegalToInline(Operation *, Region *, bool, IRMapping &) const final {
    return true;
  }
};

/// The defined function a call names, or null.
func::FuncOp getDefinedCallee(func::CallOp call, SymbolTable &symbols) {
  auto callee = symbols.lookup<func::FuncOp>(call.getCallee());
  if (!callee || callee.isExternal())
    return nullptr;
  return callee;
}

struct InlineFunctions
    : public simit::impl::SimitInlineFunctionsBase<InlineFunctions> {
  void getDependentDialects(DialectRegistry &registry) const override {
    SimitInlineFunctionsBase::getDependentDialects(registry);
    registerSimitInlinerInterface(registry);
  }

  void runOnOperation() override {
    ModuleOp module = getOperation();
    SymbolTable symbols(module);
    InlinerInterface interface(&getContext());

    // Each round inlines the calls whose callee calls no defined function;
    // without recursion every round makes progress until no call is left.
    while (true) {
      SmallVector<func::CallOp> ready;
      bool anyCall = false;
      module.walk([&](func::CallOp call) {
        func::FuncOp callee = getDefinedCallee(call, symbols);
        if (!callee)
          return;
        anyCall = true;
        bool calleeIsLeaf = !callee
                                 .walk([&](func::CallOp inner) {
                                   return getDefinedCallee(inner, symbols)
                                              ? WalkResult::interrupt()
                                              : WalkResult::advance();
                                 })
                                 .wasInterrupted();
        if (calleeIsLeaf)
          ready.push_back(call);
      });
      if (!anyCall)
        break;
      if (ready.empty()) {
        module.emitError("recursive calls cannot be inlined (Simit has no "
                         "recursion)");
        return signalPassFailure();
      }
      for (func::CallOp call : ready) {
        func::FuncOp callee = getDefinedCallee(call, symbols);
        auto cloneCallback = [](OpBuilder &builder, Region *src,
                                Block *inlineBlock, Block *postBlock,
                                IRMapping &mapper,
                                bool shouldCloneInlinedRegion) {
          // Clone the callee's body into the caller in front of postBlock.
          Region *dest = inlineBlock->getParent();
          src->cloneInto(dest, postBlock->getIterator(), mapper);
        };
        if (failed(inlineCall(interface, cloneCallback, call, callee,
                              &callee.getBody()))) {
          call.emitError("cannot inline the call of '")
              << callee.getSymName() << "'";
          return signalPassFailure();
        }
        call.erase();
      }
    }

    // Functions of the program that are neither exported nor referenced
    // any more (by a map) are gone for good, and so, in turn, are the
    // element functions only their maps referred to.
    while (true) {
      SmallVector<func::FuncOp> unused;
      for (auto function : module.getOps<func::FuncOp>())
        if (!isExportedFunction(function) && !function.isExternal() &&
            usesSimitDialect(function) &&
            SymbolTable::symbolKnownUseEmpty(function, module))
          unused.push_back(function);
      if (unused.empty())
        break;
      for (func::FuncOp function : unused)
        function.erase();
    }
  }
};
} // namespace

bool mlir::simit::isExportedFunction(func::FuncOp function) {
  return function->hasAttr("simit.export");
}

bool mlir::simit::usesSimitDialect(func::FuncOp function) {
  auto isSimitType = [](Type type) {
    return isa<SimitDialect>(type.getDialect());
  };
  if (llvm::any_of(function.getArgumentTypes(), isSimitType) ||
      llvm::any_of(function.getResultTypes(), isSimitType))
    return true;
  return function
      .walk([](Operation *op) {
        return isa_and_nonnull<SimitDialect>(op->getDialect())
                   ? WalkResult::interrupt()
                   : WalkResult::advance();
      })
      .wasInterrupted();
}

void mlir::simit::registerSimitInlinerInterface(DialectRegistry &registry) {
  func::registerInlinerExtension(registry);
  registry.addExtension(+[](MLIRContext *, SimitDialect *dialect) {
    if (!dialect->getRegisteredInterface<DialectInlinerInterface>())
      dialect->addInterfaces<SimitInlinerInterface>();
  });
}
