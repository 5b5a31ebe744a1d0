//===--- RuntimeFunctionsTest.cpp - Host functions of lowered code --------===//

#include "simit/ABI/RuntimeFunctions.h"
#include "simit/ffi.h"

#include <Eigen/Dense>

#include "gtest/gtest.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <type_traits>
#include <vector>

namespace {
using simit::abi::MemRefDescriptor;
using simit::abi::UnrankedMemRefDescriptor;

template <typename T, int N>
MemRefDescriptor<T, N> describe(T *data, std::array<int64_t, N> sizes) {
  MemRefDescriptor<T, N> m;
  m.allocated = m.data = data;
  m.offset = 0;
  int64_t stride = 1;
  for (int d = N - 1; d >= 0; --d) {
    m.sizes[d] = sizes[d];
    m.strides[d] = stride;
    stride *= sizes[d];
  }
  return m;
}

/// A dense matrix of rows x rows blocks of 3 x 3 as BCSR arrays in which
/// every block is present, with memref descriptors of them and of b and x.
struct DenseBCSR {
  static constexpr int rows = 4, b = 3, n = rows * b;
  std::vector<int32_t> rowptr, colidx;
  std::vector<double> values, rhs, x = std::vector<double>(n, 0.0);
  MemRefDescriptor<int32_t, 1> rp, ci;
  MemRefDescriptor<double, 3> vals;
  MemRefDescriptor<double, 2> bm, xm;

  DenseBCSR(const Eigen::MatrixXd &a, const Eigen::VectorXd &bv)
      : rhs(bv.data(), bv.data() + n) {
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
    rp = describe<int32_t, 1>(rowptr.data(), {rows + 1});
    ci = describe<int32_t, 1>(colidx.data(), {int64_t(colidx.size())});
    vals = describe<double, 3>(values.data(), {int64_t(colidx.size()), b, b});
    bm = describe<double, 2>(rhs.data(), {rows, b});
    xm = describe<double, 2>(x.data(), {rows, b});
  }
};

Eigen::MatrixXd randomMatrix(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  return Eigen::MatrixXd::NullaryExpr(DenseBCSR::n, DenseBCSR::n,
                                      [&] { return dist(rng); });
}

/// The packed entry point of a "program" that solves the system of args[0]
/// (a DenseBCSR), as lowered code calls the runtime.
void solveEntry(void **args) {
  auto *s = static_cast<DenseBCSR *>(args[0]);
  _mlir_ciface_simit_rt_solve_bcsr(&s->rp, &s->ci, &s->vals, &s->bm, &s->xm,
                                   "solve (program.sim:7:9)");
}

void expectSolvesLike(const Eigen::MatrixXd &a, unsigned seed) {
  Eigen::VectorXd rhs = randomMatrix(seed).col(0);
  DenseBCSR system(a, rhs);
  void *args[] = {&system};
  llvm::Error err = simit::runGuarded(solveEntry, args);
  ASSERT_FALSE(bool(err)) << llvm::toString(std::move(err));
  Eigen::VectorXd exact = a.fullPivLu().solve(rhs);
  for (int i = 0; i < DenseBCSR::n; ++i)
    EXPECT_NEAR(system.x[i], exact(i), 1e-9 * exact.norm()) << i;
}

} // namespace

// x = A \ b matches a dense solve for a symmetric positive definite A (the
// CG path), a non-symmetric A and a symmetric indefinite A (the LU paths).
TEST(RuntimeFunctionsTest, SolveMatchesADenseSolve) {
  Eigen::MatrixXd m = randomMatrix(7);
  int n = DenseBCSR::n;
  expectSolvesLike(m * m.transpose() + n * Eigen::MatrixXd::Identity(n, n), 1);
  expectSolvesLike(m + n * Eigen::MatrixXd::Identity(n, n), 2);
  Eigen::MatrixXd indefinite = m + m.transpose();
  expectSolvesLike(indefinite, 3);
}

