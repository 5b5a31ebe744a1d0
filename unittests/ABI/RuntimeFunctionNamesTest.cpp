//===--- RuntimeFunctionNamesTest.cpp - The list of runtime functions -----===//

#include "simit/ABI/RuntimeFunctionNames.h"

#include "gtest/gtest.h"

#include <set>
#include <string>

using simit::abi::parseRuntimeFunction;
using simit::abi::RuntimeFunction;
using simit::abi::runtimeFunctionName;
using simit::abi::SystemSolve;
using simit::abi::systemSolveFunction;

namespace {
constexpr RuntimeFunction kAll[] = {
#define SIMIT_LISTED(Id, ...) RuntimeFunction::Id,
    SIMIT_RUNTIME_FUNCTIONS(SIMIT_LISTED)
        SIMIT_GPU_RUNTIME_FUNCTIONS(SIMIT_LISTED)
#undef SIMIT_LISTED
};
} // namespace

// Every function has a name of its own, which names it back.
TEST(RuntimeFunctionNamesTest, NamesAreDistinctAndParseBack) {
  std::set<std::string> names;
  for (RuntimeFunction function : kAll) {
    std::string name(runtimeFunctionName(function));
    EXPECT_FALSE(name.empty());
    EXPECT_TRUE(names.insert(name).second) << name;
    EXPECT_EQ(parseRuntimeFunction(name), function) << name;
  }
  EXPECT_EQ(parseRuntimeFunction("simit_rt_lu_1"), std::nullopt);
  EXPECT_EQ(parseRuntimeFunction("simit_rt_"), std::nullopt);
}

// The solves of system matrices by method, precision and rank.
TEST(RuntimeFunctionNamesTest, SystemSolvesByMethod) {
  auto name = [](SystemSolve method, bool f32, unsigned rank = 0) {
    auto function = systemSolveFunction(method, f32, rank);
    return function ? std::string(runtimeFunctionName(*function))
                    : std::string("none");
  };
  EXPECT_EQ(name(SystemSolve::Solve, false), "simit_rt_solve_bcsr");
  EXPECT_EQ(name(SystemSolve::Diagonal, true), "simit_rt_solve_diag_f32");
  EXPECT_EQ(name(SystemSolve::Triangular, false),
            "simit_rt_triangular_solve_bcsr");
  EXPECT_EQ(name(SystemSolve::LowRank, false, 1),
            "simit_rt_sherman_morrison_bcsr");
  EXPECT_EQ(name(SystemSolve::LowRank, true, 3),
            "simit_rt_woodbury3_bcsr_f32");
  EXPECT_EQ(name(SystemSolve::LowRank, false, 5), "none");
}
