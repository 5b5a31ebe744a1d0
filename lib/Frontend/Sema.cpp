//===- Sema.cpp - Declarations, scopes and statements ---------------------===//

#include "SemaImpl.h"

#include "simit/Frontend/Parser.h"
#include "simit/Frontend/Sema.h"

using namespace simit::frontend;
using llvm::cast;
using llvm::dyn_cast;
using llvm::dyn_cast_or_null;
using llvm::isa;

FuncDecl::~FuncDecl() = default;

namespace {

/// The intrinsics as declarations; norm and dot are polymorphic and checked
/// apart (their declared types only document the common case).
const char *const kIntrinsicPrelude = R"(
extern func mod(a : int, b : int) -> (r : int);
extern func sin(x : float) -> (r : float);
extern func cos(x : float) -> (r : float);
extern func tan(x : float) -> (r : float);
extern func asin(x : float) -> (r : float);
extern func acos(x : float) -> (r : float);
extern func sqrt(x : float) -> (r : float);
extern func cbrt(x : float) -> (r : float);
extern func log(x : float) -> (r : float);
extern func exp(x : float) -> (r : float);
extern func abs(x : float) -> (r : float);
extern func atan2(y : float, x : float) -> (r : float);
extern func pow(x : float, y : float) -> (r : float);
extern func max(a : float, b : float) -> (r : float);
extern func min(a : float, b : float) -> (r : float);
extern func det(A : matrix[3,3](float)) -> (r : float);
extern func det2(A : matrix[2,2](float)) -> (r : float);
extern func det4(A : matrix[4,4](float)) -> (r : float);
extern func inv(A : matrix[3,3](float)) -> (r : matrix[3,3](float));
extern func inv2(A : matrix[2,2](float)) -> (r : matrix[2,2](float));
extern func inv4(A : matrix[4,4](float)) -> (r : matrix[4,4](float));
extern func cross(a : vector[3](float), b : vector[3](float)) -> (r : vector[3](float));
extern func norm(v : vector[3](float)) -> (r : float);
extern func dot(a : vector[3](float), b : vector[3](float)) -> (r : float);
extern func lu<N>(A : matrix[N,N](float)) -> (h : opaque);
extern func chol<N>(A : matrix[N,N](float)) -> (h : opaque);
extern func lusolve<N, M>(h : opaque, b : vector[N](float)) -> (x : vector[M](float));
extern func lltsolve<N, M>(h : opaque, b : vector[N](float)) -> (x : vector[M](float));
extern func lumatsolve<N, M, K>(h : opaque, B : matrix[N,M](float)) -> (X : matrix[K,M](float));
extern func lltmatsolve<N, M, K>(h : opaque, B : matrix[N,M](float)) -> (X : matrix[K,M](float));
extern func lufree(h : opaque);
extern func cholfree(h : opaque);
extern func triangularSolve<N, M>(A : matrix[N,M](float), b : vector[N](float)) -> (x : vector[M](float));
extern func createComplex(re : float, im : float) -> (c : complex);
extern func complexNorm(c : complex) -> (r : float);
extern func complexGetReal(c : complex) -> (r : float);
extern func complexGetImag(c : complex) -> (r : float);
extern func complexConj(c : complex) -> (r : complex);
extern func clock() -> (t : float);
extern func storeTime(i : int, t : float) -> (r : float);
)";

} // namespace

//===----------------------------------------------------------------------===//
// Lookup
//===----------------------------------------------------------------------===//

const FuncDecl *Sema::lookupFunction(const std::string &name) const {
  auto it = functions.find(name);
  if (it == functions.end() || it->second.second >= ctx.visibleBefore)
    return nullptr;
  return it->second.first;
}

const Decl *Sema::lookupVariable(const std::string &name) const {
  for (auto it = scopes.rbegin(); it != scopes.rend(); ++it) {
    auto found = it->find(name);
    if (found != it->end())
      return found->second;
  }
  auto it = globals.find(name);
  if (it == globals.end() || it->second.second >= ctx.visibleBefore)
    return nullptr;
  return it->second.first;
}

const ElementDecl *Sema::lookupElement(const std::string &name) const {
  auto it = elements.find(name);
  if (it == elements.end() || it->second.second >= ctx.visibleBefore)
    return nullptr;
  return it->second.first;
}

