//===--- ConformanceCases.h - What the conformance suite runs ---*- C++ -*-===//
//
// A case applies one operation of language.md sections 7-9 on system
// tensors to one, two or three matrices, each assembled by a map from a
// "source" (a set and the blocks its elements write: a vertex set's
// diagonal, the pattern of an edge set, a heterogeneous edge set's
// rectangular pattern, an incidence matrix). Each source is specified once,
// as data: the program generator (ConformanceProgram.h) turns it into a
// Simit function, and denseMatrix() into an Eigen matrix.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_UNITTESTS_ENGINE_CONFORMANCECASES_H
#define SIMIT_UNITTESTS_ENGINE_CONFORMANCECASES_H

#include "ConformanceScene.h"

#include <Eigen/Dense>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace simit::conformance {

/// The mapped element itself, where a write names a position instead of
/// an endpoint.
constexpr int kElement = -1;

/// One block written by every element: A(row, col) += coefficient * block,
/// where row and col are endpoint positions or kElement.
struct BlockWrite {
  int row;
  int col;
  int coefficient; // component of the coefficient vector
};

/// A matrix assembled by `map f to mapped reduce +` over (rows, cols).
struct Source {
  const char *name;
  SetId mapped;
  SetId rows;
  SetId cols;
  std::vector<BlockWrite> writes;
};

/// The fields an operand's element matrices are made of: coefficient
/// vector and 3x3 block (the block is used when the scene's are 3x3).
struct Fields {
  const char *coefficients;
  const char *block;
};

/// Operand i of a case reads the fields kOperandFields[i % 2]: two operands
/// from one source hold different values.
extern const Fields kOperandFields[2];
/// The fields of the diagonal shift added to the matrices of solves.
extern const Fields kShiftFields;

/// Every source (the diagonal shift of solves is separate).
const std::vector<Source> &allSources();
const Source &shiftSource();

/// The matrix `source` assembles with `fields` on `scene`, dense.
Eigen::MatrixXd denseMatrix(const Source &source, const Fields &fields,
                            Scene &scene);

/// What a case observes.
enum class Observed {
  /// The matrix M = expression, through M * x and M * w (M stored) and
  /// (expression) * x (fused): outputs y, z, u over M's rows.
  Matrix,
  /// The statements write output y over the first set of Case::shape().
  Vector,
  /// The function returns r = expression.
  Scalar,
};

/// The dense inputs of an operation: its operands, inputs x and w over the
/// first operand's rows and columns, and the shift S of solves.
struct DenseInputs {
  int blockSize;
  std::vector<Eigen::MatrixXd> operands;
  Eigen::VectorXd xRows, xCols, wRows;
  Eigen::MatrixXd shift;
};

/// The rows and columns of the result, or nothing where the operation is
/// not defined on operands of these sources.
using ShapeRule = std::function<std::optional<std::pair<SetId, SetId>>(
    llvm::ArrayRef<const Source *>)>;

struct Operation {
  const char *name;
  unsigned arity;
  Observed observed;
  /// Simit text on operands A, B, C (and S, the shift, in solves), with
  /// $R0/$C0 standing for the first operand's row and column sets:
  /// statements run first, then (Matrix, Scalar) the expression.
  const char *statements;
  const char *expression;
  ShapeRule shape;
  /// The dense result: a matrix (Matrix), a vector (Vector) or a 1x1
  /// matrix (Scalar).
  std::function<Eigen::MatrixXd(const DenseInputs &)> dense;
  /// Relative tolerance of the comparison.
  double tolerance = 1e-12;
  /// S, the diagonal shift, is assembled too.
  bool shifted = false;
  /// Defined on matrices of scalars only (the factorisation intrinsics).
  bool scalarBlocksOnly = false;
};

const std::vector<Operation> &allOperations();

/// One operation on operands from the given sources, on a scene of 1x1 or
/// 3x3 blocks.
struct Case {
  const Operation *operation;
  std::vector<const Source *> sources;
  int blockSize;

  /// The exported function's name, also the test's:
  /// "sum_springs_tris_3x3".
  std::string name() const;
  /// The row and column sets of the result (Matrix), or the output's set
  /// and the sets it is computed from (Vector).
  std::pair<SetId, SetId> shape() const;
};

/// Each operation on every tuple of sources it is defined on, for both
/// block sizes.
std::vector<Case> allCases();

} // namespace simit::conformance

#endif // SIMIT_UNITTESTS_ENGINE_CONFORMANCECASES_H
