//===- ASTPrinter.cpp - Readable dump of a checked AST --------------------===//

#include "simit/Frontend/ASTPrinter.h"

#include "llvm/Support/Format.h"

using namespace simit::frontend;
using llvm::cast;
using llvm::dyn_cast;
using llvm::dyn_cast_or_null;
using llvm::raw_ostream;

namespace {

const char *roleName(VarDecl::Role role) {
  switch (role) {
  case VarDecl::Role::Extern: return "extern";
  case VarDecl::Role::GlobalConst: return "global-const";
  case VarDecl::Role::Param: return "param";
  case VarDecl::Role::Result: return "result";
  case VarDecl::Role::Var: return "var";
  case VarDecl::Role::Const: return "const";
  case VarDecl::Role::Implicit: return "implicit";
  case VarDecl::Role::LoopVar: return "loop-var";
  case VarDecl::Role::IndexVar: return "ivar";
  }
  return "?";
}

std::string typeStr(const TypePtr &t) { return t ? t->str() : "<unchecked>"; }

void printFloat(raw_ostream &os, double v) { os << llvm::format("%g", v); }

class Printer {
public:
  explicit Printer(raw_ostream &os) : os(os) {}

  void program(const Program &p);
  void func(const FuncDecl &f, unsigned indent);
  void block(const Block &b, unsigned indent);
  void stmt(const Stmt &s, unsigned indent);
  void expr(const Expr &e);

private:
  void pad(unsigned indent) { os.indent(indent * 2); }
  void exprs(const std::vector<ExprPtr> &list) {
    for (const ExprPtr &e : list) {
      os << ' ';
      if (e)
        expr(*e);
      else
        os << ':';
    }
  }
  void binding(const std::vector<Dim> &b) {
    os << " <";
    for (size_t i = 0; i < b.size(); ++i)
      os << (i ? "," : "") << b[i].str();
    os << '>';
  }
  void var(const VarDecl &v) {
    os << (v.inout ? "inout " : "") << v.name << " : " << typeStr(v.type);
  }
  raw_ostream &os;
};

void Printer::program(const Program &p) {
  for (const Decl *d : p.order) {
    if (auto *element = dyn_cast<ElementDecl>(d)) {
      os << "element " << element->name << '\n';
      for (const auto &f : element->fields)
        os << "  field " << f.name << " : " << typeStr(f.type) << '\n';
    } else if (auto *v = dyn_cast<VarDecl>(d)) {
      os << roleName(v->role) << ' ' << v->name << " : " << typeStr(v->type);
      if (v->init) {
        os << " = ";
        expr(*v->init);
      }
      os << '\n';
    } else if (auto *f = dyn_cast<FuncDecl>(d)) {
      func(*f, 0);
    }
  }
  for (const TestLine &t : p.tests) {
    os << "test line " << t.line << ' ' << t.funcName
       << (t.func ? "" : " (unknown)") << '(';
    exprs(t.args);
    os << " ) == ";
    expr(*t.expected);
    os << '\n';
  }
}

void Printer::func(const FuncDecl &f, unsigned indent) {
  pad(indent);
  os << (f.isExport ? "export " : "") << (f.isExtern ? "extern " : "")
     << "func " << (f.isInstance() ? f.mangledName : f.name);
  if (!f.generics.empty()) {
    os << '<';
    for (size_t i = 0; i < f.generics.size(); ++i)
      os << (i ? ", " : "") << (f.generics[i]->isRange ? "0:" : "")
         << f.generics[i]->name;
    os << '>';
  }
  os << '(';
  for (size_t i = 0; i < f.params.size(); ++i) {
    os << (i ? ", " : "");
    var(*f.params[i]);
  }
  os << ") -> (";
  for (size_t i = 0; i < f.results.size(); ++i) {
    os << (i ? ", " : "");
    var(*f.results[i]);
  }
  os << ")\n";
  if (f.isInstance()) {
    pad(indent + 1);
    os << "instance of " << f.genericOrigin->name;
    binding(f.binding);
    os << '\n';
  }
  for (const auto &[key, set] : f.inferredOrigins) {
    pad(indent + 1);
    os << "origin " << key.first->name;
    if (key.second >= 0)
      os << '.' << key.second;
    os << " in " << set->name << '\n';
  }
  if (f.body)
    block(*f.body, indent + 1);
  for (const auto &instance : f.instances)
    func(*instance, indent + 1);
}

void Printer::block(const Block &b, unsigned indent) {
  for (const StmtPtr &s : b.stmts)
    stmt(*s, indent);
}

void Printer::stmt(const Stmt &s, unsigned indent) {
  pad(indent);
  switch (s.getKind()) {
  case Stmt::Kind::VarDecl: {
    const VarDecl &v = *cast<VarDeclStmt>(s).var;
    os << roleName(v.role) << ' ' << v.name << " : " << typeStr(v.type);
    if (v.init) {
      os << " = ";
      expr(*v.init);
    }
    os << '\n';
    return;
  }
  case Stmt::Kind::IVarDecl:
    os << "ivar " << cast<IVarDeclStmt>(s).var->name << '\n';
    return;
  case Stmt::Kind::Assign: {
    auto &a = cast<AssignStmt>(s);
    os << (a.isIndexExpr ? "index-assign" : "assign");
    for (const auto &d : a.implicitDecls)
      os << " [declares " << d->name << " : " << typeStr(d->type) << ']';
    if (a.isIndexExpr) {
      os << " [free";
      for (const VarDecl *v : a.freeIndexVars)
        os << ' ' << v->name;
      os << "] [sum";
      for (const VarDecl *v : a.reductionIndexVars)
        os << ' ' << v->name;
      os << ']';
    }
    exprs(a.targets);
    os << " = ";
    expr(*a.value);
    os << '\n';
    return;
  }
  case Stmt::Kind::Expr:
    os << "eval ";
    expr(*cast<ExprStmt>(s).expr);
    os << '\n';
    return;
  case Stmt::Kind::If: {
    auto &i = cast<IfStmt>(s);
    for (size_t c = 0; c < i.conditions.size(); ++c) {
      if (c)
        pad(indent);
      os << (c ? "elif " : "if ");
      expr(*i.conditions[c]);
      os << '\n';
      block(*i.blocks[c], indent + 1);
    }
    if (i.elseBlock) {
      pad(indent);
      os << "else\n";
      block(*i.elseBlock, indent + 1);
    }
    pad(indent);
    os << "end\n";
    return;
  }
  case Stmt::Kind::While: {
    auto &w = cast<WhileStmt>(s);
    os << "while ";
    expr(*w.condition);
    os << '\n';
    block(*w.body, indent + 1);
    pad(indent);
    os << "end\n";
    return;
  }
  case Stmt::Kind::DoWhile: {
    auto &d = cast<DoWhileStmt>(s);
    os << "do\n";
    block(*d.body, indent + 1);
    pad(indent);
    os << "end while ";
    expr(*d.condition);
    os << '\n';
    return;
  }
  case Stmt::Kind::For: {
    auto &f = cast<ForStmt>(s);
    os << "for " << f.var->name << " : " << typeStr(f.var->type) << " in ";
    if (f.isRange()) {
      expr(*f.lower);
      os << " : ";
      expr(*f.upper);
    } else {
      os << (f.set ? "set " : "domain ") << f.domain;
    }
    os << '\n';
    block(*f.body, indent + 1);
    pad(indent);
    os << "end\n";
    return;
  }
  case Stmt::Kind::Print: {
    auto &p = cast<PrintStmt>(s);
    os << (p.newline ? "println" : "print");
    exprs(p.args);
    os << '\n';
    return;
  }
  case Stmt::Kind::Apply:
    os << "apply ";
    expr(*cast<ApplyStmt>(s).map);
    os << '\n';
    return;
  }
}

void Printer::expr(const Expr &e) {
  os << '(';
  switch (e.getKind()) {
  case Expr::Kind::IntLit:
    os << "int " << cast<IntLiteral>(e).value;
    break;
  case Expr::Kind::FloatLit:
    os << "float ";
    printFloat(os, cast<FloatLiteral>(e).value);
    break;
  case Expr::Kind::BoolLit:
    os << "bool " << (cast<BoolLiteral>(e).value ? "true" : "false");
    break;
  case Expr::Kind::StringLit:
    os << "string \"";
    os.write_escaped(cast<StringLiteral>(e).value);
    os << '"';
    break;
  case Expr::Kind::ComplexLit: {
    auto &c = cast<ComplexLiteral>(e);
    os << "complex <";
    printFloat(os, c.re);
    os << ',';
    printFloat(os, c.im);
    os << '>';
    break;
  }
  case Expr::Kind::DenseLit: {
    auto &d = cast<DenseLiteral>(e);
    os << "dense [";
    size_t n = d.component == ScalarKind::Int     ? d.intValues.size()
               : d.component == ScalarKind::Float ? d.floatValues.size()
                                                  : d.complexValues.size() / 2;
    for (size_t i = 0; i < n; ++i) {
      os << (i ? " " : "");
      if (d.component == ScalarKind::Int) {
        os << d.intValues[i];
      } else if (d.component == ScalarKind::Float) {
        printFloat(os, d.floatValues[i]);
      } else {
        os << '<';
        printFloat(os, d.complexValues[2 * i]);
        os << ',';
        printFloat(os, d.complexValues[2 * i + 1]);
        os << '>';
      }
    }
    os << ']';
    break;
  }
  case Expr::Kind::Name: {
    auto &n = cast<NameExpr>(e);
    os << "name " << n.name;
    if (auto *v = dyn_cast_or_null<VarDecl>(n.decl))
      os << ' ' << roleName(v->role);
    else if (n.decl)
      os << " generic";
    break;
  }
  case Expr::Kind::Call: {
    auto &c = cast<CallExpr>(e);
    os << "call " << c.callee;
    if (c.func && c.func->isInstance())
      os << " -> " << c.func->mangledName;
    else if (c.func && c.func->isIntrinsic)
      os << " intrinsic";
    if (!c.binding.empty())
      binding(c.binding);
    exprs(c.args);
    break;
  }
  case Expr::Kind::Read: {
    auto &r = cast<ReadExpr>(e);
    os << (r.isSlice() ? "slice " : "read ");
    expr(*r.base);
    exprs(r.indices);
    break;
  }
  case Expr::Kind::TupleRead: {
    auto &t = cast<TupleReadExpr>(e);
    os << "tuple-read ";
    expr(*t.base);
    if (t.index) {
      os << ' ';
      expr(*t.index);
    } else {
      os << " ." << t.member;
    }
    break;
  }
  case Expr::Kind::Field: {
    auto &f = cast<FieldExpr>(e);
    os << (f.isSetField ? "set-field " : "field ");
    expr(*f.base);
    os << " ." << f.field;
    break;
  }
  case Expr::Kind::SetRead: {
    auto &s = cast<SetReadExpr>(e);
    os << (s.hasDirections ? "grid-edge " : "grid-point ");
    expr(*s.base);
    exprs(s.offsets);
    if (s.hasDirections) {
      os << " ;";
      exprs(s.directions);
    }
    break;
  }
  case Expr::Kind::Unary: {
    auto &u = cast<UnaryExpr>(e);
    os << (u.op == UnaryExpr::Op::Neg    ? "neg "
           : u.op == UnaryExpr::Op::Plus ? "plus "
                                         : "not ");
    expr(*u.operand);
    break;
  }
  case Expr::Kind::Binary: {
    auto &b = cast<BinaryExpr>(e);
    os << binaryOpSpelling(b.op);
    switch (b.mulKind) {
    case BinaryExpr::MulKind::Scale: os << " scale"; break;
    case BinaryExpr::MulKind::Inner: os << " inner"; break;
    case BinaryExpr::MulKind::Outer: os << " outer"; break;
    case BinaryExpr::MulKind::MatVec: os << " matvec"; break;
    case BinaryExpr::MulKind::VecMat: os << " vecmat"; break;
    case BinaryExpr::MulKind::MatMat: os << " matmat"; break;
    case BinaryExpr::MulKind::BlockRowVec: os << " blockrowvec"; break;
    case BinaryExpr::MulKind::None: break;
    }
    os << ' ';
    expr(*b.lhs);
    os << ' ';
    expr(*b.rhs);
    break;
  }
  case Expr::Kind::Compare: {
    auto &c = cast<CompareExpr>(e);
    os << "compare ";
    expr(*c.operands[0]);
    for (size_t i = 0; i < c.ops.size(); ++i) {
      os << ' ' << compareOpSpelling(c.ops[i]) << ' ';
      expr(*c.operands[i + 1]);
    }
    break;
  }
  case Expr::Kind::Transpose:
    os << "transpose ";
    expr(*cast<TransposeExpr>(e).operand);
    break;
  case Expr::Kind::Map: {
    auto &m = cast<MapExpr>(e);
    os << "map " << m.funcName;
    if (m.func && m.func->isInstance())
      os << " -> " << m.func->mangledName;
    exprs(m.args);
    os << " to " << m.target;
    if (!m.through.empty())
      os << " through " << m.through;
    if (m.endpointForm == MapExpr::EndpointForm::Unnamed)
      os << " endpoints";
    else if (m.endpointForm == MapExpr::EndpointForm::Named)
      os << " named-endpoints";
    if (m.reduce)
      os << " reduce +";
    break;
  }
  }
  os << " : " << typeStr(e.type) << ')';
}

} // namespace

void simit::frontend::printProgram(const Program &program, raw_ostream &os) {
  Printer(os).program(program);
}

void simit::frontend::printExpr(const Expr &expr, raw_ostream &os) {
  Printer(os).expr(expr);
}
