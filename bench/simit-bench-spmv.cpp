//===--- simit-bench-spmv.cpp - Simit's compiled SpMV, bandwidth ----------===//
//
// Times the sparse matrix-vector product that Simit compiles for `K * x`
// (a BCSR matrix of 3x3 blocks over a tet mesh's vertex pairs) and reports
// the memory bandwidth it reaches: bench/spmv/spmv.sim assembles K once per
// frame and multiplies by it 2 * `pairs` times in a while loop, which the
// phase timer (ProgramOptions::timePhases) times as the frame's solve part;
// the time per product is the median of frames 2..N of that, divided by the
// number of products. The traffic counted is the least any BCSR SpMV moves:
// every block (72 bytes) and its column index once, the row pointers, x read
// once and y written once. The result is checked against a product of this
// file's own, so a fast wrong answer is an error, not a figure.
//
//===----------------------------------------------------------------------===//

#include "simit/Engine/Program.h"
#include "simit/Engine/SceneRun.h"
#include "simit/Engine/ThreadsOption.h"
#include "simit/Runtime/Scene.h"
#include "simit/Runtime/Set.h"
#include "simit/Runtime/SparsityPattern.h"

#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FormatVariadic.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/TargetSelect.h"
#include "llvm/Support/raw_ostream.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

using namespace simit;
namespace cl = llvm::cl;

namespace {

cl::OptionCategory spmvCategory("simit-bench-spmv options");

cl::opt<std::string>
    scenePath("scene", cl::init(SIMIT_BENCH_SPMV_SCENE), cl::cat(spmvCategory),
              cl::desc("A scene running bench/spmv/spmv.sim (default: "
                       "bench/spmv/dragon-refined.json, fem-dragon's mesh "
                       "refined once)"));
cl::opt<int> frames("frames", cl::init(0), cl::cat(spmvCategory),
                    cl::desc("Frames (default: the scene's); the figure is "
                             "the median of frames 2..N"));
cl::opt<Target> target(
    "target", cl::cat(spmvCategory),
    cl::desc("Where the set loops run (default: cpu)"),
    cl::values(clEnumValN(Target::CPU, "cpu", "the host CPU"),
               clEnumValN(Target::GPU, "gpu",
                          "CUDA kernels on the first NVIDIA GPU")),
    cl::init(Target::CPU));

llvm::Error failure(const llvm::Twine &message) {
  return llvm::createStringError(message);
}

/// spmv.sim's matrix, K(i, j) = (tets holding i and j) / (4 n_i) I, as
/// scalar weights per block of `pattern`, from the tets' endpoints alone.
llvm::Expected<std::vector<double>>
averagingWeights(const Set &tets, const SparsityPattern &pattern) {
  std::vector<double> around(pattern.numRows(), 0.0);
  for (int e = 0; e < tets.size(); ++e)
    for (int32_t v : tets.endpointsOf(e))
      around[v] += 1;
  std::vector<double> weights(pattern.numBlocks(), 0.0);
  for (int e = 0; e < tets.size(); ++e)
    for (int32_t row : tets.endpointsOf(e))
      for (int32_t col : tets.endpointsOf(e)) {
        int k = pattern.findBlock(row, col);
        if (k < 0)
          return failure(llvm::formatv("the pattern lacks block ({0}, {1}) "
                                       "of tet {2}",
                                       row, col, e)
                             .str());
        weights[k] += 0.25 / around[row];
      }
  return weights;
}

/// max |got - K^products x| / max |K^products x|, K from averagingWeights.
double relativeError(const SparsityPattern &pattern,
                     const std::vector<double> &weights,
                     std::vector<double> x, const double *got, int products) {
  llvm::ArrayRef<int32_t> rowPtr = pattern.rowPointers();
  llvm::ArrayRef<int32_t> colIdx = pattern.columnIndices();
  std::vector<double> y(x.size());
  for (int p = 0; p < products; ++p) {
    for (int r = 0; r < pattern.numRows(); ++r)
      for (int c = 0; c < 3; ++c) {
        double sum = 0;
        for (int32_t k = rowPtr[r]; k < rowPtr[r + 1]; ++k)
          sum += weights[k] * x[3 * colIdx[k] + c];
        y[3 * r + c] = sum;
      }
    std::swap(x, y);
  }
  double error = 0, scale = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    error = std::max(error, std::fabs(got[i] - x[i]));
    scale = std::max(scale, std::fabs(x[i]));
  }
  return scale > 0 ? error / scale : error;
}

