//===- FuzzTest.cpp - Mutation fuzzing of the whole frontend --------------===//
//
// Mutates the lit test programs (byte flips, span deletions and duplications,
// truncations, token insertions) with a fixed seed for a bounded time
// (SIMIT_FUZZ_SECONDS, default 20) and runs lexer, parser, sema and the AST
// printer on every mutant. A crash is caught by a signal handler that prints
// the offending mutant and fails the test.
//
//===----------------------------------------------------------------------===//

#include "simit/Frontend/ASTPrinter.h"
#include "simit/Frontend/Frontend.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <random>
#include <unistd.h>

using namespace simit::frontend;

namespace {

// What the signal handler reports; written before each run.
const char *currentMutant = nullptr;
size_t currentMutantSize = 0;

void writeAll(const char *text, size_t size) {
  while (size > 0) {
    ssize_t n = ::write(STDERR_FILENO, text, size);
    if (n <= 0)
      return;
    text += n;
    size -= n;
  }
}

extern "C" void onCrash(int sig) {
  const char header[] = "\nfrontend crashed on this mutant:\n-----\n";
  writeAll(header, sizeof(header) - 1);
  if (currentMutant)
    writeAll(currentMutant, currentMutantSize);
  const char footer[] = "\n-----\n";
  writeAll(footer, sizeof(footer) - 1);
  ::_exit(128 + sig);
}

void installCrashHandlers() {
  static std::vector<char> altStack(1 << 16);
  stack_t ss{};
  ss.ss_sp = altStack.data();
  ss.ss_size = altStack.size();
  sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_handler = onCrash;
  sa.sa_flags = SA_ONSTACK;
  for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL})
    sigaction(sig, &sa, nullptr);
}

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
};

std::string mutate(const std::string &seed, std::mt19937 &rng) {
  std::string s = seed;
  auto pick = [&](size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(rng);
  };
  unsigned count = 1 + pick(4);
  for (unsigned m = 0; m < count; ++m) {
    size_t pos = pick(s.size() + 1);
    size_t len = 1 + pick(12);
    switch (pick(6)) {
    case 0: // byte flip
      if (!s.empty())
        s[pick(s.size())] = static_cast<char>(pick(256));
      break;
    case 1: // deletion
      s.erase(std::min(pos, s.size()), len);
      break;
    case 2: // duplication
      if (pos < s.size())
        s.insert(pos, s.substr(pos, len));
      break;
    case 3: // truncation
      s.resize(std::min(pos, s.size()));
      break;
    case 4: // fragment insertion
      s.insert(std::min(pos, s.size()), kFragments[pick(std::size(kFragments))]);
      break;
    default: // move a span elsewhere
      if (pos < s.size()) {
        std::string span = s.substr(pos, len);
        s.erase(pos, len);
        s.insert(pick(s.size() + 1), span);
      }
      break;
    }
  }
  return s;
}

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
  installCrashHandlers();
  std::vector<std::string> seeds = loadSeeds();
  ASSERT_GT(seeds.size(), 1u) << "no seed programs under "
                              << SIMIT_FRONTEND_TEST_DIR;
  double seconds = 20.0;
  if (const char *env = std::getenv("SIMIT_FUZZ_SECONDS"))
    seconds = std::atof(env);
  std::mt19937 rng(20240611);
  auto deadline = std::chrono::steady_clock::now() +
                  std::chrono::duration<double>(seconds);
  unsigned runs = 0;
  // Every seed once unmodified, then mutants until the deadline.
  for (const std::string &seed : seeds) {
    currentMutant = seed.data();
    currentMutantSize = seed.size();
    compileAll(seed);
  }
  while (std::chrono::steady_clock::now() < deadline) {
    std::string mutant = mutate(seeds[rng() % seeds.size()], rng);
    currentMutant = mutant.data();
    currentMutantSize = mutant.size();
    compileAll(mutant);
    ++runs;
  }
  currentMutant = nullptr;
  EXPECT_GT(runs, 0u);
  std::printf("fuzzed %u mutants of %zu seeds\n", runs, seeds.size());
}

} // namespace
