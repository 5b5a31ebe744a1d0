//===--- ThreadsTest.cpp - Set loops on all cores, deterministically -------===//
//
// A program that scatters a vector and a matrix over a random spring graph,
// multiplies, and reduces a dot product gives the same bits on 1, 2 and 3
// threads, and agrees with a long double computation in C++ to rounding.
//
//===----------------------------------------------------------------------===//

#include "EngineTestSupport.h"

#include "simit/Engine/Program.h"
#include "simit/Runtime/Set.h"

#include "gtest/gtest.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>

using namespace simit;
using namespace simit::test;

namespace {
constexpr const char *kSprings = R"sim(
element Point
  x : float;
  f : float;
  y : float;
end
element Spring
  k : float;
end
extern points  : set{Point};
extern springs : set{Spring}(points, points);
extern total   : float;

func force(s : Spring, p : (Point*2)) -> (f : tensor[points](float))
  d = p(1).x - p(0).x;
  f(p(0)) = s.k * d;
  f(p(1)) = -s.k * d;
end

func stiffness(s : Spring, p : (Point*2)) -> (K : tensor[points,points](float))
  K(p(0), p(0)) = s.k;
  K(p(0), p(1)) = -s.k;
  K(p(1), p(0)) = -s.k;
  K(p(1), p(1)) = s.k;
end

export func step()
  points.f = map force to springs reduce +;
  K = map stiffness to springs reduce +;
  points.y = K * points.x;
  total = dot(points.y, points.f);
end
)sim";

/// A random graph whose values span many magnitudes, so that a different
/// order of additions changes the rounding.
struct Graph {
  Set points{"points"};
  Set springs{"springs", {&points, &points}};
  FieldRef<double> x = points.addField<double>("x");
  FieldRef<double> f = points.addField<double>("f");
  FieldRef<double> y = points.addField<double>("y");
  FieldRef<double> k = springs.addField<double>("k");
  Graph() {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_int_distribution<int> exponent(-6, 6), point(0, 2999);
    for (int i = 0; i < 3000; ++i)
      x.set(points.add(), unit(random) * std::pow(10.0, exponent(random)));
    for (int e = 0; e < 20000; ++e) {
      int a = point(random), b = point(random);
      k.set(springs.add(a, b == a ? (a + 1) % 3000 : b),
            1.0 + unit(random) * 0.5);
    }
  }
};

struct Result {
  std::vector<double> f, y;
  double total = 0;
};

Result runStep(int threads) {
  ProgramOptions options;
  options.threads = threads;
  Program program(options);
  EXPECT_EQ(message(program.loadString(kSprings, "springs.sim")), "success");
  llvm::Expected<Function> step = program.compile("step");
  EXPECT_TRUE(!!step) << llvm::toString(step.takeError());
  Result result;
  if (!step)
    return result;
  Graph graph;
  EXPECT_EQ(message(step->bind("points", graph.points)), "success");
  EXPECT_EQ(message(step->bind("springs", graph.springs)), "success");
  EXPECT_EQ(message(step->bind("total", &result.total)), "success");
  EXPECT_EQ(message(step->run()), "success");
  for (int i = 0; i < graph.points.size(); ++i) {
    result.f.push_back(graph.f.get(i));
    result.y.push_back(graph.y.get(i));
  }
  return result;
}
} // namespace

TEST(ThreadsTest, SameBitsOnAnyNumberOfThreads) {
  Result one = runStep(1);
  ASSERT_EQ(one.y.size(), 3000u);
  for (int threads : {2, 3}) {
    Result many = runStep(threads);
    ASSERT_EQ(many.y.size(), one.y.size());
    EXPECT_EQ(std::memcmp(many.f.data(), one.f.data(), 3000 * sizeof(double)),
              0)
        << threads << " threads";
    EXPECT_EQ(std::memcmp(many.y.data(), one.y.data(), 3000 * sizeof(double)),
              0)
        << threads << " threads";
    EXPECT_EQ(std::memcmp(&many.total, &one.total, sizeof(double)), 0)
        << threads << " threads: " << many.total << " vs " << one.total;
  }
}

TEST(ThreadsTest, AgreesWithLongDoubleToRounding) {
  Result result = runStep(2);
  ASSERT_EQ(result.y.size(), 3000u);
  Graph graph;
  std::vector<long double> f(3000, 0), y(3000, 0), fSize(3000, 0),
      ySize(3000, 0);
  for (int e = 0; e < graph.springs.size(); ++e) {
    int a = graph.springs.endpoint(e, 0), b = graph.springs.endpoint(e, 1);
    long double k = graph.k.get(e), d = graph.x.get(b) - graph.x.get(a);
    f[a] += k * d;
    f[b] -= k * d;
    fSize[a] += std::fabs(k * d);
    fSize[b] += std::fabs(k * d);
    // K x: row a gets k (x_a - x_b), row b gets k (x_b - x_a).
    y[a] -= k * d;
    y[b] += k * d;
    ySize[a] += std::fabs(k * graph.x.get(a)) + std::fabs(k * graph.x.get(b));
    ySize[b] += std::fabs(k * graph.x.get(a)) + std::fabs(k * graph.x.get(b));
  }
  long double total = 0, totalSize = 0;
  for (int i = 0; i < 3000; ++i) {
    // Sums of n terms are within n epsilon of the sum of their magnitudes.
    EXPECT_NEAR(result.f[i], static_cast<double>(f[i]),
                256 * 1e-16 * static_cast<double>(fSize[i]))
        << i;
    EXPECT_NEAR(result.y[i], static_cast<double>(y[i]),
                256 * 1e-16 * static_cast<double>(ySize[i]))
        << i;
    total += static_cast<long double>(result.y[i]) * result.f[i];
    totalSize += std::fabs(static_cast<long double>(result.y[i]) * result.f[i]);
  }
  EXPECT_NEAR(result.total, static_cast<double>(total),
              1e-12 * static_cast<double>(totalSize));
}

TEST(ThreadsTest, ResolvesTheNumberOfThreads) {
  llvm::Expected<int> three = resolveThreadCount(3);
  ASSERT_TRUE(!!three);
  EXPECT_EQ(*three, 3);
  EXPECT_EQ(message(resolveThreadCount(-1).takeError()),
            "the number of threads must be positive, not -1");
  const char *saved = std::getenv("SIMIT_NUM_THREADS");
  std::string previous = saved ? saved : "";
  setenv("SIMIT_NUM_THREADS", "5", 1);
  llvm::Expected<int> five = resolveThreadCount(0);
  ASSERT_TRUE(!!five);
  EXPECT_EQ(*five, 5);
  setenv("SIMIT_NUM_THREADS", "many", 1);
  EXPECT_EQ(message(resolveThreadCount(0).takeError()),
            "SIMIT_NUM_THREADS must be a positive integer, not 'many'");
  unsetenv("SIMIT_NUM_THREADS");
  llvm::Expected<int> cores = resolveThreadCount(0);
  ASSERT_TRUE(!!cores);
  EXPECT_GE(*cores, 1);
  if (saved)
    setenv("SIMIT_NUM_THREADS", previous.c_str(), 1);

  // A malformed request is the compile's error.
  ProgramOptions options;
  options.threads = -2;
  Program program(options);
  ASSERT_EQ(message(program.loadString(kSprings, "springs.sim")), "success");
  llvm::Expected<Function> step = program.compile("step");
  EXPECT_EQ(message(step.takeError()),
            "the number of threads must be positive, not -2");
}