bool Sema::declareLocal(const Decl *decl) {
  auto &scope = scopes.back();
  if (scope.count(decl->name)) {
    diags.error(decl->loc, "redefinition of '" + decl->name + "'");
    return false;
  }
  scope[decl->name] = decl;
  return true;
}

std::optional<Dim> Sema::boundDim(const GenericParamDecl *param) const {
  if (ctx.func && ctx.func->isInstance() &&
      param->index < ctx.func->binding.size() &&
      param->index < ctx.func->generics.size() &&
      ctx.func->generics[param->index].get() == param)
    return ctx.func->binding[param->index];
  return std::nullopt;
}

//===----------------------------------------------------------------------===//
// Types as written
//===----------------------------------------------------------------------===//

std::optional<Dim> Sema::resolveDim(const DimExpr &dim, bool forGenericArg) {
  if (dim.isInt) {
    if (dim.value <= 0 && !forGenericArg) {
      diags.error(dim.loc, "a tensor dimension must be positive");
      return std::nullopt;
    }
    return Dim::range(dim.value);
  }
  const Decl *decl = lookupVariable(dim.name);
  if (!decl) {
    if (lookupElement(dim.name))
      diags.error(dim.loc, "undeclared set '" + dim.name +
                               "' ('" + dim.name + "' is an element type)");
    else
      diags.error(dim.loc, "undeclared set '" + dim.name + "'");
    return std::nullopt;
  }
  if (auto *generic = dyn_cast<GenericParamDecl>(decl)) {
    if (auto bound = boundDim(generic))
      return bound;
    return Dim::ofGeneric(generic);
  }
  auto *var = cast<VarDecl>(decl);
  if (!var->type || !var->type->isSet()) {
    diags.error(dim.loc, "expected a set, but '" + dim.name + "' has type '" +
                             (var->type ? var->type->str() : "?") + "'");
    return std::nullopt;
  }
  return Dim::ofSet(var);
}

/// No element type has this many endpoints or tuple members; the types
/// below hold one entry per repetition.
constexpr int64_t kMaxRepeat = 1024;

bool Sema::checkRepeatBound(const TypeExpr &type, llvm::StringRef what) {
  if (type.repeat <= kMaxRepeat)
    return true;
  diags.error(type.repeatLoc, what + " can be at most " +
                                  std::to_string(kMaxRepeat) + ", found " +
                                  std::to_string(type.repeat));
  return false;
}

