//===--- HostABITest.cpp - Reading simit.bindings back from the IR --------===//

#include "simit/Engine/HostABI.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/Dialect/LLVMIR/LLVMDialect.h"
#include "mlir/Dialect/MemRef/IR/MemRef.h"
#include "mlir/IR/BuiltinOps.h"
#include "mlir/IR/MLIRContext.h"
#include "mlir/Parser/Parser.h"

#include "gtest/gtest.h"

using namespace simit;

namespace {
class HostABITest : public ::testing::Test {
protected:
  HostABITest() {
    context.loadDialect<mlir::func::FuncDialect, mlir::memref::MemRefDialect,
                        mlir::LLVM::LLVMDialect>();
  }

  /// The signature of the only function (func.func or llvm.func) of
  /// `text`.
  llvm::Expected<HostSignature> read(llvm::StringRef text) {
    module = mlir::parseSourceString<mlir::ModuleOp>(text, &context);
    if (!module)
      return llvm::createStringError("parse error");
    return readHostSignature(&module->getBody()->front());
  }

  std::string readError(llvm::StringRef text) {
    auto signature = read(text);
    if (signature)
      return "no error";
    return llvm::toString(signature.takeError());
  }

  mlir::MLIRContext context;
  mlir::OwningOpRef<mlir::ModuleOp> module;
};
} // namespace

TEST_F(HostABITest, ReadsEveryKind) {
  auto signature = read(R"mlir(
    func.func private @step(index, memref<?x3xf64>, memref<?x2xi32>,
        memref<?xi32>, memref<?xi32>, memref<?x4xi32>, memref<f64>,
        memref<3xf32>, i32) -> f64
      attributes {simit.bindings = [
        {kind = "set_size", set = "points"},
        {kind = "field", set = "points", field = "x"},
        {kind = "endpoints", set = "springs"},
        {kind = "pattern_rowptr", set = "springs", rows = "points", cols = "points"},
        {kind = "pattern_colidx", set = "springs", rows = "points", cols = "points"},
        {kind = "pattern_locations", set = "springs", rows = "points", cols = "points"},
        {kind = "extern", name = "h"},
        {kind = "extern", name = "g"},
        {kind = "param", index = 0}]}
  )mlir");
  ASSERT_TRUE(!!signature) << llvm::toString(signature.takeError());
  EXPECT_EQ(signature->function, "step");
  ASSERT_EQ(signature->arguments.size(), 9u);
  using Kind = ArgumentBinding::Kind;
  const auto &args = signature->arguments;
  EXPECT_EQ(args[0].kind, Kind::SetSize);
  EXPECT_EQ(args[0].set, "points");
  EXPECT_EQ(args[0].type.scalar, ScalarKind::Index);
  EXPECT_EQ(args[1].kind, Kind::Field);
  EXPECT_EQ(args[1].field, "x");
  EXPECT_EQ(args[1].type.str(), "memref<?x3xf64>");
  EXPECT_EQ(args[2].kind, Kind::Endpoints);
  EXPECT_EQ(args[3].kind, Kind::PatternRowPtr);
  EXPECT_EQ(args[3].rows, "points");
  EXPECT_EQ(args[4].kind, Kind::PatternColIdx);
  EXPECT_EQ(args[5].kind, Kind::PatternLocations);
  EXPECT_EQ(args[5].cols, "points");
  EXPECT_EQ(args[6].kind, Kind::Extern);
  EXPECT_EQ(args[6].type.str(), "memref<f64>");
  EXPECT_EQ(args[7].type.str(), "memref<3xf32>");
  EXPECT_EQ(args[8].kind, Kind::Parameter);
  EXPECT_EQ(args[8].index, 0);
  EXPECT_FALSE(args[8].type.isMemRef);
  ASSERT_EQ(signature->results.size(), 1u);
  EXPECT_EQ(signature->results[0].str(), "f64");
}

