//===--- SimImport.cpp - Simit source to the simit dialect ----------------===//

#include "SimImport.h"

#include "simit/Frontend/Frontend.h"
#include "simit/Frontend/IRGen.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

using namespace simit;

llvm::Expected<mlir::OwningOpRef<mlir::ModuleOp>>
simit::importSimit(llvm::StringRef source, llvm::StringRef bufferName,
                   mlir::MLIRContext &context, const ProgramOptions &options) {
  llvm::SourceMgr sourceMgr;
  unsigned buffer = sourceMgr.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(source, bufferName), llvm::SMLoc());
  frontend::DiagnosticEngine diags(sourceMgr);
  std::unique_ptr<frontend::Program> program =
      frontend::parseProgram(sourceMgr, buffer, diags);
  if (!diags.hasErrors())
    frontend::checkProgram(*program, diags);
  if (diags.hasErrors()) {
    std::string text;
    llvm::raw_string_ostream os(text);
    diags.print(os);
    return llvm::createStringError(text);
  }
  for (std::unique_ptr<frontend::FuncDecl> &func : program->funcs)
    if (llvm::is_contained(options.hostFunctions, func->name))
      func->isExport = true;
  frontend::IRGenOptions irgenOptions;
  irgenOptions.singlePrecision = options.precision == FloatPrecision::Single;
  irgenOptions.onlyFunctions = options.specialisation.entryFunctions;
  mlir::OwningOpRef<mlir::ModuleOp> module =
      frontend::generateIR(*program, diags, context, irgenOptions);
  if (!module || diags.hasErrors()) {
    std::string text;
    llvm::raw_string_ostream os(text);
    diags.print(os);
    return llvm::createStringError(text);
  }
  // What is left are warnings (a leading zero): the program compiles.
  diags.print(llvm::errs());
  return module;
}
