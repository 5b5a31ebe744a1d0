//===- StorageTest.cpp - #simit.storage builders, containment, join -------===//

#include "simit/Dialect/Simit/IR/SimitStorage.h"

#include "mlir/AsmParser/AsmParser.h"
#include "mlir/IR/Diagnostics.h"
#include "mlir/IR/MLIRContext.h"

#include <gtest/gtest.h>

using namespace mlir;
using namespace mlir::simit;

namespace {
class StorageTest : public ::testing::Test {
protected:
  StorageTest() { ctx.loadDialect<SimitDialect>(); }

  StringAttr name(StringRef s) { return StringAttr::get(&ctx, s); }
  StorageAttr diag(StringRef set) { return storage::diag(name(set)); }
  StorageAttr pattern(StringRef edges, ArrayRef<int64_t> rows,
                      ArrayRef<int64_t> cols) {
    return storage::pattern(name(edges), rows, cols);
  }
  StorageAttr incidence(StringRef edges, ArrayRef<int64_t> cols) {
    return storage::incidence(name(edges), cols);
  }
  StorageAttr stencil(StringRef grid, ArrayRef<SmallVector<int64_t>> offsets) {
    return storage::stencil(name(grid), offsets);
  }
  /// The encoding `#simit.storage<body>`, or null with the parser's error
  /// in `error`.
  StorageAttr parse(StringRef body) {
    error.clear();
    ScopedDiagnosticHandler handler(&ctx, [&](Diagnostic &diag) {
      error = diag.str();
      return success();
    });
    std::string text = ("#simit.storage<" + body + ">").str();
    return dyn_cast_or_null<StorageAttr>(parseAttribute(text, &ctx));
  }

