//===- LoopsTypeConverterTest.cpp - Types of the loop lowering ------------===//

#include "simit/Dialect/Simit/Transforms/LoopsTypeConverter.h"

#include "simit/Dialect/Simit/IR/Simit.h"

#include "mlir/AsmParser/AsmParser.h"
#include "mlir/Dialect/LLVMIR/LLVMDialect.h"
#include "mlir/IR/MLIRContext.h"

#include <gtest/gtest.h>

using namespace mlir;
using namespace mlir::simit;

namespace {
class LoopsTypeConverterTest : public ::testing::Test {
protected:
  LoopsTypeConverterTest() {
    ctx.loadDialect<SimitDialect, LLVM::LLVMDialect>();
  }

  /// The lowered type of the type spelled `source`, printed ("null" when
  /// there is none).
  std::string converted(StringRef source) {
    Type type = parseType(source, &ctx);
    EXPECT_TRUE(type) << source.str();
    Type lowered = converter.convertType(type);
    if (!lowered)
      return "null";
    std::string text;
    llvm::raw_string_ostream os(text);
    lowered.print(os);
    return text;
  }

  MLIRContext ctx;
  LoopsTypeConverter converter;
};

TEST_F(LoopsTypeConverterTest, ScalarsHandlesSetsAndElements) {
  EXPECT_EQ(converted("f64"), "f64");
  EXPECT_EQ(converted("complex<f32>"), "complex<f32>");
  EXPECT_EQ(converted("!simit.string"), "!llvm.ptr");
  EXPECT_EQ(converted("!simit.opaque"), "!llvm.ptr");
  EXPECT_EQ(converted("!simit.set<\"points\", !simit.element<\"P\", {}>>"),
            "index");
  EXPECT_EQ(converted("!simit.element<\"P\", {x : f64}>"), "index");
}

TEST_F(LoopsTypeConverterTest, LocalTensorsAreFlatVectors) {
  EXPECT_EQ(converted("tensor<f64>"), "f64");
  EXPECT_EQ(converted("tensor<3x3xf64>"), "vector<9xf64>");
  // Complex components are (re, im) pairs.
  EXPECT_EQ(converted("tensor<2xcomplex<f64>>"), "vector<4xf64>");
  EXPECT_EQ(converted("!simit.tensor<[2] x tensor<3xf32>>"), "vector<6xf32>");
}

TEST_F(LoopsTypeConverterTest, SystemTensorsAreArraysOfBlocks) {
  EXPECT_EQ(converted("!simit.tensor<[\"points\"] x f64>"), "memref<?xf64>");
  EXPECT_EQ(converted("!simit.tensor<[\"points\"] x tensor<3xf64>>"),
            "memref<?x3xf64>");
  // A matrix's stored blocks, whatever its encoding.
  EXPECT_EQ(converted("!simit.tensor<[\"points\", \"points\"] x "
                      "tensor<3x3xf64>>"),
            "memref<?x3x3xf64>");
  EXPECT_EQ(converted("!simit.tensor<[\"springs\", \"points\"] x f32, "
                      "#simit.storage<incidence(\"springs\", cols [0, 1])>>"),
            "memref<?xf32>");
  EXPECT_EQ(converted("!simit.tensor<[\"points\", \"points\"] x f64, "
                      "#simit.storage<dense>>"),
            "memref<?xf64>");
  // Complex components stay complex numbers in the arrays.
  EXPECT_EQ(converted("!simit.tensor<[\"points\"] x complex<f64>>"),
            "memref<?xcomplex<f64>>");
  EXPECT_EQ(converted("!simit.tensor<[\"points\"] x tensor<2xcomplex<f32>>>"),
            "memref<?x2xcomplex<f32>>");
  // No lowering: three sets.
  EXPECT_EQ(converted("!simit.tensor<[\"a\", \"b\", \"c\"] x f64>"), "null");
}

TEST_F(LoopsTypeConverterTest, VariablesAreSlots) {
  EXPECT_EQ(converted("!simit.ref<f64>"), "memref<f64>");
  EXPECT_EQ(converted("!simit.ref<tensor<3xf64>>"), "memref<3xf64>");
  EXPECT_EQ(converted("!simit.ref<tensor<2xcomplex<f64>>>"), "memref<4xf64>");
  EXPECT_EQ(converted("!simit.ref<!simit.string>"), "memref<!llvm.ptr>");
  // A variable holding a system tensor is that tensor's array.
  EXPECT_EQ(converted("!simit.ref<!simit.tensor<[\"points\"] x f64>>"),
            "memref<?xf64>");
}

} // namespace
