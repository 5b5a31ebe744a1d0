//===--- RuntimeFunctionsTest.cpp - Host functions of lowered code --------===//

#include "simit/Engine/RuntimeFunctions.h"

#include <Eigen/Dense>

#include "gtest/gtest.h"

#include <random>
#include <vector>

namespace {
template <typename T, int N>
StridedMemRefType<T, N> describe(T *data, std::array<int64_t, N> sizes) {
  StridedMemRefType<T, N> m;
  m.basePtr = m.data = data;
  m.offset = 0;
  int64_t stride = 1;
  for (int d = N - 1; d >= 0; --d) {
    m.sizes[d] = sizes[d];
    m.strides[d] = stride;
    stride *= sizes[d];
  }
  return m;
}
} // namespace

// A random SPD matrix of 4 x 4 blocks of 3 x 3, stored densely in BCSR
// (every block present), solved to convergence and compared with Eigen.
TEST(RuntimeFunctionsTest, CGSolveMatchesADenseSolve) {
  const int rows = 4, b = 3, n = rows * b;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Eigen::MatrixXd m(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      m(i, j) = dist(rng);
  Eigen::MatrixXd a = m * m.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  Eigen::VectorXd rhs(n);
  for (int i = 0; i < n; ++i)
    rhs(i) = dist(rng);

  std::vector<int32_t> rowptr, colidx;
  std::vector<double> values;
  for (int r = 0; r < rows; ++r) {
    rowptr.push_back(static_cast<int32_t>(colidx.size()));
    for (int c = 0; c < rows; ++c) {
      colidx.push_back(c);
      for (int i = 0; i < b; ++i)
        for (int j = 0; j < b; ++j)
          values.push_back(a(r * b + i, c * b + j));
    }
  }
  rowptr.push_back(static_cast<int32_t>(colidx.size()));
  std::vector<double> bv(rhs.data(), rhs.data() + n), x(n, 0.0);

  auto rp = describe<int32_t, 1>(rowptr.data(), {rows + 1});
  auto ci = describe<int32_t, 1>(colidx.data(), {int64_t(colidx.size())});
  auto vals = describe<double, 3>(values.data(), {int64_t(colidx.size()), b, b});
  auto bm = describe<double, 2>(bv.data(), {rows, b});
  auto xm = describe<double, 2>(x.data(), {rows, b});
  int32_t iterations = _mlir_ciface_simit_rt_cg_solve_bcsr(
      &rp, &ci, &vals, &bm, &xm, 1e-24, 100);
  EXPECT_GT(iterations, 0);
  EXPECT_LE(iterations, 100);

  Eigen::VectorXd exact = a.ldlt().solve(rhs);
  for (int i = 0; i < n; ++i)
    EXPECT_NEAR(x[i], exact(i), 1e-9) << "component " << i;
}

TEST(RuntimeFunctionsTest, CGStopsAtTheIterationCap) {
  // diag(1, 2): from x = 0, one CG step cannot reach the solution.
  std::vector<int32_t> rowptr{0, 1, 2}, colidx{0, 1};
  std::vector<double> values{1.0, 2.0}, bv{1.0, 1.0}, x{0.0, 0.0};
  auto rp = describe<int32_t, 1>(rowptr.data(), {3});
  auto ci = describe<int32_t, 1>(colidx.data(), {2});
  auto vals = describe<double, 3>(values.data(), {2, 1, 1});
  auto bm = describe<double, 2>(bv.data(), {2, 1});
  auto xm = describe<double, 2>(x.data(), {2, 1});
  EXPECT_EQ(_mlir_ciface_simit_rt_cg_solve_bcsr(&rp, &ci, &vals, &bm, &xm,
                                                1e-30, 1),
            1);
  // The first step is x = alpha r with r = b, alpha = (r.r) / (r.Ar) = 2/3.
  EXPECT_NEAR(x[0], 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(x[1], 2.0 / 3.0, 1e-15);
  // Restarted from there, the residual (1/3, -1/3) spans both eigenvectors:
  // two more steps reach the solution and r.r falls below the tolerance.
  EXPECT_EQ(_mlir_ciface_simit_rt_cg_solve_bcsr(&rp, &ci, &vals, &bm, &xm,
                                                1e-20, 5),
            2);
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 0.5, 1e-12);
}

TEST(RuntimeFunctionsTest, LargeFreedBlocksAreReusedBySize) {
  constexpr size_t kLarge = 1 << 20;
  auto *first = static_cast<char *>(_mlir_memref_to_llvm_alloc(kLarge));
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(first) % 16, 0u);
  first[0] = 1;
  first[kLarge - 1] = 2; // the whole payload is usable
  _mlir_memref_to_llvm_free(first);
  // The same size gets the kept block back; another size does not.
  void *again = _mlir_memref_to_llvm_alloc(kLarge);
  EXPECT_EQ(again, first);
  void *other = _mlir_memref_to_llvm_alloc(kLarge + 16);
  EXPECT_NE(other, first);
  // Two live blocks of one size are distinct.
  void *second = _mlir_memref_to_llvm_alloc(kLarge);
  EXPECT_NE(second, again);
  for (void *block : {again, other, second})
    _mlir_memref_to_llvm_free(block);
  // Small blocks go straight to malloc and free.
  void *small = _mlir_memref_to_llvm_alloc(24);
  ASSERT_NE(small, nullptr);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(small) % 16, 0u);
  _mlir_memref_to_llvm_free(small);
  _mlir_memref_to_llvm_free(nullptr);
}

