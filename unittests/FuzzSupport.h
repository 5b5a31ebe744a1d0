//===- FuzzSupport.h - Seeded, time-bounded mutation fuzzing ----*- C++ -*-===//
//
// Shared by the fuzz tests of the frontend and of the runtime's readers:
// mutates seed inputs (byte flips, span deletions, duplications and moves,
// truncations, insertions of format-specific fragments) with a fixed seed
// for a bounded time (SIMIT_FUZZ_SECONDS, or each test's default), runs a
// reader on every mutant, and turns a crash into a report of the mutant
// that caused it.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_UNITTESTS_FUZZSUPPORT_H
#define SIMIT_UNITTESTS_FUZZSUPPORT_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/STLFunctionalExtras.h"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

namespace simit::fuzz {

/// What the crash handler reports; set before each run.
inline const char *currentInput = nullptr;
inline size_t currentInputSize = 0;
inline const char *currentFuzzer = "";

inline void writeAll(const char *text, size_t size) {
  while (size > 0) {
    ssize_t n = ::write(STDERR_FILENO, text, size);
    if (n <= 0)
      return;
    text += n;
    size -= n;
  }
}

extern "C" inline void onCrash(int sig) {
  writeAll("\n", 1);
  writeAll(currentFuzzer, std::char_traits<char>::length(currentFuzzer));
  const char header[] = " crashed on this input:\n-----\n";
  writeAll(header, sizeof(header) - 1);
  if (currentInput)
    writeAll(currentInput, currentInputSize);
  const char footer[] = "\n-----\n";
  writeAll(footer, sizeof(footer) - 1);
  ::_exit(128 + sig);
}

/// Reports the input being read when the process dies of a signal (a stack
/// overflow included: the handler runs on its own stack).
inline void installCrashHandlers() {
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

/// Applies 1 to 4 random edits to `seed`; `fragments` are the pieces of the
/// format worth inserting (keywords, delimiters, extreme numbers).
inline std::string mutate(const std::string &seed, std::mt19937 &rng,
                          llvm::ArrayRef<const char *> fragments) {
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
      if (!fragments.empty())
        s.insert(std::min(pos, s.size()), fragments[pick(fragments.size())]);
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

/// Runs `read` on every seed, then on mutants of random seeds until
/// SIMIT_FUZZ_SECONDS (else `defaultSeconds`) have passed. Returns the
/// number of mutants and prints it with the fuzzer's `name`.
inline unsigned
fuzz(const char *name, const std::vector<std::string> &seeds,
     llvm::ArrayRef<const char *> fragments, double defaultSeconds,
     uint32_t rngSeed, llvm::function_ref<void(const std::string &)> read) {
  installCrashHandlers();
  currentFuzzer = name;
  double seconds = defaultSeconds;
  if (const char *env = std::getenv("SIMIT_FUZZ_SECONDS"))
    seconds = std::atof(env);
  std::mt19937 rng(rngSeed);
  auto deadline = std::chrono::steady_clock::now() +
                  std::chrono::duration<double>(seconds);
  for (const std::string &seed : seeds) {
    currentInput = seed.data();
    currentInputSize = seed.size();
    read(seed);
  }
  unsigned runs = 0;
  while (!seeds.empty() && std::chrono::steady_clock::now() < deadline) {
    std::string mutant = mutate(seeds[rng() % seeds.size()], rng, fragments);
    currentInput = mutant.data();
    currentInputSize = mutant.size();
    read(mutant);
    ++runs;
  }
  currentInput = nullptr;
  std::printf("%s: fuzzed %u mutants of %zu seeds\n", name, runs,
              seeds.size());
  return runs;
}

} // namespace simit::fuzz

#endif // SIMIT_UNITTESTS_FUZZSUPPORT_H
