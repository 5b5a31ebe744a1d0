//===--- SimProgramTest.cpp - Simit programs through the whole stack ------===//
//
// The paper's section 5 usage: sets built in C++, a .sim program compiled
// by the frontend, the lowering and the JIT, fields updated in place.
// Expected numbers are computed by hand.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/ABI/RuntimeFunctions.h"
#include "simit/Runtime/Set.h"

#include "gmock/gmock.h"
#include "gtest/gtest.h"

#include <chrono>
#include <cmath>

using namespace simit;
using namespace simit::test;
using ::testing::HasSubstr;

namespace {
constexpr const char *kChain = R"sim(
element Point
  x : float;
  y : float;
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);
extern scale   : float;

% Spring forces k (x1 - x0) on endpoint 0 and its opposite on endpoint 1.
func force(s : Spring, p : (Point*2)) -> (f : tensor[points](float))
  d = p(1).x - p(0).x;
  f(p(0)) = s.k * d;
  f(p(1)) = -s.k * d;
end

% The stiffness matrix: K(a,a) = k, K(a,b) = -k.
func stiffness(s : Spring, p : (Point*2)) -> (K : tensor[points,points](float))
  K(p(0), p(0)) = s.k;
  K(p(0), p(1)) = -s.k;
  K(p(1), p(0)) = -s.k;
  K(p(1), p(1)) = s.k;
end

export func forces()
  f = map force to springs reduce +;
  points.y = scale * f;
end

export func multiply()
  K = map stiffness to springs reduce +;
  points.y = K * points.x;
end
)sim";

/// Points at x = 0, 1, 3 joined by springs of stiffness 2 and 3.
struct Chain {
  Set points{"points"};
  Set springs{"springs", {&points, &points}};
  FieldRef<double> x = points.addField<double>("x");
  FieldRef<double> y = points.addField<double>("y");
  FieldRef<double> k = springs.addField<double>("k");
  Chain() {
    for (double xi : {0.0, 1.0, 3.0})
      x.set(points.add(), xi);
    k.set(springs.add(0, 1), 2.0);
    k.set(springs.add(1, 2), 3.0);
  }
};
} // namespace

TEST(SimProgramTest, AssemblesAVectorIntoAField) {
  Program program;
  ASSERT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
  llvm::Expected<Function> forces = program.compile("forces");
  ASSERT_TRUE(!!forces) << llvm::toString(forces.takeError());
  Chain chain;
  double scale = 0.5;
  ASSERT_EQ(message(forces->bind("points", chain.points)), "success");
  ASSERT_EQ(message(forces->bind("springs", chain.springs)), "success");
  ASSERT_EQ(message(forces->bind("scale", &scale)), "success");
  ASSERT_EQ(message(forces->init()), "success");
  ASSERT_EQ(message(forces->run()), "success");
  // f = (2 (1 - 0), -2 + 3 (3 - 1), -3 (3 - 1)) = (2, 4, -6), halved.
  EXPECT_DOUBLE_EQ(chain.y.get(0), 1.0);
  EXPECT_DOUBLE_EQ(chain.y.get(1), 2.0);
  EXPECT_DOUBLE_EQ(chain.y.get(2), -3.0);
}

TEST(SimProgramTest, AssemblesAMatrixAndMultiplies) {
  Program program;
  ASSERT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
  llvm::Expected<Function> multiply = program.compile("multiply");
  ASSERT_TRUE(!!multiply) << llvm::toString(multiply.takeError());
  Chain chain;
  ASSERT_EQ(message(multiply->bind("points", chain.points)), "success");
  ASSERT_EQ(message(multiply->bind("springs", chain.springs)), "success");
  ASSERT_EQ(message(multiply->run()), "success");
  // K x = (2 (0 - 1), 2 (1 - 0) + 3 (1 - 3), 3 (3 - 1)) = (-2, -4, 6).
  EXPECT_DOUBLE_EQ(chain.y.get(0), -2.0);
  EXPECT_DOUBLE_EQ(chain.y.get(1), -4.0);
  EXPECT_DOUBLE_EQ(chain.y.get(2), 6.0);
}