TypePtr Sema::resolveType(const TypeExpr &type) {
  switch (type.kind) {
  case TypeExpr::Kind::Scalar:
    return Type::scalar(type.scalar);
  case TypeExpr::Kind::Opaque:
    return Type::opaque();
  case TypeExpr::Kind::Tensor: {
    std::vector<Dim> dims;
    for (const DimExpr &d : type.dims) {
      auto dim = resolveDim(d, false);
      if (!dim)
        return Type::error();
      dims.push_back(*dim);
    }
    TypePtr block;
    ScalarKind component = ScalarKind::Float;
    if (type.block->kind == TypeExpr::Kind::Scalar) {
      component = type.block->scalar;
    } else {
      block = resolveType(*type.block);
      if (block->isError())
        return block;
      component = block->component;
      if (!block->isScalar() && block->order() != dims.size()) {
        diags.error(type.block->loc,
                    "block order mismatch: a block of order " +
                        std::to_string(block->order()) +
                        " inside a tensor of order " +
                        std::to_string(dims.size()));
        return Type::error();
      }
    }
    if (type.transposed && dims.size() != 1) {
      diags.error(type.loc, "transposed type must be a vector");
      return Type::error();
    }
    return Type::tensor(component, dims, block, type.transposed);
  }
  case TypeExpr::Kind::Element: {
    const ElementDecl *element = lookupElement(type.name);
    if (!element) {
      diags.error(type.nameLoc, "undeclared element type '" + type.name + "'");
      return Type::error();
    }
    return Type::elementOf(element);
  }
  case TypeExpr::Kind::Set:
  case TypeExpr::Kind::Grid: {
    const ElementDecl *element = lookupElement(type.name);
    if (!element) {
      diags.error(type.nameLoc, "undeclared element type '" + type.name + "'");
      return Type::error();
    }
    auto set = std::make_shared<Type>();
    set->kind = Type::Kind::Set;
    set->element = element;
    for (const DimExpr &e : type.endpoints) {
      auto dim = resolveDim(e, false);
      if (!dim)
        return Type::error();
      if (dim->kind != Dim::Kind::Set) {
        diags.error(e.loc, "expected a set, but '" + e.name +
                               "' is a generic parameter");
        return Type::error();
      }
      set->endpoints.push_back(dim->set);
    }
    if (type.kind == TypeExpr::Kind::Grid) {
      if (type.repeat <= 0) {
        diags.error(type.repeatLoc, "a grid needs a positive dimension count");
        return Type::error();
      }
      if (!checkRepeatBound(type, "a grid's dimension count"))
        return Type::error();
      const Type &points = *set->endpoints.front()->type;
      if (!points.endpoints.empty()) {
        diags.error(type.endpoints.front().loc,
                    "a grid needs a zero-cardinality point set, but '" +
                        type.endpoints.front().name + "' is an edge set");
        return Type::error();
      }
      set->gridRank = type.repeat;
      return set;
    }
    if (type.hasEndpoints && type.repeatLoc.isValid()) {
      if (type.repeat <= 0) {
        diags.error(type.repeatLoc,
                    "an edge set needs a positive arity, found " +
                        std::to_string(type.repeat));
        return Type::error();
      }
      if (!checkRepeatBound(type, "an edge set's arity"))
        return Type::error();
      set->endpoints.assign(type.repeat, set->endpoints.front());
    }
    return set;
  }
  case TypeExpr::Kind::Tuple: {
    auto tuple = std::make_shared<Type>();
    tuple->kind = Type::Kind::Tuple;
    if (type.memberNames.empty()) {
      const ElementDecl *element = lookupElement(type.name);
      if (!element) {
        diags.error(type.nameLoc,
                    "undeclared element type '" + type.name + "'");
        return Type::error();
      }
      if (type.repeat <= 0) {
        diags.error(type.repeatLoc, "a tuple needs a positive length, found " +
                                        std::to_string(type.repeat));
        return Type::error();
      }
      if (!checkRepeatBound(type, "a tuple's length"))
        return Type::error();
      tuple->members.assign(type.repeat, element);
      return tuple;
    }
    for (size_t i = 0; i < type.memberNames.size(); ++i) {
      for (size_t j = 0; j < i; ++j)
        if (type.memberNames[j] == type.memberNames[i]) {
          diags.error(type.memberLocs[i], "redefinition of tuple member '" +
                                              type.memberNames[i] + "'");
          return Type::error();
        }
      const ElementDecl *element = lookupElement(type.memberTypes[i]);
      if (!element) {
        diags.error(type.memberLocs[i], "undeclared element type '" +
                                            type.memberTypes[i] + "'");
        return Type::error();
      }
      tuple->members.push_back(element);
      tuple->memberNames.push_back(type.memberNames[i]);
    }
    return tuple;
  }
  }
  return Type::error();
}

//===----------------------------------------------------------------------===//
// Declarations
//===----------------------------------------------------------------------===//

static Intrinsic intrinsicByName(const std::string &name) {
  static const std::map<std::string, Intrinsic> table = {
      {"mod", Intrinsic::Mod}, {"sin", Intrinsic::Sin},
      {"cos", Intrinsic::Cos}, {"tan", Intrinsic::Tan},
      {"asin", Intrinsic::Asin}, {"acos", Intrinsic::Acos},
      {"sqrt", Intrinsic::Sqrt}, {"cbrt", Intrinsic::Cbrt},
      {"log", Intrinsic::Log}, {"exp", Intrinsic::Exp},
      {"abs", Intrinsic::Abs}, {"atan2", Intrinsic::Atan2},
      {"pow", Intrinsic::Pow}, {"max", Intrinsic::Max},
      {"min", Intrinsic::Min}, {"det", Intrinsic::Det},
      {"det2", Intrinsic::Det2}, {"det4", Intrinsic::Det4},
      {"inv", Intrinsic::Inv}, {"inv2", Intrinsic::Inv2},
      {"inv4", Intrinsic::Inv4}, {"cross", Intrinsic::Cross},
      {"norm", Intrinsic::Norm}, {"dot", Intrinsic::Dot},
      {"lu", Intrinsic::Lu}, {"chol", Intrinsic::Chol},
      {"lusolve", Intrinsic::LuSolve}, {"lltsolve", Intrinsic::LltSolve},
      {"lumatsolve", Intrinsic::LuMatSolve},
      {"lltmatsolve", Intrinsic::LltMatSolve},
      {"lufree", Intrinsic::LuFree}, {"cholfree", Intrinsic::CholFree},
      {"triangularSolve", Intrinsic::TriangularSolve},
      {"createComplex", Intrinsic::CreateComplex},
      {"complexNorm", Intrinsic::ComplexNorm},
      {"complexGetReal", Intrinsic::ComplexGetReal},
      {"complexGetImag", Intrinsic::ComplexGetImag},
      {"complexConj", Intrinsic::ComplexConj}, {"clock", Intrinsic::Clock},
      {"storeTime", Intrinsic::StoreTime}};
  auto it = table.find(name);
  return it == table.end() ? Intrinsic::None : it->second;
}

