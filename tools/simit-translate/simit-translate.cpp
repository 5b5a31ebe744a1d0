//===- simit-translate.cpp - .sim to MLIR ---------------------------------===//
//
// --import-sim parses and checks a .sim file (each enabled `%%%` section as
// its own program) and prints the generated (and verified) simit-dialect
// module; --dump-ast prints the checked AST.
// Diagnostics go to stderr; the exit status is 1 when any program fails.
//
//===----------------------------------------------------------------------===//

#include "simit/Frontend/ASTPrinter.h"
#include "simit/Frontend/Frontend.h"
#include "simit/Frontend/IRGen.h"

#include "mlir/IR/MLIRContext.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/WithColor.h"

using namespace simit::frontend;

static llvm::cl::OptionCategory translateCategory("simit-translate options");

static llvm::cl::opt<std::string> inputFilename(llvm::cl::cat(translateCategory), llvm::cl::Positional,
                                                llvm::cl::desc("<input .sim>"),
                                                llvm::cl::init("-"));

enum class Action { ImportSim, DumpAST };
static llvm::cl::opt<Action> action(llvm::cl::cat(translateCategory), 
    llvm::cl::desc("Action:"), llvm::cl::init(Action::ImportSim),
    llvm::cl::values(
        clEnumValN(Action::ImportSim, "import-sim",
                   "Parse and check Simit source, print the MLIR module"),
        clEnumValN(Action::DumpAST, "dump-ast",
                   "Parse and check Simit source, print the checked AST")));

static llvm::cl::opt<int>
    sectionIndex(llvm::cl::cat(translateCategory), "section",
                 llvm::cl::desc("Process only the %%% section with this "
                                "0-based index"),
                 llvm::cl::init(-1));

static llvm::cl::opt<bool>
    singlePrecision(llvm::cl::cat(translateCategory), "single-precision",
                    llvm::cl::desc("Compile `float` as f32 instead of f64"),
                    llvm::cl::init(false));

static llvm::cl::opt<bool> printDebugLocations(llvm::cl::cat(translateCategory), 
    "print-locations",
    llvm::cl::desc("Print the source locations of the generated operations"),
    llvm::cl::init(false));

/// Compiles one program; prints its output or its diagnostics.
static bool processProgram(llvm::StringRef text, llvm::StringRef bufferName) {
  llvm::SourceMgr sourceMgr;
  unsigned id = sourceMgr.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(text, bufferName), llvm::SMLoc());
  DiagnosticEngine diags(sourceMgr);
  std::unique_ptr<Program> program = parseProgram(sourceMgr, id, diags);
  bool ok = !diags.hasErrors() && checkProgram(*program, diags);
  mlir::MLIRContext context;
  mlir::OwningOpRef<mlir::ModuleOp> module;
  if (ok && action == Action::ImportSim) {
    IRGenOptions options;
    options.singlePrecision = singlePrecision;
    module = generateIR(*program, diags, context, options);
    ok = static_cast<bool>(module);
  }
  llvm::outs().flush();
  diags.print(llvm::errs());
  if (!ok)
    return false;
  if (action == Action::DumpAST) {
    printProgram(*program, llvm::outs());
    return true;
  }
  mlir::OpPrintingFlags flags;
  if (printDebugLocations)
    flags.enableDebugInfo(/*enable=*/true, /*prettyForm=*/false)
        .useLocalScope(); // locations inline, not as #loc aliases
  module->print(llvm::outs(), flags);
  llvm::outs() << "\n";
  return true;
}

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  llvm::cl::HideUnrelatedOptions(translateCategory);
  llvm::cl::ParseCommandLineOptions(argc, argv, "Simit translation tool\n");

  auto file = llvm::MemoryBuffer::getFileOrSTDIN(inputFilename);
  if (std::error_code ec = file.getError()) {
    llvm::WithColor::error() << "cannot open '" << inputFilename
                             << "': " << ec.message() << '\n';
    return 1;
  }
  llvm::StringRef source = (*file)->getBuffer();
  std::vector<Section> sections = splitSections(source);
  if (sectionIndex >= (int)sections.size()) {
    llvm::WithColor::error() << "there is no section " << sectionIndex
                             << " in '" << inputFilename << "'\n";
    return 1;
  }
  bool sectioned = source.starts_with("%%%");
  bool ok = true;
  bool first = true;
  for (const Section &section : sections) {
    if (sectionIndex >= 0 && (int)section.index != sectionIndex)
      continue;
    if (section.disabled)
      continue;
    if (sectioned) {
      llvm::outs() << (first ? "" : "\n") << "// ----- section "
                   << section.index << " '" << section.name << "'\n";
      first = false;
    }
    ok &= processProgram(section.text, inputFilename);
  }
  return ok ? 0 : 1;
}
