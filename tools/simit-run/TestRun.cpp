//===--- TestRun.cpp - Running %! assertions and --eval calls -------------===//
//
// language.md section 11: every enabled `%%%` section is compiled on its
// own, and its assertions run in order, stopping at the section's first
// failure. An assertion names a non-generic function, passes literals of the
// parameter types (orientation included) and expects one result of the
// result type (orientation ignored); results compare by compareResult.
//
//===----------------------------------------------------------------------===//

#include "TestRun.h"

#include "Literal.h"

#include "simit/Engine/Program.h"
#include "simit/Frontend/Frontend.h"
#include "simit/Frontend/Types.h"

#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"

using namespace simit;

namespace {
/// "1 argument", "2 arguments".
std::string countOf(size_t n, llvm::StringRef noun) {
  return std::to_string(n) + " " + noun.str() + (n == 1 ? "" : "s");
}

/// Host storage of the arguments of one call.
struct Arguments {
  std::vector<std::vector<uint64_t>> storage;
};

/// Binds literal i to the function's parameter i.
llvm::Error bindArguments(Function &function, llvm::ArrayRef<Literal> args,
                          Arguments &holder) {
  if (function.numParameters() != args.size())
    return llvm::createStringError(
        "function '" + function.name() + "' takes " +
        countOf(function.numParameters(), "parameter") + ", " +
        llvm::Twine(args.size()) + " given");
  holder.storage.resize(args.size());
  for (const ArgumentBinding &param : function.signature().arguments) {
    if (param.kind != ArgumentBinding::Kind::Parameter)
      continue;
    size_t i = static_cast<size_t>(param.index);
    std::vector<int> shape;
    ComponentType component;
    if (llvm::Error err = toHostBuffer(args[i], param.type, holder.storage[i],
                                       shape, component))
      return llvm::createStringError("argument " + llvm::Twine(i + 1) + ": " +
                                     llvm::toString(std::move(err)));
    if (llvm::Error err = function.bindParameter(
            i, holder.storage[i].data(), component, shape))
      return err;
  }
  return llvm::Error::success();
}

/// The text of line `line` (1-based) of `text`.
llvm::StringRef lineText(llvm::StringRef text, unsigned line) {
  for (unsigned i = 1; i < line && !text.empty(); ++i)
    text = text.split('\n').second;
  return text.split('\n').first.rtrim();
}

class SectionRunner {
public:
  SectionRunner(const TestRunOptions &options, llvm::raw_ostream &os)
      : options(options), os(os) {}

  unsigned passed = 0, failed = 0, notRun = 0;

  void run(const frontend::Section &section) {
    llvm::SourceMgr sourceMgr;
    unsigned buffer = sourceMgr.AddNewSourceBuffer(
        llvm::MemoryBuffer::getMemBufferCopy(section.text, options.path),
        llvm::SMLoc());
    frontend::DiagnosticEngine diags(sourceMgr);
    std::unique_ptr<frontend::Program> ast =
        frontend::parseProgram(sourceMgr, buffer, diags);
    if (!diags.hasErrors())
      frontend::checkProgram(*ast, diags);
    // A section that compiles prints its warnings when it is loaded below.
    if (diags.hasErrors()) {
      diags.print(os);
      sectionFailed(section, "does not compile",
                    ast ? ast->tests.size() : 0);
      return;
    }
    if (ast->tests.empty())
      return;

    ProgramOptions programOptions = options.program;
    for (const frontend::TestLine &test : ast->tests)
      if (test.func)
        programOptions.hostFunctions.push_back(test.funcName);
    Program program(programOptions);
    if (llvm::Error err = program.loadString(section.text, options.path)) {
      os << llvm::toString(std::move(err)) << "\n";
      sectionFailed(section, "does not compile", ast->tests.size());
      return;
    }
    for (size_t i = 0; i < ast->tests.size(); ++i) {
      std::string problem = runAssertion(program, ast->tests[i]);
      if (problem.empty()) {
        ++passed;
        continue;
      }
      unsigned line = section.firstLine + ast->tests[i].line - 1;
      os << options.path << ":" << line << ": error: " << problem << "\n  "
         << lineText(section.text, ast->tests[i].line) << "\n";
      ++failed;
      notRun += ast->tests.size() - i - 1;
      return;
    }
  }

private:
  void sectionFailed(const frontend::Section &section, llvm::StringRef why,
                     size_t assertions) {
    os << options.path << ":" << section.firstLine << ": error: section";
    if (!section.name.empty())
      os << " '" << section.name << "'";
    os << " " << why << "\n";
    // Each of its assertions fails; a section without any counts once.
    failed += std::max<size_t>(assertions, 1);
  }