llvm::Error measure(int threads) {
  llvm::Expected<int> threadCount = resolveThreadCount(threads);
  if (!threadCount)
    return failure("--threads: " + llvm::toString(threadCount.takeError()));
  auto scene = loadScene(scenePath);
  if (!scene)
    return scene.takeError();
  SceneRunOptions options;
  options.timePhases = true;
  options.checkFrames = false;
  options.threads = *threadCount;
  options.target = target;
  if (frames.getNumOccurrences())
    options.frames = frames;
  auto runner = SceneRunner::create(std::move(*scene), options);
  if (!runner)
    return runner.takeError();
  SetRegistry &sets = (*runner)->sets();
  Set *verts = sets.find("verts"), *tets = sets.find("tets");
  ExternTensor *pairs = sets.findExtern("pairs");
  if (!verts || !tets || !pairs || pairs->values.size() != 1)
    return failure(scenePath + ": expected the sets verts and tets and the "
                               "extern pairs of bench/spmv/spmv.sim");
  if ((*runner)->frames() < 2)
    return failure("at least 2 frames are needed (frame 1 is the warm-up)");
  const double *x = static_cast<const double *>(verts->fieldData("x"));
  std::vector<double> x0(x, x + 3 * static_cast<size_t>(verts->size()));
  if (llvm::Error err = (*runner)->run())
    return err;

  auto pattern = SparsityPattern::get(*tets, *verts, *verts);
  if (!pattern)
    return pattern.takeError();
  int products = 2 * static_cast<int>(pairs->values[0]);
  if (products <= 0)
    return failure(scenePath + ": externs.pairs must be positive");
  auto weights = averagingWeights(*tets, **pattern);
  if (!weights)
    return weights.takeError();
  double error = relativeError(
      **pattern, *weights, x0,
      static_cast<const double *>(verts->fieldData("y")), products);
  if (!(error <= 1e-12))
    return failure(llvm::formatv("K^{0} x differs from the reference by {1:e} "
                                 "(relative, largest component)",
                                 products, error)
                       .str());

  SceneTimeSummary times = (*runner)->times().summarize();
  double msPerProduct = times.solveMs / products;
  int64_t rows = (*pattern)->numRows(), blocks = (*pattern)->numBlocks();
  int64_t matrixBytes = blocks * (9 * 8 + 4) + (rows + 1) * 4;
  int64_t bytes = matrixBytes + 2 * rows * 3 * 8;
  double gbs = bytes / (msPerProduct * 1e-3) / 1e9;
  llvm::outs() << llvm::formatv(
      "matrix   {0} x {0} blocks of 3x3, {1} blocks ({2:F1} MiB with indices)\n"
      "product  {3:F3} ms (median of frames 2..{4} of {5} products each), "
      "{6} bytes: {7:F2} GB/s on {8} thread(s), {9}\n"
      "check    relative error {10:e} against the reference product\n",
      rows, blocks, matrixBytes / 1048576.0, msPerProduct, times.frames,
      products, bytes, gbs, *threadCount, targetName(target), error);
  llvm::outs() << llvm::formatv(
      "RESULT spmv target={0} threads={1} rows={2} blocks={3} "
      "matrix_bytes={4} bytes={5} products={6} frames={7} "
      "ms_per_product={8:F5} gbs={9:F4} error={10:e}\n",
      targetName(target), *threadCount, rows, blocks, matrixBytes, bytes,
      products, times.frames, msPerProduct, gbs, error);
  return llvm::Error::success();
}

} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM init(argc, argv);
  llvm::InitializeNativeTarget();
  llvm::InitializeNativeTargetAsmPrinter();
  cl::opt<int> &threads = threadsOption(
      spmvCategory, "Threads of the set loops (default: $SIMIT_NUM_THREADS, "
                    "else every core)");
  cl::HideUnrelatedOptions(spmvCategory);
  cl::ParseCommandLineOptions(
      argc, argv,
      "Simit's compiled SpMV (K * x, 3x3 BCSR) on a tet mesh: time per "
      "product and bandwidth\n");
  if (llvm::Error err = measure(threads)) {
    llvm::errs() << "simit-bench-spmv: " << llvm::toString(std::move(err))
                 << "\n";
    return 1;
  }
  return 0;
}
