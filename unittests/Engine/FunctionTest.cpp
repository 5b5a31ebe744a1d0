//===--- FunctionTest.cpp - Binding sets and running compiled code --------===//
//
// The kernels below are written at the loops level with the host ABI of
// docs/lowering.md (simit.bindings), as convert-simit-to-loops emits them,
// so these tests exercise the engine alone: JIT compilation, binding checks,
// in-place descriptors, patterns, results and re-initialisation. Expected
// numbers are computed by hand.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <cmath>
#include <limits>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {

/// x(p) = h * x(p) for every point.
constexpr const char *kScale = R"mlir(
func.func @scale(%n: index, %x: memref<?x3xf64>, %h: memref<f64>)
    attributes {llvm.emit_c_interface, simit.bindings = [
      {kind = "set_size", set = "points"},
      {kind = "field", set = "points", field = "x"},
      {kind = "extern", name = "h"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %hv = memref.load %h[] : memref<f64>
  scf.for %i = %c0 to %n step %c1 {
    scf.for %j = %c0 to %c3 step %c1 {
      %v = memref.load %x[%i, %j] : memref<?x3xf64>
      %w = arith.mulf %v, %hv : f64
      memref.store %w, %x[%i, %j] : memref<?x3xf64>
    }
  }
  return
}
)mlir";

/// Assembles the scalar spring stiffness K (K(a,a) += k, K(a,b) -= k) into
/// the BCSR pattern of (springs; points, points) through the location
/// table, then writes f = K u.
constexpr const char *kStiffness = R"mlir(
func.func @stiffness(%np: index, %ne: index, %k: memref<?xf64>,
    %rowptr: memref<?xi32>, %colidx: memref<?xi32>, %loc: memref<?x4xi32>,
    %u: memref<?xf64>, %f: memref<?xf64>)
    attributes {simit.bindings = [
      {kind = "set_size", set = "points"},
      {kind = "set_size", set = "springs"},
      {kind = "field", set = "springs", field = "k"},
      {kind = "pattern_rowptr", set = "springs", rows = "points", cols = "points"},
      {kind = "pattern_colidx", set = "springs", rows = "points", cols = "points"},
      {kind = "pattern_locations", set = "springs", rows = "points", cols = "points"},
      {kind = "field", set = "points", field = "u"},
      {kind = "field", set = "points", field = "f"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c2 = arith.constant 2 : index
  %zero = arith.constant 0.0 : f64
  %nb = memref.dim %colidx, %c0 : memref<?xi32>
  %vals = memref.alloc(%nb) : memref<?xf64>
  scf.for %b = %c0 to %nb step %c1 {
    memref.store %zero, %vals[%b] : memref<?xf64>
  }
  scf.for %e = %c0 to %ne step %c1 {
    %ke = memref.load %k[%e] : memref<?xf64>
    %nk = arith.negf %ke : f64
    scf.for %i = %c0 to %c2 step %c1 {
      scf.for %j = %c0 to %c2 step %c1 {
        %i2 = arith.muli %i, %c2 : index
        %ij = arith.addi %i2, %j : index
        %l32 = memref.load %loc[%e, %ij] : memref<?x4xi32>
        %l = arith.index_cast %l32 : i32 to index
        %same = arith.cmpi eq, %i, %j : index
        %v = arith.select %same, %ke, %nk : f64
        %old = memref.load %vals[%l] : memref<?xf64>
        %new = arith.addf %old, %v : f64
        memref.store %new, %vals[%l] : memref<?xf64>
      }
    }
  }
  scf.for %r = %c0 to %np step %c1 {
    %r1 = arith.addi %r, %c1 : index
    %s32 = memref.load %rowptr[%r] : memref<?xi32>
    %e32 = memref.load %rowptr[%r1] : memref<?xi32>
    %s = arith.index_cast %s32 : i32 to index
    %t = arith.index_cast %e32 : i32 to index
    %sum = scf.for %b = %s to %t step %c1 iter_args(%acc = %zero) -> (f64) {
      %c32 = memref.load %colidx[%b] : memref<?xi32>
      %c = arith.index_cast %c32 : i32 to index
      %a = memref.load %vals[%b] : memref<?xf64>
      %x = memref.load %u[%c] : memref<?xf64>
      %p = arith.mulf %a, %x : f64
      %acc1 = arith.addf %acc, %p : f64
      scf.yield %acc1 : f64
    }
    memref.store %sum, %f[%r] : memref<?xf64>
  }
  return
}
)mlir";

/// Parameters in, mixed results out: (a * x + y, a + x0, n + 1).
constexpr const char *kAxpy = R"mlir(
func.func @axpy(%a: f64, %x: memref<3xf64>, %y: memref<3xf64>, %n: i32)
    -> (memref<3xf64>, f64, i32)
    attributes {simit.bindings = [
      {kind = "param", index = 0}, {kind = "param", index = 1},
      {kind = "param", index = 2}, {kind = "param", index = 3}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  %c3 = arith.constant 3 : index
  %one = arith.constant 1 : i32
  %r = memref.alloc() : memref<3xf64>
  scf.for %i = %c0 to %c3 step %c1 {
    %xi = memref.load %x[%i] : memref<3xf64>
    %yi = memref.load %y[%i] : memref<3xf64>
    %p = arith.mulf %a, %xi : f64
    %s = arith.addf %p, %yi : f64
    memref.store %s, %r[%i] : memref<3xf64>
  }
  %x0 = memref.load %x[%c0] : memref<3xf64>
  %ax = arith.addf %a, %x0 : f64
  %n1 = arith.addi %n, %one : i32
  return %r, %ax, %n1 : memref<3xf64>, f64, i32
}
)mlir";

/// Local tensors cross by value as vectors: (s v, sum of v) for a 2 x 2
/// matrix flattened row-major, as the lowering passes it.
constexpr const char *kVectors = R"mlir(
func.func @vscale(%v: vector<4xf64>, %s: f64) -> (vector<4xf64>, f64)
    attributes {simit.bindings = [
      {kind = "param", index = 0}, {kind = "param", index = 1}]} {
  %b = vector.broadcast %s : f64 to vector<4xf64>
  %r = arith.mulf %v, %b : vector<4xf64>
  %sum = vector.reduction <add>, %v : vector<4xf64> into f64
  return %r, %sum : vector<4xf64>, f64
}
)mlir";

/// z * v for a complex z and a vector of two complex numbers (the lowering's
/// vector<N x 2 x T> at the host boundary), and the conjugate of z.
constexpr const char *kComplex = R"mlir(
func.func @cscale(%z: complex<f64>, %v: vector<2x2xf64>)
    -> (vector<2x2xf64>, complex<f64>)
    attributes {simit.bindings = [
      {kind = "param", index = 0}, {kind = "param", index = 1}]} {
  %r0 = vector.extract %v[0, 0] : f64 from vector<2x2xf64>
  %i0 = vector.extract %v[0, 1] : f64 from vector<2x2xf64>
  %r1 = vector.extract %v[1, 0] : f64 from vector<2x2xf64>
  %i1 = vector.extract %v[1, 1] : f64 from vector<2x2xf64>
  %c0 = complex.create %r0, %i0 : complex<f64>
  %c1 = complex.create %r1, %i1 : complex<f64>
  %p0 = complex.mul %z, %c0 : complex<f64>
  %p1 = complex.mul %z, %c1 : complex<f64>
  %x0 = complex.re %p0 : complex<f64>
  %y0 = complex.im %p0 : complex<f64>
  %x1 = complex.re %p1 : complex<f64>
  %y1 = complex.im %p1 : complex<f64>
  %out = vector.from_elements %x0, %y0, %x1, %y1 : vector<2x2xf64>
  %zc = complex.conj %z : complex<f64>
  return %out, %zc : vector<2x2xf64>, complex<f64>
}
)mlir";

