//===--- ObjectCodegenTest.cpp - LLVM IR to objects, on several cores -----===//

#include "ObjectCodegen.h"
#include "ObjectCode.h"

#include "llvm/AsmParser/Parser.h"
#include "llvm/ExecutionEngine/Orc/LLJIT.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"

#include "gtest/gtest.h"

using namespace simit;

namespace {
// An entry point calling local functions that share a local constant table
// and a local mutable counter: cut apart, each partition must reach the
// others' functions and the one counter.
constexpr const char *kModule = R"ir(
@table = private unnamed_addr constant [4 x i64] [i64 1, i64 10, i64 100, i64 1000]
@calls = internal global i64 0

define internal i64 @weigh(i64 %i) {
  %slot = getelementptr [4 x i64], ptr @table, i64 0, i64 %i
  %w = load i64, ptr %slot
  %n = load i64, ptr @calls
  %n1 = add i64 %n, 1
  store i64 %n1, ptr @calls
  ret i64 %w
}

define internal i64 @sum(i64 %a, i64 %b) {
  %wa = call i64 @weigh(i64 %a)
  %wb = call i64 @weigh(i64 %b)
  %s = add i64 %wa, %wb
  ret i64 %s
}

define i64 @entry(i64 %a, i64 %b) {
  %s = call i64 @sum(i64 %a, i64 %b)
  %n = load i64, ptr @calls
  %r = mul i64 %s, %n
  ret i64 %r
}
)ir";

/// The objects `partitions` partitions of kModule compile to, and
/// entry(1, 3) through them linked in a JIT.
struct Linked {
  std::vector<std::string> objects;
  int64_t result = 0;
};

Linked compileAndRun(unsigned partitions) {
  Linked linked;
  auto target = hostTarget();
  EXPECT_TRUE(bool(target));
  if (!target)
    return linked;
  llvm::LLVMContext context;
  llvm::SMDiagnostic diagnostic;
  std::unique_ptr<llvm::Module> module =
      llvm::parseAssemblyString(kModule, diagnostic, context);
  EXPECT_TRUE(module) << diagnostic.getMessage().str();
  if (!module)
    return linked;
  auto machine = target->createTargetMachine();
  EXPECT_TRUE(bool(machine));
  if (!machine)
    return linked;
  module->setDataLayout((*machine)->createDataLayout());
  module->setTargetTriple((*machine)->getTargetTriple());
  CompileTimes times;
  auto objects = compileToObjects(*module, *target, partitions, times);
  EXPECT_TRUE(bool(objects)) << toString(objects.takeError());
  if (!objects)
    return linked;
  linked.objects = *objects;
  auto jit = llvm::orc::LLJITBuilder()
                 .setJITTargetMachineBuilder(*target)
                 .setPlatformSetUp(llvm::orc::setUpInactivePlatform)
                 .create();
  EXPECT_TRUE(bool(jit));
  if (!jit)
    return linked;
  for (const std::string &object : linked.objects)
    EXPECT_FALSE(bool((*jit)->addObjectFile(
        llvm::MemoryBuffer::getMemBufferCopy(object, "part.o"))));
  auto entry = (*jit)->lookup("entry");
  EXPECT_TRUE(bool(entry)) << toString(entry.takeError());
  if (entry)
    linked.result = entry->toPtr<int64_t (*)(int64_t, int64_t)>()(1, 3);
  return linked;
}

/// How many function definitions `object` holds.
size_t definedFunctions(const std::string &object) {
  auto file = llvm::object::ObjectFile::createObjectFile(
      llvm::MemoryBufferRef(object, "part.o"));
  EXPECT_TRUE(bool(file));
  if (!file)
    return 0;
  size_t count = 0;
  for (const llvm::object::SymbolRef &symbol : (*file)->symbols()) {
    auto type = symbol.getType();
    auto flags = symbol.getFlags();
    if (type && *type == llvm::object::SymbolRef::ST_Function && flags &&
        !(*flags & llvm::object::SymbolRef::SF_Undefined))
      ++count;
  }
  return count;
}
} // namespace

TEST(ObjectCodegen, OnePartitionIsTheWholeModule) {
  Linked whole = compileAndRun(1);
  ASSERT_EQ(whole.objects.size(), 1u);
  // (10 + 1000) weights, times the two calls of weigh.
  EXPECT_EQ(whole.result, 2020);
}

TEST(ObjectCodegen, PartitionsReachEachOthersFunctionsAndGlobals) {
  Linked parts = compileAndRun(3);
  ASSERT_EQ(parts.objects.size(), 3u);
  for (const std::string &object : parts.objects)
    EXPECT_GE(definedFunctions(object), 1u);
  EXPECT_EQ(parts.result, 2020);
}

TEST(ObjectCodegen, NoMorePartitionsThanFunctions) {
  EXPECT_EQ(compileAndRun(8).objects.size(), 3u);
}
