//===- FuzzTest.cpp - Mutation fuzzing of the whole frontend --------------===//
//
// Mutates the lit test programs (FuzzSupport.h) for a bounded time
// (SIMIT_FUZZ_SECONDS, default 20) and runs lexer, parser, sema and the AST
// printer on every mutant. A crash prints the offending mutant and fails
// the test.
//
//===----------------------------------------------------------------------===//

#include "simit/Frontend/ASTPrinter.h"
#include "simit/Frontend/Frontend.h"

#include "../FuzzSupport.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

using namespace simit::frontend;

namespace {

std::vector<std::string> loadSeeds() {
  std::vector<std::string> seeds = {
      "element V\n x : vector[3](float);\nend\nextern S : set{V};\n"
      "extern E : set{V}(S, S);\nfunc f(v : V, p : (V*2)) -> (A : "
      "matrix[S,S](float))\n A(p(0), p(1)) = norm(v.x);\nend\n"
      "export func main()\n A = map f to E reduce +;\n S.x = A * S.x;\nend\n"};
  std::error_code ec;
  for (llvm::sys::fs::recursive_directory_iterator it(SIMIT_FRONTEND_TEST_DIR,
                                                      ec),
       end;
       it != end && !ec; it.increment(ec)) {
    if (!llvm::StringRef(it->path()).ends_with(".sim"))
      continue;
    auto buffer = llvm::MemoryBuffer::getFile(it->path());
    if (buffer)
      seeds.push_back((*buffer)->getBuffer().str());
  }
  return seeds;
}

const char *const kFragments[] = {
    "(", ")", "[", "]", "{", "}", ",", ";", ":", ".", "->", "=", "==", "<",
    ">", "+", "-", "*", "/", "\\", ".*", "'", "^", "%!", "%{", "%}", "\n",
    "end", "func", "map", "to", "reduce", "ivar", "element", "set{V}",
    "tensor[3](float)", "(V*2)", "inout", "0:", "<V>", "\"s\"", "1.5e3",
    "2147483648", "not", "apply", "through", "grid[2]{V}(S)", "%%%\n",
    "(V*2147483647)", "1e999", "''''",
};

void compileAll(const std::string &text) {
  for (const Section &section : splitSections(text)) {
    llvm::SourceMgr sourceMgr;
    unsigned id = sourceMgr.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(section.text, "mutant.sim"),
        llvm::SMLoc());
    DiagnosticEngine diags(sourceMgr);
    std::unique_ptr<Program> program = parseProgram(sourceMgr, id, diags);
    if (!diags.hasErrors() && checkProgram(*program, diags))
      printProgram(*program, llvm::nulls());
    diags.print(llvm::nulls());
  }
}

TEST(FrontendFuzz, MutantsNeverCrash) {
  std::vector<std::string> seeds = loadSeeds();
  ASSERT_GT(seeds.size(), 1u) << "no seed programs under "
                              << SIMIT_FRONTEND_TEST_DIR;
  unsigned runs = simit::fuzz::fuzz("frontend", seeds, kFragments, 20.0,
                                    20240611, compileAll);
  EXPECT_GT(runs, 0u);
}

} // namespace