Intrinsic simit::frontend::intrinsicOf(const FuncDecl &func) {
  return func.isIntrinsic ? intrinsicByName(func.name) : Intrinsic::None;
}

void Sema::declareIntrinsics() {
  // The prelude is parsed with its own source manager: it never produces
  // diagnostics, and user diagnostics never point into it.
  llvm::SourceMgr preludeMgr;
  DiagnosticEngine preludeDiags(preludeMgr);
  std::unique_ptr<Program> prelude = parse(kIntrinsicPrelude, preludeDiags);
  for (auto &func : prelude->funcs) {
    func->isIntrinsic = true;
    ctx = Context();
    ctx.func = func.get();
    ctx.genericMode = func->isGeneric();
    scopes.assign(1, {});
    for (auto &g : func->generics)
      declareLocal(g.get());
    for (auto &p : func->params) {
      p->type = resolveType(*p->typeExpr);
      declareLocal(p.get());
    }
    for (auto &r : func->results)
      r->type = resolveType(*r->typeExpr);
    functions[func->name] = {func.get(), 0};
    allFunctionNames.insert(func->name);
    program.intrinsics.push_back(std::move(func));
  }
  scopes.clear();
  ctx = Context();
}

void Sema::checkElement(ElementDecl &element, unsigned order) {
  if (elements.count(element.name))
    diags.error(element.loc, "redefinition of element type '" + element.name +
                                 "'");
  ctx = Context();
  ctx.visibleBefore = order;
  for (size_t i = 0; i < element.fields.size(); ++i) {
    auto &field = element.fields[i];
    for (size_t j = 0; j < i; ++j)
      if (element.fields[j].name == field.name)
        diags.error(field.loc, "redefinition of field '" + field.name + "'");
    field.type = resolveType(*field.typeExpr);
    if (field.type->isSystem()) {
      diags.error(field.loc, "a field cannot have a set dimension");
      field.type = Type::error();
    }
  }
  if (!elements.count(element.name))
    elements[element.name] = {&element, order};
}

/// `const` initialisation: components equal and shapes equal after dropping
/// leading size-1 dimensions, orientation ignored.
static bool constShapeMatches(const Type &declared, const Type &value) {
  if (declared.component != value.component)
    return false;
  auto trimmed = [](const Type &t) {
    std::vector<Dim> dims;
    for (const Type *level = &t; level; level = level->block.get())
      dims.insert(dims.end(), level->dims.begin(), level->dims.end());
    size_t first = 0;
    while (first < dims.size() && dims[first] == Dim::range(1))
      ++first;
    return std::vector<Dim>(dims.begin() + first, dims.end());
  };
  if (declared.block || value.block)
    return simit::frontend::typesEqual(std::make_shared<Type>(declared),
                 std::make_shared<Type>(value), false);
  return trimmed(declared) == trimmed(value);
}

