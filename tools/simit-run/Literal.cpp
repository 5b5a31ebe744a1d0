//===--- Literal.cpp - Simit literals of assertions and --eval ------------===//

#include "Literal.h"

#include "simit/Frontend/Lexer.h"

#include "simit/Frontend/AST.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/Casting.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace simit;

size_t Literal::numComponents() const {
  size_t n = 1;
  for (int64_t d : shape)
    n *= d;
  return n;
}

static Literal transpose(Literal literal) {
  if (literal.shape.size() == 1) {
    literal.column = !literal.column;
  } else if (literal.shape.size() == 2) {
    int64_t rows = literal.shape[0], cols = literal.shape[1];
    size_t width = literal.kind == Literal::Kind::Complex ? 2 : 1;
    std::vector<double> flipped(literal.values.size());
    for (int64_t i = 0; i < rows; ++i)
      for (int64_t j = 0; j < cols; ++j)
        for (size_t w = 0; w < width; ++w)
          flipped[(j * rows + i) * width + w] =
              literal.values[(i * cols + j) * width + w];
    literal.values = std::move(flipped);
    std::swap(literal.shape[0], literal.shape[1]);
  }
  return literal;
}

llvm::Expected<Literal> simit::literalFromExpr(const frontend::Expr &expr) {
  using namespace frontend;
  Literal literal;
  if (auto *e = llvm::dyn_cast<IntLiteral>(&expr)) {
    literal.kind = Literal::Kind::Int;
    literal.values = {static_cast<double>(e->value)};
  } else if (auto *e = llvm::dyn_cast<FloatLiteral>(&expr)) {
    literal.values = {e->value};
  } else if (auto *e = llvm::dyn_cast<BoolLiteral>(&expr)) {
    literal.kind = Literal::Kind::Bool;
    literal.values = {e->value ? 1.0 : 0.0};
  } else if (auto *e = llvm::dyn_cast<StringLiteral>(&expr)) {
    literal.kind = Literal::Kind::String;
    literal.text = e->value;
  } else if (auto *e = llvm::dyn_cast<ComplexLiteral>(&expr)) {
    literal.kind = Literal::Kind::Complex;
    literal.values = {e->re, e->im};
  } else if (auto *e = llvm::dyn_cast<DenseLiteral>(&expr)) {
    literal.shape = e->shape;
    literal.column = e->column;
    switch (e->component) {
    case frontend::ScalarKind::Int:
      literal.kind = Literal::Kind::Int;
      literal.values.assign(e->intValues.begin(), e->intValues.end());
      break;
    case frontend::ScalarKind::Float:
      literal.values = e->floatValues;
      break;
    case frontend::ScalarKind::Complex:
      literal.kind = Literal::Kind::Complex;
      literal.values = e->complexValues;
      break;
    default:
      return llvm::createStringError("unsupported dense literal");
    }
  } else if (auto *e = llvm::dyn_cast<UnaryExpr>(&expr)) {
    llvm::Expected<Literal> operand = literalFromExpr(*e->operand);
    if (!operand || e->op == UnaryExpr::Op::Plus)
      return operand;
    if (e->op != UnaryExpr::Op::Neg || operand->kind == Literal::Kind::Bool ||
        operand->kind == Literal::Kind::String)
      return llvm::createStringError("not a literal");
    for (double &v : operand->values)
      v = -v;
    return operand;
  } else if (auto *e = llvm::dyn_cast<TransposeExpr>(&expr)) {
    llvm::Expected<Literal> operand = literalFromExpr(*e->operand);
    if (!operand)
      return operand;
    return transpose(std::move(*operand));
  } else {
    return llvm::createStringError("not a literal");
  }
  return literal;
}

//===--- Parsing --eval calls ---------------------------------------------===//

namespace {
class CallParser {
public:
  explicit CallParser(llvm::StringRef text) : text(text) {}