  std::string runAssertion(Program &program, const frontend::TestLine &test) {
    const frontend::FuncDecl *func = test.func;
    // A host function (extern func) has no body to test.
    if (!func || func->isGeneric() || func->isExtern)
      return "attempting to test unknown function '" + test.funcName + "'";
    if (func->params.size() != test.args.size())
      return "function '" + test.funcName + "' takes " +
             countOf(func->params.size(), "argument") + ", " +
             std::to_string(test.args.size()) + " given";
    std::vector<Literal> args;
    for (size_t i = 0; i < test.args.size(); ++i) {
      const frontend::Expr &arg = *test.args[i];
      if (!arg.type || !frontend::typesEqual(func->params[i]->type, arg.type))
        return "argument " + std::to_string(i + 1) + " of type " +
               (arg.type ? arg.type->str() : std::string("?")) +
               " does not match parameter '" + func->params[i]->name +
               "' of type " + func->params[i]->type->str();
      llvm::Expected<Literal> literal = literalFromExpr(arg);
      if (!literal)
        return llvm::toString(literal.takeError());
      args.push_back(std::move(*literal));
    }
    if (func->results.size() != 1)
      return "function '" + test.funcName + "' has " +
             std::to_string(func->results.size()) +
             " results; only functions with one result can be tested";
    const frontend::Expr &expected = *test.expected;
    if (!expected.type ||
        !frontend::typesEqual(func->results[0]->type, expected.type,
                              /*orientation=*/false))
      return "expected value of type " +
             (expected.type ? expected.type->str() : std::string("?")) +
             " does not match the result type " +
             func->results[0]->type->str();
    llvm::Expected<Literal> expectedValue = literalFromExpr(expected);
    if (!expectedValue)
      return llvm::toString(expectedValue.takeError());

    llvm::Expected<Function> function = program.compile(test.funcName);
    if (!function)
      return llvm::toString(function.takeError());
    Arguments holder;
    if (llvm::Error err = bindArguments(*function, args, holder))
      return llvm::toString(std::move(err));
    if (llvm::Error err = function->run())
      return llvm::toString(std::move(err));
    if (function->results().size() != 1)
      return "the compiled function returned " +
             std::to_string(function->results().size()) + " values";
    return compareResult(function->results()[0], *expectedValue);
  }

  const TestRunOptions &options;
  llvm::raw_ostream &os;
};
} // namespace

int simit::runTests(const TestRunOptions &options, llvm::raw_ostream &os) {
  auto file = llvm::MemoryBuffer::getFile(options.path, /*IsText=*/true);
  if (!file) {
    os << options.path << ": error: cannot read the file: "
       << file.getError().message() << "\n";
    return 1;
  }
  SectionRunner runner(options, os);
  for (const frontend::Section &section :
       frontend::splitSections((*file)->getBuffer()))
    if (!section.disabled)
      runner.run(section);
  os << runner.passed << " passed, " << runner.failed << " failed";
  if (runner.notRun)
    os << " (" << runner.notRun << " not run after a failure)";
  os << "\n";
  return runner.failed ? 1 : 0;
}