/// Reads the endpoints: d(s) = e(s, 1) - e(s, 0) as a float.
constexpr const char *kEndpoints = R"mlir(
func.func @spans(%ne: index, %ends: memref<?x2xi32>, %d: memref<?xf64>)
    attributes {simit.bindings = [
      {kind = "set_size", set = "springs"},
      {kind = "endpoints", set = "springs"},
      {kind = "field", set = "springs", field = "d"}]} {
  %c0 = arith.constant 0 : index
  %c1 = arith.constant 1 : index
  scf.for %e = %c0 to %ne step %c1 {
    %a = memref.load %ends[%e, %c0] : memref<?x2xi32>
    %b = memref.load %ends[%e, %c1] : memref<?x2xi32>
    %diff = arith.subi %b, %a : i32
    %fd = arith.sitofp %diff : i32 to f64
    memref.store %fd, %d[%e] : memref<?xf64>
  }
  return
}
)mlir";

/// Compiles `name` from the MLIR text, failing the test on an error.
Function compile(Program &program, llvm::StringRef text, llvm::StringRef name) {
  if (llvm::Error err = program.loadMLIR(text)) {
    ADD_FAILURE() << llvm::toString(std::move(err));
    return Function();
  }
  llvm::Expected<Function> function = program.compile(name);
  if (!function) {
    ADD_FAILURE() << llvm::toString(function.takeError());
    return Function();
  }
  return std::move(*function);
}