  llvm::Expected<CallText> parse() {
    CallText call;
    skipSpace();
    size_t start = pos;
    while (pos < text.size() && (llvm::isAlnum(text[pos]) || text[pos] == '_'))
      ++pos;
    if (pos == start || llvm::isDigit(text[start]))
      return error("expected a function name");
    call.function = text.slice(start, pos).str();
    if (!consume('('))
      return error("expected '('");
    if (!consume(')')) {
      do {
        llvm::Expected<Literal> arg = literal();
        if (!arg)
          return arg.takeError();
        call.args.push_back(std::move(*arg));
      } while (consume(','));
      if (!consume(')'))
        return error("expected ',' or ')'");
    }
    skipSpace();
    if (pos != text.size())
      return error("unexpected text after the call");
    return call;
  }

private:
  llvm::Error error(const llvm::Twine &what) {
    return llvm::createStringError("--eval: column " + llvm::Twine(pos + 1) +
                                   ": " + what);
  }
  void skipSpace() {
    while (pos < text.size() && llvm::isSpace(text[pos]))
      ++pos;
  }
  bool consume(char c) {
    skipSpace();
    if (pos < text.size() && text[pos] == c) {
      ++pos;
      return true;
    }
    return false;
  }
  bool peek(char c) {
    skipSpace();
    return pos < text.size() && text[pos] == c;
  }

  /// [+-] number, with its kind.
  llvm::Error number(double &value, Literal::Kind &kind) {
    skipSpace();
    bool negative = false;
    if (pos < text.size() && (text[pos] == '-' || text[pos] == '+'))
      negative = text[pos++] == '-';
    skipSpace();
    size_t start = pos;
    while (pos < text.size() && llvm::isDigit(text[pos]))
      ++pos;
    if (pos == start)
      return error("expected a number");
    kind = Literal::Kind::Int;
    if (pos < text.size() && text[pos] == '.') {
      kind = Literal::Kind::Float;
      ++pos;
      size_t digits = pos;
      while (pos < text.size() && llvm::isDigit(text[pos]))
        ++pos;
      if (pos == digits)
        return error("expected digits after '.'");
    }
    if (pos < text.size() && (text[pos] == 'e' || text[pos] == 'E')) {
      kind = Literal::Kind::Float;
      ++pos;
      if (pos < text.size() && (text[pos] == '+' || text[pos] == '-'))
        ++pos;
      size_t digits = pos;
      while (pos < text.size() && llvm::isDigit(text[pos]))
        ++pos;
      if (pos == digits)
        return error("expected an exponent");
    }
    value = std::strtod(text.slice(start, pos).str().c_str(), nullptr);
    if (negative)
      value = -value;
    return llvm::Error::success();
  }

  /// `re, im>` after a `<`: the parts of a complex literal.
  llvm::Error complexParts(std::vector<double> &parts) {
    double re, im;
    Literal::Kind kind;
    if (llvm::Error err = number(re, kind))
      return err;
    if (!consume(','))
      return error("expected ','");
    if (llvm::Error err = number(im, kind))
      return err;
    if (!consume('>'))
      return error("expected '>'");
    parts = {re, im};
    return llvm::Error::success();
  }

  /// `[ ... ]`: rows separated by `;`, or nested literals.
  llvm::Expected<Literal> dense() {
    Literal result;
    if (peek('[')) {
      std::vector<Literal> parts;
      while (peek('[')) {
        ++pos;
        llvm::Expected<Literal> part = dense();
        if (!part)
          return part.takeError();
        parts.push_back(std::move(*part));
        consume(',');
      }
      if (!consume(']'))
        return error("expected ']'");
      result.kind = parts[0].kind;
      result.shape = parts[0].shape;
      result.shape.insert(result.shape.begin(), parts.size());
      for (const Literal &part : parts) {
        if (part.shape != parts[0].shape || part.kind != parts[0].kind)
          return error("mismatched dimension sizes or element types");
        llvm::append_range(result.values, part.values);
      }
      return result;
    }
    std::vector<size_t> rowLengths{0};
    bool first = true;
    while (!consume(']')) {
      if (consume(';')) {
        rowLengths.push_back(0);
        continue;
      }
      std::vector<double> values;
      Literal::Kind kind;
      skipSpace();
      size_t start = pos;
      if (consume('<')) {
        if (llvm::Error err = complexParts(values))
          return std::move(err);
        kind = Literal::Kind::Complex;
      } else {
        values.resize(1);
        if (llvm::Error err = number(values[0], kind))
          return std::move(err);
      }
      if (!first && kind != result.kind) {
        pos = start;
        return error("mismatched element types");
      }
      result.kind = kind;
      first = false;
      llvm::append_range(result.values, values);
      ++rowLengths.back();
      consume(',');
    }
    if (first)
      return error("an empty literal");
    for (size_t length : rowLengths)
      if (length != rowLengths[0])
        return error("mismatched dimension sizes");
    if (rowLengths.size() == 1)
      result.shape = {static_cast<int64_t>(rowLengths[0])};
    else
      result.shape = {static_cast<int64_t>(rowLengths.size()),
                      static_cast<int64_t>(rowLengths[0])};
    return result;
  }

