//===- IRGen.h - Checked Simit AST to the simit dialect ---------*- C++ -*-===//
//
// Translates a program that sema accepted into a module of the simit dialect
// (with func, scf, arith, math and complex), one op per source construct,
// each located at its .sim source position. See lib/Frontend/IRGen.cpp for
// the mapping and the runtime functions calls are made to.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_IRGEN_H
#define SIMIT_FRONTEND_IRGEN_H

#include "simit/Frontend/AST.h"
#include "simit/Frontend/Diagnostics.h"

#include "mlir/IR/BuiltinOps.h"
#include "mlir/IR/MLIRContext.h"
#include "mlir/IR/OwningOpRef.h"

namespace simit::frontend {

struct IRGenOptions {
  /// `float` is f32 (and `complex` complex<f32>) instead of f64.
  bool singlePrecision = false;
  /// When every name is an exported function: only these functions
  /// and those they use are generated, so that a construct the generator
  /// does not support elsewhere in the file stops nothing. Empty: all.
  std::vector<std::string> onlyFunctions;
};

/// Loads the dialects generated modules use into `context`.
void loadIRGenDialects(mlir::MLIRContext &context);

/// Generates the module of a checked `program` whose source buffers belong
/// to `diags`' source manager. Constructs the generator does not support and
/// IR that fails to verify are reported to `diags` at their source position;
/// the result is null then.
mlir::OwningOpRef<mlir::ModuleOp> generateIR(const Program &program,
                                             DiagnosticEngine &diags,
                                             mlir::MLIRContext &context,
                                             const IRGenOptions &options = {});

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_IRGEN_H
