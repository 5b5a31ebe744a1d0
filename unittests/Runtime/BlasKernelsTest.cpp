//===- BlasKernelsTest.cpp - The kernels OpenBLAS runs on -----------------===//

#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/StringRef.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace {

TEST(BlasKernelsTest, NotTheGenericKernelsOnAVX2) {
  // Where OpenBLAS falls back to Prescott (an unknown CPU model) the runtime
  // chooses the kernels by the CPU's features; on a CPU it knows, OpenBLAS's
  // own choice is not Prescott either.
  std::string kernels = simit::selectBlasKernels();
  ASSERT_FALSE(kernels.empty());
  if (std::getenv("OPENBLAS_CORETYPE") ||
      llvm::StringRef(std::getenv("SIMIT_BLAS_CORETYPE")) == "keep")
    GTEST_SKIP() << "the environment chooses OpenBLAS's kernels";
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
    GTEST_SKIP() << "no AVX2 and FMA: the generic kernels are right here";
  EXPECT_FALSE(llvm::StringRef(kernels).equals_insensitive("prescott"));
  // The configuration the solvers report names the same kernels.
  EXPECT_NE(simit::sparseDirectBLAS().find(kernels), std::string::npos)
      << simit::sparseDirectBLAS();
}

} // namespace
