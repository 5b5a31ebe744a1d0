//===--- ConformanceCases.cpp - What the conformance suite runs -----------===//

#include "ConformanceCases.h"

#include "llvm/ADT/STLExtras.h"

using namespace simit;
using namespace simit::conformance;

const Fields simit::conformance::kOperandFields[2] = {{"k", "B"}, {"l", "C"}};
const Fields simit::conformance::kShiftFields = {"s", "I"};

namespace {
/// Every endpoint pair (i, j) of an element of `cardinality` endpoints,
/// coefficient i * cardinality + j: the whole (non-symmetric) element
/// matrix.
std::vector<BlockWrite> allEndpointPairs(int cardinality) {
  std::vector<BlockWrite> writes;
  for (int i = 0; i < cardinality; ++i)
    for (int j = 0; j < cardinality; ++j)
      writes.push_back({i, j, i * cardinality + j});
  return writes;
}
} // namespace

const std::vector<Source> &simit::conformance::allSources() {
  static const std::vector<Source> sources = {
      {"diag",
       SetId::Verts,
       SetId::Verts,
       SetId::Verts,
       {{kElement, kElement, 0}}},
      {"springs", SetId::Springs, SetId::Verts, SetId::Verts,
       allEndpointPairs(2)},
      {"tris", SetId::Tris, SetId::Verts, SetId::Verts, allEndpointPairs(3)},
      {"tets", SetId::Tets, SetId::Verts, SetId::Verts, allEndpointPairs(4)},
      // Heterogeneous endpoint sets: (verts, nodes) and (verts, nodes,
      // nodes) patterns, and the first one written as (nodes, verts).
      {"links", SetId::Links, SetId::Verts, SetId::Nodes, {{0, 1, 0}}},
      {"hinges",
       SetId::Hinges,
       SetId::Verts,
       SetId::Nodes,
       {{0, 1, 0}, {0, 2, 1}}},
      {"linksT", SetId::Links, SetId::Nodes, SetId::Verts, {{1, 0, 0}}},
      // Incidence: the edge set itself is a dimension.
      {"incidence",
       SetId::Springs,
       SetId::Springs,
       SetId::Verts,
       {{kElement, 0, 0}, {kElement, 1, 1}}},
      {"incidenceT",
       SetId::Springs,
       SetId::Verts,
       SetId::Springs,
       {{0, kElement, 0}, {1, kElement, 1}}},
  };
  return sources;
}

const Source &simit::conformance::shiftSource() {
  static const Source shift = {"shift",
                               SetId::Verts,
                               SetId::Verts,
                               SetId::Verts,
                               {{kElement, kElement, 0}}};
  return shift;
}

Eigen::MatrixXd simit::conformance::denseMatrix(const Source &source,
                                                const Fields &fields,
                                                Scene &scene) {
  int b = scene.blockSize();
  Set &mapped = scene.set(source.mapped);
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(
      scene.set(source.rows).size() * b, scene.set(source.cols).size() * b);
  auto position = [&](int element, int endpoint) {
    return endpoint == kElement ? element : mapped.endpoint(element, endpoint);
  };
  for (int e = 0; e < mapped.size(); ++e)
    for (const BlockWrite &write : source.writes) {
      double coefficient = scene.coefficient(source.mapped, fields.coefficients,
                                             e, write.coefficient);
      Eigen::MatrixXd block = Eigen::MatrixXd::Constant(1, 1, coefficient);
      if (b == 3)
        block = coefficient * scene.blockField(source.mapped, fields.block, e);
      result.block(position(e, write.row) * b, position(e, write.col) * b, b,
                   b) += block;
    }
  return result;
}