void Sema::checkGlobal(VarDecl &var, unsigned order) {
  ctx = Context();
  ctx.visibleBefore = order;
  scopes.clear();
  if (var.role == VarDecl::Role::Extern) {
    var.type = resolveType(*var.typeExpr);
    if (!var.type->isError() && !var.type->isSet() && !var.type->isTensor()) {
      diags.error(var.typeExpr->loc,
                  "an extern must be a set, grid or tensor, not '" +
                      var.type->str() + "'");
      var.type = Type::error();
    }
  } else {
    TypePtr value = checkExpr(var.init);
    TypePtr declared = var.typeExpr ? resolveType(*var.typeExpr) : nullptr;
    var.type = declared ? declared : value;
    if (!value->isError() && !isLiteral(*var.init)) {
      diags.error(var.init->loc, "global constant must be a literal");
    } else if (declared && !declared->isError() && !value->isError()) {
      if (value->isScalar() && !declared->isScalar())
        diags.error(var.init->loc,
                    "a non-scalar global constant cannot be initialized "
                    "from a scalar");
      else if (!constShapeMatches(*declared, *value))
        diags.error(var.init->loc, "cannot initialize a constant of type '" +
                                       declared->str() +
                                       "' with a value of type '" +
                                       value->str() + "'");
    }
  }
  if (globals.count(var.name))
    diags.error(var.loc, "redefinition of '" + var.name + "'");
  else
    globals[var.name] = {&var, order};
}

void Sema::checkFunctionDecl(FuncDecl &func, unsigned order) {
  func.order = order;
  auto existing = functions.find(func.name);
  if (existing != functions.end())
    diags.error(func.loc, existing->second.first->isIntrinsic
                              ? "redefinition of intrinsic function '" +
                                    func.name + "'"
                              : "redefinition of function '" + func.name +
                                    "'");
  if (func.isExport && !func.generics.empty())
    diags.error(func.loc, "exported function '" + func.name +
                              "' cannot be generic");
  ctx = Context();
  ctx.func = &func;
  ctx.visibleBefore = order;
  ctx.genericMode = func.isGeneric();
  checkFunctionBody(func);
  if (existing == functions.end())
    functions[func.name] = {&func, order};
  allFunctionNames.insert(func.name);
}

void Sema::checkFunctionBody(FuncDecl &func) {
  scopes.assign(1, {});
  for (auto &g : func.generics)
    declareLocal(g.get());
  for (auto &p : func.params) {
    p->type = resolveType(*p->typeExpr);
    declareLocal(p.get());
  }
  for (auto &r : func.results) {
    r->type = resolveType(*r->typeExpr);
    if (r->type->isElement() || r->type->isSet()) {
      diags.error(r->typeExpr->loc, "a result must be a tensor or opaque "
                                    "value, not '" + r->type->str() + "'");
      r->type = Type::error();
    }
    declareLocal(r.get());
  }
  if (func.body)
    checkBlock(*func.body);
  scopes.clear();
}

void Sema::checkTestLine(TestLine &test) {
  ctx = Context();
  scopes.clear();
  auto it = functions.find(test.funcName);
  if (it != functions.end() && !it->second.first->isIntrinsic)
    test.func = it->second.first;
  auto checkLiteral = [&](ExprPtr &e) {
    TypePtr t = checkExpr(e);
    if (!t->isError() && !isLiteral(*e))
      diags.error(e->loc, "input to test must be a literal");
  };
  for (ExprPtr &arg : test.args)
    checkLiteral(arg);
  checkLiteral(test.expected);
}

bool Sema::run() {
  declareIntrinsics();
  for (auto &func : program.funcs)
    allFunctionNames.insert(func->name);
  unsigned order = 1;
  for (Decl *decl : program.order) {
    if (auto *element = dyn_cast<ElementDecl>(decl))
      checkElement(*element, order);
    else if (auto *var = dyn_cast<VarDecl>(decl))
      checkGlobal(*var, order);
    else if (auto *func = dyn_cast<FuncDecl>(decl))
      checkFunctionDecl(*func, order);
    ++order;
  }
  for (TestLine &test : program.tests)
    checkTestLine(test);
  return !diags.hasErrors();
}

bool simit::frontend::check(Program &program, DiagnosticEngine &diags) {
  return Sema(program, diags).run();
}

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

void Sema::checkBlock(Block &block) {
  pushScope();
  for (StmtPtr &stmt : block.stmts)
    checkStmt(*stmt);
  popScope();
}

void Sema::checkCondition(ExprPtr &cond) {
  TypePtr t = checkExpr(cond);
  if (!t->isError() && !t->isScalar(ScalarKind::Bool))
    diags.error(cond->loc, "condition must be a boolean, found '" + t->str() +
                               "'");
}

