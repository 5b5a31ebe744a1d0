//===--- SceneExpression.cpp - Tiny expressions over coordinates ----------===//

#include "simit/Runtime/SceneExpression.h"

#include "TextReader.h"

#include "llvm/ADT/StringSwitch.h"

#include <cctype>
#include <cmath>

using namespace simit;

struct SceneExpression::Node {
  enum Kind {
    Number,
    Coordinate, // index = axis
    Minimum,    // index = axis
    Maximum,    // index = axis
    Negate,
    Not,
    Add,
    Subtract,
    Multiply,
    Divide,
    Less,
    LessEqual,
    Greater,
    GreaterEqual,
    Equal,
    NotEqual,
    And,
    Or,
    Select, // operands: condition, then, else
  };
  Kind kind;
  bool boolean = false;
  /// The longest path to a leaf, counting this node.
  unsigned height = 1;
  double value = 0;
  int index = 0;
  std::unique_ptr<Node> operands[3];
};

namespace {

using Node = SceneExpression::Node;

/// Parsing, evaluating and destroying an expression recurse on its nesting
/// and on the height of its tree, so both are bounded.
constexpr unsigned kMaxNesting = 200;
constexpr unsigned kMaxHeight = 1000;

class Parser {
public:
  explicit Parser(llvm::StringRef text) : text(text) {}

  llvm::Expected<std::unique_ptr<Node>> parseAll() {
    auto root = parseConditional();
    if (!root)
      return root.takeError();
    skipSpace();
    if (pos != text.size())
      return error("expected an operator or the end of the expression");
    return root;
  }

private:
  llvm::Error error(const llvm::Twine &message) const {
    return llvm::createStringError("column " + llvm::Twine(pos + 1) + ": " +
                                   message);
  }

  void skipSpace() {
    while (pos < text.size() &&
           std::isspace(static_cast<unsigned char>(text[pos])))
      ++pos;
  }

  /// Consumes `token` if the input continues with it (whole words for
  /// keywords).
  bool accept(llvm::StringRef token) {
    skipSpace();
    if (!text.substr(pos).starts_with(token))
      return false;
    if (std::isalpha(static_cast<unsigned char>(token[0]))) {
      size_t end = pos + token.size();
      if (end < text.size() &&
          (std::isalnum(static_cast<unsigned char>(text[end])) ||
           text[end] == '_'))
        return false;
    }
    pos += token.size();
    return true;
  }

  std::unique_ptr<Node> make(Node::Kind kind, bool boolean,
                             std::unique_ptr<Node> a = nullptr,
                             std::unique_ptr<Node> b = nullptr,
                             std::unique_ptr<Node> c = nullptr) {
    auto node = std::make_unique<Node>();
    node->kind = kind;
    node->boolean = boolean;
    node->operands[0] = std::move(a);
    node->operands[1] = std::move(b);
    node->operands[2] = std::move(c);
    for (const std::unique_ptr<Node> &operand : node->operands)
      if (operand)
        node->height = std::max(node->height, operand->height + 1);
    return node;
  }

  /// Counts one level of recursion of the parser; the error names the
  /// column where the limit was passed.
  class NestingGuard {
  public:
    explicit NestingGuard(Parser &parser) : parser(parser) {
      ++parser.nesting;
    }
    ~NestingGuard() { --parser.nesting; }
    bool tooDeep() const { return parser.nesting > kMaxNesting; }

  private:
    Parser &parser;
  };
  llvm::Error nestingError() const {
    return error("expression nested too deeply (more than " +
                 llvm::Twine(kMaxNesting) + " levels)");
  }
  /// Checks a new node's height; chains of binary operators grow the tree
  /// without recursing in the parser.
  llvm::Expected<std::unique_ptr<Node>> checked(std::unique_ptr<Node> node,
                                                size_t at) const {
    if (node->height <= kMaxHeight)
      return node;
    return llvm::createStringError("column " + llvm::Twine(at + 1) +
                                   ": expression nested too deeply (more "
                                   "than " +
                                   llvm::Twine(kMaxHeight) +
                                   " operators on one path)");
  }

  llvm::Error expectType(const Node &node, bool boolean, size_t at,
                         llvm::StringRef role) const {
    if (node.boolean == boolean)
      return llvm::Error::success();
    return llvm::createStringError(
        "column " + llvm::Twine(at + 1) + ": expected " +
        (boolean ? "a boolean" : "a number") + " " + role + ", found " +
        (node.boolean ? "a boolean" : "a number"));
  }

