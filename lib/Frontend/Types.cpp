//===- Types.cpp - Semantic types of Simit values -------------------------===//

#include "simit/Frontend/Types.h"
#include "simit/Frontend/AST.h"

using namespace simit::frontend;

const char *simit::frontend::scalarKindName(ScalarKind kind) {
  switch (kind) {
  case ScalarKind::Int: return "int";
  case ScalarKind::Float: return "float";
  case ScalarKind::Bool: return "bool";
  case ScalarKind::Complex: return "complex";
  case ScalarKind::String: return "string";
  }
  return "?";
}

std::string Dim::str() const {
  switch (kind) {
  case Kind::Range: return std::to_string(size);
  case Kind::Set: return set->name;
  case Kind::Generic: return generic->name;
  }
  return "?";
}

TypePtr Type::error() {
  static TypePtr t = [] {
    auto e = std::make_shared<Type>();
    e->kind = Kind::Error;
    return e;
  }();
  return t;
}

TypePtr Type::voidType() {
  static TypePtr t = [] {
    auto v = std::make_shared<Type>();
    v->kind = Kind::Void;
    return v;
  }();
  return t;
}

TypePtr Type::opaque() {
  static TypePtr t = [] {
    auto o = std::make_shared<Type>();
    o->kind = Kind::Opaque;
    return o;
  }();
  return t;
}

TypePtr Type::scalar(ScalarKind kind) {
  return tensor(kind, {}, nullptr, false);
}

TypePtr Type::tensor(ScalarKind component, std::vector<Dim> dims,
                     TypePtr block, bool row) {
  auto t = std::make_shared<Type>();
  t->kind = Kind::Tensor;
  t->component = component;
  t->dims = std::move(dims);
  // A scalar block adds nothing to the hierarchy.
  if (block && !block->isScalar())
    t->block = std::move(block);
  t->row = row && t->dims.size() == 1;
  return t;
}

TypePtr Type::elementOf(const ElementDecl *element, const VarDecl *origin) {
  auto t = std::make_shared<Type>();
  t->kind = Kind::Element;
  t->element = element;
  t->origin = origin;
  return t;
}

TypePtr Type::resultsOf(std::vector<TypePtr> results) {
  auto t = std::make_shared<Type>();
  t->kind = Kind::Results;
  t->results = std::move(results);
  return t;
}

bool Type::isSystem() const {
  if (!isTensor())
    return false;
  for (const Dim &d : dims)
    if (d.kind == Dim::Kind::Set)
      return true;
  return block && block->isSystem();
}

bool Type::isHomogeneous() const {
  for (const VarDecl *e : endpoints)
    if (e != endpoints.front())
      return false;
  return true;
}

std::vector<Dim> Type::hierarchy(unsigned i) const {
  std::vector<Dim> result;
  for (const Type *t = this; t && i < t->dims.size(); t = t->block.get())
    result.push_back(t->dims[i]);
  return result;
}

std::string Type::str() const {
  switch (kind) {
  case Kind::Error: return "<error>";
  case Kind::Void: return "void";
  case Kind::Opaque: return "opaque";
  case Kind::Element: return element->name;
  case Kind::Tensor: {
    if (dims.empty())
      return scalarKindName(component);
    std::string s = "tensor[";
    for (size_t i = 0; i < dims.size(); ++i)
      s += (i ? "," : "") + dims[i].str();
    s += "](";
    s += block ? block->str() : scalarKindName(component);
    s += ")";
    if (row)
      s += "'";
    return s;
  }
  case Kind::Set: {
    if (gridRank) {
      return "grid[" + std::to_string(gridRank) + "]{" + element->name +
             "}(" + endpoints.front()->name + ")";
    }
    std::string s = "set{" + element->name + "}";
    if (!endpoints.empty()) {
      s += "(";
      for (size_t i = 0; i < endpoints.size(); ++i)
        s += (i ? "," : "") + endpoints[i]->name;
      s += ")";
    }
    return s;
  }
  case Kind::Tuple: {
    std::string s = "(";
    if (memberNames.empty()) {
      s += members.front()->name + "*" + std::to_string(members.size());
    } else {
      for (size_t i = 0; i < members.size(); ++i)
        s += (i ? ", " : "") + memberNames[i] + " : " + members[i]->name;
    }
    return s + ")";
  }
  case Kind::Results: {
    std::string s = "(";
    for (size_t i = 0; i < results.size(); ++i)
      s += (i ? ", " : "") + results[i]->str();
    return s + ")";
  }
  }
  return "?";
}

