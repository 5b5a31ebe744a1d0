//===- BlasKernelsTest.cpp - The kernels OpenBLAS runs on -----------------===//

#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/StringRef.h"

#include <gtest/gtest.h>

#include <cstdlib>

extern "C" char *openblas_get_corename(void);

namespace {

TEST(BlasKernelsTest, WidestKernelsUnlessChosenOrUnavailable) {
  // OpenBLAS's own choice, made when it was loaded (nothing has run yet:
  // CTest runs each test in a process of its own).
  std::string own = openblas_get_corename();
  std::string kernels = simit::selectBlasKernels();
  ASSERT_FALSE(kernels.empty());
  // The configuration the solvers report names the kernels in use.
  EXPECT_NE(simit::sparseDirectBLAS().find(kernels), std::string::npos)
      << simit::sparseDirectBLAS();
  __builtin_cpu_init();
  bool chosen = std::getenv("OPENBLAS_CORETYPE") ||
                llvm::StringRef(std::getenv("SIMIT_BLAS_CORETYPE")) == "keep";
  bool wide =
      __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (chosen || !wide) {
    // A choice of the environment, or a CPU without AVX2 and FMA (whose
    // generic kernels are right): left as it is.
    EXPECT_EQ(kernels, own);
    return;
  }
  // Where OpenBLAS fell back to Prescott (an unknown CPU model) the runtime
  // chose by the CPU's features; on a CPU it knows, its own choice is not
  // Prescott either.
  EXPECT_FALSE(llvm::StringRef(kernels).equals_insensitive("prescott"))
      << "OpenBLAS chose " << own;
}

} // namespace