  // conditional := or ['if' or 'else' conditional]
  llvm::Expected<std::unique_ptr<Node>> parseConditional() {
    NestingGuard guard(*this);
    if (guard.tooDeep())
      return nestingError();
    auto thenValue = parseOr();
    if (!thenValue)
      return thenValue.takeError();
    skipSpace();
    size_t at = pos;
    if (!accept("if"))
      return thenValue;
    skipSpace();
    at = pos;
    auto condition = parseOr();
    if (!condition)
      return condition.takeError();
    if (auto err = expectType(**condition, true, at, "condition after 'if'"))
      return err;
    if (!accept("else"))
      return error("expected 'else'");
    size_t elseAt = pos;
    auto elseValue = parseConditional();
    if (!elseValue)
      return elseValue.takeError();
    if ((*thenValue)->boolean != (*elseValue)->boolean)
      return llvm::createStringError(
          "column " + llvm::Twine(elseAt + 1) +
          ": expected both branches of 'if' to have one type");
    bool boolean = (*thenValue)->boolean;
    return make(Node::Select, boolean, std::move(*condition),
                std::move(*thenValue), std::move(*elseValue));
  }

  // or := and ('or' and)*     and := not ('and' not)*
  llvm::Expected<std::unique_ptr<Node>> parseOr() { return parseLogic(true); }

  llvm::Expected<std::unique_ptr<Node>> parseLogic(bool isOr) {
    skipSpace();
    size_t at = pos;
    auto lhs = isOr ? parseLogic(false) : parseNot();
    if (!lhs)
      return lhs.takeError();
    while (true) {
      skipSpace();
      size_t opAt = pos;
      if (!accept(isOr ? "or" : "and"))
        return lhs;
      if (auto err = expectType(**lhs, true, at,
                                isOr ? "operand of 'or'" : "operand of 'and'"))
        return err;
      skipSpace();
      at = pos;
      auto rhs = isOr ? parseLogic(false) : parseNot();
      if (!rhs)
        return rhs.takeError();
      if (auto err = expectType(**rhs, true, at,
                                isOr ? "operand of 'or'" : "operand of 'and'"))
        return err;
      lhs = checked(make(isOr ? Node::Or : Node::And, true, std::move(*lhs),
                         std::move(*rhs)),
                    opAt);
      if (!lhs)
        return lhs.takeError();
    }
  }

  // not := 'not' not | comparison
  llvm::Expected<std::unique_ptr<Node>> parseNot() {
    if (!accept("not"))
      return parseComparison();
    NestingGuard guard(*this);
    if (guard.tooDeep())
      return nestingError();
    skipSpace();
    size_t at = pos;
    auto operand = parseNot();
    if (!operand)
      return operand.takeError();
    if (auto err = expectType(**operand, true, at, "operand of 'not'"))
      return err;
    return make(Node::Not, true, std::move(*operand));
  }

  // comparison := sum [('<' | '<=' | '>' | '>=' | '==' | '!=') sum]
  llvm::Expected<std::unique_ptr<Node>> parseComparison() {
    skipSpace();
    size_t at = pos;
    auto lhs = parseSum();
    if (!lhs)
      return lhs.takeError();
    Node::Kind kind;
    if (accept("<="))
      kind = Node::LessEqual;
    else if (accept(">="))
      kind = Node::GreaterEqual;
    else if (accept("=="))
      kind = Node::Equal;
    else if (accept("!="))
      kind = Node::NotEqual;
    else if (accept("<"))
      kind = Node::Less;
    else if (accept(">"))
      kind = Node::Greater;
    else
      return lhs;
    if (auto err = expectType(**lhs, false, at, "operand of a comparison"))
      return err;
    skipSpace();
    at = pos;
    auto rhs = parseSum();
    if (!rhs)
      return rhs.takeError();
    if (auto err = expectType(**rhs, false, at, "operand of a comparison"))
      return err;
    return make(kind, true, std::move(*lhs), std::move(*rhs));
  }

  // sum := product (('+' | '-') product)*
  // product := unary (('*' | '/') unary)*
  llvm::Expected<std::unique_ptr<Node>> parseArithmetic(bool isSum) {
    skipSpace();
    size_t at = pos;
    auto lhs = isSum ? parseArithmetic(false) : parseUnary();
    if (!lhs)
      return lhs.takeError();
    while (true) {
      skipSpace();
      size_t opAt = pos;
      Node::Kind kind;
      if (isSum && accept("+"))
        kind = Node::Add;
      else if (isSum && accept("-"))
        kind = Node::Subtract;
      else if (!isSum && accept("*"))
        kind = Node::Multiply;
      else if (!isSum && accept("/"))
        kind = Node::Divide;
      else
        return lhs;
      if (auto err = expectType(**lhs, false, at, "arithmetic operand"))
        return err;
      skipSpace();
      at = pos;
      auto rhs = isSum ? parseArithmetic(false) : parseUnary();
      if (!rhs)
        return rhs.takeError();
      if (auto err = expectType(**rhs, false, at, "arithmetic operand"))
        return err;
      lhs = checked(make(kind, false, std::move(*lhs), std::move(*rhs)), opAt);
      if (!lhs)
        return lhs.takeError();
    }
  }
  llvm::Expected<std::unique_ptr<Node>> parseSum() {
    return parseArithmetic(true);
  }