bool simit::frontend::typesEqual(const TypePtr &a, const TypePtr &b,
                            bool orientation) {
  if (!a || !b)
    return a == b;
  if (a->kind != b->kind)
    return false;
  switch (a->kind) {
  case Type::Kind::Error:
  case Type::Kind::Void:
  case Type::Kind::Opaque:
    return true;
  case Type::Kind::Element:
    return a->element == b->element;
  case Type::Kind::Tensor:
    if (a->component != b->component || a->dims != b->dims)
      return false;
    if (orientation && a->row != b->row)
      return false;
    if (!a->block || !b->block)
      return !a->block && !b->block;
    return typesEqual(a->block, b->block, orientation);
  case Type::Kind::Set:
    return a->element == b->element && a->endpoints == b->endpoints &&
           a->gridRank == b->gridRank;
  case Type::Kind::Tuple:
    return a->members == b->members && a->memberNames == b->memberNames;
  case Type::Kind::Results:
    if (a->results.size() != b->results.size())
      return false;
    for (size_t i = 0; i < a->results.size(); ++i)
      if (!typesEqual(a->results[i], b->results[i], orientation))
        return false;
    return true;
  }
  return false;
}

TypePtr simit::frontend::transposed(const TypePtr &t) {
  if (!t->isTensor() || t->order() == 0)
    return t;
  // A vector of matrix blocks (a column A(:,q) of a blocked matrix)
  // transposes its blocks too: A(:,q)' is row q of A'.
  if (t->order() == 1)
    return Type::tensor(t->component, t->dims,
                        t->block && t->block->isMatrix() ? transposed(t->block)
                                                         : t->block,
                        !t->row);
  std::vector<Dim> dims = {t->dims[1], t->dims[0]};
  TypePtr block = t->block ? transposed(t->block) : nullptr;
  return Type::tensor(t->component, dims, block, false);
}

TypePtr simit::frontend::substitute(
    const TypePtr &t, const std::vector<const GenericParamDecl *> &params,
    const std::vector<Dim> &binding) {
  if (!t || !t->isTensor())
    return t;
  std::vector<Dim> dims = t->dims;
  for (Dim &d : dims) {
    if (d.kind != Dim::Kind::Generic)
      continue;
    for (size_t i = 0; i < params.size() && i < binding.size(); ++i)
      if (params[i] == d.generic)
        d = binding[i];
  }
  TypePtr block = t->block ? substitute(t->block, params, binding) : nullptr;
  return Type::tensor(t->component, dims, block, t->row);
}

TypePtr simit::frontend::substituteSets(
    const TypePtr &t,
    const std::vector<std::pair<const VarDecl *, const VarDecl *>> &sets) {
  if (!t || sets.empty())
    return t;
  if (t->isResults()) {
    std::vector<TypePtr> results;
    for (const TypePtr &r : t->results)
      results.push_back(substituteSets(r, sets));
    return Type::resultsOf(results);
  }
  if (!t->isTensor())
    return t;
  std::vector<Dim> dims = t->dims;
  for (Dim &d : dims)
    for (const auto &[param, arg] : sets)
      if (d.kind == Dim::Kind::Set && d.set == param)
        d = Dim::ofSet(arg);
  TypePtr block = t->block ? substituteSets(t->block, sets) : nullptr;
  return Type::tensor(t->component, dims, block, t->row);
}
