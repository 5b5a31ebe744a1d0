//===--- SceneExpression.h - Tiny expressions over coordinates --*- C++ -*-===//
//
// The expression language of scene field initialisers (docs/scene-format.md):
// numbers, the element's coordinates x y z, the bounding box min_x .. max_z,
// true/false, + - * / (unary -), < <= > >= == !=, and or not, parentheses,
// and `a if cond else b`. Expressions are typed: arithmetic and comparisons
// take numbers, logic takes booleans, `if` takes a boolean condition and two
// branches of one type.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_SCENEEXPRESSION_H
#define SIMIT_RUNTIME_SCENEEXPRESSION_H

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"

#include <array>
#include <memory>

namespace simit {

/// What an expression can read: an element's coordinates and the bounding
/// box of the coordinates of its set.
struct CoordinateFrame {
  std::array<double, 3> position{};
  std::array<double, 3> min{};
  std::array<double, 3> max{};
};

class SceneExpression {
public:
  struct Node;

  /// Parses `text`; errors read "column N: expected ...".
  static llvm::Expected<SceneExpression> parse(llvm::StringRef text);

  SceneExpression(SceneExpression &&) noexcept;
  SceneExpression &operator=(SceneExpression &&) noexcept;
  ~SceneExpression();

  bool isBoolean() const;
  /// The value; booleans read as 1 and 0.
  double evaluate(const CoordinateFrame &frame) const;

private:
  explicit SceneExpression(std::unique_ptr<Node> root);
  std::unique_ptr<Node> root;
};

} // namespace simit

#endif // SIMIT_RUNTIME_SCENEEXPRESSION_H
