//===- SemaCall.cpp - Calls, maps and generic instances -------------------===//

#include "SemaImpl.h"

#include "simit/Frontend/Parser.h"
#include "simit/Frontend/Sema.h"

using namespace simit::frontend;
using llvm::cast;
using llvm::dyn_cast;
using llvm::dyn_cast_or_null;
using llvm::isa;

static std::vector<const GenericParamDecl *> genericsOf(const FuncDecl &f) {
  std::vector<const GenericParamDecl *> params;
  for (auto &g : f.generics)
    params.push_back(g.get());
  return params;
}

static std::string ordinal(unsigned i) { return std::to_string(i + 1); }

void Sema::unify(const FuncDecl &callee, const TypePtr &param,
                 const TypePtr &arg, std::vector<std::optional<Dim>> &binding) {
  const Type *p = param.get(), *a = arg.get();
  while (p && a && p->isTensor() && a->isTensor()) {
    for (size_t i = 0; i < p->dims.size() && i < a->dims.size(); ++i) {
      const Dim &d = p->dims[i];
      if (d.kind != Dim::Kind::Generic)
        continue;
      unsigned index = d.generic->index;
      if (index < callee.generics.size() &&
          callee.generics[index].get() == d.generic && !binding[index])
        binding[index] = a->dims[i];
    }
    p = p->block.get();
    a = a->block.get();
  }
}

TypePtr Sema::resultTypeOf(const FuncDecl &callee,
                           const std::vector<Dim> &binding) {
  auto params = genericsOf(callee);
  std::vector<TypePtr> results;
  for (auto &r : callee.results)
    results.push_back(substitute(r->type ? r->type : Type::error(), params,
                                 binding));
  if (results.empty())
    return Type::voidType();
  if (results.size() == 1)
    return results.front();
  return Type::resultsOf(results);
}

bool Sema::inferBinding(const FuncDecl &callee,
                        std::vector<std::optional<Dim>> &binding,
                        const std::vector<DimExpr> &explicitArgs,
                        bool hasExplicit, SMLoc loc) {
  (void)hasExplicit;
  if (explicitArgs.size() > callee.generics.size()) {
    diags.error(loc, "too many generic arguments for '" + callee.name +
                         "': it has " + std::to_string(callee.generics.size()));
    return false;
  }
  for (size_t i = 0; i < explicitArgs.size(); ++i) {
    auto dim = resolveDim(explicitArgs[i], /*forGenericArg=*/true);
    if (!dim)
      return false;
    binding[i] = *dim;
  }
  return true;
}

/// Checks an argument against a parameter type (generics substituted);
/// elements and tuples also against the origins the callee inferred.
bool Sema::checkArgument(const FuncDecl &callee, unsigned i, ExprPtr &arg,
                         const TypePtr &paramType, const std::string &what) {
  const VarDecl &param = *callee.params[i];
  TypePtr t = arg->type;
  if (!t || t->isError() || paramType->isError())
    return false;
  if (!typesEqual(t, paramType)) {
    diags.error(arg->loc, what + " passes argument of type '" + t->str() +
                              "' but '" + callee.name + "' expects '" +
                              paramType->str() + "'");
    return false;
  }
  auto expectedOrigin = [&](int member) -> const VarDecl * {
    auto it = callee.inferredOrigins.find({&param, member});
    return it == callee.inferredOrigins.end() ? nullptr : it->second;
  };
  if (t->isElement()) {
    const VarDecl *origin = originOf(*arg, nullptr);
    const VarDecl *expected = expectedOrigin(-1);
    if (origin && expected && origin != expected) {
      diags.error(arg->loc, "expected an element of set '" + expected->name +
                                "', but the argument is inferred to be of "
                                "set '" + origin->name + "'");
      return false;
    }
  }
  if (t->isTuple()) {
    auto origins = tupleOriginsOf(*arg);
    bool named = !t->memberNames.empty();
    for (size_t m = 0; m < origins.size(); ++m) {
      const VarDecl *expected = expectedOrigin(named ? (int)m : -1);
      if (origins[m] && expected && origins[m] != expected) {
        diags.error(arg->loc, "expected elements of set '" + expected->name +
                                  "', but the argument's are inferred to be "
                                  "of set '" + origins[m]->name + "'");
        return false;
      }
    }
  }
  if (param.inout && !isWritable(*arg)) {
    diags.error(arg->loc, "inout argument " + ordinal(i) + " of '" +
                              callee.name + "' must be writable");
    return false;
  }
  return true;
}