TEST_F(HostABITest, ReadsComplexScalarsAndVectors) {
  auto signature = read(R"mlir(
    func.func private @f(complex<f64>, vector<3x2xf32>) -> vector<2x2xf64>
      attributes {simit.bindings = [{kind = "param", index = 0},
                                    {kind = "param", index = 1}]}
  )mlir");
  ASSERT_TRUE(!!signature) << llvm::toString(signature.takeError());
  const ValueType &z = signature->arguments[0].type;
  EXPECT_TRUE(z.isComplex);
  EXPECT_FALSE(z.isVector);
  EXPECT_EQ(z.scalar, ScalarKind::Float64);
  EXPECT_EQ(z.str(), "complex<f64>");
  EXPECT_EQ(z.hostShape(), (std::vector<int64_t>{2}));
  const ValueType &v = signature->arguments[1].type;
  EXPECT_TRUE(v.isComplex);
  EXPECT_TRUE(v.isVector);
  EXPECT_EQ(v.scalar, ScalarKind::Float32);
  EXPECT_EQ(v.shape, (std::vector<int64_t>{3}));
  EXPECT_EQ(v.numComponents(), 3);
  EXPECT_EQ(v.str(), "vector<3x2xf32>");
  EXPECT_TRUE(signature->results[0].isComplex);
  // Other 2-D vectors are not host types: local tensors are flat.
  std::string error = readError(R"mlir(func.func private @g(vector<2x3xf64>)
      attributes {simit.bindings = [{kind = "param", index = 0}]})mlir");
  EXPECT_NE(error.find("unsupported host type vector<2x3xf64>"),
            std::string::npos)
      << error;
}

TEST_F(HostABITest, ReadsAnElementColouring) {
  auto signature = read(R"mlir(
    func.func private @f(memref<?xi32>) attributes {simit.bindings = [
        {kind = "element_colours", set = "tets", chunk = 64 : i64}]}
  )mlir");
  ASSERT_TRUE(!!signature) << llvm::toString(signature.takeError());
  const ArgumentBinding &colours = signature->arguments[0];
  EXPECT_EQ(colours.kind, ArgumentBinding::Kind::ElementColours);
  EXPECT_EQ(colours.set, "tets");
  EXPECT_EQ(colours.chunk, 64);
  EXPECT_EQ(colours.describe(), "element colouring of set 'tets' in chunks of 64");
  EXPECT_EQ(readError(R"mlir(func.func private @f(memref<?xi32>)
      attributes {simit.bindings = [
        {kind = "element_colours", set = "tets", chunk = 0 : i64}]})mlir"),
            "function 'f': simit.bindings entry 0: expected a positive "
            "32-bit integer 'chunk'");
  EXPECT_EQ(readError(R"mlir(func.func private @f(memref<?xf64>)
      attributes {simit.bindings = [
        {kind = "element_colours", set = "tets", chunk = 8 : i64}]})mlir"),
            "function 'f': element colouring of set 'tets' in chunks of 8 has "
            "type memref<?xf64>, expected memref<?xi32>");
}

// A product binding is the union of chains of factors: '|' separates the
// chains of "set" and of "mid", a chain of one factor has no mid.
TEST_F(HostABITest, ReadsTheChainsOfAProduct) {
  auto signature = read(R"mlir(
    func.func private @f(memref<?xi32>) attributes {simit.bindings = [
        {kind = "product_rowptr", set = "springs*tris+hinges|springs",
         mid = "points|", rows = "points", cols = "points"}]}
  )mlir");
  ASSERT_TRUE(!!signature) << llvm::toString(signature.takeError());
  const ArgumentBinding &product = signature->arguments[0];
  ASSERT_EQ(product.chains.size(), 2u);
  using Sets = std::vector<std::vector<std::string>>;
  EXPECT_EQ(product.chains[0].factorSets,
            (Sets{{"springs"}, {"tris", "hinges"}}));
  EXPECT_EQ(product.chains[0].mids, std::vector<std::string>{"points"});
  EXPECT_EQ(product.chains[1].factorSets, Sets{{"springs"}});
  EXPECT_TRUE(product.chains[1].mids.empty());
  EXPECT_EQ(product.describe(),
            "the product of the sparsity patterns of 'springs' over "
            "('points', 'points'), 'tris', 'hinges' over ('points', "
            "'points'), united with the sparsity pattern of 'springs' over "
            "('points', 'points')");
  // Each chain needs one mid fewer than it has factors.
  EXPECT_EQ(readError(R"mlir(func.func private @f(memref<?xi32>)
      attributes {simit.bindings = [
        {kind = "product_rowptr", set = "a*b|c", mid = "p", rows = "p",
         cols = "p"}]})mlir"),
            "function 'f': simit.bindings entry 0: expected 'set' of the "
            "form \"A*B*...|C*...\" and 'mid' naming the sets between the "
            "factors of each chain, \"M1,...|M2,...\"");
}