/// A chain of points 0 - 1 - 2 joined by two springs.
struct Chain {
  Set points{"points"};
  Set springs{"springs", {&points, &points}};
  Chain() {
    for (int i = 0; i < 3; ++i)
      points.add();
    springs.add(0, 1);
    springs.add(1, 2);
  }
};

} // namespace

TEST(FunctionTest, ScalesAFieldInPlace) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  Set points("points");
  auto x = points.addField<double, 3>("x");
  for (int i = 0; i < 2; ++i)
    x.set(points.add(), {1.0 + i, -2.0, 0.5});
  double h = 2.0;
  ASSERT_EQ(message(scale.bind("points", points)), "success");
  ASSERT_EQ(message(scale.bind("h", &h)), "success");
  ASSERT_EQ(message(scale.init()), "success");
  ASSERT_EQ(message(scale.run()), "success");
  EXPECT_EQ(x.get(0), (std::array<double, 3>{2.0, -4.0, 1.0}));
  EXPECT_EQ(x.get(1), (std::array<double, 3>{4.0, -4.0, 1.0}));

  // The compiled code works on the set's arrays and the bound scalar
  // themselves: host writes between runs are seen without binding again.
  x.set(1, {1.0, 1.0, 1.0});
  h = 0.5;
  ASSERT_EQ(message(scale.run()), "success");
  EXPECT_EQ(x.get(0), (std::array<double, 3>{1.0, -2.0, 0.5}));
  EXPECT_EQ(x.get(1), (std::array<double, 3>{0.5, 0.5, 0.5}));
}

TEST(FunctionTest, RunPreparesAgainAfterTheSetGrows) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  Set points("points");
  auto x = points.addField<double, 3>("x");
  x.set(points.add(), {1.0, 1.0, 1.0});
  double h = 3.0;
  ASSERT_EQ(message(scale.bind("points", points)), "success");
  ASSERT_EQ(message(scale.bind("h", &h)), "success");
  ASSERT_EQ(message(scale.run()), "success");
  // Growing past the capacity moves the arrays; run() must see the new
  // size and pointers.
  points.reserve(64);
  for (int i = 0; i < 40; ++i)
    x.set(points.add(), {1.0, 2.0, 3.0});
  ASSERT_EQ(message(scale.run()), "success");
  EXPECT_EQ(x.get(0), (std::array<double, 3>{9.0, 9.0, 9.0}));
  EXPECT_EQ(x.get(40), (std::array<double, 3>{3.0, 6.0, 9.0}));
}

