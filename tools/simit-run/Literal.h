//===--- Literal.h - Simit literals of assertions and --eval --------------===//
//
// The literal values of `%!` assertions and of `--eval 'f(args)'`: read from
// the checked AST or parsed from the command line, converted to host buffers
// for a compiled function's parameters, compared with its results by the
// rules of language.md section 11, and printed back as Simit literals.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_TOOLS_SIMIT_RUN_LITERAL_H
#define SIMIT_TOOLS_SIMIT_RUN_LITERAL_H

#include "simit/Engine/Function.h"

#include "llvm/Support/Error.h"

#include <string>
#include <vector>

namespace simit {
namespace frontend {
class Expr;
} // namespace frontend

struct Literal {
  enum class Kind { Int, Float, Bool, Complex, String };
  Kind kind = Kind::Float;
  /// Dimensions, outer first; empty for a scalar.
  std::vector<int64_t> shape;
  /// A one-dimensional literal transposed into a column (`[1, 2]'`).
  bool column = false;
  /// Components row-major (Int and Bool exactly; Complex as re, im pairs).
  std::vector<double> values;
  std::string text; // String

  size_t numComponents() const;
};

/// The literal an assertion argument or expected value denotes (after
/// folding unary minus and plus and transposes).
llvm::Expected<Literal> literalFromExpr(const frontend::Expr &expr);

/// A call `name(literal, ...)` as given to --eval.
struct CallText {
  std::string function;
  std::vector<Literal> args;
};
llvm::Expected<CallText> parseCall(llvm::StringRef text);

/// "an int", "a float", ...: the kind of a literal, in errors.
llvm::StringRef kindName(Literal::Kind kind);

/// Host storage for a literal passed as a parameter of `type`; errors say
/// what does not match.
llvm::Error toHostBuffer(const Literal &literal, const ValueType &type,
                         std::vector<uint64_t> &storage,
                         std::vector<int> &shape, ComponentType &component);

/// Compares a result with the expected literal: ints and bools exactly,
/// floats equal when identical or within a relative 1e-3, an expected 0.0
/// only by an exact zero. An empty string when they match, else a reason.
std::string compareResult(const HostValue &actual, const Literal &expected);

/// Prints a result as a Simit literal: `2.5`, `[1, 2, 3]`, `[1, 2; 3, 4]`.
std::string formatValue(const HostValue &value);
std::string formatLiteral(const Literal &literal);

} // namespace simit

#endif // SIMIT_TOOLS_SIMIT_RUN_LITERAL_H
