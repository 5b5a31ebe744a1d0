//===--- CompileCacheTest.cpp - Compiled programs kept on disk ------------===//
//
// Each test has its own temporary cache directory. Whether a compile came
// from the cache is read from Program::compileTimes().cached, never from
// how long it took; what the code computes is checked against numbers
// worked out by hand.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "gtest/gtest.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"

#include <array>
#include <cstdlib>
#include <functional>
#include <map>
#include <optional>

using namespace simit;
using namespace simit::test;

namespace {
/// y = scale K x, K assembled from springs between points.
constexpr llvm::StringLiteral kChain = R"sim(
element Point
  x : float;
  y : float;
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);
extern scale   : float;

func stiffness(s : Spring, p : (Point*2)) -> (K : tensor[points,points](float))
  K(p(0), p(0)) = s.k;
  K(p(0), p(1)) = -s.k;
  K(p(1), p(0)) = -s.k;
  K(p(1), p(1)) = s.k;
end

export func multiply()
  K = map stiffness to springs reduce +;
  points.y = scale * (K * points.x);
end

func twice(a : float) -> (b : float)
  b = 2.0 * a;
end
)sim";

class CompileCacheTest : public ::testing::Test {
protected:
  void SetUp() override {
    ASSERT_FALSE(
        llvm::sys::fs::createUniqueDirectory("simit-cache-test", directory));
  }
  void TearDown() override { llvm::sys::fs::remove_directories(directory); }

  std::string cacheIn(llvm::StringRef name) const {
    llvm::SmallString<128> path(directory);
    llvm::sys::path::append(path, name);
    return std::string(path);
  }

  /// The files in `cache`.
  static std::vector<std::string> entries(llvm::StringRef cache) {
    std::vector<std::string> paths;
    std::error_code ec;
    for (llvm::sys::fs::directory_iterator it(cache, ec), end; !ec && it != end;
         it.increment(ec))
      paths.push_back(it->path());
    return paths;
  }

  /// Compiles `source`'s multiply with `options`, runs it on points at
  /// x = 0, 1, 3 joined by springs of stiffness 2 and 3 with scale 0.5,
  /// and returns y; `cached` tells where the code came from.
  static std::vector<double> runMultiply(llvm::StringRef source,
                                         const ProgramOptions &options,
                                         bool &cached) {
    Program program(options);
    EXPECT_EQ(message(program.loadString(source, "chain.sim")), "success");
    llvm::Expected<Function> multiply = program.compile("multiply");
    if (!multiply) {
      ADD_FAILURE() << llvm::toString(multiply.takeError());
      return {};
    }
    cached = program.compileTimes().cached;
    Set points("points");
    Set springs("springs", {&points, &points});
    auto x = points.addField<double>("x");
    auto y = points.addField<double>("y");
    auto k = springs.addField<double>("k");
    for (double xi : {0.0, 1.0, 3.0})
      x.set(points.add(), xi);
    k.set(springs.add(0, 1), 2.0);
    k.set(springs.add(1, 2), 3.0);
    double scale = 0.5;
    EXPECT_EQ(message(multiply->bind("points", points)), "success");
    EXPECT_EQ(message(multiply->bind("springs", springs)), "success");
    EXPECT_EQ(message(multiply->bind("scale", &scale)), "success");
    EXPECT_EQ(message(multiply->run()), "success");
    return {y.get(0), y.get(1), y.get(2)};
  }

  ProgramOptions cachedOptions(llvm::StringRef name = "cache") const {
    ProgramOptions options;
    options.cacheDirectory = cacheIn(name);
    return options;
  }

  /// K x = (2 (0 - 1), 2 (1 - 0) + 3 (1 - 3), 3 (3 - 1)) = (-2, -4, 6).
  const std::vector<double> halfKx = {-1.0, -2.0, 3.0};
  llvm::SmallString<128> directory;
};
} // namespace

TEST_F(CompileCacheTest, TheSecondCompileLoadsTheFirstsCode) {
  bool cached = true;
  EXPECT_EQ(runMultiply(kChain, cachedOptions(), cached), halfKx);
  EXPECT_FALSE(cached);
  EXPECT_EQ(entries(cacheIn("cache")).size(), 1u);
  EXPECT_EQ(runMultiply(kChain, cachedOptions(), cached), halfKx);
  EXPECT_TRUE(cached);
  EXPECT_EQ(entries(cacheIn("cache")).size(), 1u);
}