  llvm::Expected<Literal> literal() {
    skipSpace();
    Literal result;
    if (consume('-')) {
      llvm::Expected<Literal> operand = literal();
      if (!operand)
        return operand;
      if (operand->kind == Literal::Kind::Bool ||
          operand->kind == Literal::Kind::String)
        return error("cannot negate a bool or a string");
      for (double &v : operand->values)
        v = -v;
      return operand;
    }
    if (consume('+'))
      return literal();
    if (consume('[')) {
      llvm::Expected<Literal> value = dense();
      if (!value)
        return value;
      result = std::move(*value);
    } else if (consume('<')) {
      result.kind = Literal::Kind::Complex;
      if (llvm::Error err = complexParts(result.values))
        return std::move(err);
    } else if (text.substr(pos).starts_with("true") ||
               text.substr(pos).starts_with("false")) {
      bool value = text.substr(pos).starts_with("true");
      pos += value ? 4 : 5;
      result.kind = Literal::Kind::Bool;
      result.values = {value ? 1.0 : 0.0};
    } else if (consume('"')) {
      // Escapes as in the language's string literals.
      result.kind = Literal::Kind::String;
      while (pos < text.size() && text[pos] != '"') {
        char c = text[pos++];
        if (c == '\\') {
          std::optional<char> decoded = pos < text.size()
                                            ? frontend::decodeEscape(text[pos])
                                            : std::nullopt;
          if (!decoded) {
            --pos; // at the backslash
            return error("unrecognized escape sequence in a string");
          }
          c = *decoded;
          ++pos;
        }
        result.text += c;
      }
      if (!consume('"'))
        return error("unclosed string");
    } else {
      double value;
      if (llvm::Error err = number(value, result.kind))
        return std::move(err);
      result.values = {value};
    }
    while (consume('\''))
      result = transpose(std::move(result));
    return result;
  }

  llvm::StringRef text;
  size_t pos = 0;
};
} // namespace

llvm::Expected<CallText> simit::parseCall(llvm::StringRef text) {
  return CallParser(text).parse();
}

//===--- Host buffers and comparison --------------------------------------===//

llvm::StringRef simit::kindName(Literal::Kind kind) {
  switch (kind) {
  case Literal::Kind::Int:
    return "an int";
  case Literal::Kind::Float:
    return "a float";
  case Literal::Kind::Bool:
    return "a bool";
  case Literal::Kind::Complex:
    return "a complex";
  case Literal::Kind::String:
    return "a string";
  }
  llvm_unreachable("unknown literal kind");
}

static bool kindMatches(Literal::Kind kind, ScalarKind scalar, bool isComplex) {
  bool isFloat = scalar == ScalarKind::Float64 || scalar == ScalarKind::Float32;
  if (isComplex || kind == Literal::Kind::Complex)
    return isComplex && kind == Literal::Kind::Complex && isFloat;
  switch (kind) {
  case Literal::Kind::Int:
    return scalar == ScalarKind::Int32 || scalar == ScalarKind::Int64 ||
           scalar == ScalarKind::Index;
  case Literal::Kind::Float:
    return isFloat;
  case Literal::Kind::Bool:
    return scalar == ScalarKind::Bool;
  case Literal::Kind::String:
    return scalar == ScalarKind::String;
  case Literal::Kind::Complex:
    break;
  }
  llvm_unreachable("unknown literal kind");
}