  // unary := '-' unary | primary
  llvm::Expected<std::unique_ptr<Node>> parseUnary() {
    if (!accept("-"))
      return parsePrimary();
    NestingGuard guard(*this);
    if (guard.tooDeep())
      return nestingError();
    skipSpace();
    size_t at = pos;
    auto operand = parseUnary();
    if (!operand)
      return operand.takeError();
    if (auto err = expectType(**operand, false, at, "operand of '-'"))
      return err;
    return make(Node::Negate, false, std::move(*operand));
  }

  // primary := number | name | '(' conditional ')'
  llvm::Expected<std::unique_ptr<Node>> parsePrimary() {
    skipSpace();
    if (pos >= text.size())
      return error("expected a number, a name or '(', found the end of the "
                   "expression");
    if (accept("(")) {
      auto inner = parseConditional();
      if (!inner)
        return inner.takeError();
      if (!accept(")"))
        return error("expected ')'");
      return inner;
    }
    char c = text[pos];
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      size_t start = pos;
      while (pos < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[pos])) ||
              text[pos] == '.' ||
              ((text[pos] == '+' || text[pos] == '-') &&
               (text[pos - 1] == 'e' || text[pos - 1] == 'E'))))
        ++pos;
      auto node = make(Node::Number, false);
      llvm::StringRef word = text.slice(start, pos);
      if (!detail::parseDoubleToken(word, node->value)) {
        pos = start;
        return error("expected a number, found '" + word + "'");
      }
      if (!std::isfinite(node->value)) {
        pos = start;
        return error("expected a finite number, found '" + word + "'");
      }
      return node;
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      size_t start = pos;
      while (pos < text.size() &&
             (std::isalnum(static_cast<unsigned char>(text[pos])) ||
              text[pos] == '_'))
        ++pos;
      llvm::StringRef name = text.slice(start, pos);
      if (name == "true" || name == "false") {
        auto node = make(Node::Number, true);
        node->value = name == "true";
        return node;
      }
      Node::Kind kind = Node::Coordinate;
      llvm::StringRef axisName = name;
      if (name.consume_front("min_"))
        kind = Node::Minimum, axisName = name;
      else if (name.consume_front("max_"))
        kind = Node::Maximum, axisName = name;
      int axis = llvm::StringSwitch<int>(axisName)
                     .Case("x", 0)
                     .Case("y", 1)
                     .Case("z", 2)
                     .Default(-1);
      if (axis < 0) {
        llvm::StringRef word = text.slice(start, pos);
        pos = start;
        return error("unknown name '" + word +
                     "' (expected x, y, z, min_x .. max_z, true or false)");
      }
      auto node = make(kind, false);
      node->index = axis;
      return node;
    }
    return error(llvm::Twine("expected a number, a name or '(', found '") +
                 text.substr(pos, 1) + "'");
  }

  llvm::StringRef text;
  size_t pos = 0;
  unsigned nesting = 0;
};

double evaluateNode(const Node &node, const CoordinateFrame &frame) {
  auto operand = [&](int i) { return evaluateNode(*node.operands[i], frame); };
  switch (node.kind) {
  case Node::Number:
    return node.value;
  case Node::Coordinate:
    return frame.position[node.index];
  case Node::Minimum:
    return frame.min[node.index];
  case Node::Maximum:
    return frame.max[node.index];
  case Node::Negate:
    return -operand(0);
  case Node::Not:
    return operand(0) == 0.0 ? 1.0 : 0.0;
  case Node::Add:
    return operand(0) + operand(1);
  case Node::Subtract:
    return operand(0) - operand(1);
  case Node::Multiply:
    return operand(0) * operand(1);
  case Node::Divide:
    return operand(0) / operand(1);
  case Node::Less:
    return operand(0) < operand(1);
  case Node::LessEqual:
    return operand(0) <= operand(1);
  case Node::Greater:
    return operand(0) > operand(1);
  case Node::GreaterEqual:
    return operand(0) >= operand(1);
  case Node::Equal:
    return operand(0) == operand(1);
  case Node::NotEqual:
    return operand(0) != operand(1);
  case Node::And:
    return operand(0) != 0.0 && operand(1) != 0.0;
  case Node::Or:
    return operand(0) != 0.0 || operand(1) != 0.0;
  case Node::Select:
    return operand(0) != 0.0 ? operand(1) : operand(2);
  }
  return 0;
}

} // namespace

SceneExpression::SceneExpression(std::unique_ptr<Node> root)
    : root(std::move(root)) {}
SceneExpression::SceneExpression(SceneExpression &&) noexcept = default;
SceneExpression &
SceneExpression::operator=(SceneExpression &&) noexcept = default;
SceneExpression::~SceneExpression() = default;

llvm::Expected<SceneExpression> SceneExpression::parse(llvm::StringRef text) {
  auto root = Parser(text).parseAll();
  if (!root)
    return root.takeError();
  return SceneExpression(std::move(*root));
}

bool SceneExpression::isBoolean() const { return root->boolean; }

double SceneExpression::evaluate(const CoordinateFrame &frame) const {
  return evaluateNode(*root, frame);
}
