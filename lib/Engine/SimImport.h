//===--- SimImport.h - Simit source to the simit dialect ------------------===//

#ifndef SIMIT_LIB_ENGINE_SIMIMPORT_H
#define SIMIT_LIB_ENGINE_SIMIMPORT_H

#include "simit/Engine/Program.h"

#include "mlir/IR/BuiltinOps.h"
#include "mlir/IR/OwningOpRef.h"

#include "llvm/Support/Error.h"

namespace simit {

/// Parses, checks and translates one Simit program (one `%%%` section at
/// most) into the simit dialect, exporting options.hostFunctions as well.
/// Errors carry the frontend's diagnostics (`file:line:col: error: ...`
/// with the source line and a caret).
llvm::Expected<mlir::OwningOpRef<mlir::ModuleOp>>
importSimit(llvm::StringRef source, llvm::StringRef bufferName,
            mlir::MLIRContext &context, const ProgramOptions &options);

} // namespace simit

#endif // SIMIT_LIB_ENGINE_SIMIMPORT_H
