//===- IRGenTest.cpp - The IR generator's C++ interface -------------------===//
//
// What the engine relies on: a verified module for a legal program, the
// precision option, null plus a positioned diagnostic for what the
// generator does not support, and repeated use of one context.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Frontend/Frontend.h"
#include "simit/Frontend/IRGen.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/IR/Verifier.h"
#include "llvm/Support/MemoryBuffer.h"

#include <gtest/gtest.h>

using namespace simit::frontend;

namespace {

/// Parses, checks and generates one program.
struct Generated {
  Generated(llvm::StringRef source, mlir::MLIRContext &context,
            IRGenOptions options = {})
      : diags(sourceMgr) {
    unsigned id = sourceMgr.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(source, "test.sim"),
        llvm::SMLoc());
    program = parseProgram(sourceMgr, id, diags);
    checked = !diags.hasErrors() && checkProgram(*program, diags);
    if (checked)
      module = generateIR(*program, diags, context, options);
  }

  std::string errors() const {
    std::string text;
    llvm::raw_string_ostream os(text);
    diags.print(os);
    return text;
  }

  llvm::SourceMgr sourceMgr;
  DiagnosticEngine diags;
  std::unique_ptr<Program> program;
  bool checked = false;
  mlir::OwningOpRef<mlir::ModuleOp> module;
};

const char *kSprings = R"(
element Point
  x : vector[3](float);
end
element Spring
  k : float;
end
extern points : set{Point};
extern springs : set{Spring}(points, points);
func force(s : Spring, p : (Point*2)) -> (f : vector[points](vector[3](float)))
  f(p(0)) = s.k * (p(1).x - p(0).x);
end
export func step()
  f = map force to springs reduce +;
  points.x = points.x + f;
end
)";

TEST(IRGen, LegalProgramGivesVerifiedModule) {
  mlir::MLIRContext context;
  Generated g(kSprings, context);
  ASSERT_TRUE(g.checked) << g.errors();
  ASSERT_TRUE(g.module) << g.errors();
  EXPECT_TRUE(mlir::succeeded(mlir::verify(*g.module)));
  auto step = g.module->lookupSymbol<mlir::func::FuncOp>("step");
  auto force = g.module->lookupSymbol<mlir::func::FuncOp>("force");
  ASSERT_TRUE(step && force);
  EXPECT_TRUE(step->hasAttr("simit.export"));
  EXPECT_FALSE(force->hasAttr("simit.export"));
  unsigned assemblies = 0;
  step.walk([&](mlir::simit::AssembleOp op) {
    ++assemblies;
    EXPECT_EQ(op.getCallee(), "force");
    EXPECT_EQ(op.getReduction(), mlir::simit::ReductionKind::Add);
  });
  EXPECT_EQ(assemblies, 1u);
}

TEST(IRGen, SinglePrecisionMakesFloatsF32) {
  mlir::MLIRContext context;
  IRGenOptions options;
  options.singlePrecision = true;
  Generated g(kSprings, context, options);
  ASSERT_TRUE(g.module) << g.errors();
  auto force = g.module->lookupSymbol<mlir::func::FuncOp>("force");
  auto spring = llvm::cast<mlir::simit::ElementType>(
      force.getFunctionType().getInput(0));
  EXPECT_TRUE(spring.getFieldType("k").isF32());
  auto result = llvm::cast<mlir::simit::SystemTensorType>(
      force.getFunctionType().getResult(0));
  EXPECT_TRUE(mlir::simit::getComponentType(result).isF32());
}

TEST(IRGen, UnsupportedConstructIsAPositionedError) {
  mlir::MLIRContext context;
  Generated g(R"(element V
  m : float;
end
extern verts : set{V};
func bump(inout r : float)
  r = r + 1.0;
end
func add(inout s : float, v : V) -> (r : float)
  s = s + v.m;
  bump(r);
end
export func main()
  var t = 0.0;
  r = map add(t) to verts reduce +;
end
)",
              context);
  ASSERT_TRUE(g.checked) << g.errors();
  EXPECT_FALSE(g.module);
  EXPECT_NE(g.errors().find("test.sim:10:8: error: not supported by the IR "
                            "generator: a result passed as an inout argument "
                            "in a function mapped with reduce and inout extra "
                            "arguments"),
            std::string::npos)
      << g.errors();
}

TEST(IRGen, OneContextServesSeveralPrograms) {
  mlir::MLIRContext context;
  Generated first(kSprings, context);
  Generated second(kSprings, context);
  ASSERT_TRUE(first.module && second.module);
  // Types are uniqued in the context: both modules share the element type.
  auto a = first.module->lookupSymbol<mlir::func::FuncOp>("force");
  auto b = second.module->lookupSymbol<mlir::func::FuncOp>("force");
  EXPECT_EQ(a.getFunctionType(), b.getFunctionType());
}

} // namespace