/// A program found in the cache is not imported to compile it, but still
/// answers everything a freshly compiled one does.
TEST_F(CompileCacheTest, ACachedProgramAnswersAsACompiledOne) {
  std::map<std::string, std::vector<std::string>> fields = {
      {"points", {"x", "y"}}, {"springs", {"k"}}};
  for (bool expectCached : {false, true}) {
    Program program(cachedOptions());
    ASSERT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
    auto declared = program.externSetFields();
    ASSERT_TRUE(!!declared) << llvm::toString(declared.takeError());
    std::map<std::string, std::vector<std::string>> fieldNames;
    for (const auto &[set, setFields] : *declared)
      for (const DeclaredField &field : setFields) {
        fieldNames[set].push_back(field.name);
        EXPECT_EQ(field.type.str(), "memref<?xf64>")
            << set << "." << field.name;
      }
    EXPECT_EQ(fieldNames, fields);
    auto names = program.exportedFunctions();
    ASSERT_TRUE(!!names) << llvm::toString(names.takeError());
    EXPECT_EQ(*names, std::vector<std::string>{"multiply"});
    ASSERT_TRUE(!!program.compile("multiply"));
    EXPECT_EQ(program.compileTimes().cached, expectCached);
    auto simit = program.emit(Stage::Simit);
    ASSERT_TRUE(!!simit) << llvm::toString(simit.takeError());
    EXPECT_NE(simit->find("func.func @multiply"), std::string::npos);
  }
}

TEST_F(CompileCacheTest, WithoutADirectoryNothingIsCached) {
  bool cached = true;
  EXPECT_EQ(runMultiply(kChain, ProgramOptions(), cached), halfKx);
  EXPECT_FALSE(cached);
  EXPECT_EQ(runMultiply(kChain, ProgramOptions(), cached), halfKx);
  EXPECT_FALSE(cached);
}

TEST_F(CompileCacheTest, ADamagedEntryIsCompiledAgainAndReplaced) {
  using Damage = std::function<std::string(std::string)>;
  auto flipAt = [](double where) {
    return [where](std::string bytes) {
      bytes[static_cast<size_t>(where * (bytes.size() - 1))] ^= 0x20;
      return bytes;
    };
  };
  const std::array<std::pair<const char *, Damage>, 7> damages = {{
      {"magic flipped", flipAt(0.0)},
      {"key flipped", flipAt(0.01)},
      {"payload flipped", flipAt(0.5)},
      {"last byte flipped", flipAt(1.0)},
      {"truncated by one byte",
       [](std::string bytes) { return bytes.substr(0, bytes.size() - 1); }},
      {"truncated to half",
       [](std::string bytes) { return bytes.substr(0, bytes.size() / 2); }},
      {"a byte appended", [](std::string bytes) { return bytes + "x"; }},
  }};
  for (const auto &[what, damage] : damages) {
    SCOPED_TRACE(what);
    ProgramOptions options = cachedOptions(what);
    bool cached = true;
    EXPECT_EQ(runMultiply(kChain, options, cached), halfKx);
    std::vector<std::string> files = entries(options.cacheDirectory);
    ASSERT_EQ(files.size(), 1u);
    auto original = llvm::MemoryBuffer::getFile(files[0]);
    ASSERT_TRUE(!!original);
    {
      std::error_code ec;
      llvm::raw_fd_ostream os(files[0], ec);
      ASSERT_FALSE(ec);
      os << damage((*original)->getBuffer().str());
    }
    EXPECT_EQ(runMultiply(kChain, options, cached), halfKx);
    EXPECT_FALSE(cached);
    EXPECT_EQ(runMultiply(kChain, options, cached), halfKx);
    EXPECT_TRUE(cached);
  }
}

/// Another program's entry under this program's name, as a stale entry
/// from another compiler would be, is not run.
TEST_F(CompileCacheTest, AnEntryWithAnotherKeyIsNotRun) {
  std::string doubled = kChain.str();
  size_t at = doubled.find("scale * (K");
  ASSERT_NE(at, std::string::npos);
  doubled.insert(at, "2.0 * ");
  bool cached = true;
  EXPECT_EQ(runMultiply(kChain, cachedOptions("original"), cached), halfKx);
  EXPECT_EQ(runMultiply(doubled, cachedOptions("doubled"), cached),
            (std::vector<double>{-2.0, -4.0, 6.0}));
  std::vector<std::string> original = entries(cacheIn("original"));
  std::vector<std::string> doubledEntry = entries(cacheIn("doubled"));
  ASSERT_EQ(original.size(), 1u);
  ASSERT_EQ(doubledEntry.size(), 1u);
  ASSERT_FALSE(llvm::sys::fs::copy_file(original[0], doubledEntry[0]));
  EXPECT_EQ(runMultiply(doubled, cachedOptions("doubled"), cached),
            (std::vector<double>{-2.0, -4.0, 6.0}));
  EXPECT_FALSE(cached);
}