TEST_F(HostABITest, RequiresTheBindingsAttribute) {
  EXPECT_EQ(readError("func.func private @f(f64) -> i32"),
            "function 'f' has no simit.bindings attribute");
}

// After the conversion to LLVM, the memref types are gone from the
// signature: simit.host_type keeps them.
TEST_F(HostABITest, ReadsTheHostTypeOfAnLLVMFunction) {
  auto signature = read(R"mlir(
    llvm.func @step(%n : i64, %a : !llvm.ptr, %b : !llvm.ptr, %o : i64,
                    %s : i64, %t : i64) -> f64
      attributes {simit.bindings = [{kind = "set_size", set = "points"},
                                    {kind = "field", set = "points", field = "m"}],
                  simit.host_type = (index, memref<?xf64>) -> f64,
                  simit.memref_convention = "descriptor"} {
      %0 = llvm.mlir.constant(0.0 : f64) : f64
      llvm.return %0 : f64
    }
  )mlir");
  ASSERT_TRUE(!!signature) << llvm::toString(signature.takeError());
  EXPECT_EQ(signature->function, "step");
  ASSERT_EQ(signature->arguments.size(), 2u);
  EXPECT_EQ(signature->arguments[1].type.str(), "memref<?xf64>");
  EXPECT_EQ(signature->arguments[1].field, "m");
  ASSERT_EQ(signature->results.size(), 1u);
  EXPECT_EQ(signature->results[0].str(), "f64");
}

TEST_F(HostABITest, RequiresTheHostTypeOfAnLLVMFunction) {
  EXPECT_EQ(readError(R"mlir(llvm.func @f(%n : i64)
      attributes {simit.bindings = [{kind = "set_size", set = "p"}]} {
      llvm.return
    })mlir"),
            "function 'f' has no function type in simit.host_type "
            "(simit-record-host-abi)");
}

TEST_F(HostABITest, RejectsAnUnknownKind) {
  EXPECT_EQ(readError(R"mlir(func.func private @f(index)
      attributes {simit.bindings = [{kind = "sizes", set = "p"}]})mlir"),
            "function 'f': simit.bindings entry 0: unknown kind 'sizes'");
}

TEST_F(HostABITest, RejectsAMissingKey) {
  EXPECT_EQ(readError(R"mlir(func.func private @f(memref<?xf64>)
      attributes {simit.bindings = [{kind = "field", set = "p"}]})mlir"),
            "function 'f': simit.bindings entry 0: expected a string 'field'");
}

TEST_F(HostABITest, RejectsACountMismatch) {
  EXPECT_EQ(readError(R"mlir(func.func private @f(index, index)
      attributes {simit.bindings = [{kind = "set_size", set = "p"}]})mlir"),
            "function 'f': simit.bindings has 1 entries for 2 arguments");
}

TEST_F(HostABITest, RejectsATypeThatDoesNotFitTheKind) {
  EXPECT_EQ(readError(R"mlir(func.func private @f(memref<?xf64>)
      attributes {simit.bindings = [{kind = "endpoints", set = "s"}]})mlir"),
            "function 'f': endpoints of set 's' has type memref<?xf64>, "
            "expected memref<?xNxi32>");
  EXPECT_EQ(readError(R"mlir(func.func private @f(memref<?xf64>)
      attributes {simit.bindings = [{kind = "extern", name = "g"}]})mlir"),
            "function 'f': extern 'g' has type memref<?xf64>, expected a "
            "statically shaped memref or a scalar");
}

TEST_F(HostABITest, RejectsUnsupportedHostTypes) {
  std::string error = readError(R"mlir(func.func private @f(i16)
      attributes {simit.bindings = [{kind = "param", index = 0}]})mlir");
  EXPECT_NE(error.find("parameter 0: unsupported host type i16"), std::string::npos)
      << error;
}

TEST(ValueTypeTest, PrintsLikeMLIR) {
  ValueType type;
  type.isMemRef = true;
  type.scalar = ScalarKind::Int32;
  type.shape = {ValueType::kDynamic, 4};
  EXPECT_EQ(type.str(), "memref<?x4xi32>");
  EXPECT_EQ(scalarSize(ScalarKind::Bool), 1u);
  EXPECT_EQ(scalarSize(ScalarKind::Index), 8u);
}