TEST(FunctionTest, AssemblesThroughTheLocationTable) {
  Program program;
  Function stiffness = compile(program, kStiffness, "stiffness");
  Chain chain;
  auto k = chain.springs.addField<double>("k");
  k.set(0, 2.0);
  k.set(1, 3.0);
  auto u = chain.points.addField<double>("u");
  auto f = chain.points.addField<double>("f");
  u.set(0, 1.0);
  u.set(1, 4.0);
  u.set(2, 9.0);
  ASSERT_EQ(message(stiffness.bind("points", chain.points)), "success");
  ASSERT_EQ(message(stiffness.bind("springs", chain.springs)), "success");
  ASSERT_EQ(message(stiffness.run()), "success");
  // f0 = 2 (1 - 4), f1 = 2 (4 - 1) + 3 (4 - 9), f2 = 3 (9 - 4).
  EXPECT_DOUBLE_EQ(f.get(0), -6.0);
  EXPECT_DOUBLE_EQ(f.get(1), -9.0);
  EXPECT_DOUBLE_EQ(f.get(2), 15.0);

  // A new spring changes the pattern; the next run rebuilds it.
  chain.springs.add(0, 2);
  k.set(2, 1.0);
  ASSERT_EQ(message(stiffness.run()), "success");
  EXPECT_DOUBLE_EQ(f.get(0), -6.0 + (1.0 - 9.0));
  EXPECT_DOUBLE_EQ(f.get(2), 15.0 + (9.0 - 1.0));
}

TEST(FunctionTest, ReadsEndpoints) {
  Program program;
  Function spans = compile(program, kEndpoints, "spans");
  Chain chain;
  chain.springs.add(2, 0);
  auto d = chain.springs.addField<double>("d");
  ASSERT_EQ(message(spans.bind("springs", chain.springs)), "success");
  ASSERT_EQ(message(spans.run()), "success");
  EXPECT_EQ(d.get(0), 1.0);
  EXPECT_EQ(d.get(1), 1.0);
  EXPECT_EQ(d.get(2), -2.0);
}

TEST(FunctionTest, PassesParametersAndReturnsResults) {
  Program program;
  Function axpy = compile(program, kAxpy, "axpy");
  double a = 2.0;
  double x[3] = {1.0, 2.0, 3.0};
  double y[3] = {10.0, 20.0, 30.0};
  int32_t n = 41;
  ASSERT_EQ(axpy.numParameters(), 4u);
  ASSERT_EQ(message(axpy.bindParameter(0, &a, ComponentType::Float64, {})),
            "success");
  ASSERT_EQ(message(axpy.bindParameter(1, x, ComponentType::Float64, {3})),
            "success");
  ASSERT_EQ(message(axpy.bindParameter(2, y, ComponentType::Float64, {3})),
            "success");
  EXPECT_EQ(message(axpy.run()), "function 'axpy': parameter 3 is not bound");
  ASSERT_EQ(message(axpy.bindParameter(3, &n, ComponentType::Int32, {})),
            "success");
  EXPECT_EQ(message(axpy.bindParameter(4, &n, ComponentType::Int32, {})),
            "function 'axpy': has 4 parameters, not 5");
  ASSERT_EQ(message(axpy.run()), "success");
  llvm::ArrayRef<HostValue> results = axpy.results();
  ASSERT_EQ(results.size(), 3u);
  EXPECT_EQ(results[0].shape, (std::vector<int64_t>{3}));
  EXPECT_EQ(results[0].component(0), 12.0);
  EXPECT_EQ(results[0].component(1), 24.0);
  EXPECT_EQ(results[0].component(2), 36.0);
  EXPECT_TRUE(results[1].shape.empty());
  EXPECT_EQ(results[1].component(0), 3.0);
  EXPECT_EQ(results[2].scalar, ScalarKind::Int32);
  EXPECT_EQ(results[2].component(0), 42.0);
}

