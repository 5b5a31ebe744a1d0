//===--- BlasKernels.cpp - The BLAS the direct solvers run on -------------===//
//
// OpenBLAS built with DYNAMIC_ARCH (Debian 12's 0.3.21) chooses its kernels
// by the CPU's family and model when it is loaded, and falls back to its
// generic Prescott (SSE3) kernels on CPUs newer than it knows: a Sapphire
// Rapids VM that reports "Intel(R) Xeon(R) Processor", AMD Zen 5. CHOLMOD's
// supernodal factorisation then runs on kernels a quarter as wide as the
// CPU's (fem-dragon's Cholesky solve: 149 ms per frame, against 111 ms on
// the SkylakeX kernels). So before the first factorisation the runtime
// selects, by the CPU's features, the widest kernels OpenBLAS has for it;
// a core type the user chose (OPENBLAS_CORETYPE) is kept, and
// SIMIT_BLAS_CORETYPE=keep keeps OpenBLAS's own choice.
//
//===----------------------------------------------------------------------===//

#include "simit/Runtime/SolveSession.h"

#include "llvm/ADT/StringRef.h"

#include <cstdlib>
#include <mutex>

extern "C" {
// OpenBLAS's own entry points; the runtime links OpenBLAS directly, so
// CHOLMOD's and UMFPACK's BLAS calls go to it whatever libblas.so.3 is.
char *openblas_get_config(void);
char *openblas_get_corename(void);
// DYNAMIC_ARCH's kernel table: quit forgets it, init chooses it again
// (reading OPENBLAS_CORETYPE).
void gotoblas_dynamic_init(void);
void gotoblas_dynamic_quit(void);
}

namespace {
/// The OpenBLAS core type whose kernels the CPU's features allow, or null.
const char *coreTypeForThisCPU() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    return "Haswell";
  return nullptr;
}
} // namespace

std::string simit::selectBlasKernels() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (std::getenv("OPENBLAS_CORETYPE") ||
        llvm::StringRef(std::getenv("SIMIT_BLAS_CORETYPE")) == "keep")
      return;
    const char *current = openblas_get_corename();
    const char *wanted = coreTypeForThisCPU();
    if (!current || !wanted || !llvm::StringRef(current).equals_insensitive(
                                   "prescott"))
      return;
    // OpenBLAS reads the core type from the environment only.
    setenv("OPENBLAS_CORETYPE", wanted, /*overwrite=*/0);
    gotoblas_dynamic_quit();
    gotoblas_dynamic_init();
    unsetenv("OPENBLAS_CORETYPE");
  });
  const char *core = openblas_get_corename();
  return core ? core : "unknown";
}

std::string simit::sparseDirectBLAS() {
  // "OpenBLAS 0.3.21 DYNAMIC_ARCH NO_AFFINITY SkylakeX MAX_THREADS=64": the
  // core named is that of the kernels in use.
  selectBlasKernels();
  const char *config = openblas_get_config();
  return config ? config : "OpenBLAS";
}