TypePtr Sema::checkNormOrDot(CallExpr &call) {
  bool isNorm = call.intrinsic == Intrinsic::Norm;
  size_t arity = isNorm ? 1 : 2;
  if (call.args.size() != arity) {
    diags.error(call.loc, "function '" + call.callee + "' expects " +
                              std::to_string(arity) +
                              (arity == 1 ? " argument" : " arguments") +
                              " but " + std::to_string(call.args.size()) +
                              " were given");
    return Type::error();
  }
  std::vector<TypePtr> types;
  for (ExprPtr &arg : call.args) {
    types.push_back(checkExpr(arg));
    if (types.back()->isError())
      return Type::error();
  }
  for (size_t i = 0; i < types.size(); ++i)
    if (!types[i]->isNumericTensor() || !types[i]->isVector()) {
      diags.error(call.args[i]->loc, "'" + call.callee +
                                         "' expects a numeric vector, found '" +
                                         types[i]->str() + "'");
      return Type::error();
    }
  if (isNorm)
    return Type::scalar(ScalarKind::Float);
  if (!typesEqual(types[0], types[1], /*orientation=*/false)) {
    diags.error(call.loc, "'dot' expects two vectors of the same type, found '" +
                              types[0]->str() + "' and '" + types[1]->str() +
                              "'");
    return Type::error();
  }
  // language.md 9: a float; complex vectors give their complex sum.
  if (types[0]->component == ScalarKind::Int)
    return Type::scalar(ScalarKind::Float);
  return Type::scalar(types[0]->component);
}