TEST_F(CompileCacheTest, AChangedSourceOrOptionMisses) {
  bool cached = true;
  EXPECT_EQ(runMultiply(kChain, cachedOptions(), cached), halfKx);
  EXPECT_FALSE(cached);

  std::string doubled = kChain.str();
  doubled.insert(doubled.find("scale * (K"), "2.0 * ");
  EXPECT_EQ(runMultiply(doubled, cachedOptions(), cached),
            (std::vector<double>{-2.0, -4.0, 6.0}));
  EXPECT_FALSE(cached);

  ProgramOptions timed = cachedOptions();
  timed.timePhases = true;
  EXPECT_EQ(runMultiply(kChain, timed, cached), halfKx);
  EXPECT_FALSE(cached);

  ProgramOptions checked = cachedOptions();
  checked.checkNumerics = true;
  EXPECT_EQ(runMultiply(kChain, checked, cached), halfKx);
  EXPECT_FALSE(cached);

  ProgramOptions host = cachedOptions();
  host.hostFunctions = {"twice"};
  EXPECT_EQ(runMultiply(kChain, host, cached), halfKx);
  EXPECT_FALSE(cached);

  EXPECT_EQ(entries(cacheIn("cache")).size(), 5u);
  // Each of them is found again.
  for (const ProgramOptions &options :
       {cachedOptions(), timed, checked, host}) {
    EXPECT_EQ(runMultiply(kChain, options, cached), halfKx);
    EXPECT_TRUE(cached);
  }
}

TEST_F(CompileCacheTest, SinglePrecisionIsAnotherEntry) {
  ProgramOptions single = cachedOptions();
  single.precision = FloatPrecision::Single;
  for (const ProgramOptions &options : {cachedOptions(), single}) {
    Program program(options);
    ASSERT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
    ASSERT_TRUE(!!program.compile("multiply"));
    EXPECT_FALSE(program.compileTimes().cached);
  }
  EXPECT_EQ(entries(cacheIn("cache")).size(), 2u);
}

TEST_F(CompileCacheTest, AnUnwritableDirectoryOnlyCostsTheCache) {
  std::string file = cacheIn("file");
  {
    std::error_code ec;
    llvm::raw_fd_ostream os(file, ec);
    ASSERT_FALSE(ec);
  }
  ProgramOptions options;
  options.cacheDirectory = file + "/cache";
  bool cached = true;
  EXPECT_EQ(runMultiply(kChain, options, cached), halfKx);
  EXPECT_FALSE(cached);
  EXPECT_EQ(runMultiply(kChain, options, cached), halfKx);
  EXPECT_FALSE(cached);
}

/// Sets environment variable `name` for its lifetime.
class ScopedEnvironment {
public:
  ScopedEnvironment(const char *name, const char *value) : name(name) {
    if (const char *old = std::getenv(name))
      saved = old;
    if (value)
      setenv(name, value, /*overwrite=*/1);
    else
      unsetenv(name);
  }
  ~ScopedEnvironment() {
    if (saved)
      setenv(name, saved->c_str(), 1);
    else
      unsetenv(name);
  }

private:
  const char *name;
  std::optional<std::string> saved;
};

TEST(CompileCacheDirectoryTest, XdgCacheHomeElseHomeDotCache) {
  {
    ScopedEnvironment xdg("XDG_CACHE_HOME", "/x/cache");
    ScopedEnvironment home("HOME", "/h");
    EXPECT_EQ(defaultCompileCacheDirectory(), "/x/cache/simit");
  }
  {
    ScopedEnvironment xdg("XDG_CACHE_HOME", nullptr);
    ScopedEnvironment home("HOME", "/h");
    EXPECT_EQ(defaultCompileCacheDirectory(), "/h/.cache/simit");
  }
  {
    ScopedEnvironment xdg("XDG_CACHE_HOME", "");
    ScopedEnvironment home("HOME", nullptr);
    EXPECT_EQ(defaultCompileCacheDirectory(), "");
  }
}