TEST(FunctionTest, PassesAndReturnsVectorsByValue) {
  Program program;
  Function vscale = compile(program, kVectors, "vscale");
  // Host buffers need no particular alignment: the engine copies vector
  // arguments into aligned storage before each call.
  double storage[5] = {0.0, 1.0, -2.0, 3.5, 4.0};
  double s = 2.0;
  ASSERT_EQ(message(vscale.bindParameter(0, storage + 1,
                                         ComponentType::Float64, {2, 2})),
            "success");
  ASSERT_EQ(message(vscale.bindParameter(1, &s, ComponentType::Float64, {})),
            "success");
  ASSERT_EQ(message(vscale.run()), "success");
  ASSERT_EQ(vscale.results().size(), 2u);
  const HostValue &scaled = vscale.results()[0];
  EXPECT_EQ(scaled.shape, (std::vector<int64_t>{4}));
  EXPECT_EQ(scaled.component(0), 2.0);
  EXPECT_EQ(scaled.component(1), -4.0);
  EXPECT_EQ(scaled.component(2), 7.0);
  EXPECT_EQ(scaled.component(3), 8.0);
  EXPECT_EQ(vscale.results()[1].component(0), 6.5);
  // The copy is taken per run, so host changes are seen.
  storage[1] = 10.0;
  ASSERT_EQ(message(vscale.run()), "success");
  EXPECT_EQ(vscale.results()[0].component(0), 20.0);
  // A buffer of another component count does not fit.
  ASSERT_EQ(message(vscale.bindParameter(0, storage, ComponentType::Float64,
                                         {5})),
            "success");
  EXPECT_EQ(message(vscale.init()),
            "function 'vscale': parameter 0 is bound to float64 of shape [5], "
            "but the program expects float64 of shape [4]");
}

TEST(FunctionTest, PassesAndReturnsComplexValues) {
  Program program;
  Function cscale = compile(program, kComplex, "cscale");
  // Complex values are bound as (re, im) pairs: z = 1 + 2i,
  // v = (3 - i, i).
  double z[2] = {1.0, 2.0};
  double v[4] = {3.0, -1.0, 0.0, 1.0};
  ASSERT_EQ(message(cscale.bindParameter(0, z, ComponentType::Float64, {})),
            "success");
  ASSERT_EQ(message(cscale.bindParameter(1, v, ComponentType::Float64, {2, 2})),
            "success");
  EXPECT_EQ(message(cscale.init()),
            "function 'cscale': parameter 0 is bound to float64 of shape [], "
            "but the program expects float64 of shape [2]");
  ASSERT_EQ(message(cscale.bindParameter(0, z, ComponentType::Float64, {2})),
            "success");
  ASSERT_EQ(message(cscale.run()), "success");
  ASSERT_EQ(cscale.results().size(), 2u);
  // (1 + 2i)(3 - i) = 3 - i + 6i + 2 = 5 + 5i; (1 + 2i) i = -2 + i.
  const HostValue &scaled = cscale.results()[0];
  EXPECT_TRUE(scaled.isComplex);
  EXPECT_EQ(scaled.shape, (std::vector<int64_t>{2}));
  ASSERT_EQ(scaled.numComponents(), 2u);
  EXPECT_EQ(scaled.component(0), 5.0);
  EXPECT_EQ(scaled.component(1), 5.0);
  EXPECT_EQ(scaled.component(2), -2.0);
  EXPECT_EQ(scaled.component(3), 1.0);
  // conj(1 + 2i) = 1 - 2i.
  const HostValue &conjugate = cscale.results()[1];
  EXPECT_TRUE(conjugate.isComplex);
  EXPECT_TRUE(conjugate.shape.empty());
  ASSERT_EQ(conjugate.numNumbers(), 2u);
  EXPECT_EQ(conjugate.component(0), 1.0);
  EXPECT_EQ(conjugate.component(1), -2.0);
}

TEST(FunctionTest, ListsWhatItNeeds) {
  Program program;
  Function stiffness = compile(program, kStiffness, "stiffness");
  EXPECT_EQ(stiffness.requiredSets(),
            (std::vector<std::string>{"points", "springs"}));
  EXPECT_TRUE(stiffness.requiredTensors().empty());
  Function scale = compile(program, kScale, "scale");
  EXPECT_EQ(scale.requiredTensors(), (std::vector<std::string>{"h"}));
}