bool Sema::checkAssignable(const TypePtr &target, const TypePtr &value,
                           SMLoc loc, const char *what) {
  if (target->isError() || value->isError())
    return true;
  if (value->isResults() || value->isVoid()) {
    diags.error(loc, std::string("cannot ") + what + " from " +
                         (value->isVoid() ? "a call without results"
                                          : std::to_string(value->results.size()) +
                                                " values"));
    return false;
  }
  if (typesEqual(target, value))
    return true;
  if (target->isTensor() && value->isScalar() &&
      value->component == target->component)
    return true;
  if (std::string(what) == "initialize")
    diags.error(loc, "cannot initialize a variable of type '" +
                         target->str() + "' with a value of type '" +
                         value->str() + "'");
  else
    diags.error(loc, "cannot assign a value of type '" + value->str() +
                         "' to a target of type '" + target->str() + "'");
  return false;
}

void Sema::checkVarDecl(VarDecl &var) {
  TypePtr declared = var.typeExpr ? resolveType(*var.typeExpr) : nullptr;
  TypePtr value = var.init ? checkExpr(var.init) : nullptr;
  SMLoc valueLoc = var.init ? var.init->loc : var.loc;
  if (declared) {
    var.type = declared;
  } else if (value && (value->isTensor() || value->isOpaque() ||
                       value->isError())) {
    var.type = value;
  } else {
    diags.error(valueLoc, "variable '" + var.name +
                              "' must have a tensor type, but its "
                              "initializer has type '" +
                              (value ? value->str() : "?") + "'");
    var.type = Type::error();
  }
  // language.md 4.5: implicit locals hold opaque handles, `var`s do not.
  if (var.role == VarDecl::Role::Var && var.type->isOpaque()) {
    diags.error(var.loc, "variable '" + var.name +
                             "' must have a tensor type; an opaque handle "
                             "(from lu, chol or an extern func) is held by "
                             "an implicit local ('" +
                             var.name + " = lu(A);')");
    var.type = Type::error();
  }
  if (declared && value) {
    if (var.role == VarDecl::Role::Const && !value->isError() &&
        value->isTensor() && !value->isScalar() && !declared->isError()) {
      if (!constShapeMatches(*declared, *value))
        diags.error(valueLoc, "cannot initialize a constant of type '" +
                                  declared->str() + "' with a value of type '" +
                                  value->str() + "'");
    } else {
      checkAssignable(declared, value, valueLoc, "initialize");
    }
  }
  declareLocal(&var);
}

void Sema::checkStmt(Stmt &stmt) {
  switch (stmt.getKind()) {
  case Stmt::Kind::VarDecl:
    checkVarDecl(*cast<VarDeclStmt>(stmt).var);
    return;
  case Stmt::Kind::IVarDecl: {
    VarDecl &var = *cast<IVarDeclStmt>(stmt).var;
    var.type = Type::scalar(ScalarKind::Int);
    declareLocal(&var);
    return;
  }
  case Stmt::Kind::Assign:
    checkAssign(cast<AssignStmt>(stmt));
    return;
  case Stmt::Kind::Expr:
    checkExpr(cast<ExprStmt>(stmt).expr);
    return;
  case Stmt::Kind::If: {
    auto &s = cast<IfStmt>(stmt);
    for (size_t i = 0; i < s.conditions.size(); ++i) {
      checkCondition(s.conditions[i]);
      checkBlock(*s.blocks[i]);
    }
    if (s.elseBlock)
      checkBlock(*s.elseBlock);
    return;
  }
  case Stmt::Kind::While: {
    auto &s = cast<WhileStmt>(stmt);
    checkCondition(s.condition);
    checkBlock(*s.body);
    return;
  }
  case Stmt::Kind::DoWhile: {
    auto &s = cast<DoWhileStmt>(stmt);
    checkBlock(*s.body);
    checkCondition(s.condition);
    return;
  }
  case Stmt::Kind::For:
    checkFor(cast<ForStmt>(stmt));
    return;
  case Stmt::Kind::Print:
    for (ExprPtr &arg : cast<PrintStmt>(stmt).args) {
      TypePtr t = checkExpr(arg);
      if (!t->isError() && !t->isTensor())
        diags.error(arg->loc, "cannot print a value of type '" + t->str() +
                                  "'");
    }
    return;
  case Stmt::Kind::Apply: {
    auto &s = cast<ApplyStmt>(stmt);
    s.map->type = checkMap(*s.map, /*isApply=*/true);
    return;
  }
  }
}

