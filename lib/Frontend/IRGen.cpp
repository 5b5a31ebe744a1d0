//===- IRGen.cpp - Checked Simit AST to the simit dialect -----------------===//
//
// The module: externs become `simit.extern`, functions `func.func` (exported
// ones carry `simit.export`; generic functions are emitted once per instance
// under sema's instance name). Factorisations and solves are simit ops
// (simit.factorize, simit.factor_solve, ...); the other functions the
// runtime or the host implement are calls of private declarations:
//
//   clock storeTime   ->  @simit_rt_<name>
//   extern func f     ->  @f (implemented by the host)
//
// A function used with two signatures (e.g. a generic extern func of two
// matrix types) gets one declaration per signature, `@f`, then `@f_1`, ...;
// every declaration carries `simit.runtime_function` naming the intrinsic
// (or `simit.extern_function` for host functions).
//
//===----------------------------------------------------------------------===//

#include "IRGenImpl.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/Dialect/ControlFlow/IR/ControlFlow.h"
#include "mlir/Dialect/Math/IR/Math.h"
#include "mlir/Dialect/SCF/IR/SCF.h"
#include "mlir/Dialect/UB/IR/UBOps.h"
#include "mlir/IR/Diagnostics.h"
#include "mlir/IR/Dominance.h"
#include "mlir/IR/Iterators.h"
#include "mlir/IR/PatternMatch.h"
#include "mlir/IR/Verifier.h"
#include "mlir/Interfaces/SideEffectInterfaces.h"
#include "mlir/Transforms/CSE.h"

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

void frontend::loadIRGenDialects(MLIRContext &context) {
  context.loadDialect<dialect::SimitDialect, func::FuncDialect, scf::SCFDialect,
                      arith::ArithDialect, math::MathDialect,
                      complex::ComplexDialect, ub::UBDialect,
                      cf::ControlFlowDialect>();
}

OwningOpRef<ModuleOp>
frontend::generateIR(const Program &program, frontend::DiagnosticEngine &diags,
                            MLIRContext &context, const IRGenOptions &options) {
  loadIRGenDialects(context);
  return IRGenerator(program, diags, context, options).generate();
}

IRGenerator::IRGenerator(const Program &program, frontend::DiagnosticEngine &diags,
                         MLIRContext &context, const IRGenOptions &options)
    : program(program), diags(diags), context(context), options(options),
      builder(&context) {
  llvm::SourceMgr &sourceMgr = diags.getSourceMgr();
  llvm::StringRef name =
      sourceMgr.getNumBuffers() == 0
          ? "<unknown>"
          : sourceMgr.getMemoryBuffer(sourceMgr.getMainFileID())
                ->getBufferIdentifier();
  fileName = StringAttr::get(&context, name);
}

/// The functions `names` name and those they use, or null when a name is
/// no exported function of `program` (everything is generated then, and
/// compiling reports the unknown name with the exported ones).
static std::optional<llvm::SmallPtrSet<const FuncDecl *, 16>>
reachableFunctions(const Program &program, ArrayRef<std::string> names) {
  if (names.empty())
    return std::nullopt;
  SmallVector<const FuncDecl *> work;
  for (const std::string &name : names) {
    auto found = llvm::find_if(program.funcs, [&](const auto &func) {
      return func->name == name && !func->isGeneric() && func->isExport;
    });
    if (found == program.funcs.end())
      return std::nullopt;
    work.push_back(found->get());
  }
  llvm::SmallPtrSet<const FuncDecl *, 16> reached;
  while (!work.empty()) {
    const FuncDecl *func = work.pop_back_val();
    if (func && reached.insert(func).second)
      llvm::append_range(work, func->callees);
  }
  return reached;
}