TypePtr Sema::checkCall(CallExpr &call) {
  const FuncDecl *found = lookupFunction(call.callee);
  if (!found) {
    diags.error(call.loc, "undeclared function '" + call.callee + "'");
    for (ExprPtr &arg : call.args)
      if (arg)
        checkExpr(arg);
    return Type::error();
  }
  FuncDecl &callee = const_cast<FuncDecl &>(*found);
  call.func = &callee;
  call.intrinsic = intrinsicOf(callee);
  for (ExprPtr &arg : call.args)
    if (!arg) {
      diags.error(call.loc, "expected an expression, found ':' in the "
                            "arguments of '" + call.callee + "'");
      return Type::error();
    }
  if (call.intrinsic == Intrinsic::Norm || call.intrinsic == Intrinsic::Dot)
    return checkNormOrDot(call);

  bool ok = true;
  for (ExprPtr &arg : call.args) {
    TypePtr t = checkExpr(arg);
    if (t->isError()) {
      ok = false;
    } else if (t->isVoid() || t->isResults()) {
      diags.error(arg->loc, "argument of '" + call.callee +
                                "' must be a single non-void value");
      ok = false;
    }
  }
  if (call.args.size() != callee.params.size()) {
    diags.error(call.loc, "function '" + call.callee + "' expects " +
                              std::to_string(callee.params.size()) +
                              (callee.params.size() == 1 ? " argument"
                                                         : " arguments") +
                              " but " + std::to_string(call.args.size()) +
                              (call.args.size() == 1 ? " was" : " were") +
                              " given");
    return Type::error();
  }
  if (!ok)
    return Type::error();

  std::vector<std::optional<Dim>> binding(callee.generics.size());
  if (!inferBinding(callee, binding, call.genericArgs, call.hasGenericArgs,
                    call.loc))
    return Type::error();
  for (size_t i = 0; i < call.args.size(); ++i) {
    const VarDecl &param = *callee.params[i];
    unify(callee, param.type, call.args[i]->type, binding);
    // Generic parameters indexed by element parameters bind to the origin
    // of the element (or tuple member) passed.
    for (auto &[generic, key] : callee.genericFromOrigin) {
      if (key.first != &param || binding[generic->index])
        continue;
      const VarDecl *origin = nullptr;
      if (call.args[i]->type->isTuple()) {
        auto origins = tupleOriginsOf(*call.args[i]);
        size_t m = key.second < 0 ? 0 : key.second;
        if (m < origins.size())
          origin = origins[m];
      } else {
        origin = originOf(*call.args[i], nullptr);
      }
      if (origin)
        binding[generic->index] = Dim::ofSet(origin);
    }
  }
  std::vector<Dim> bound;
  for (size_t g = 0; g < binding.size(); ++g) {
    if (!binding[g]) {
      diags.error(call.loc, "unable to resolve type parameter '" +
                                callee.generics[g]->name + "' of '" +
                                callee.name + "'");
      return Type::error();
    }
    bound.push_back(*binding[g]);
  }
  // A set parameter stands for the set passed: tensors over it are tensors
  // over that set, in the other arguments and in the results.
  std::vector<std::pair<const VarDecl *, const VarDecl *>> sets;
  for (size_t i = 0; i < call.args.size(); ++i)
    if (callee.params[i]->type && callee.params[i]->type->isSet())
      if (const VarDecl *set = varOf(*call.args[i]))
        sets.push_back({callee.params[i].get(), set});
  auto params = genericsOf(callee);
  for (size_t i = 0; i < call.args.size(); ++i)
    ok &= checkArgument(
        callee, i, call.args[i],
        substituteSets(substitute(callee.params[i]->type, params, bound), sets),
        "call of '" + callee.name + "'");
  if (!ok)
    return Type::error();
  call.binding = bound;
  if (callee.isGeneric() && callee.body && !ctx.genericMode)
    call.func = instantiate(callee, bound);
  if (ctx.func)
    ctx.func->callees.push_back(call.func);
  return substituteSets(resultTypeOf(callee, bound), sets);
}

const FuncDecl *Sema::instantiate(FuncDecl &generic,
                                  const std::vector<Dim> &binding) {
  for (auto &instance : generic.instances)
    if (instance->binding == binding)
      return instance.get();
  std::set<std::string> known = intrinsicNames();
  for (auto &[name, entry] : functions)
    if (entry.second < generic.order)
      known.insert(name);
  std::unique_ptr<FuncDecl> instance =
      parseFunction(generic.source, diags, known);
  if (!instance)
    return &generic;
  instance->genericOrigin = &generic;
  instance->binding = binding;
  instance->order = generic.order;
  instance->mangledName = generic.name;
  for (const Dim &d : binding)
    instance->mangledName += "_" + d.str();
  FuncDecl *raw = instance.get();
  generic.instances.push_back(std::move(instance));

  Context savedCtx = std::move(ctx);
  auto savedScopes = std::move(scopes);
  ctx = Context();
  ctx.func = raw;
  ctx.visibleBefore = raw->order;
  checkFunctionBody(*raw);
  ctx = std::move(savedCtx);
  scopes = std::move(savedScopes);
  return raw;
}