void Sema::checkFor(ForStmt &stmt) {
  VarDecl &var = *stmt.var;
  if (stmt.isRange()) {
    for (ExprPtr *bound : {&stmt.lower, &stmt.upper}) {
      TypePtr t = checkExpr(*bound);
      if (!t->isError() && !t->isScalar(ScalarKind::Int))
        diags.error((*bound)->loc, "for-loop bounds must be integral, found '" +
                                       t->str() + "'");
    }
    var.type = Type::scalar(ScalarKind::Int);
  } else {
    const Decl *decl = lookupVariable(stmt.domain);
    var.type = Type::error();
    if (!decl) {
      diags.error(stmt.domainLoc, "undeclared set '" + stmt.domain + "'");
    } else if (auto *generic = dyn_cast<GenericParamDecl>(decl)) {
      if (generic->isRange) {
        diags.error(stmt.domainLoc, "range parameter '" + generic->name +
                                        "' is iterated as '0:" +
                                        generic->name + "'");
      } else if (auto bound = boundDim(generic)) {
        stmt.domainDim = *bound;
        if (bound->kind == Dim::Kind::Set) {
          stmt.set = bound->set;
          var.type = Type::elementOf(bound->set->type->element, bound->set);
        } else {
          var.type = Type::scalar(ScalarKind::Int);
        }
      } else {
        stmt.generic = generic;
        stmt.domainDim = Dim::ofGeneric(generic);
        var.type = Type::scalar(ScalarKind::Int);
      }
    } else {
      auto *set = cast<VarDecl>(decl);
      if (set->type && set->type->isSet()) {
        stmt.set = set;
        stmt.domainDim = Dim::ofSet(set);
        var.type = Type::elementOf(set->type->element, set);
      } else if (!set->type || !set->type->isError()) {
        diags.error(stmt.domainLoc,
                    "expected a set, but '" + stmt.domain + "' has type '" +
                        (set->type ? set->type->str() : "?") + "'");
      }
    }
  }
  pushScope();
  declareLocal(&var);
  for (StmtPtr &s : stmt.body->stmts)
    checkStmt(*s);
  popScope();
}

/// Index expressions allow only element-wise and product operators.
static void checkIndexExprOperators(const Expr &e, DiagnosticEngine &diags) {
  if (auto *b = dyn_cast<BinaryExpr>(&e)) {
    if (b->op == BinaryExpr::Op::Div || b->op == BinaryExpr::Op::LeftDiv)
      diags.error(b->loc, std::string("operator '") + binaryOpSpelling(b->op) +
                              "' is not allowed in an index expression");
    checkIndexExprOperators(*b->lhs, diags);
    checkIndexExprOperators(*b->rhs, diags);
  } else if (auto *u = dyn_cast<UnaryExpr>(&e)) {
    checkIndexExprOperators(*u->operand, diags);
  } else if (auto *t = dyn_cast<TransposeExpr>(&e)) {
    checkIndexExprOperators(*t->operand, diags);
  }
}

void Sema::checkAssign(AssignStmt &stmt) {
  ctx.inAssignment = true;
  ctx.ivarsSeen.clear();
  TypePtr value = checkExpr(stmt.value);
  std::set<const VarDecl *> valueIvars = ctx.ivarsSeen;
  ctx.ivarsSeen.clear();

  std::vector<TypePtr> values;
  if (value->isResults())
    values = value->results;
  else
    values.push_back(value);
  if (!value->isError() && values.size() != stmt.targets.size()) {
    diags.error(stmt.value->loc,
                "cannot assign " + std::to_string(values.size()) +
                    (values.size() == 1 ? " value" : " values") + " to " +
                    std::to_string(stmt.targets.size()) +
                    (stmt.targets.size() == 1 ? " target" : " targets"));
    for (ExprPtr &target : stmt.targets)
      checkAssignTarget(stmt, target, Type::error(), stmt.value->loc);
  } else {
    for (size_t i = 0; i < stmt.targets.size(); ++i)
      checkAssignTarget(stmt, stmt.targets[i],
                        value->isError() ? value : values[i], stmt.value->loc);
  }
  std::set<const VarDecl *> targetIvars = ctx.ivarsSeen;
  if (!valueIvars.empty() || !targetIvars.empty()) {
    stmt.isIndexExpr = true;
    stmt.freeIndexVars.assign(targetIvars.begin(), targetIvars.end());
    for (const VarDecl *v : valueIvars)
      if (!targetIvars.count(v))
        stmt.reductionIndexVars.push_back(v);
    checkIndexExprOperators(*stmt.value, diags);
  }
  ctx.inAssignment = false;
  ctx.ivarsSeen.clear();
  ctx.ivarRanges.clear();
}