// A singular system ends the run with the statement's position; the host
// goes on.
TEST(RuntimeFunctionsTest, SingularSolveEndsTheRunWithItsPosition) {
  Eigen::MatrixXd a = randomMatrix(9);
  a.row(4) = a.row(2); // rank deficient
  DenseBCSR system(a, randomMatrix(10).col(0));
  void *args[] = {&system};
  llvm::Error err = simit::runGuarded(solveEntry, args);
  ASSERT_TRUE(bool(err));
  std::string message = llvm::toString(std::move(err));
  EXPECT_NE(message.find("solve (program.sim:7:9): "), std::string::npos)
      << message;
  EXPECT_TRUE(message.find("singular") != std::string::npos) << message;
  // A later run on this thread is unaffected.
  DenseBCSR fine(Eigen::MatrixXd::Identity(DenseBCSR::n, DenseBCSR::n),
                 randomMatrix(11).col(0));
  void *fineArgs[] = {&fine};
  EXPECT_FALSE(bool(simit::runGuarded(solveEntry, fineArgs)));
  // To rounding: the solve warm-starts from this statement's previous
  // answer, which the tests before this one (in one process) left.
  for (size_t i = 0; i < fine.x.size(); ++i)
    EXPECT_NEAR(fine.x[i], fine.rhs[i], 1e-12) << i;
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

// [1 2; 0 1] as 1x1 blocks: CHOLMOD reads one triangle only, so chol must
// reject the non-symmetric matrix rather than factorise [1 0; 0 1] or
// [1 2; 2 1]. Outside a guarded run the failure is fatal, with `where`.
TEST(RuntimeFunctionsTest, SparseCholeskyRejectsANonSymmetricMatrix) {
  std::vector<int32_t> rowptr{0, 2, 3}, colidx{0, 1, 1};
  std::vector<double> values{1.0, 2.0, 1.0};
  auto rp = describe<int32_t, 1>(rowptr.data(), {3});
  auto ci = describe<int32_t, 1>(colidx.data(), {3});
  auto vals = describe<double, 3>(values.data(), {3, 1, 1});
  EXPECT_DEATH(_mlir_ciface_simit_rt_chol_bcsr(&rp, &ci, &vals, "chol"),
               "chol: the matrix is not symmetric");
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
  void *lu = _mlir_ciface_simit_rt_lu_bcsr(&rp, &ci, &vals, "lu");
  _mlir_ciface_simit_rt_lusolve_bcsr(lu, &bm, &xm, "lusolve");
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 1.0, 1e-12);
  EXPECT_DEATH(_mlir_ciface_simit_rt_lltsolve_bcsr(lu, &bm, &xm, "lltsolve"),
               "lltsolve: the handle is not a sparse Cholesky factorisation");
  simit_rt_lufree(lu, "lufree");
}

// Dense handles: chol of [1 2; 2 1] (not positive definite), a handle of
// the other kind, a right-hand side of another size and a second free
// each end the run naming the call.
TEST(RuntimeFunctionsTest, DenseFactorisationsAndHandlesAreChecked) {
  std::vector<double> a{1.0, 2.0, 2.0, 1.0}, b{3.0, 3.0}, b3{1.0, 1.0, 1.0},
      x{0.0, 0.0};
  auto am = describe<double, 1>(a.data(), {4});
  auto bm = describe<double, 1>(b.data(), {2});
  auto b3m = describe<double, 1>(b3.data(), {3});
  auto xm = describe<double, 1>(x.data(), {2});
  EXPECT_DEATH(_mlir_ciface_simit_rt_chol(&am, 2, "chol (f.sim:2:7)"),
               "chol \\(f.sim:2:7\\): the matrix is not positive definite");
  void *lu = _mlir_ciface_simit_rt_lu(&am, 2, "lu");
  _mlir_ciface_simit_rt_lusolve(lu, &bm, &xm, "lusolve");
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 1.0, 1e-12);
  EXPECT_DEATH(_mlir_ciface_simit_rt_lltsolve(lu, &bm, &xm, "lltsolve"),
               "lltsolve: the handle is not a dense Cholesky factorisation");
  EXPECT_DEATH(_mlir_ciface_simit_rt_lusolve(lu, &b3m, &xm, "lusolve"),
               "lusolve: operand size does not match its shape");
  simit_rt_lufree(lu, "lufree");
  EXPECT_DEATH(_mlir_ciface_simit_rt_lusolve(lu, &bm, &xm, "lusolve"),
               "lusolve: the factorisation was freed");
  EXPECT_DEATH(simit_rt_lufree(lu, "lufree (f.sim:9:3)"),
               "lufree \\(f.sim:9:3\\): the factorisation was freed");
}

namespace {
/// Hands `m` to the scan as the unranked memref lowered code passes.
template <typename T, int N>
void scan(
    MemRefDescriptor<T, N> &m, int32_t layout, int64_t perRow,
    MemRefDescriptor<int32_t, 1> &rowptr, MemRefDescriptor<int32_t, 1> &colidx,
    const char *result, const char *rowSet, const char *colSet,
    MemRefDescriptor<int32_t, 1> mapEndpoints = {nullptr, nullptr, 0, {0}, {1}},
    int64_t mapCardinality = 0) {
  UnrankedMemRefDescriptor<T> unranked{N, &m};
  if constexpr (std::is_same_v<T, double>)
    _mlir_ciface_simit_rt_check_numerics_f64(
        &unranked, layout, perRow, &rowptr, &colidx, "map f to e", result,
        rowSet, colSet, &mapEndpoints, mapCardinality, "e");
  else
    _mlir_ciface_simit_rt_check_numerics_f32(
        &unranked, layout, perRow, &rowptr, &colidx, "map f to e", result,
        rowSet, colSet, &mapEndpoints, mapCardinality, "e");
}
} // namespace