llvm::Error simit::toHostBuffer(const Literal &literal, const ValueType &type,
                                std::vector<uint64_t> &storage,
                                std::vector<int> &shape,
                                ComponentType &component) {
  // A string is passed as a pointer to its text, which the literal keeps.
  if (literal.kind == Literal::Kind::String &&
      type.scalar == ScalarKind::String && !type.isMemRef && !type.isVector) {
    const char *text = literal.text.c_str();
    storage.assign(1, 0);
    std::memcpy(storage.data(), &text, sizeof text);
    shape.clear();
    component = ComponentType::Float64; // not checked for strings
    return llvm::Error::success();
  }
  if (!kindMatches(literal.kind, type.scalar, type.isComplex) ||
      !componentTypeFor(type.scalar, component))
    return llvm::createStringError(kindName(literal.kind) +
                                   " literal cannot be passed as " +
                                   type.str());
  // Vectors (and the static memrefs of `inout` parameters) are the
  // lowering's flattened form of local tensors: the components must agree;
  // the Simit types were compared before.
  bool flattened = type.isVector ||
                   (type.isMemRef && llvm::none_of(type.shape, [](int64_t d) {
                      return d == ValueType::kDynamic;
                    }));
  bool fits = flattened ? static_cast<int64_t>(literal.numComponents()) ==
                              type.numComponents()
                        : literal.shape == type.shape;
  if (!fits)
    return llvm::createStringError("a literal of " +
                                   llvm::Twine(literal.numComponents()) +
                                   " components cannot be passed as " +
                                   type.str());
  // Values that do not fit are errors, as in source (language.md 2), never
  // wrapped or rounded to infinity.
  for (double v : literal.values) {
    if (type.scalar == ScalarKind::Int32 &&
        (v < std::numeric_limits<int32_t>::min() ||
         v > std::numeric_limits<int32_t>::max()))
      return llvm::createStringError("integer literal " +
                                     llvm::Twine(static_cast<int64_t>(v)) +
                                     " does not fit in 32 bits");
    bool single = type.scalar == ScalarKind::Float32;
    if ((type.scalar == ScalarKind::Float64 || single) &&
        (std::isinf(v) || (single && std::isinf(static_cast<float>(v)))))
      return llvm::createStringError(
          llvm::Twine("float literal is too large for a ") +
          (single ? "32" : "64") + "-bit float");
  }
  // Complex components are passed as (re, im) pairs of floats.
  shape.assign(literal.shape.begin(), literal.shape.end());
  if (type.isComplex)
    shape.push_back(2);
  size_t size = scalarSize(type.scalar);
  storage.assign((literal.values.size() * size + 7) / 8, 0);
  auto *bytes = reinterpret_cast<uint8_t *>(storage.data());
  for (size_t i = 0; i < literal.values.size(); ++i) {
    double v = literal.values[i];
    uint8_t *p = bytes + i * size;
    switch (type.scalar) {
    case ScalarKind::Float64:
      std::memcpy(p, &v, 8);
      break;
    case ScalarKind::Float32: {
      float f = static_cast<float>(v);
      std::memcpy(p, &f, 4);
      break;
    }
    case ScalarKind::Int32: {
      int32_t n = static_cast<int32_t>(v);
      std::memcpy(p, &n, 4);
      break;
    }
    case ScalarKind::Bool:
      *p = v != 0;
      break;
    case ScalarKind::Int64:
    case ScalarKind::Index:
    case ScalarKind::String:
      llvm_unreachable("no component type");
    }
  }
  return llvm::Error::success();
}

/// The text of a string result (its bytes hold a `const char *`).
static std::string stringOf(const HostValue &value) {
  const char *text = nullptr;
  if (value.bytes.size() >= sizeof text)
    std::memcpy(&text, value.bytes.data(), sizeof text);
  return text ? text : "";
}

/// `text` in double quotes, its line breaks, tabs, quotes and backslashes
/// escaped as in Simit source, so that a failed comparison shows where two
/// strings differ.
static std::string quoted(llvm::StringRef text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    default:
      out += c;
    }
  }
  return out + "\"";
}

std::string simit::compareResult(const HostValue &actual,
                                 const Literal &expected) {
  if (!kindMatches(expected.kind, actual.scalar, actual.isComplex))
    return "the result is " +
           (actual.isComplex
                ? "complex<" + scalarKindName(actual.scalar).str() + ">"
                : scalarKindName(actual.scalar).str()) +
           ", the expected value " + kindName(expected.kind).str();
  if (expected.kind == Literal::Kind::String) {
    std::string text = stringOf(actual);
    if (text == expected.text)
      return "";
    return quoted(text) + " != " + quoted(expected.text);
  }
  if (actual.numComponents() != expected.numComponents())
    return "the result has shape [" + llvm::join(llvm::map_range(actual.shape, [](int64_t d) { return std::to_string(d); }), ", ") +
           "], the expected value [" +
           llvm::join(llvm::map_range(expected.shape, [](int64_t d) { return std::to_string(d); }), ", ") + "]";
  // Complex values compare part by part, like floats.
  // A single-precision result is compared with the literal in single
  // precision, as the program would read it (--float32).
  bool single = actual.scalar == ScalarKind::Float32;
  for (size_t i = 0; i < expected.values.size(); ++i) {
    double a = actual.component(i), e = expected.values[i];
    if (single && expected.kind != Literal::Kind::Int &&
        expected.kind != Literal::Kind::Bool)
      e = static_cast<float>(e);
    bool equal;
    if (expected.kind != Literal::Kind::Float &&
        expected.kind != Literal::Kind::Complex)
      equal = a == e;
    else if (e == 0.0)
      equal = a == 0.0;
    else
      equal = a == e || std::fabs(a - e) / std::max(std::fabs(a), std::fabs(e)) <=
                            0.001;
    if (!equal)
      return formatValue(actual) + " != " + formatLiteral(expected);
  }
  return "";
}