  MLIRContext ctx;
  std::string error;
};

TEST_F(StorageTest, BuildersSortPositionsAndOffsets) {
  EXPECT_EQ(pattern("springs", {1, 0, 1}, {1, 0}).str(),
            "pattern(\"springs\", rows [0, 1], cols [0, 1])");
  EXPECT_EQ(stencil("cells", {{1, 0}, {-1, 0}}).str(),
            "stencil(\"cells\", [[-1, 0], [0, 0], [1, 0]])");
  EXPECT_EQ(incidence("springs", {1, 0}), incidence("springs", {0, 1}));
}

TEST_F(StorageTest, TransposeCanonicalises) {
  StorageAttr a = incidence("springs", {0, 1});
  EXPECT_EQ(storage::transpose(storage::transpose(a)), a);
  EXPECT_EQ(storage::transpose(diag("points")), diag("points"));
  StorageAttr empty = storage::empty(&ctx);
  EXPECT_EQ(storage::transpose(empty), empty);
  EXPECT_EQ(storage::transpose(a).str(),
            "transpose(incidence(\"springs\", cols [0, 1]))");
  EXPECT_EQ(storage::transpose(storage::lowRank(a, 1)),
            storage::lowRank(storage::transpose(a), 1));
  // (K H)' = H' K': the product of the transposed factors, reversed.
  StorageAttr k = pattern("springs", {0, 1}, {0, 1});
  StorageAttr h = pattern("hinges", {0, 1, 2}, {0, 1, 2});
  StorageAttr kh = storage::product({k, h});
  EXPECT_EQ(storage::transpose(kh),
            storage::product({storage::transpose(h), storage::transpose(k)}));
  EXPECT_EQ(storage::transpose(storage::transpose(kh)), kh);
  EXPECT_EQ(storage::product({kh, storage::transpose(kh)}).getMembers().size(),
            4u);
}

TEST_F(StorageTest, UnionFlattensSortsAndDropsContainedMembers) {
  StorageAttr springs = pattern("springs", {0, 1}, {0, 1});
  StorageAttr hinges = pattern("hinges", {0, 1}, {0, 1});
  StorageAttr u = storage::unionOf({springs, diag("points"), hinges, springs});
  // diag is contained in the square patterns; members sort by their text.
  EXPECT_EQ(u.str(), "union(pattern(\"hinges\", rows [0, 1], cols [0, 1]), "
                     "pattern(\"springs\", rows [0, 1], cols [0, 1]))");
  EXPECT_EQ(storage::unionOf({hinges, u}), u);
  EXPECT_EQ(storage::unionOf({springs}), springs);
  EXPECT_EQ(storage::unionOf({storage::empty(&ctx), springs}), springs);
  EXPECT_EQ(storage::unionOf({springs, storage::dense(&ctx)}),
            storage::dense(&ctx));
}

TEST_F(StorageTest, UnionOfStencilsOfOneGridIsOneStencil) {
  StorageAttr a = stencil("cells", {{1, 0}});
  StorageAttr b = stencil("cells", {{0, 1}});
  EXPECT_EQ(storage::unionOf({a, b}), stencil("cells", {{1, 0}, {0, 1}}));
  StorageAttr other = stencil("faces", {{0, 1}});
  EXPECT_EQ(storage::unionOf({a, other}).getKind(), StorageKind::Union);
}

TEST_F(StorageTest, ProductDropsDiagonalsAndComposesIncidences) {
  StorageAttr p = incidence("springs", {0});
  StorageAttr q = incidence("springs", {1});
  EXPECT_EQ(storage::product({storage::transpose(p), diag("springs"), q}),
            pattern("springs", {0}, {1}));
  StorageAttr k = pattern("springs", {0, 1}, {0, 1});
  EXPECT_EQ(storage::product({diag("points"), k}), k);
  EXPECT_EQ(storage::product({diag("points"), diag("points")}),
            diag("points"));
  StorageAttr kk = storage::product({k, k});
  EXPECT_EQ(kk.getKind(), StorageKind::Product);
  EXPECT_EQ(storage::product({kk, k}), storage::product({k, k, k}));
  EXPECT_EQ(storage::product({k, storage::empty(&ctx)}), storage::empty(&ctx));
  // A dense factor (lumatsolve's solution) makes the product dense.
  StorageAttr dense = storage::dense(&ctx);
  EXPECT_EQ(storage::product({dense, k}), dense);
  EXPECT_EQ(storage::product({storage::transpose(p), dense}), dense);
  EXPECT_EQ(storage::transpose(dense), dense);
}

// A periodic stencil's transpose is the stencil of the negated offsets,
// and a product of stencils of one grid the stencil of the sums.
TEST_F(StorageTest, StencilsTransposeAndComposeIntoStencils) {
  StorageAttr right = stencil("cells", {{1, 0}});
  EXPECT_EQ(storage::transpose(right), stencil("cells", {{-1, 0}}));
  EXPECT_EQ(storage::transpose(storage::transpose(right)), right);
  EXPECT_EQ(storage::unionOf({right, storage::transpose(right)}),
            stencil("cells", {{1, 0}, {-1, 0}}));
  StorageAttr laplace = stencil("cells", {{1, 0}, {-1, 0}});
  EXPECT_EQ(storage::product({laplace, laplace}),
            stencil("cells", {{2, 0}, {1, 0}, {-1, 0}, {-2, 0}}));
  EXPECT_EQ(storage::product({right, diag("points"), right}),
            stencil("cells", {{1, 0}, {2, 0}}));
  // Stencils of other grids do not compose.
  EXPECT_EQ(storage::product({right, stencil("faces", {{1, 0}})}).getKind(),
            StorageKind::Product);
}

// Two host calls may return any two patterns: a host encoding holds only
// itself, and joins with anything else into a union.
TEST_F(StorageTest, HostPatternsContainOnlyThemselves) {
  StringAttr f = StringAttr::get(&ctx, "f");
  StorageAttr first = storage::host(f, 0), second = storage::host(f, 1);
  EXPECT_EQ(first.str(), "host(\"f\", 0)");
  EXPECT_EQ(storage::host(f, 0), first);
  EXPECT_TRUE(storage::contains(first, first));
  EXPECT_TRUE(storage::contains(storage::dense(&ctx), first));
  EXPECT_TRUE(storage::contains(first, storage::empty(&ctx)));
  EXPECT_FALSE(storage::contains(first, second));
  EXPECT_FALSE(storage::contains(first, diag("points")));
  StorageAttr k = pattern("springs", {0, 1}, {0, 1});
  EXPECT_FALSE(storage::contains(k, first));
  EXPECT_EQ(storage::join(first, first), first);
  EXPECT_EQ(storage::join(first, second).getKind(), StorageKind::Union);
  EXPECT_EQ(storage::join(first, k).getKind(), StorageKind::Union);
  EXPECT_EQ(storage::transpose(first).getKind(), StorageKind::Transpose);
}

TEST_F(StorageTest, LowRankAccumulatesTerms) {
  StorageAttr k = pattern("springs", {0, 1}, {0, 1});
  EXPECT_EQ(storage::lowRank(k, 0), k);
  EXPECT_EQ(storage::lowRank(storage::lowRank(k, 1), 2), storage::lowRank(k, 3));
}

TEST_F(StorageTest, Containment) {
  StorageAttr k = pattern("springs", {0, 1}, {0, 1});
  StorageAttr k0 = pattern("springs", {0}, {0, 1});
  StorageAttr h = pattern("hinges", {0, 1}, {0, 1});
  StorageAttr empty = storage::empty(&ctx), dense = storage::dense(&ctx);
  EXPECT_TRUE(storage::contains(k, k));
  EXPECT_TRUE(storage::contains(k, empty));
  EXPECT_TRUE(storage::contains(dense, k));
  EXPECT_FALSE(storage::contains(k, dense));
  EXPECT_FALSE(storage::contains(empty, k));
  // Square patterns and stencils hold the diagonal; positions by subset.
  EXPECT_TRUE(storage::contains(k, diag("points")));
  EXPECT_FALSE(storage::contains(diag("points"), k));
  EXPECT_TRUE(storage::contains(stencil("cells", {{1}}), diag("points")));
  EXPECT_TRUE(storage::contains(k, k0));
  EXPECT_FALSE(storage::contains(k0, k));
  EXPECT_FALSE(storage::contains(k, h));
  EXPECT_TRUE(storage::contains(stencil("cells", {{1}, {-1}}),
                                stencil("cells", {{1}})));
  EXPECT_FALSE(storage::contains(stencil("cells", {{1}}),
                                 stencil("cells", {{-1}})));
  EXPECT_TRUE(storage::contains(incidence("springs", {0, 1}),
                                incidence("springs", {1})));
  // Unions contain what a member contains, and their members' union.
  StorageAttr u = storage::unionOf({k0, h});
  EXPECT_TRUE(storage::contains(u, h));
  EXPECT_TRUE(storage::contains(u, pattern("springs", {0}, {1})));
  EXPECT_FALSE(storage::contains(u, k));
  EXPECT_TRUE(storage::contains(storage::unionOf({k, h}), u));
  // Transpose and lowrank are monotone.
  EXPECT_TRUE(storage::contains(storage::transpose(k), storage::transpose(k0)));
  EXPECT_FALSE(storage::contains(storage::transpose(k0), storage::transpose(k)));
  EXPECT_TRUE(storage::contains(storage::transpose(k), diag("points")));
  EXPECT_TRUE(storage::contains(storage::lowRank(k, 2), storage::lowRank(k0, 1)));
  EXPECT_FALSE(storage::contains(storage::lowRank(k, 1), storage::lowRank(k, 2)));
  EXPECT_FALSE(storage::contains(k, storage::lowRank(k, 1)));
}

TEST_F(StorageTest, JoinPrefersAnExistingEncoding) {
  StorageAttr k = pattern("springs", {0, 1}, {0, 1});
  StorageAttr h = pattern("hinges", {0, 1}, {0, 1});
  EXPECT_EQ(storage::join(diag("points"), k), k);
  EXPECT_EQ(storage::join(k, diag("points")), k);
  EXPECT_EQ(storage::join(k, storage::empty(&ctx)), k);
  StorageAttr kh = storage::join(k, h);
  EXPECT_EQ(kh, storage::join(h, k));
  EXPECT_EQ(kh, storage::unionOf({h, k}));
  EXPECT_EQ(storage::join(kh, diag("points")), kh);
}

TEST_F(StorageTest, ParsePrintRoundTrip) {
  for (StringRef body :
       {"dense", "empty", "diag(\"points\")",
        "pattern(\"links\", rows [0], cols [1])",
        "transpose(incidence(\"springs\", cols [0, 1]))",
        "stencil(\"cells\", [[-1, 0], [0, 0], [1, 0]])",
        "union(pattern(\"hinges\", rows [0], cols [1]), "
        "pattern(\"springs\", rows [0, 1], cols [0, 1]))",
        "product(pattern(\"springs\", rows [0, 1], cols [0, 1]), "
        "pattern(\"springs\", rows [0, 1], cols [0, 1]))",
        "lowrank(empty, 1)"}) {
    StorageAttr attr = parse(body);
    ASSERT_TRUE(attr) << body.str() << ": " << error;
    EXPECT_EQ(attr.str(), body.str());
  }
}

TEST_F(StorageTest, VerifierRejectsNonCanonicalText) {
  struct Case {
    StringRef body, message;
  } cases[] = {
      {"pattern(\"s\", rows [1, 0], cols [0])",
       "row positions must be non-negative, sorted, unique"},
      {"transpose(transpose(diag(\"p\")))", "is not canonical"},
      {"transpose(diag(\"p\"))", "is not canonical"},
      {"union(diag(\"p\"))", "needs two members or more"},
      {"union(pattern(\"s\", rows [0], cols [0]), diag(\"p\"))",
       "must be sorted and unique"},
      {"union(diag(\"p\"), pattern(\"s\", rows [0], cols [0]))",
       "is contained in"},
      {"union(pattern(\"s\", rows [0], cols [0, 1]), pattern(\"s\", rows "
       "[0], cols [1]))",
       "is contained in"},
      {"union(stencil(\"g\", [[-1], [0]]), stencil(\"g\", [[0], [1]]))",
       "one stencil per grid"},
      {"product(diag(\"p\"), pattern(\"s\", rows [0], cols [0]))",
       "cannot be 'diag'"},
      {"product(transpose(incidence(\"s\", cols [0])), incidence(\"s\", "
       "cols [1]))",
       "compose to a pattern"},
      {"stencil(\"g\", [[1]])", "must hold offset 0"},
      {"stencil(\"g\", [[0], [0, 1]])", "must all have rank 1"},
      {"lowrank(lowrank(empty, 1), 1)", "not canonical"},
      {"diag", "expected '('"},
      {"blocked(\"p\")", "unknown storage kind 'blocked'"},
  };
  for (const Case &c : cases) {
    EXPECT_FALSE(parse(c.body)) << c.body.str();
    EXPECT_NE(error.find(c.message.str()), std::string::npos)
        << c.body.str() << ": " << error;
  }
}
} // namespace
