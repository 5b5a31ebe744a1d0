//===--- ProgramTest.cpp - Loading, emitting and compiling programs -------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include "llvm/Support/FileSystem.h"
#include "llvm/Support/raw_ostream.h"

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {
constexpr const char *kTwoFunctions = R"mlir(
func.func @first(%n: index) attributes {simit.bindings = [
    {kind = "set_size", set = "a"}]} {
  return
}
func.func @second(%n: index) attributes {simit.bindings = [
    {kind = "set_size", set = "b"}]} {
  return
}
func.func private @helper() {
  return
}
)mlir";

} // namespace

TEST(ProgramTest, ExportsTheFunctionsWithBindings) {
  Program program;
  ASSERT_EQ(message(program.loadMLIR(kTwoFunctions)), "success");
  auto names = program.exportedFunctions();
  ASSERT_TRUE(!!names) << llvm::toString(names.takeError());
  EXPECT_EQ(*names, (std::vector<std::string>{"first", "second"}));
}

TEST(ProgramTest, AnUnknownFunctionListsTheExportedOnes) {
  Program program;
  ASSERT_EQ(message(program.loadMLIR(kTwoFunctions)), "success");
  auto function = program.compile("helper");
  ASSERT_FALSE(!!function);
  EXPECT_EQ(llvm::toString(function.takeError()),
            "unknown function 'helper' (exported functions: first, second)");
}

TEST(ProgramTest, FunctionsShareOneCompiledModule) {
  Program program;
  ASSERT_EQ(message(program.loadMLIR(kTwoFunctions)), "success");
  auto first = program.compile("first");
  auto second = program.compile("second");
  ASSERT_TRUE(!!first && !!second);
  EXPECT_EQ(first->name(), "first");
  EXPECT_EQ(second->name(), "second");
  EXPECT_EQ(second->requiredSets(), (std::vector<std::string>{"b"}));
}

TEST(ProgramTest, MalformedMLIRNamesTheLine) {
  Program program;
  std::string error =
      message(program.loadMLIR("func.func @f() {\n  return %x\n}\n", "bad.mlir"));
  EXPECT_THAT(error, HasSubstr("bad.mlir:2:"));
}

TEST(ProgramTest, NothingLoaded) {
  Program program;
  auto text = program.emit(Stage::Simit);
  ASSERT_FALSE(!!text);
  EXPECT_EQ(llvm::toString(text.takeError()), "no program is loaded");
}

TEST(ProgramTest, EmitsEachStage) {
  Program program;
  ASSERT_EQ(message(program.loadMLIR(kTwoFunctions)), "success");
  auto simit = program.emit(Stage::Simit);
  ASSERT_TRUE(!!simit);
  EXPECT_THAT(*simit, HasSubstr("func.func @first"));
  auto llvmText = program.emit(Stage::LLVM);
  ASSERT_TRUE(!!llvmText);
  EXPECT_THAT(*llvmText, HasSubstr("llvm.func @first"));
  // Input that is already loops passes convert-simit-to-loops unchanged.
  auto loops = program.emit(Stage::Loops);
  ASSERT_TRUE(!!loops);
  EXPECT_THAT(*loops, HasSubstr("func.func @first"));
}

TEST(ProgramTest, AMissingFileIsNamed) {
  Program program;
  EXPECT_THAT(message(program.loadFile("/nonexistent/dir/p.sim")),
              HasSubstr("/nonexistent/dir/p.sim: cannot read the file"));
}

TEST(ProgramTest, IllegalSimitReportsTheFrontendDiagnostic) {
  Program program;
  std::string error = message(program.loadString(
      "func f() -> (r : float)\n  r = 1.0 * 2;\nend\n", "bad.sim"));
  EXPECT_THAT(error, HasSubstr("bad.sim:2:"));
  EXPECT_THAT(error, HasSubstr("error:"));
}

TEST(ProgramTest, LoadFileDispatchesOnTheExtension) {
  llvm::SmallString<128> path;
  ASSERT_FALSE(llvm::sys::fs::createTemporaryFile("program", "mlir", path));
  {
    std::error_code ec;
    llvm::raw_fd_ostream os(path, ec);
    ASSERT_FALSE(ec);
    os << kTwoFunctions;
  }
  Program program;
  EXPECT_EQ(message(program.loadFile(path)), "success");
  llvm::sys::fs::remove(path);
  auto names = program.exportedFunctions();
  ASSERT_TRUE(!!names);
  EXPECT_EQ(names->size(), 2u);
}