OwningOpRef<ModuleOp> IRGenerator::generate() {
  OwningOpRef<ModuleOp> owned =
      ModuleOp::create(FileLineColLoc::get(fileName, 1, 1));
  module = *owned;
  builder.setInsertionPointToEnd(module.getBody());
  auto reached = reachableFunctions(program, options.onlyFunctions);
  auto wanted = [&](const FuncDecl &func) {
    return !reached || reached->contains(&func);
  };
  for (const Decl *decl : program.order) {
    if (auto *var = dyn_cast<VarDecl>(decl)) {
      if (var->role == VarDecl::Role::Extern)
        genExtern(*var);
      continue;
    }
    auto *func = dyn_cast<FuncDecl>(decl);
    if (!func || func->isIntrinsic || func->isExtern)
      continue; // extern functions are declared where they are called
    if (func->isGeneric()) {
      for (const auto &instance : func->instances)
        if (wanted(*instance))
          genFunction(*instance);
      continue;
    }
    if (wanted(*func))
      genFunction(*func);
  }
  if (failed)
    return nullptr;
  simplify();
  if (!checkResultWrites() || !verifyModule())
    return nullptr;
  return owned;
}

/// The source position of an IR location (none outside the main file).
SMLoc IRGenerator::sourceLoc(Location where) {
  llvm::SourceMgr &sourceMgr = diags.getSourceMgr();
  auto fileLoc = where->findInstanceOf<FileLineColLoc>();
  if (!fileLoc || sourceMgr.getNumBuffers() == 0)
    return SMLoc();
  return sourceMgr.FindLocForLineAndColumn(
      sourceMgr.getMainFileID(), fileLoc.getLine(), fileLoc.getColumn());
}

/// Element functions write map results only at their own element and
/// endpoints: a write elsewhere is the program's error, reported at the
/// write (the maps' verifier would report it as an internal one).
bool IRGenerator::checkResultWrites() {
  bool ok = true;
  module.walk([&](Operation *op) {
    if (!isa<dialect::MapOp, dialect::AssembleOp>(op))
      return;
    if (auto bad = dialect::findUnindexedResultWrite(op)) {
      diags.error(sourceLoc(bad->first.getLoc()),
                  "an element function writes a result of a map only at its "
                  "own element and endpoints (language.md 8.3); this index "
                  "is neither");
      ok = false;
    }
  });
  return ok;
}

/// Generation leaves unused side-effect-free values behind (the int
/// constants of indices that became `index` constants, loads of variables
/// read only to be replaced) and repeats values (constants, endpoint reads
/// of unrolled loops, extern slots); dead ones go, innermost first, and
/// repeated ones are merged.
void IRGenerator::simplify() {
  module.walk<WalkOrder::PostOrder, ReverseIterator>([&](Operation *op) {
    if (op != module && isOpTriviallyDead(op))
      op->erase();
  });
  IRRewriter rewriter(&context);
  DominanceInfo dominance;
  eliminateCommonSubExpressions(rewriter, dominance, module);
}

void IRGenerator::genExtern(const VarDecl &global) {
  mlir::Type type = global.type->isSet() ? setType(&global)
                                   : convertType(global.type, global.loc);
  dialect::ExternOp::create(builder, loc(global.loc), global.name, type);
}

std::string IRGenerator::symbolOf(const FuncDecl &func) const {
  return func.isInstance() ? func.mangledName : func.name;
}

FunctionType IRGenerator::functionType(const FuncDecl &func) {
  SmallVector<mlir::Type> inputs, results;
  for (const auto &param : func.params)
    inputs.push_back(paramType(*param));
  for (const auto &result : func.results)
    results.push_back(convertType(result->type, result->loc));
  return builder.getFunctionType(inputs, results);
}