TypePtr Sema::checkMap(MapExpr &map, bool isApply) {
  const FuncDecl *found = lookupFunction(map.funcName);
  bool ok = true;
  for (ExprPtr &arg : map.args) {
    TypePtr t = checkExpr(arg);
    if (t->isError()) {
      ok = false;
    } else if (!t->isTensor() && !t->isOpaque()) {
      diags.error(arg->loc, "extra map argument must be a tensor or opaque "
                            "value, found '" + t->str() + "'");
      ok = false;
    }
  }
  if (!found) {
    diags.error(map.funcLoc, "undeclared function '" + map.funcName + "'");
    return Type::error();
  }
  if (found->isIntrinsic) {
    diags.error(map.funcLoc, "cannot map intrinsic function '" +
                                 map.funcName + "'");
    return Type::error();
  }
  FuncDecl &callee = const_cast<FuncDecl &>(*found);
  map.func = &callee;

  const Decl *targetDecl = lookupVariable(map.target);
  const VarDecl *target = dyn_cast_or_null<VarDecl>(targetDecl);
  if (!targetDecl) {
    diags.error(map.targetLoc, "undeclared set '" + map.target + "'");
    return Type::error();
  }
  if (!target || !target->type || !target->type->isSet()) {
    diags.error(map.targetLoc,
                "expected a set to map over, but '" + map.target +
                    (target && target->type
                         ? "' has type '" + target->type->str() + "'"
                         : "' is a generic parameter"));
    return Type::error();
  }
  map.targetSet = target;
  const Type &set = *target->type;
  if (!map.through.empty()) {
    auto *grid = dyn_cast_or_null<VarDecl>(lookupVariable(map.through));
    if (!grid || !grid->type || !grid->type->isGrid() ||
        grid->type->endpoints.front() != target) {
      diags.error(map.throughLoc, "'through' needs a grid over '" +
                                      map.target + "'");
      return Type::error();
    }
    map.grid = grid;
  }
  if (!ok)
    return Type::error();

  // Arguments: extras, the element, the endpoint tuple, the grid.
  size_t extras = map.args.size();
  size_t base = extras + 1 + (map.grid ? 1 : 0);
  bool passesEndpoints = set.isEdgeSet() && callee.params.size() > base;
  size_t expected = base + (passesEndpoints ? 1 : 0);
  if (callee.params.size() != expected) {
    diags.error(map.funcLoc,
                "function '" + callee.name + "' takes " +
                    std::to_string(callee.params.size()) +
                    (callee.params.size() == 1 ? " argument" : " arguments") +
                    " but the map passes " + std::to_string(expected));
    return Type::error();
  }
  std::vector<std::optional<Dim>> binding(callee.generics.size());
  if (!inferBinding(callee, binding, map.genericArgs, map.hasGenericArgs,
                    map.funcLoc))
    return Type::error();
  for (size_t i = 0; i < extras; ++i)
    unify(callee, callee.params[i]->type, map.args[i]->type, binding);

  std::string what = "map of '" + callee.name + "' over '" + map.target + "'";
  // The element.
  const VarDecl &elementParam = *callee.params[extras];
  if (!elementParam.type || elementParam.type->isError())
    return Type::error();
  if (!elementParam.type->isElement() ||
      elementParam.type->element != set.element) {
    diags.error(map.targetLoc, what + " passes argument of type '" +
                                   set.element->name + "' but function "
                                   "expects '" + elementParam.type->str() +
                                   "'");
    return Type::error();
  }
  auto inferred = [&](const VarDecl *p, int m) -> const VarDecl * {
    auto it = callee.inferredOrigins.find({p, m});
    return it == callee.inferredOrigins.end() ? nullptr : it->second;
  };
  if (const VarDecl *origin = inferred(&elementParam, -1);
      origin && origin != target) {
    diags.error(map.targetLoc, "function '" + callee.name +
                                   "' expects elements of set '" +
                                   origin->name + "', but the map passes '" +
                                   map.target + "'");
    return Type::error();
  }
  // The endpoint tuple.
  const VarDecl *tupleParam = passesEndpoints ? callee.params[extras + 1].get()
                                              : nullptr;
  if (tupleParam) {
    const TypePtr &tt = tupleParam->type;
    if (!tt || tt->isError())
      return Type::error();
    if (!tt->isTuple()) {
      diags.error(map.targetLoc, what + " passes an endpoint tuple but '" +
                                     callee.name + "' expects '" + tt->str() +
                                     "'");
      return Type::error();
    }
    bool named = !tt->memberNames.empty();
    if (!named && !set.isHomogeneous()) {
      diags.error(map.targetLoc, "heterogeneous edge set '" + map.target +
                                     "' needs a named endpoint tuple "
                                     "parameter");
      return Type::error();
    }
    if (tt->members.size() != set.cardinality()) {
      diags.error(map.targetLoc,
                  what + " passes " + std::to_string(set.cardinality()) +
                      " endpoints but '" + callee.name + "' expects '" +
                      tt->str() + "'");
      return Type::error();
    }
    for (size_t m = 0; m < set.cardinality(); ++m) {
      const VarDecl *endpoint = set.endpoint(m);
      if (tt->members[m] != endpoint->type->element) {
        diags.error(map.targetLoc,
                    what + " passes endpoint of type '" +
                        endpoint->type->element->name + "' but '" +
                        callee.name + "' expects '" + tt->members[m]->name +
                        "'");
        return Type::error();
      }
      const VarDecl *origin = inferred(tupleParam, named ? (int)m : -1);
      if (origin && origin != endpoint) {
        diags.error(map.targetLoc,
                    "function '" + callee.name + "' expects endpoints of set '" +
                        origin->name + "', but '" + map.target +
                        "' connects '" + endpoint->name + "'");
        return Type::error();
      }
    }
    map.endpointForm = named ? MapExpr::EndpointForm::Named
                             : MapExpr::EndpointForm::Unnamed;
  }
  // The grid.
  if (map.grid) {
    const VarDecl &gridParam = *callee.params.back();
    if (!gridParam.type || !typesEqual(gridParam.type, map.grid->type)) {
      diags.error(map.throughLoc,
                  what + " passes grid '" + map.through + "' but '" +
                      callee.name + "' expects '" +
                      (gridParam.type ? gridParam.type->str() : "?") + "'");
      return Type::error();
    }
  }
  // Generic parameters indexed by the element or its endpoints.
  for (auto &[generic, key] : callee.genericFromOrigin) {
    if (binding[generic->index])
      continue;
    if (key.first == &elementParam)
      binding[generic->index] = Dim::ofSet(target);
    else if (tupleParam && key.first == tupleParam)
      binding[generic->index] =
          Dim::ofSet(set.endpoint(key.second < 0 ? 0 : key.second));
  }
  std::vector<Dim> bound;
  for (size_t g = 0; g < binding.size(); ++g) {
    if (!binding[g]) {
      diags.error(map.funcLoc, "unable to resolve type parameter '" +
                                   callee.generics[g]->name + "' of '" +
                                   callee.name + "'");
      return Type::error();
    }
    bound.push_back(*binding[g]);
  }
  auto params = genericsOf(callee);
  for (size_t i = 0; i < extras; ++i)
    ok &= checkArgument(callee, i, map.args[i],
                        substitute(callee.params[i]->type, params, bound), what);
  if (!ok)
    return Type::error();

  TypePtr result = resultTypeOf(callee, bound);
  // Results may only be over the mapped set, its endpoint sets and ranges.
  std::vector<TypePtr> results =
      result->isResults() ? result->results : std::vector<TypePtr>{result};
  for (size_t r = 0; r < results.size(); ++r) {
    if (!results[r]->isTensor())
      continue;
    for (const Type *level = results[r].get(); level;
         level = level->block.get())
      for (const Dim &d : level->dims) {
        if (d.kind != Dim::Kind::Set || d.set == target)
          continue;
        bool endpoint = false;
        for (const VarDecl *e : set.endpoints)
          endpoint |= e == d.set;
        if (!endpoint) {
          diags.error(map.targetLoc,
                      "result '" + callee.results[r]->name + "' of '" +
                          callee.name + "' is over set '" + d.set->name +
                          "', which is neither '" + map.target +
                          "' nor one of its endpoint sets");
          return Type::error();
        }
      }
  }
  if (isApply && !result->isVoid()) {
    diags.error(map.funcLoc, "cannot apply a non-void function '" +
                                 callee.name + "'; use map");
    return Type::error();
  }
  map.binding = bound;
  if (callee.isGeneric() && callee.body && !ctx.genericMode)
    map.func = instantiate(callee, bound);
  if (ctx.func)
    ctx.func->callees.push_back(map.func);
  return result;
}
