//===--- RuntimeFunctionNames.h - Names of runtime functions -*- C++ -*-===//
//
// Lowered code calls the runtime (simit/ABI/RuntimeFunctions.h)
// by name: the lowering declares `func.func private @simit_rt_...` and the
// engine binds each name to the runtime's function in every JIT. The one
// list below serves both sides, so a rename cannot split them: the engine
// takes the address of the C function the list names, which must exist.
// This header depends on nothing but the C++ standard library.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ABI_RUNTIMEFUNCTIONNAMES_H
#define SIMIT_ABI_RUNTIMEFUNCTIONNAMES_H

#include <optional>
#include <string_view>

/// X(Id, symbol, Interface) for every function of the runtime that lowered
/// CPU code calls. Interface is CInterface when the declaration carries
/// `llvm.emit_c_interface` (memref arguments; the JIT binds
/// `_mlir_ciface_<symbol>`), else Plain.
#define SIMIT_RUNTIME_FUNCTIONS(X)                                             \
  X(Fail, simit_rt_fail, Plain)                                                \
  X(RaiseParallelFailure, simit_rt_raise_parallel_failure, Plain)              \
  X(SolveBCSR, simit_rt_solve_bcsr, CInterface)                                \
  X(SolveBCSRF32, simit_rt_solve_bcsr_f32, CInterface)                         \
  X(ShermanMorrisonBCSR, simit_rt_sherman_morrison_bcsr, CInterface)           \
  X(ShermanMorrisonBCSRF32, simit_rt_sherman_morrison_bcsr_f32, CInterface)    \
  X(Woodbury2BCSR, simit_rt_woodbury2_bcsr, CInterface)                        \
  X(Woodbury3BCSR, simit_rt_woodbury3_bcsr, CInterface)                        \
  X(Woodbury4BCSR, simit_rt_woodbury4_bcsr, CInterface)                        \
  X(Woodbury2BCSRF32, simit_rt_woodbury2_bcsr_f32, CInterface)                 \
  X(Woodbury3BCSRF32, simit_rt_woodbury3_bcsr_f32, CInterface)                 \
  X(Woodbury4BCSRF32, simit_rt_woodbury4_bcsr_f32, CInterface)                 \
  X(MatmulBCSR, simit_rt_matmul_bcsr, CInterface)                              \
  X(MatmulBCSRF32, simit_rt_matmul_bcsr_f32, CInterface)                       \
  X(MatmulBCSRI32, simit_rt_matmul_bcsr_i32, CInterface)                       \
  X(TriangularSolveBCSR, simit_rt_triangular_solve_bcsr, CInterface)           \
  X(TriangularSolveBCSRF32, simit_rt_triangular_solve_bcsr_f32, CInterface)    \
  X(SolveDiag, simit_rt_solve_diag, CInterface)                                \
  X(SolveDiagF32, simit_rt_solve_diag_f32, CInterface)                         \
  X(HostMatrixBlocks, simit_rt_host_matrix_blocks, Plain)                      \
  X(HostMatrixAdopt, simit_rt_host_matrix_adopt, Plain)                        \
  X(ProductPattern, simit_rt_product_pattern, CInterface)                      \
  X(UnionPattern, simit_rt_union_pattern, CInterface)                          \
  X(TransposePattern, simit_rt_transpose_pattern, CInterface)                  \
  X(PatternBlocks, simit_rt_pattern_blocks, Plain)                             \
  X(PatternTake, simit_rt_pattern_take, CInterface)                            \
  X(PrintF64, simit_rt_print_f64, Plain)                                       \
  X(PrintI64, simit_rt_print_i64, Plain)                                       \
  X(PrintStr, simit_rt_print_str, Plain)                                       \
  X(StringConcat, simit_rt_string_concat, Plain)                               \
  X(StringCompare, simit_rt_string_compare, Plain)                             \
  X(Clock, simit_rt_clock, Plain)                                              \
  X(StoreTime, simit_rt_storeTime, Plain)                                      \
  X(MemRefAlloc, _mlir_memref_to_llvm_alloc, Plain)                            \
  X(MemRefFree, _mlir_memref_to_llvm_free, Plain)                              \
  X(PhaseBegin, simit_rt_phase_begin, Plain)                                   \
  X(PhaseEnd, simit_rt_phase_end, Plain)                                       \
  X(CheckNumericsF64, simit_rt_check_numerics_f64, CInterface)                 \
  X(CheckNumericsF32, simit_rt_check_numerics_f32, CInterface)                 \
  X(LU, simit_rt_lu, CInterface)                                               \
  X(Chol, simit_rt_chol, CInterface)                                           \
  X(LUSolve, simit_rt_lusolve, CInterface)                                     \
  X(LLTSolve, simit_rt_lltsolve, CInterface)                                   \
  X(LUMatSolve, simit_rt_lumatsolve, CInterface)                               \
  X(LLTMatSolve, simit_rt_lltmatsolve, CInterface)                             \
  X(LUBCSR, simit_rt_lu_bcsr, CInterface)                                      \
  X(CholBCSR, simit_rt_chol_bcsr, CInterface)                                  \
  X(LUSolveBCSR, simit_rt_lusolve_bcsr, CInterface)                            \
  X(LLTSolveBCSR, simit_rt_lltsolve_bcsr, CInterface)                          \
  X(LUFree, simit_rt_lufree, Plain)                                            \
  X(CholFree, simit_rt_cholfree, Plain)                                        \
  X(TriangularSolve, simit_rt_triangularSolve, CInterface)