void Sema::checkAssignTarget(AssignStmt &stmt, ExprPtr &target,
                             const TypePtr &value, SMLoc valueLoc) {
  if (auto *name = dyn_cast<NameExpr>(target.get());
      name && !name->parenthesized) {
    const Decl *decl = lookupVariable(name->name);
    if (!decl) {
      // Implicit declaration of an immutable local.
      auto var = std::make_unique<VarDecl>(VarDecl::Role::Implicit, name->name,
                                           name->loc);
      if (!value->isError() && !value->isTensor() && !value->isOpaque()) {
        diags.error(valueLoc, "cannot declare '" + name->name +
                                  "' from a non-tensor value of type '" +
                                  value->str() + "'");
        var->type = Type::error();
      } else {
        var->type = value;
      }
      name->decl = var.get();
      name->type = var->type;
      declareLocal(var.get());
      stmt.implicitDecls.push_back(std::move(var));
      return;
    }
    name->decl = decl;
    auto *var = dyn_cast<VarDecl>(decl);
    if (!var) {
      diags.error(name->loc, "assignment target is not writable: '" +
                                 name->name + "' is a generic parameter");
      name->type = Type::error();
      return;
    }
    name->type = var->type;
    if (var->role == VarDecl::Role::IndexVar) {
      diags.error(name->loc, "index variable '" + name->name +
                                 "' is not writable");
      return;
    }
    if (!isWritable(*name)) {
      diags.error(name->loc, "assignment target is not writable: '" +
                                 name->name + "' is read-only");
      return;
    }
    if (var->type->isError())
      return;
    if (!var->type->isTensor() && !var->type->isOpaque()) {
      diags.error(name->loc, "only tensors and opaque values can be "
                             "assigned, not '" + var->type->str() + "'");
      return;
    }
    checkAssignable(var->type, value, valueLoc, "assign");
    return;
  }
  TypePtr t = checkExpr(target);
  if (t->isError())
    return;
  if (auto *read = dyn_cast<ReadExpr>(target.get()); read && read->isSlice()) {
    diags.error(target->loc, "assignment through a slice is not supported");
    return;
  }
  if (!isWritable(*target)) {
    diags.error(target->loc, "assignment target is not writable");
    return;
  }
  if (!t->isTensor() && !t->isOpaque()) {
    diags.error(target->loc, "only tensors and opaque values can be "
                             "assigned, not '" + t->str() + "'");
    return;
  }
  checkAssignable(t, value, valueLoc, "assign");
}

//===----------------------------------------------------------------------===//
// Writability
//===----------------------------------------------------------------------===//

bool Sema::isWritable(const Expr &e) const {
  if (const VarDecl *var = varOf(e)) {
    switch (var->role) {
    case VarDecl::Role::Var:
    case VarDecl::Role::Result:
    case VarDecl::Role::Extern:
      return true;
    case VarDecl::Role::Param:
      return var->inout;
    default:
      return false;
    }
  }
  if (auto *read = dyn_cast<ReadExpr>(&e))
    return !read->isSlice() && isWritable(*read->base);
  if (auto *field = dyn_cast<FieldExpr>(&e)) {
    if (field->isSetField)
      return true;
    return isWritableElement(*field->base);
  }
  return false;
}

bool Sema::isWritableElement(const Expr &e) const {
  if (const VarDecl *var = varOf(e))
    return var->role == VarDecl::Role::Param && var->inout;
  if (auto *tuple = dyn_cast<TupleReadExpr>(&e))
    return isWritableElement(*tuple->base);
  return false;
}