// The BCSR matrix [[A B 0]; [0 C D]; [0 0 E]] of 2x2 blocks: rowptr
// (0, 2, 4, 5), colidx (0, 1, 1, 2, 2). Block 3 is D = (1, 2) of the row
// blocks: row 1, column colidx[3] = 2. Its component (1, 0) (flat 2) is
// the first NaN; the -inf in block 4 comes later in the array.
TEST(RuntimeFunctionsTest, CheckNumericsNamesTheFirstBadBlock) {
  ASSERT_FALSE(simit::takeNumericsProblem());
  std::vector<int32_t> rowptr{0, 2, 4, 5}, colidx{0, 1, 1, 2, 2};
  std::vector<double> values(5 * 4, 1.0);
  values[3 * 4 + 2] = std::nan("");
  values[4 * 4 + 0] = -INFINITY;
  auto rp = describe<int32_t, 1>(rowptr.data(), {4});
  auto ci = describe<int32_t, 1>(colidx.data(), {5});
  auto vals = describe<double, 3>(values.data(), {5, 2, 2});
  scan(vals, SIMIT_NUMERICS_PATTERN, 0, rp, ci, "K", "p", "q");
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced nan: K block (p 1, q 2) component (1, 0)");
  // Taken: the slot is empty again.
  EXPECT_FALSE(simit::takeNumericsProblem());

  // Only the first problem of a run is kept.
  std::vector<double> vector{0.0, 1.0, INFINITY, 2.0};
  auto vm = describe<double, 2>(vector.data(), {2, 2});
  auto none = describe<int32_t, 1>(nullptr, {0});
  scan(vm, SIMIT_NUMERICS_VECTOR, 0, none, none, "f", "p", "");
  scan(vals, SIMIT_NUMERICS_PATTERN, 0, rp, ci, "K", "p", "q");
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced inf: f element (p 1) component 0");
}

// An assembly over an edge set e of triangles (0 1 2), (1 2 3), (2 3 4)
// names the elements that have the bad block's row (and column) among their
// endpoints: vertex 1 is in triangles 0 and 1, the block (3, 4) only in 2.
TEST(RuntimeFunctionsTest, CheckNumericsNamesTheAssemblingElements) {
  std::vector<int32_t> triangles{0, 1, 2, 1, 2, 3, 2, 3, 4};
  auto ends = describe<int32_t, 1>(triangles.data(), {9});
  auto none = describe<int32_t, 1>(nullptr, {0});
  std::vector<double> vector{0.0, NAN, 0.0, 0.0, 0.0};
  auto vm = describe<double, 1>(vector.data(), {5});
  scan(vm, SIMIT_NUMERICS_VECTOR, 0, none, none, "f", "p", "", ends, 3);
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced nan: f element (p 1), assembled from e 0, 1");

  // Row 3 holds the blocks (3, 2), (3, 4): the second is the first bad one.
  std::vector<int32_t> rowptr{0, 0, 0, 0, 2, 2}, colidx{2, 4};
  auto rp = describe<int32_t, 1>(rowptr.data(), {6});
  auto ci = describe<int32_t, 1>(colidx.data(), {2});
  std::vector<double> blocks{1.0, INFINITY};
  auto bm = describe<double, 1>(blocks.data(), {2});
  scan(bm, SIMIT_NUMERICS_PATTERN, 0, rp, ci, "K", "p", "p", ends, 3);
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced inf: K block (p 3, p 4), assembled from e 2");
}