TEST(SimProgramTest, SinglePrecisionNeedsFloat32Fields) {
  ProgramOptions options;
  options.precision = FloatPrecision::Single;
  Program program(options);
  ASSERT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
  llvm::Expected<Function> multiply = program.compile("multiply");
  ASSERT_TRUE(!!multiply) << llvm::toString(multiply.takeError());
  Chain doubles;
  ASSERT_EQ(message(multiply->bind("points", doubles.points)), "success");
  ASSERT_EQ(message(multiply->bind("springs", doubles.springs)), "success");
  EXPECT_THAT(message(multiply->init()),
              HasSubstr("holds float64 components of shape [], but the "
                        "program expects float32 components"));

  Set points("points");
  Set springs("springs", {&points, &points});
  auto x = points.addField<float>("x");
  auto y = points.addField<float>("y");
  auto k = springs.addField<float>("k");
  for (float xi : {0.0f, 1.0f, 3.0f})
    x.set(points.add(), xi);
  k.set(springs.add(0, 1), 2.0f);
  k.set(springs.add(1, 2), 3.0f);
  ASSERT_EQ(message(multiply->bind("points", points)), "success");
  ASSERT_EQ(message(multiply->bind("springs", springs)), "success");
  ASSERT_EQ(message(multiply->run()), "success");
  EXPECT_EQ(y.get(0), -2.0f);
  EXPECT_EQ(y.get(1), -4.0f);
  EXPECT_EQ(y.get(2), 6.0f);
}

TEST(SimProgramTest, UnexportedFunctionsAreNotCompiled) {
  Program program;
  ASSERT_EQ(message(program.loadString(kChain, "chain.sim")), "success");
  llvm::Expected<Function> force = program.compile("force");
  ASSERT_FALSE(!!force);
  EXPECT_EQ(llvm::toString(force.takeError()),
            "unknown function 'force' (exported functions: forces, multiply)");
}

TEST(SimProgramTest, PhaseTimesSplitAssemblyFromSolve) {
  // kChain's forces (2, 4, -6), halved 200 times in a while loop.
  std::string steps = std::string(kChain) + R"sim(
export func step()
  f = map force to springs reduce +;
  var r = f;
  var i = 0;
  while i < 200
    r = 0.5 * r;
    i = i + 1;
  end
  points.y = r;
end
)sim";
  using Clock = std::chrono::steady_clock;
  for (bool timed : {true, false}) {
    ProgramOptions options;
    options.timePhases = timed;
    Program program(options);
    ASSERT_EQ(message(program.loadString(steps, "steps.sim")), "success");
    llvm::Expected<Function> step = program.compile("step");
    ASSERT_TRUE(bool(step)) << llvm::toString(step.takeError());
    Chain chain;
    ASSERT_EQ(message(step->bind("points", chain.points)), "success");
    ASSERT_EQ(message(step->bind("springs", chain.springs)), "success");
    ASSERT_EQ(message(step->init()), "success");
    resetPhaseTimes();
    Clock::time_point start = Clock::now();
    ASSERT_EQ(message(step->run()), "success");
    double wallMs =
        std::chrono::duration<double, std::milli>(Clock::now() - start)
            .count();
    PhaseTimes phases = readPhaseTimes();
    if (timed) {
      EXPECT_GT(phases.assemblyMs, 0.0);
      EXPECT_GT(phases.solveMs, 0.0);
      EXPECT_LE(phases.assemblyMs + phases.solveMs, wallMs);
    } else {
      EXPECT_EQ(phases.assemblyMs, 0.0);
      EXPECT_EQ(phases.solveMs, 0.0);
    }
    // f = (2, 4, -6) times 2^-200, exact in binary.
    EXPECT_EQ(chain.y.get(0), std::ldexp(2.0, -200));
    EXPECT_EQ(chain.y.get(1), std::ldexp(4.0, -200));
    EXPECT_EQ(chain.y.get(2), std::ldexp(-6.0, -200));
  }
}

namespace {
constexpr const char *kEnergy = R"sim(
element Point
  x : float;
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);
extern total   : float;

func energy(s : Spring, p : (Point*2)) -> (E : float)
  E = s.k * (p(1).x - p(0).x);
end

export func sum()
  total = map energy to springs reduce +;
end

export func last()
  total = map energy to springs;
end
)sim";

/// Runs `name` of kEnergy on the chain and returns `total`.
double runEnergy(llvm::StringRef name) {
  Program program;
  EXPECT_EQ(message(program.loadString(kEnergy, "energy.sim")), "success");
  llvm::Expected<Function> function = program.compile(name);
  EXPECT_TRUE(!!function) << llvm::toString(function.takeError());
  if (!function)
    return 0.0;
  Chain chain;
  double total = -1.0;
  EXPECT_EQ(message(function->bind("points", chain.points)), "success");
  EXPECT_EQ(message(function->bind("springs", chain.springs)), "success");
  EXPECT_EQ(message(function->bind("total", &total)), "success");
  EXPECT_EQ(message(function->run()), "success");
  return total;
}
} // namespace

TEST(SimProgramTest, ReducesAScalarResult) {
  // k (x1 - x0) per spring: 2 (1 - 0) + 3 (3 - 1) = 8.
  EXPECT_DOUBLE_EQ(runEnergy("sum"), 8.0);
}

TEST(SimProgramTest, AScalarResultWithoutReductionKeepsTheLastWrite) {
  // The last spring in set order writes 3 (3 - 1) = 6.
  EXPECT_DOUBLE_EQ(runEnergy("last"), 6.0);
}
