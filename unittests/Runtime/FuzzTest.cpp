//===--- FuzzTest.cpp - Mutation fuzzing of the runtime's input readers ---===//
//
// Mutates scene files, scene expressions and meshes of each format
// (FuzzSupport.h) for a bounded time each (SIMIT_FUZZ_SECONDS, default 3)
// and reads every mutant. A crash fails the test with the mutant; so does
// an error that does not start by naming its place (the file, or the
// column of an expression), the readers' contract.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/Mesh.h"
#include "simit/Runtime/Scene.h"
#include "simit/Runtime/SceneExpression.h"

#include "../FuzzSupport.h"
#include "TestFiles.h"

#include "llvm/Support/MemoryBuffer.h"

#include "gtest/gtest.h"

using namespace simit;
using namespace simit::test;

namespace {

constexpr double kSeconds = 3.0;

/// Fails the test (once per fuzzer, with the input) when a reader's error
/// does not start with `place`.
class LocatedErrors {
public:
  explicit LocatedErrors(std::string place) : place(std::move(place)) {}
  void check(llvm::Error err, const std::string &input) {
    if (!err)
      return;
    std::string message = llvm::toString(std::move(err));
    if (message.rfind(place, 0) == 0 || reported)
      return;
    reported = true;
    ADD_FAILURE() << "error without its place: " << message
                  << "\ninput:\n-----\n" << input << "\n-----";
  }

private:
  std::string place;
  bool reported = false;
};

std::vector<std::string> filesUnder(llvm::ArrayRef<std::string> directories,
                                    llvm::StringRef extension) {
  std::vector<std::string> texts;
  for (const std::string &directory : directories) {
    std::error_code ec;
    for (llvm::sys::fs::directory_iterator it(directory, ec), end;
         it != end && !ec; it.increment(ec)) {
      if (!llvm::StringRef(it->path()).ends_with(extension))
        continue;
      if (auto buffer = llvm::MemoryBuffer::getFile(it->path()))
        texts.push_back((*buffer)->getBuffer().str());
    }
  }
  return texts;
}

//===--- Scenes and expressions -------------------------------------------===//

const char *const kJsonFragments[] = {
    "{", "}", "[", "]", ",", ":", "\"", "null", "true", "1e999", "-1e999",
    "3e9", "2147483648", "-2147483649", "1e-400", "0.5", "[[[[[[[[",
    "\"type\": \"int32\", ", "\"type\": \"float32\", ", "\"shape\": [3], ",
    "\"expr\": \"x +\", ", "\"refine\": 11, ", "\"last\": true, ",
    "\"path\": \"a.csv\", ", "{frame}", "\"size\": 2000000000, ",
};

TEST(RuntimeFuzz, SceneFiles) {
  std::vector<std::string> seeds = filesUnder(
      {SIMIT_SOURCE_DIR "/examples/springs", SIMIT_SOURCE_DIR "/examples/fem",
       SIMIT_SOURCE_DIR "/test/Run/Inputs",
       SIMIT_SOURCE_DIR "/test/Programs/System/Inputs"},
      ".json");
  ASSERT_GT(seeds.size(), 10u);
  LocatedErrors errors("mutant.json");
  unsigned runs = fuzz::fuzz(
      "scene files", seeds, kJsonFragments, kSeconds, 1,
      [&](const std::string &text) {
        auto scene = parseScene(text, "mutant.json", "/nonexistent");
        errors.check(scene.takeError(), text);
      });
  EXPECT_GT(runs, 0u);
}

const char *const kExpressionFragments[] = {
    "(", ")", "-", "not ", " and ", " or ", " if ", " else ", "+", "*", "/",
    "<", "<=", "==", "!=", "x", "min_y", "max_z", "true", "1e999", "1e-999",
    "0.5", ".", "e", "((((((((((", "----------",
};

TEST(RuntimeFuzz, SceneExpressions) {
  std::vector<std::string> seeds = {
      "y < min_y + 0.05 * (max_y - min_y)",
      "z < 0.1",
      "0.1 if y > 1e-4 else 0",
      "not (x < 0.5 or y >= 2) and z != 1",
      "-x * (y - 3) / 2 + 1.5e-3",
      "(x < 0 if y > 0 else x > 0) or false",
      "((x + y) * (z - 1)) / (max_x - min_x)",
  };
  CoordinateFrame frame;
  frame.position = {0.25, 0.5, 0.75};
  frame.max = {1, 1, 1};
  LocatedErrors errors("column ");
  unsigned runs = fuzz::fuzz(
      "scene expressions", seeds, kExpressionFragments, kSeconds, 2,
      [&](const std::string &text) {
        auto expression = SceneExpression::parse(text);
        if (expression)
          (void)expression->evaluate(frame);
        errors.check(expression.takeError(), text);
      });
  EXPECT_GT(runs, 0u);
}

//===--- Meshes -----------------------------------------------------------===//

/// Fuzzes a mesh format: each mutant is written to a file in `dir` named
/// `name` and read with `load`. Errors name a file m.* of `dir`.
unsigned fuzzMesh(const char *fuzzer, const TempDir &dir, llvm::StringRef name,
                  const std::vector<std::string> &seeds,
                  llvm::ArrayRef<const char *> fragments, uint32_t rngSeed,
                  llvm::function_ref<llvm::Expected<Mesh>()> load) {
  LocatedErrors errors(dir.path("m"));
  return fuzz::fuzz(fuzzer, seeds, fragments, kSeconds, rngSeed,
                    [&](const std::string &text) {
                      dir.write(name, text);
                      errors.check(load().takeError(), text);
                    });
}

const char *const kTetGenFragments[] = {
    " ", "\n", "#", "0", "1", "-1", "2", "3", "4", "10", "nan", "inf",
    "1e999", "2000000000", "4294967296", "0.5", "1e-300",
};

TEST(RuntimeFuzz, TetGenNodeAndElementFiles) {
  TempDir dir;
  std::string node = "5 3 0 1\n0 0 0 0 1\n1 1 0 0 0\n2 0 1 0 0\n"
                     "3 0 0 1 1\n4 1 1 2 0\n";
  std::string ele = "2 4 1\n0 0 1 2 3 7\n1 1 2 3 4 7\n";
  // Seeds of the .node file read with the .ele above, and the reverse.
  dir.write("m.ele", ele);
  unsigned runs = fuzzMesh(
      "tetgen .node", dir, "m.node",
      {node, "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n",
       "4 3 2 0\n1 0 0 0 5 6\n2 1 0 0 5 6\n3 0 1 0 5 6\n4 0 0 1 5 6\n"},
      kTetGenFragments, 3, [&] { return loadTetGen(dir.path("m")); });
  dir.write("m.node", node);
  runs += fuzzMesh("tetgen .ele", dir, "m.ele",
                   {ele, "1 10 0\n0 0 1 2 3 0 0 0 0 0 0\n"}, kTetGenFragments,
                   4, [&] { return loadTetGen(dir.path("m")); });
  EXPECT_GT(runs, 0u);
}

const char *const kGmshFragments[] = {
    " ", "\n", "$Nodes", "$EndNodes", "$Elements", "$EndElements",
    "$MeshFormat", "0", "1", "2", "4", "-1", "nan", "1e999", "2000000000",
    "4.1", "2.2", "\"",
};

TEST(RuntimeFuzz, GmshFiles) {
  TempDir dir;
  std::string v2 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n5\n"
                   "10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n50 1 1 1\n"
                   "$EndNodes\n$Elements\n4\n1 15 2 0 10 10\n"
                   "2 1 2 0 1 10 20\n3 2 2 0 1 20 30 40\n"
                   "4 4 2 1 1 10 20 30 40\n$EndElements\n";
  std::string v41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n"
                    "1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n"
                    "0 0 1\n$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n"
                    "1 1 2 3 4\n$EndElements\n";
  std::string v40 = "$MeshFormat\n4 0 8\n$EndMeshFormat\n$Nodes\n"
                    "1 4\n1 3 0 4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
                    "$EndNodes\n$Elements\n1 1\n1 3 4 1\n1 1 2 3 4\n"
                    "$EndElements\n";
  unsigned runs = fuzzMesh("gmsh 2", dir, "m.msh", {v2}, kGmshFragments, 5,
                           [&] { return loadGmsh(dir.path("m.msh")); });
  runs += fuzzMesh("gmsh 4", dir, "m.msh", {v41, v40}, kGmshFragments, 6,
                   [&] { return loadGmsh(dir.path("m.msh")); });
  EXPECT_GT(runs, 0u);
}

const char *const kObjFragments[] = {
    " ", "\n", "v ", "f ", "vt ", "/", "//", "-1", "0", "1", "nan", "inf",
    "1e999", "2147483648", "#",
};

TEST(RuntimeFuzz, ObjFiles) {
  TempDir dir;
  unsigned runs = fuzzMesh(
      "obj", dir, "m.obj",
      {"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf -1 -2 -3\n",
       "# textured\nv 0 0 0 1\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
       "f 1/1/1 2/1/1 3//1\n"},
      kObjFragments, 7, [&] { return loadObj(dir.path("m.obj")); });
  EXPECT_GT(runs, 0u);
}

} // namespace