// The other layouts place block k by their own rule; scalar blocks name no
// component. Incidence rows of 2 blocks: block 3 is row 1 at column
// colidx[3] = 7. A stencil of 2 offsets over 3 points: block 4 is point
// 4 % 3 = 1 at offset 4 / 3 = 1. Diagonal: block 2 is (2, 2).
TEST(RuntimeFunctionsTest, CheckNumericsPlacesBlocksByLayout) {
  std::vector<int32_t> endpoints{4, 5, 6, 7};
  auto ends = describe<int32_t, 1>(endpoints.data(), {4});
  auto none = describe<int32_t, 1>(nullptr, {0});
  std::vector<double> incidence{0, 0, 0, -INFINITY};
  auto im = describe<double, 1>(incidence.data(), {4});
  scan(im, SIMIT_NUMERICS_FIXED_ROWS, 2, none, ends, "B", "e", "p");
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced -inf: B block (e 1, p 7)");

  std::vector<float> stencil(6 * 3, 0.0f);
  stencil[4 * 3 + 2] = NAN;
  auto sm = describe<float, 2>(stencil.data(), {6, 3});
  scan(sm, SIMIT_NUMERICS_STENCIL, 2, none, none, "A", "p", "p");
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced nan: A block (p 1, stencil offset 1) "
            "component 2");

  std::vector<double> diagonal{1, 2, NAN};
  auto dm = describe<double, 1>(diagonal.data(), {3});
  scan(dm, SIMIT_NUMERICS_DIAGONAL, 0, none, none, "M", "p", "p");
  EXPECT_EQ(simit::takeNumericsProblem(),
            "map f to e produced nan: M block (p 2, p 2)");

  // A finite array records nothing.
  diagonal[2] = 3;
  scan(dm, SIMIT_NUMERICS_DIAGONAL, 0, none, none, "M", "p", "p");
  EXPECT_FALSE(simit::takeNumericsProblem());
}

namespace {
/// A malloc'd copy of `values`, as a host function returns its arrays.
template <typename T> T *mallocCopy(const std::vector<T> &values) {
  auto *copy = static_cast<T *>(std::malloc(values.size() * sizeof(T)));
  std::copy(values.begin(), values.end(), copy);
  return copy;
}

/// The entry point of a "program" that checks the host matrix args[0..2]
/// (malloc'd rowptr, colidx, blocks of 3 x 3 block rows and columns).
void checkHostMatrixEntry(void **args) {
  simit_rt_host_matrix_blocks(static_cast<int32_t *>(args[0]),
                              static_cast<int32_t *>(args[1]), args[2], 3, 3,
                              "extern func 'f' (program.sim:4:5)");
}
} // namespace

// A host function's matrix is copied with each row sorted by column (the
// blocks move with their columns), and a malformed one ends the run naming
// the call and the first bad block.
TEST(RuntimeFunctionsTest, HostMatricesAreCheckedAndSorted) {
  std::vector<int32_t> rowptr = {0, 2, 2, 3}, colidx = {2, 0, 1};
  std::vector<double> blocks = {20, 21, 0, 1, 11, 12};
  int32_t *hostRowptr = mallocCopy(rowptr), *hostColidx = mallocCopy(colidx);
  double *hostBlocks = mallocCopy(blocks);
  ASSERT_EQ(simit_rt_host_matrix_blocks(hostRowptr, hostColidx, hostBlocks, 3,
                                        3, "f"),
            3);
  std::vector<int32_t> rowptrOut(4), colidxOut(3);
  std::vector<double> blocksOut(6);
  EXPECT_EQ(simit_rt_host_matrix_adopt(hostRowptr, hostColidx, hostBlocks, 3,
                                       2 * sizeof(double), rowptrOut.data(),
                                       colidxOut.data(), blocksOut.data()),
            0);
  EXPECT_EQ(rowptrOut, rowptr);
  EXPECT_EQ(colidxOut, (std::vector<int32_t>{0, 2, 1}));
  EXPECT_EQ(blocksOut, (std::vector<double>{0, 1, 20, 21, 11, 12}));

  auto expectRejected = [](std::vector<int32_t> rowptr,
                           std::vector<int32_t> colidx,
                           llvm::StringRef problem) {
    void *args[] = {mallocCopy(rowptr), mallocCopy(colidx),
                    mallocCopy(std::vector<double>(colidx.size(), 1.0))};
    llvm::Error err = simit::runGuarded(checkHostMatrixEntry, args);
    ASSERT_TRUE(bool(err));
    std::string message = llvm::toString(std::move(err));
    EXPECT_NE(
        message.find("extern func 'f' (program.sim:4:5): " + problem.str()),
        std::string::npos)
        << message;
  };
  expectRejected({1, 1, 1, 1}, {0},
                 "returned a matrix whose row pointers start at 1, not 0");
  expectRejected({0, 2, 1, 2}, {0, 1},
                 "returned a matrix whose row pointers decrease at block row "
                 "1 (2 then 1)");
  expectRejected({0, 1, 1, 1}, {3},
                 "returned a matrix with a block at (block row 0, block "
                 "column 3) outside its 3 block columns");
  expectRejected({0, 0, 2, 2}, {1, 1},
                 "returned a matrix with two blocks at (block row 1, block "
                 "column 1)");
}