// [1 2; 0 1] as 1x1 blocks: SimplicialLLT would read one triangle only, so
// chol must reject the non-symmetric matrix rather than factorise [1 0; 0 1]
// or [1 2; 2 1].
TEST(RuntimeFunctionsTest, SparseCholeskyRejectsANonSymmetricMatrix) {
  std::vector<int32_t> rowptr{0, 2, 3}, colidx{0, 1, 1};
  std::vector<double> values{1.0, 2.0, 1.0};
  auto rp = describe<int32_t, 1>(rowptr.data(), {3});
  auto ci = describe<int32_t, 1>(colidx.data(), {3});
  auto vals = describe<double, 3>(values.data(), {3, 1, 1});
  EXPECT_DEATH(_mlir_ciface_simit_rt_chol_bcsr(&rp, &ci, &vals),
               "chol: the system matrix is not symmetric");
}

// The LU handle of [4 1; 3 2] (blocks 1x1) solves b = (5, 5) to x = (1, 1)
// (det 5, x = (2*5 - 1*5, 4*5 - 3*5) / 5); a Cholesky solve refuses it.
TEST(RuntimeFunctionsTest, SparseLUSolvesAndHandlesAreChecked) {
  std::vector<int32_t> rowptr{0, 2, 4}, colidx{0, 1, 0, 1};
  std::vector<double> values{4.0, 1.0, 3.0, 2.0}, bv{5.0, 5.0}, x{0.0, 0.0};
  auto rp = describe<int32_t, 1>(rowptr.data(), {3});
  auto ci = describe<int32_t, 1>(colidx.data(), {4});
  auto vals = describe<double, 3>(values.data(), {4, 1, 1});
  auto bm = describe<double, 2>(bv.data(), {2, 1});
  auto xm = describe<double, 2>(x.data(), {2, 1});
  void *lu = _mlir_ciface_simit_rt_lu_bcsr(&rp, &ci, &vals);
  _mlir_ciface_simit_rt_lusolve_bcsr(lu, &bm, &xm);
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 1.0, 1e-12);
  EXPECT_DEATH(_mlir_ciface_simit_rt_lltsolve_bcsr(lu, &bm, &xm),
               "lltsolve: the handle is not a sparse Cholesky factorisation");
  simit_rt_lufree(lu);
}