/// X(Id, symbol) for the functions the host code of simit-gpu-pipeline
/// calls: the statement marker of the engine's GPU lowering and the mgpu*
/// functions MLIR's gpu-to-llvm lowering emits (all Plain).
#define SIMIT_GPU_RUNTIME_FUNCTIONS(X)                                         \
  X(GPUStatement, simit_rt_gpu_statement)                                      \
  X(GPUModuleLoadJIT, mgpuModuleLoadJIT)                                       \
  X(GPUModuleUnload, mgpuModuleUnload)                                         \
  X(GPUModuleGetFunction, mgpuModuleGetFunction)                               \
  X(GPULaunchKernel, mgpuLaunchKernel)                                         \
  X(GPUStreamCreate, mgpuStreamCreate)                                         \
  X(GPUStreamDestroy, mgpuStreamDestroy)                                       \
  X(GPUStreamSynchronize, mgpuStreamSynchronize)                               \
  X(GPUMemAlloc, mgpuMemAlloc)                                                 \
  X(GPUMemFree, mgpuMemFree)                                                   \
  X(GPUMemcpy, mgpuMemcpy)

namespace simit {
namespace abi {

/// A function of the runtime that lowered code calls.
enum class RuntimeFunction {
#define SIMIT_RUNTIME_FUNCTION_ID(Id, symbol, ...) Id,
  SIMIT_RUNTIME_FUNCTIONS(SIMIT_RUNTIME_FUNCTION_ID)
      SIMIT_GPU_RUNTIME_FUNCTIONS(SIMIT_RUNTIME_FUNCTION_ID)
#undef SIMIT_RUNTIME_FUNCTION_ID
};

/// The name lowered code declares and calls `function` by.
constexpr std::string_view runtimeFunctionName(RuntimeFunction function) {
  switch (function) {
#define SIMIT_RUNTIME_FUNCTION_NAME(Id, symbol, ...)                           \
  case RuntimeFunction::Id:                                                    \
    return #symbol;
    SIMIT_RUNTIME_FUNCTIONS(SIMIT_RUNTIME_FUNCTION_NAME)
    SIMIT_GPU_RUNTIME_FUNCTIONS(SIMIT_RUNTIME_FUNCTION_NAME)
#undef SIMIT_RUNTIME_FUNCTION_NAME
  }
  return {};
}

/// The function lowered code calls by `name`, if it is the runtime's.
constexpr std::optional<RuntimeFunction>
parseRuntimeFunction(std::string_view name) {
#define SIMIT_RUNTIME_FUNCTION_PARSE(Id, symbol, ...)                          \
  if (name == #symbol)                                                         \
    return RuntimeFunction::Id;
  SIMIT_RUNTIME_FUNCTIONS(SIMIT_RUNTIME_FUNCTION_PARSE)
  SIMIT_GPU_RUNTIME_FUNCTIONS(SIMIT_RUNTIME_FUNCTION_PARSE)
#undef SIMIT_RUNTIME_FUNCTION_PARSE
  return std::nullopt;
}

/// The solve of a square system matrix by `x = A \ b` and its rewrites:
/// `method` with `rank` outer products for Woodbury (1: Sherman-Morrison),
/// on f32 or f64 components.
enum class SystemSolve { Solve, Diagonal, LowRank, Triangular };
constexpr std::optional<RuntimeFunction>
systemSolveFunction(SystemSolve method, bool f32, unsigned rank = 0) {
  using F = RuntimeFunction;
  switch (method) {
  case SystemSolve::Solve:
    return f32 ? F::SolveBCSRF32 : F::SolveBCSR;
  case SystemSolve::Diagonal:
    return f32 ? F::SolveDiagF32 : F::SolveDiag;
  case SystemSolve::Triangular:
    return f32 ? F::TriangularSolveBCSRF32 : F::TriangularSolveBCSR;
  case SystemSolve::LowRank:
    switch (rank) {
    case 1:
      return f32 ? F::ShermanMorrisonBCSRF32 : F::ShermanMorrisonBCSR;
    case 2:
      return f32 ? F::Woodbury2BCSRF32 : F::Woodbury2BCSR;
    case 3:
      return f32 ? F::Woodbury3BCSRF32 : F::Woodbury3BCSR;
    case 4:
      return f32 ? F::Woodbury4BCSRF32 : F::Woodbury4BCSR;
    }
    return std::nullopt;
  }
  return std::nullopt;
}

} // namespace abi
} // namespace simit

#endif // SIMIT_ABI_RUNTIMEFUNCTIONNAMES_H