/// The shortest text that reads back as `v`, always with a '.' or an
/// exponent so that it is a float literal: positional for decimal
/// exponents from -4 to 15 (30.0, 0.001), scientific beyond (1e+16), as
/// Python's repr.
static std::string formatFloat(double v, bool single = false) {
  if (std::isnan(v))
    return "nan";
  if (std::isinf(v))
    return v < 0 ? "-inf" : "inf";
  char buffer[64];
  // The fewest digits that read back as the same number of its precision.
  int maxDigits = single ? 9 : 17;
  int digits = 1;
  for (; digits < maxDigits; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, v);
    if (single ? std::strtof(buffer, nullptr) == static_cast<float>(v)
               : std::strtod(buffer, nullptr) == v)
      break;
  }
  std::snprintf(buffer, sizeof buffer, "%.*e", digits - 1, v);
  int exponent = std::atoi(std::strchr(buffer, 'e') + 1);
  if (exponent >= -4 && exponent < 16)
    std::snprintf(buffer, sizeof buffer, "%.*f",
                  std::max(0, digits - 1 - exponent), v);
  else
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  std::string text = buffer;
  if (text.find_first_of(".e") == std::string::npos)
    text += ".0";
  return text;
}

static std::string formatComponents(const std::vector<int64_t> &shape,
                                    size_t &next,
                                    const std::function<std::string(size_t)> &component,
                                    size_t level) {
  size_t rank = shape.size() - level;
  if (rank == 1) {
    std::vector<std::string> items;
    for (int64_t i = 0; i < shape[level]; ++i)
      items.push_back(component(next++));
    return "[" + llvm::join(items, ", ") + "]";
  }
  if (rank == 2) {
    std::vector<std::string> rows;
    for (int64_t i = 0; i < shape[level]; ++i) {
      std::vector<std::string> items;
      for (int64_t j = 0; j < shape[level + 1]; ++j)
        items.push_back(component(next++));
      rows.push_back(llvm::join(items, ", "));
    }
    return "[" + llvm::join(rows, "; ") + "]";
  }
  std::vector<std::string> parts;
  for (int64_t i = 0; i < shape[level]; ++i)
    parts.push_back(formatComponents(shape, next, component, level + 1));
  return "[" + llvm::join(parts, ", ") + "]";
}

std::string simit::formatValue(const HostValue &value) {
  auto number = [&](size_t i) -> std::string {
    double v = value.component(i);
    switch (value.scalar) {
    case ScalarKind::Float64:
      return formatFloat(v);
    case ScalarKind::Float32:
      return formatFloat(v, /*single=*/true);
    case ScalarKind::Bool:
      return v != 0 ? "true" : "false";
    case ScalarKind::Int32:
    case ScalarKind::Int64:
    case ScalarKind::Index:
      return std::to_string(static_cast<int64_t>(v));
    case ScalarKind::String:
      return quoted(stringOf(value));
    }
    llvm_unreachable("unknown scalar kind");
  };
  auto component = [&](size_t i) -> std::string {
    if (!value.isComplex)
      return number(i);
    return "<" + number(2 * i) + ", " + number(2 * i + 1) + ">";
  };
  if (value.shape.empty())
    return component(0);
  size_t next = 0;
  return formatComponents(value.shape, next, component, 0);
}

std::string simit::formatLiteral(const Literal &literal) {
  auto component = [&](size_t i) -> std::string {
    switch (literal.kind) {
    case Literal::Kind::Float:
      return formatFloat(literal.values[i]);
    case Literal::Kind::Bool:
      return literal.values[i] != 0 ? "true" : "false";
    case Literal::Kind::Int:
      return std::to_string(static_cast<int64_t>(literal.values[i]));
    case Literal::Kind::Complex:
      return "<" + formatFloat(literal.values[2 * i]) + ", " +
             formatFloat(literal.values[2 * i + 1]) + ">";
    case Literal::Kind::String:
      return quoted(literal.text);
    }
    llvm_unreachable("unknown literal kind");
  };
  if (literal.shape.empty())
    return component(0);
  size_t next = 0;
  std::string text = formatComponents(literal.shape, next, component, 0);
  return literal.column ? text + "'" : text;
}