namespace {
/// Why `literal` is no value of the Simit type `type` although its
/// components may fit the compiled parameter: a row for a column vector or
/// the reverse, a matrix for a vector or the reverse, other sizes
/// (language.md section 11: arguments have the parameter types, orientation
/// included).
std::optional<std::string> typeMismatch(const Literal &literal,
                                        const frontend::Type &type) {
  using frontend::ScalarKind;
  auto sameKind = [](Literal::Kind literal, ScalarKind component) {
    switch (literal) {
    case Literal::Kind::Int:
      return component == ScalarKind::Int;
    case Literal::Kind::Float:
      return component == ScalarKind::Float;
    case Literal::Kind::Bool:
      return component == ScalarKind::Bool;
    case Literal::Kind::Complex:
      return component == ScalarKind::Complex;
    case Literal::Kind::String:
      return component == ScalarKind::String;
    }
    return false;
  };
  if (type.isTensor() && !type.block && !sameKind(literal.kind, type.component))
    return kindName(literal.kind).str() + " literal for a parameter of type '" +
           type.str() + "'";
  if (!type.isTensor() || type.block || type.order() == 0 || type.order() > 2 ||
      literal.kind == Literal::Kind::String)
    return std::nullopt;
  auto shapeOf = [](const Literal &l) -> std::string {
    if (l.shape.size() == 2)
      return "a matrix";
    if (l.shape.size() == 1)
      return l.column ? "a column vector" : "a row vector";
    return l.shape.empty() ? "a scalar" : "a tensor";
  };
  bool fits = type.isMatrix() ? literal.shape.size() == 2
                              : literal.shape.size() == 1 &&
                                    literal.column == type.isColumnVector();
  if (!fits)
    return shapeOf(literal) + " for a parameter of type '" + type.str() + "'" +
           (type.isColumnVector() && literal.shape.size() == 1
                ? " (write a column as [a, b, ...]')"
                : "");
  for (size_t d = 0; d < type.dims.size(); ++d)
    if (type.dims[d].kind == frontend::Dim::Kind::Range &&
        type.dims[d].size != literal.shape[d]) {
      std::vector<std::string> sizes;
      for (int64_t size : literal.shape)
        sizes.push_back(std::to_string(size));
      return shapeOf(literal) + " of size " + llvm::join(sizes, "x") +
             " for a parameter of type '" + type.str() + "'";
    }
  return std::nullopt;
}

/// The type check (orientation, sizes, component kind) of `args` against
/// the parameters of the Simit function `name` in the file `path` (.mlir
/// files have no Simit types).
llvm::Error checkArgumentTypes(llvm::StringRef path, llvm::StringRef name,
                               llvm::ArrayRef<Literal> args) {
  if (!path.ends_with(".sim"))
    return llvm::Error::success();
  auto file = llvm::MemoryBuffer::getFile(path, /*IsText=*/true);
  if (!file)
    return llvm::Error::success(); // loading the program reports it
  llvm::SourceMgr sourceMgr;
  unsigned buffer =
      sourceMgr.AddNewSourceBuffer(std::move(*file), llvm::SMLoc());
  frontend::DiagnosticEngine diags(sourceMgr);
  std::unique_ptr<frontend::Program> ast =
      frontend::parseProgram(sourceMgr, buffer, diags);
  if (!diags.hasErrors())
    frontend::checkProgram(*ast, diags);
  if (diags.hasErrors())
    return llvm::Error::success(); // so does compiling it
  for (const auto &func : ast->funcs) {
    if (func->name != name || func->params.size() != args.size())
      continue;
    for (size_t i = 0; i < args.size(); ++i)
      if (func->params[i]->type)
        if (std::optional<std::string> why =
                typeMismatch(args[i], *func->params[i]->type))
          return llvm::createStringError("argument " + llvm::Twine(i + 1) +
                                         ": " + *why);
  }
  return llvm::Error::success();
}
} // namespace

int simit::runEval(const EvalOptions &options, llvm::raw_ostream &os) {
  llvm::Expected<CallText> call = parseCall(options.call);
  if (!call) {
    llvm::errs() << llvm::toString(call.takeError()) << "\n";
    return 1;
  }
  if (llvm::Error err =
          checkArgumentTypes(options.path, call->function, call->args)) {
    llvm::errs() << "--eval: " << llvm::toString(std::move(err)) << "\n";
    return 1;
  }
  ProgramOptions programOptions = options.program;
  programOptions.hostFunctions = {call->function};
  // Only the function called is compiled (as a scene's uncalled ones are
  // not): another that does not lower yet does not stop it.
  programOptions.specialisation.entryFunctions = {call->function};
  Program program(programOptions);
  if (llvm::Error err = program.loadFile(options.path)) {
    llvm::errs() << llvm::toString(std::move(err)) << "\n";
    return 1;
  }
  llvm::Expected<Function> function = program.compile(call->function);
  if (!function) {
    llvm::errs() << options.path << ": " << llvm::toString(function.takeError())
                 << "\n";
    return 1;
  }
  Arguments holder;
  if (llvm::Error err = bindArguments(*function, call->args, holder)) {
    llvm::errs() << "--eval: " << llvm::toString(std::move(err)) << "\n";
    return 1;
  }
  if (llvm::Error err = function->run()) {
    // Binding errors name the function already; failures of the run not.
    std::string message = llvm::toString(std::move(err));
    std::string prefix = "function '" + call->function + "': ";
    if (!llvm::StringRef(message).starts_with(prefix))
      message = prefix + message;
    llvm::errs() << options.path << ": " << message << "\n";
    return 1;
  }
  for (const HostValue &result : function->results())
    os << formatValue(result) << "\n";
  return 0;
}