TEST(FunctionTest, ReportsAnUnboundSetOrExtern) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  EXPECT_EQ(message(scale.init()),
            "function 'scale': extern set 'points' is not bound");
  Set points("points");
  points.addField<double, 3>("x");
  ASSERT_EQ(message(scale.bind("points", points)), "success");
  EXPECT_EQ(message(scale.run()), "function 'scale': extern 'h' is not bound");
}

TEST(FunctionTest, ReportsAFieldOfAnotherShapeOrType) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  double h = 1.0;
  ASSERT_EQ(message(scale.bind("h", &h)), "success");

  Set flat("points");
  flat.addField<double, 2>("x");
  ASSERT_EQ(message(scale.bind("points", flat)), "success");
  EXPECT_EQ(message(scale.init()),
            "function 'scale': field 'points.x' holds float64 components of "
            "shape [2], but the program expects float64 components of shape "
            "[3]");

  Set single("points");
  single.addField<float, 3>("x");
  ASSERT_EQ(message(scale.bind("points", single)), "success");
  EXPECT_EQ(message(scale.init()),
            "function 'scale': field 'points.x' holds float32 components of "
            "shape [3], but the program expects float64 components of shape "
            "[3]");

  Set missing("points");
  ASSERT_EQ(message(scale.bind("points", missing)), "success");
  EXPECT_EQ(message(scale.init()),
            "function 'scale': set 'points' has no field 'x'; the program "
            "expects float64 components of shape [3]");
}

TEST(FunctionTest, ReportsAnExternOfAnotherShapeOrType) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  Set points("points");
  points.addField<double, 3>("x");
  ASSERT_EQ(message(scale.bind("points", points)), "success");
  double h3[3] = {1, 2, 3};
  ASSERT_EQ(message(scale.bind("h", h3, {3})), "success");
  EXPECT_EQ(message(scale.init()),
            "function 'scale': extern 'h' is bound to float64 of shape [3], "
            "but the program expects float64 of shape []");
  int32_t hi = 1;
  ASSERT_EQ(message(scale.bind("h", &hi)), "success");
  EXPECT_EQ(message(scale.init()),
            "function 'scale': extern 'h' is bound to int32 of shape [], but "
            "the program expects float64 of shape []");
}

TEST(FunctionTest, ReportsAVertexSetBoundAsAnEdgeSet) {
  Program program;
  Function spans = compile(program, kEndpoints, "spans");
  Set notEdges("springs");
  notEdges.addField<double>("d");
  ASSERT_EQ(message(spans.bind("springs", notEdges)), "success");
  EXPECT_EQ(message(spans.init()),
            "function 'spans': set 'springs' has 0 endpoints per element, "
            "but the program expects 2");
}

TEST(FunctionTest, RejectsBindingNamesItDoesNotUse) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  Set other("verts");
  double g = 0;
  EXPECT_EQ(message(scale.bind("verts", other)),
            "function 'scale': uses no set named 'verts'");
  EXPECT_EQ(message(scale.bind("g", &g)),
            "function 'scale': uses no extern tensor named 'g'");
}

TEST(FunctionTest, FindsTheFirstNonFiniteComponent) {
  Program program;
  Function scale = compile(program, kScale, "scale");
  Set points("points");
  auto x = points.addField<double, 3>("x");
  x.set(points.add(), {1.0, 1.0, 1.0});
  x.set(points.add(), {1.0, 1.0, std::numeric_limits<double>::infinity()});
  double h = 0.0;
  ASSERT_EQ(message(scale.bind("points", points)), "success");
  ASSERT_EQ(message(scale.bind("h", &h)), "success");
  ASSERT_EQ(message(scale.run()), "success");
  // 0 * inf is nan.
  EXPECT_EQ(scale.findNonFinite(),
            "field 'points.x' of element 1, component 2, is nan");
  x.set(1, {0.0, 0.0, 0.0});
  EXPECT_EQ(scale.findNonFinite(), "");
}

TEST(FunctionTest, AnUncompiledFunctionReportsIt) {
  Function empty;
  Set points("points");
  EXPECT_EQ(message(empty.bind("points", points)),
            "the function was not compiled by a Program");
  EXPECT_EQ(message(empty.run()), "the function was not compiled by a Program");
}