namespace {
using Shape = std::optional<std::pair<SetId, SetId>>;
using Sources = llvm::ArrayRef<const Source *>;

Shape sameShape(Sources sources) {
  for (const Source *source : sources)
    if (source->rows != sources[0]->rows || source->cols != sources[0]->cols)
      return std::nullopt;
  return std::make_pair(sources[0]->rows, sources[0]->cols);
}

Shape ownShape(Sources sources) { return sameShape(sources.take_front()); }

Shape transposedShape(Sources sources) {
  return std::make_pair(sources[0]->cols, sources[0]->rows);
}

/// Square matrices over verts (where solves add the shift).
Shape squareOnVerts(Sources sources) {
  Shape shape = sameShape(sources);
  if (shape != std::make_pair(SetId::Verts, SetId::Verts))
    return std::nullopt;
  return shape;
}

Shape squareSameShape(Sources sources) {
  Shape shape = sameShape(sources);
  if (!shape || shape->first != shape->second)
    return std::nullopt;
  return shape;
}

/// A ./ B is defined where B's pattern holds A's: operands of one source.
Shape oneSource(Sources sources) {
  if (sources[0] != sources[1])
    return std::nullopt;
  return ownShape(sources);
}

/// Three different sources, each set of three once.
Shape threeDifferentSources(Sources sources) {
  if (!(sources[0] < sources[1] && sources[1] < sources[2]))
    return std::nullopt;
  return sameShape(sources);
}

Shape transposedSumShape(Sources sources) {
  if (sources[0]->cols != sources[1]->rows ||
      sources[0]->rows != sources[1]->cols)
    return std::nullopt;
  return std::make_pair(sources[1]->rows, sources[1]->cols);
}

Shape productShape(Sources sources) {
  if (sources[0]->cols != sources[1]->rows)
    return std::nullopt;
  return std::make_pair(sources[0]->rows, sources[1]->cols);
}

/// A B C, each factor's columns the next one's rows.
Shape chainOfThreeShape(Sources sources) {
  if (sources[0]->cols != sources[1]->rows ||
      sources[1]->cols != sources[2]->rows)
    return std::nullopt;
  return std::make_pair(sources[0]->rows, sources[2]->cols);
}

/// A chain of three different sources, each set of three once (207 chains
/// would be too many to compile).
Shape chainOfThreeDifferent(Sources sources) {
  if (!(sources[0] < sources[1] && sources[1] < sources[2]))
    return std::nullopt;
  return chainOfThreeShape(sources);
}

/// A chain A B A of two different sources (A' A-like sandwiches).
Shape sandwichShape(Sources sources) {
  if (sources[0] != sources[2] || sources[0] == sources[1])
    return std::nullopt;
  return chainOfThreeShape(sources);
}

/// A B + (A B)' of two different sources whose product is square.
Shape productPlusTransposedShape(Sources sources) {
  Shape shape = productShape(sources);
  if (sources[0] == sources[1] || !shape || shape->first != shape->second)
    return std::nullopt;
  return shape;
}

/// A B + A: B square over A's columns.
Shape productPlusFirstShape(Sources sources) {
  if (sources[1]->rows != sources[1]->cols)
    return std::nullopt;
  return productShape(sources);
}

/// (A B)' and (A B)(A B)' for two different sources (the product with
/// itself is `product` and `productTransposed` already).
Shape productOfTwoDifferent(Sources sources) {
  if (sources[0] == sources[1])
    return std::nullopt;
  return productShape(sources);
}

Shape transposeOfProductShape(Sources sources) {
  Shape shape = productOfTwoDifferent(sources);
  if (!shape)
    return std::nullopt;
  return std::make_pair(shape->second, shape->first);
}

Shape productTimesItsTransposeShape(Sources sources) {
  Shape shape = productOfTwoDifferent(sources);
  if (!shape)
    return std::nullopt;
  return std::make_pair(shape->first, shape->first);
}

Shape transposedProductShape(Sources sources) {
  if (sources[0]->rows != sources[1]->rows)
    return std::nullopt;
  return std::make_pair(sources[0]->cols, sources[1]->cols);
}

Shape productTransposedShape(Sources sources) {
  if (sources[0]->cols != sources[1]->cols)
    return std::nullopt;
  return std::make_pair(sources[0]->rows, sources[1]->rows);
}

/// A ./ B, with 0 where both are 0 (outside the pattern both share).
Eigen::MatrixXd quotientOnPattern(const Eigen::MatrixXd &a,
                                  const Eigen::MatrixXd &b) {
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(a.rows(), a.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      if (b(i, j) != 0.0)
        result(i, j) = a(i, j) / b(i, j);
  return result;
}

/// A + B with 1 added to every component of its diagonal blocks.
Eigen::MatrixXd diagonalBlocksPlusOne(const DenseInputs &in) {
  Eigen::MatrixXd result = in.operands[0] + in.operands[1];
  int b = in.blockSize;
  for (Eigen::Index q = 0; q < result.rows() / b; ++q)
    result.block(q * b, q * b, b, b).array() += 1.0;
  return result;
}

Eigen::MatrixXd scalar(double value) {
  return Eigen::MatrixXd::Constant(1, 1, value);
}
} // namespace

const std::vector<Operation> &simit::conformance::allOperations() {
  using M = Observed;
  static const std::vector<Operation> operations = {
      {"sum", 2, M::Matrix, "", "A + B", sameShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] + in.operands[1];
       }},
      {"difference", 2, M::Matrix, "", "A - B", sameShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] - in.operands[1];
       }},
      {"elementwiseProduct", 2, M::Matrix, "", "A .* B", sameShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0].cwiseProduct(in.operands[1]);
       }},
      {"elementwiseQuotient", 2, M::Matrix, "", "A ./ B", oneSource,
       [](const DenseInputs &in) {
         return quotientOnPattern(in.operands[0], in.operands[1]);
       }},
      {"scaled", 1, M::Matrix, "", "2.0 * A", ownShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return 2.0 * in.operands[0];
       }},
      {"negated", 1, M::Matrix, "", "-A", ownShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return -in.operands[0];
       }},
      {"transposed", 1, M::Matrix, "", "A'", transposedShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0].transpose();
       }},
      {"transposedSum", 2, M::Matrix, "", "A' + B", transposedSumShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0].transpose() + in.operands[1];
       }},
      {"sumOfThree", 3, M::Matrix, "", "A + B + C", threeDifferentSources,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] + in.operands[1] + in.operands[2];
       }},
      {"product", 2, M::Matrix, "", "A * B", productShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] * in.operands[1];
       }},
      // Products of products: the result is stored on the bind-time
      // pattern of the chain, whichever way it is associated.
      {"productOfThree", 3, M::Matrix, "", "(A * B) * C", chainOfThreeDifferent,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] * in.operands[1] * in.operands[2];
       }},
      {"productOfThreeRight", 3, M::Matrix, "", "A * (B * C)", sandwichShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] * (in.operands[1] * in.operands[2]);
       }},
      // A product's pattern need not be symmetric: its transpose holds
      // blocks the product does not, which the fused loop must visit.
      // (Stored, their union has no layout yet: a located error.)
      {"productPlusTransposedMatvec", 2, M::Vector,
       "  $R0.y = (A * B + (A * B)') * $R0.x;\n", "",
       productPlusTransposedShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         Eigen::MatrixXd p = in.operands[0] * in.operands[1];
         return (p + p.transpose()) * in.xRows;
       }},
      // Sums of products stored in a variable: on the union of the
      // patterns of the chains of factors (and of a pattern).
      {"productPlusItsTranspose", 2, M::Matrix, "", "A * B + (A * B)'",
       productPlusTransposedShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         Eigen::MatrixXd p = in.operands[0] * in.operands[1];
         return p + p.transpose();
       }},
      {"productPlusFactor", 2, M::Matrix, "", "A * B + A",
       productPlusFirstShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] * in.operands[1] + in.operands[0];
       }},
      // The transpose of a product is the product of the transposed
      // factors, reversed: stored on its own chain pattern.
      {"transposeOfProduct", 2, M::Matrix, "", "(A * B)'",
       transposeOfProductShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return (in.operands[0] * in.operands[1]).transpose();
       }},
      {"productTimesItsTranspose", 2, M::Matrix, "", "(A * B) * (A * B)'",
       productTimesItsTransposeShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         Eigen::MatrixXd p = in.operands[0] * in.operands[1];
         return p * p.transpose();
       }},
      {"transposedProduct", 2, M::Matrix, "", "A' * B", transposedProductShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0].transpose() * in.operands[1];
       }},
      {"productTransposed", 2, M::Matrix, "", "A * B'", productTransposedShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] * in.operands[1].transpose();
       }},
      {"transposedMatvec", 1, M::Vector, "  $C0.y = A' * $R0.x;\n", "",
       transposedShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0].transpose() * in.xRows;
       }},
      // Blocks read one at a time, zero outside the pattern (language.md
      // 7.5): y = (A + B) x.
      {"componentRead", 2, M::Vector,
       "  N = A + B;\n"
       "  $R0.y = 0.0;\n"
       "  for q in $R0\n"
       "    for r in $C0\n"
       "      $R0.y(q) = $R0.y(q) + N(q,r) * $C0.x(r);\n"
       "    end\n"
       "  end\n",
       "", sameShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return (in.operands[0] + in.operands[1]) * in.xCols;
       }},
      {"componentUpdate", 2, M::Matrix,
       "  var N = A + B;\n"
       "  for q in $R0\n"
       "    N(q,q) = 1.0 + N(q,q);\n"
       "  end\n",
       "N", squareSameShape, diagonalBlocksPlusOne},
      {"rowSlices", 1, M::Vector,
       "  for q in $R0\n    $R0.y(q) = A(q,:) * $C0.x;\n  end\n", "", ownShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0] * in.xCols;
       }},
      // A column transposed is a row of A' (its blocks transposed).
      {"columnSlices", 1, M::Vector,
       "  for q in $C0\n    $C0.y(q) = A(:,q)' * $R0.x;\n  end\n", "",
       transposedShape,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return in.operands[0].transpose() * in.xRows;
       }},
      {"symmetricSolve", 1, M::Vector, "  $R0.y = (A + A' + S) \\ $R0.x;\n", "",
       squareOnVerts,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         Eigen::MatrixXd a = in.operands[0];
         return (a + a.transpose() + in.shift).lu().solve(in.xRows);
       },
       1e-9, /*shifted=*/true},
      {"solve", 1, M::Vector, "  $R0.y = (A + S) \\ $R0.x;\n", "",
       squareOnVerts,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return (in.operands[0] + in.shift).lu().solve(in.xRows);
       },
       1e-9, /*shifted=*/true},
      {"solveOfSum", 2, M::Vector, "  $R0.y = (A + B + S) \\ $R0.x;\n", "",
       squareOnVerts,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return (in.operands[0] + in.operands[1] + in.shift)
             .lu()
             .solve(in.xRows);
       },
       1e-9, /*shifted=*/true},
      // The factorisation intrinsics of section 9, on matrices of scalars.
      {"luSolve", 1, M::Vector,
       "  h = lu(A + S);\n"
       "  $R0.y = lusolve<$R0,$R0>(h, $R0.x);\n"
       "  lufree(h);\n",
       "", squareOnVerts,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         return (in.operands[0] + in.shift).lu().solve(in.xRows);
       },
       1e-9, /*shifted=*/true, /*scalarBlocksOnly=*/true},
      {"cholSolve", 1, M::Vector,
       "  h = chol(A + A' + S);\n"
       "  $R0.y = lltsolve<$R0,$R0>(h, $R0.x);\n"
       "  cholfree(h);\n",
       "", squareOnVerts,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         Eigen::MatrixXd a = in.operands[0];
         return (a + a.transpose() + in.shift).llt().solve(in.xRows);
       },
       1e-9, /*shifted=*/true, /*scalarBlocksOnly=*/true},
      {"luMatSolve", 2, M::Vector,
       "  h = lu(A + S);\n"
       "  X = lumatsolve<$R0,$R0,$R0>(h, B);\n"
       "  lufree(h);\n"
       "  $R0.y = X * $R0.x;\n",
       "", squareOnVerts,
       [](const DenseInputs &in) -> Eigen::
                                     MatrixXd {
                                       return (in.operands[0] + in.shift)
                                           .lu()
                                           .solve(in.operands[1] * in.xRows);
                                     },
       1e-9, /*shifted=*/true, /*scalarBlocksOnly=*/true},
      {"cholMatSolve", 2, M::Vector,
       "  h = chol(A + A' + S);\n"
       "  X = lltmatsolve<$R0,$R0,$R0>(h, B);\n"
       "  cholfree(h);\n"
       "  $R0.y = X * $R0.x;\n",
       "", squareOnVerts,
       [](const DenseInputs &in) -> Eigen::
                                     MatrixXd {
                                       Eigen::MatrixXd a = in.operands[0];
                                       return (a + a.transpose() + in.shift)
                                           .llt()
                                           .solve(in.operands[1] * in.xRows);
                                     },
       1e-9, /*shifted=*/true, /*scalarBlocksOnly=*/true},
      // The lower triangle of the matrix of components.
      {"triangularSolve", 1, M::Vector,
       "  $R0.y = triangularSolve<$R0,$R0>(A + S, $R0.x);\n", "", squareOnVerts,
       [](const DenseInputs &in) -> Eigen::MatrixXd {
         Eigen::MatrixXd a = in.operands[0] + in.shift;
         return a.triangularView<Eigen::Lower>().solve(in.xRows);
       },
       1e-9, /*shifted=*/true, /*scalarBlocksOnly=*/true},
      {"dot", 1, M::Scalar, "", "dot(A * $C0.x, $R0.w)", ownShape,
       [](const DenseInputs &in) {
         return scalar(in.wRows.dot(in.operands[0] * in.xCols));
       }},
      {"norm", 1, M::Scalar, "", "norm(A * $C0.x)", ownShape,
       [](const DenseInputs &in) {
         return scalar((in.operands[0] * in.xCols).norm());
       }},
  };
  return operations;
}

std::string Case::name() const {
  std::string result = operation->name;
  for (const Source *source : sources)
    result += std::string("_") + source->name;
  return result + (blockSize == 1 ? "_1x1" : "_3x3");
}

std::pair<SetId, SetId> Case::shape() const {
  return *operation->shape(sources);
}

namespace {
/// Appends a case for every tuple of `arity` sources the operation is
/// defined on.
void addTuples(const Operation &operation, int blockSize,
               std::vector<const Source *> &prefix, std::vector<Case> &cases) {
  if (prefix.size() == operation.arity) {
    if (operation.shape(prefix))
      cases.push_back({&operation, prefix, blockSize});
    return;
  }
  for (const Source &source : allSources()) {
    prefix.push_back(&source);
    addTuples(operation, blockSize, prefix, cases);
    prefix.pop_back();
  }
}
} // namespace

std::vector<Case> simit::conformance::allCases() {
  std::vector<Case> cases;
  for (int blockSize : {1, 3})
    for (const Operation &operation : allOperations()) {
      if (operation.scalarBlocksOnly && blockSize != 1)
        continue;
      std::vector<const Source *> prefix;
      addTuples(operation, blockSize, prefix, cases);
    }
  return cases;
}
