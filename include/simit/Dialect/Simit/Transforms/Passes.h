//===- Passes.h - Passes on the simit dialect -------------------*- C++ -*-===//

#ifndef SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_H
#define SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_H

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/Dialect/ControlFlow/IR/ControlFlowOps.h"
#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/Dialect/LLVMIR/LLVMDialect.h"
#include "mlir/Dialect/Math/IR/Math.h"
#include "mlir/Dialect/MemRef/IR/MemRef.h"
#include "mlir/Dialect/OpenMP/OpenMPDialect.h"
#include "mlir/Dialect/SCF/IR/SCF.h"
#include "mlir/Dialect/Vector/IR/VectorOps.h"
#include "mlir/IR/BuiltinOps.h"
#include "mlir/Pass/Pass.h"

namespace mlir {
class OpPassManager;
namespace simit {

#define GEN_PASS_DECL
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"

#define GEN_PASS_REGISTRATION
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"

/// The attribute simit-check-numerics gives the ops whose results
/// convert-simit-to-loops scans for NaN and infinity: {op = "<what and
/// where>", results = [<result names>]}.
constexpr llvm::StringLiteral kCheckNumericsAttr = "simit.check_numerics";

/// The attribute simit-parallel-loops gives the scf.parallel loops whose
/// iterations may run concurrently: "owned", "reduction" (a loop over
/// chunks of a reduction) or "scatter" (a loop over the chunks of one colour
/// of a scatter loop).
constexpr llvm::StringLiteral kParallelLoopAttr = "simit.parallel";
constexpr llvm::StringLiteral kOwnedLoop = "owned";
constexpr llvm::StringLiteral kReductionLoop = "reduction";
constexpr llvm::StringLiteral kScatterLoop = "scatter";

/// Whether `function` is an entry point the host calls: it carries the
/// `simit.export` unit attribute (the frontend's `export func`).
bool isExportedFunction(func::FuncOp function);

/// Whether `function` has simit types in its signature or simit operations
/// in its body (host code such as test drivers has neither).
bool usesSimitDialect(func::FuncOp function);

/// Registers the simit dialect's inliner interface (every simit op may be
/// inlined) together with func's, as a dialect extension.
void registerSimitInlinerInterface(DialectRegistry &registry);

/// Adds the passes that precede the lowering on both targets: inlining,
/// then what the scene lets the compiler skip (folded constants, dead
/// assemblies), as the options say.
void buildSimitScenePasses(OpPassManager &pm,
                           const SimitCpuPipelineOptions &options);

/// Adds the passes from simit IR down to the LLVM dialect for the CPU:
/// inlining, linear algebra to index expressions, fusion, loops, LLVM.
void buildSimitCpuPipeline(OpPassManager &pm,
                           const SimitCpuPipelineOptions &options = {});

} // namespace simit
} // namespace mlir

#endif // SIMIT_DIALECT_SIMIT_TRANSFORMS_PASSES_H