// Patterns of products, sums and transposes of a host function's matrix,
// against the blocks worked out by hand.
TEST(RuntimeFunctionsTest, RuntimeProductAndUnionPatterns) {
  // A = [x x .; . x .; . . x], B = [. x .; . . x; x . .] over 3 x 3 blocks.
  std::vector<int32_t> rpA = {0, 2, 3, 4}, ciA = {0, 1, 1, 2};
  std::vector<int32_t> rpB = {0, 1, 2, 3}, ciB = {1, 2, 0};
  auto rA = describe<int32_t, 1>(rpA.data(), {4});
  auto cA = describe<int32_t, 1>(ciA.data(), {4});
  auto rB = describe<int32_t, 1>(rpB.data(), {4});
  auto cB = describe<int32_t, 1>(ciB.data(), {3});
  auto take = [](void *handle) {
    int64_t blocks = simit_rt_pattern_blocks(handle);
    std::vector<int32_t> rowptr(4), colidx(blocks);
    auto r = describe<int32_t, 1>(rowptr.data(), {4});
    auto c = describe<int32_t, 1>(colidx.data(), {blocks});
    _mlir_ciface_simit_rt_pattern_take(handle, &r, &c);
    return std::make_pair(rowptr, colidx);
  };
  // A B = [x x .; . . x; x . .].
  auto product =
      take(_mlir_ciface_simit_rt_product_pattern(&rA, &cA, &rB, &cB, 3));
  EXPECT_EQ(product.first, (std::vector<int32_t>{0, 2, 3, 4}));
  EXPECT_EQ(product.second, (std::vector<int32_t>{1, 2, 2, 0}));
  // A + B = [x x .; . x x; x . x]; B + I, the diagonal as its BCSR
  // pattern.
  auto sum = take(_mlir_ciface_simit_rt_union_pattern(&rA, &cA, &rB, &cB, 3));
  EXPECT_EQ(sum.first, (std::vector<int32_t>{0, 2, 4, 6}));
  EXPECT_EQ(sum.second, (std::vector<int32_t>{0, 1, 1, 2, 0, 2}));
  std::vector<int32_t> rpI = {0, 1, 2, 3}, ciI = {0, 1, 2};
  auto rI = describe<int32_t, 1>(rpI.data(), {4});
  auto cI = describe<int32_t, 1>(ciI.data(), {3});
  auto withDiagonal =
      take(_mlir_ciface_simit_rt_union_pattern(&rI, &cI, &rB, &cB, 3));
  EXPECT_EQ(withDiagonal.first, (std::vector<int32_t>{0, 2, 4, 6}));
  EXPECT_EQ(withDiagonal.second, (std::vector<int32_t>{0, 1, 1, 2, 0, 2}));
  // A' = [x . .; x x .; . . x].
  auto transposed = take(_mlir_ciface_simit_rt_transpose_pattern(&rA, &cA, 3));
  EXPECT_EQ(transposed.first, (std::vector<int32_t>{0, 1, 3, 4}));
  EXPECT_EQ(transposed.second, (std::vector<int32_t>{0, 0, 1, 2}));
}

// The ffi header's convertToCSR expands 2 x 2 blocks: [1 2 | 0 0; 3 4 | 0 0;
// 0 0 | 5 6; 7 8 | 9 10] from block rows {(0, 0)} and {(1, 0), (1, 1)}.
TEST(RuntimeFunctionsTest, ConvertToCSRExpandsBlocks) {
  std::vector<int> rowptr = {0, 1, 3}, colidx = {0, 0, 1};
  std::vector<double> blocks = {1, 2, 3, 4, 0, 0, 7, 8, 5, 6, 9, 10};
  int *csrRowptr = nullptr, *csrColidx = nullptr;
  double *csrValues = nullptr;
  simit::ffi::convertToCSR(blocks.data(), rowptr.data(), colidx.data(), 4, 4, 2,
                           2, &csrRowptr, &csrColidx, &csrValues);
  EXPECT_EQ(std::vector<int>(csrRowptr, csrRowptr + 5),
            (std::vector<int>{0, 2, 4, 8, 12}));
  EXPECT_EQ(std::vector<int>(csrColidx, csrColidx + 12),
            (std::vector<int>{0, 1, 0, 1, 0, 1, 2, 3, 0, 1, 2, 3}));
  EXPECT_EQ(std::vector<double>(csrValues, csrValues + 12),
            (std::vector<double>{1, 2, 3, 4, 0, 0, 5, 6, 7, 8, 9, 10}));
  std::free(csrRowptr);
  std::free(csrColidx);
  std::free(csrValues);
}
