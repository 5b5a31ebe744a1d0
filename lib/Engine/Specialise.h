//===--- Specialise.h - A program made for the runs a host promises -------===//

#ifndef SIMIT_LIB_ENGINE_SPECIALISE_H
#define SIMIT_LIB_ENGINE_SPECIALISE_H

#include "simit/Engine/Program.h"

#include "mlir/IR/BuiltinOps.h"

#include "llvm/Support/raw_ostream.h"

namespace simit {

/// Applies `specialisation` to the program in the simit dialect: exported
/// functions that are not entries lose `simit.export` (so that inlining
/// erases them), and constant externs and uniform fields become the
/// `simit.constant` and `simit.uniform_fields` attributes that
/// simit-fold-scene-constants folds. Values whose count does not fit the
/// declared type are left alone (binding reports them).
void specialiseModule(mlir::ModuleOp module,
                      const ProgramSpecialisation &specialisation);

/// Writes every part of `specialisation` to the compile cache's key.
void writeSpecialisationKey(llvm::raw_ostream &os,
                            const ProgramSpecialisation &specialisation);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_SPECIALISE_H