void IRGenerator::genFunction(const FuncDecl &func,
                              ArrayRef<unsigned> inoutResults,
                              bool accumulateResults) {
  currentFunc = &func;
  bindings.clear();
  accumulatedResults.clear();
  if (accumulateResults)
    for (const auto &result : func.results)
      accumulatedResults.insert(result.get());
  FunctionType type = functionType(func);
  std::string symbol = symbolOf(func);
  if (!inoutResults.empty()) {
    // The `inout` parameters become leading results, their parameters the
    // values they start from (a map's `simit.result_inits`).
    SmallVector<mlir::Type> inputs(type.getInputs()), results;
    for (unsigned i : inoutResults) {
      inputs[i] = cast<dialect::RefType>(inputs[i]).getValueType();
      results.push_back(inputs[i]);
    }
    llvm::append_range(results, type.getResults());
    type = builder.getFunctionType(inputs, results);
    symbol = inoutVariantOf(func, accumulateResults);
  }
  auto function = func::FuncOp::create(builder, loc(func.loc), symbol, type);
  if (func.isExport && inoutResults.empty())
    function->setAttr("simit.export", builder.getUnitAttr());
  mlir::Block *entry = function.addEntryBlock();
  OpBuilder::InsertionGuard guard(builder);
  builder.setInsertionPointToStart(entry);
  for (auto [i, param, argument] :
       llvm::enumerate(func.params, entry->getArguments())) {
    argument.setLoc(loc(param->loc));
    if (llvm::is_contained(inoutResults, i))
      allocSlot(*param);
    else
      bindings[param.get()] = {argument, isSlotParam(*param)};
  }
  for (const auto &result : func.results)
    allocSlot(*result);
  if (func.body)
    genBlock(*func.body);
  SmallVector<Value> results;
  SMLoc end = func.body ? func.body->loc : func.loc;
  // The result's name travels in the location of its final load, for
  // messages about the value (simit-check-numerics).
  auto loadResult = [&](const VarDecl &var) {
    results.push_back(dialect::LoadOp::create(
        builder, NameLoc::get(builder.getStringAttr(var.name), loc(var.loc)),
        bindings[&var].value));
  };
  for (unsigned i : inoutResults)
    loadResult(*func.params[i]);
  for (const auto &result : func.results)
    loadResult(*result);
  func::ReturnOp::create(builder, loc(end), results);
  currentFunc = nullptr;
  accumulatedResults.clear();
}

std::string IRGenerator::inoutVariantOf(const FuncDecl &func,
                                        bool reduce) const {
  return symbolOf(func) + (reduce ? ".inout.reduce" : ".inout");
}

const VarDecl *IRGenerator::accumulatedResultOf(const Expr &target) const {
  const Expr *root = &target;
  while (auto *read = dyn_cast<ReadExpr>(root))
    root = read->base.get();
  auto *name = dyn_cast<NameExpr>(root);
  auto *var = name ? dyn_cast<VarDecl>(name->decl) : nullptr;
  return var && accumulatedResults.count(var) ? var : nullptr;
}

func::FuncOp IRGenerator::declareRuntimeFunction(llvm::StringRef base,
                                                 llvm::StringRef simitName,
                                                 FunctionType type) {
  for (unsigned k = 0;; ++k) {
    std::string name = k == 0 ? base.str() : (base + "_" + Twine(k)).str();
    auto it = runtimeFunctions.find(name);
    if (it != runtimeFunctions.end()) {
      if (it->second.getFunctionType() == type)
        return it->second;
      continue;
    }
    OpBuilder::InsertionGuard guard(builder);
    builder.setInsertionPointToEnd(module.getBody());
    auto decl = func::FuncOp::create(builder, module.getLoc(), name, type);
    decl.setPrivate();
    bool isHost = !::simit::abi::parseRuntimeFunction(base);
    decl->setAttr(isHost ? "simit.extern_function" : "simit.runtime_function",
                  builder.getStringAttr(simitName));
    runtimeFunctions[name] = decl;
    return decl;
  }
}

/// Runs the verifier; its messages become internal errors at the source
/// position of the offending operation.
bool IRGenerator::verifyModule() {
  bool ok = true;
  ScopedDiagnosticHandler handler(&context, [&](mlir::Diagnostic &diag) {
    if (diag.getSeverity() != mlir::DiagnosticSeverity::Error)
      return success();
    ok = false;
    SMLoc where = sourceLoc(diag.getLocation());
    std::string text;
    llvm::raw_string_ostream os(text);
    os << "internal error: the generated IR does not verify: " << diag;
    for (const mlir::Diagnostic &note : diag.getNotes())
      os << "; " << note;
    diags.error(where, text);
    return success();
  });
  return succeeded(verify(module)) && ok;
}

Value IRGenerator::unsupported(SMLoc where, const Twine &what, mlir::Type type) {
  diags.error(where, "not supported by the IR generator: " + what);
  failed = true;
  if (!type)
    type = builder.getI32Type();
  return ub::PoisonOp::create(builder, loc(where), type);
}
