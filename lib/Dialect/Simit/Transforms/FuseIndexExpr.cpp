//===- FuseIndexExpr.cpp - Fuse chains of index expressions ---------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITFUSEINDEXEXPR
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
struct FuseIndexExpr
    : public simit::impl::SimitFuseIndexExprBase<FuseIndexExpr> {
  void runOnOperation() override {}
};
} // namespace
