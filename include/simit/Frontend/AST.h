//===- AST.h - Simit abstract syntax tree -----------------------*- C++ -*-===//
//
// The parser builds these nodes; sema resolves them in place: every
// expression gets a type, every name its declaration, reads are told apart
// from calls and tuple reads, calls of generic functions point at a checked
// instance, and maps know their function, target set, endpoint form and grid.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_FRONTEND_AST_H
#define SIMIT_FRONTEND_AST_H

#include "simit/Frontend/Types.h"

#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Casting.h"
#include "llvm/Support/SMLoc.h"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace simit::frontend {

using llvm::SMLoc;

class Expr;
class Stmt;
class FuncDecl;
using ExprPtr = std::unique_ptr<Expr>;
using StmtPtr = std::unique_ptr<Stmt>;

//===----------------------------------------------------------------------===//
// Types as written
//===----------------------------------------------------------------------===//

/// A dimension or generic argument as written: an integer or a name.
struct DimExpr {
  SMLoc loc;
  bool isInt = false;
  int64_t value = 0;
  std::string name;
};

struct TypeExpr {
  enum class Kind { Scalar, Tensor, Element, Set, Grid, Tuple, Opaque };
  enum class Keyword { Tensor, Vector, Matrix };
  Kind kind = Kind::Scalar;
  SMLoc loc;

  ScalarKind scalar = ScalarKind::Float; // Scalar

  Keyword keyword = Keyword::Tensor; // Tensor
  std::vector<DimExpr> dims;
  std::unique_ptr<TypeExpr> block; // Tensor: the block or scalar inside (...)
  bool transposed = false;

  std::string name; // Element; Set/Grid: element name; Tuple: unnamed member
  SMLoc nameLoc;
  std::vector<DimExpr> endpoints; // Set: endpoint names; Grid: point set
  bool hasEndpoints = false;
  int64_t repeat = 0;    // Set `S*n`, unnamed Tuple `(E*n)`, Grid rank
  SMLoc repeatLoc;
  std::vector<std::string> memberNames; // named Tuple
  std::vector<std::string> memberTypes;
  std::vector<SMLoc> memberLocs;
};

//===----------------------------------------------------------------------===//
// Declarations
//===----------------------------------------------------------------------===//

class Decl {
public:
  enum class Kind { Element, Var, Generic, Func };
  Decl(Kind kind, std::string name, SMLoc loc)
      : kind(kind), name(std::move(name)), loc(loc) {}
  virtual ~Decl() = default;
  Kind getKind() const { return kind; }

  const Kind kind;
  std::string name;
  SMLoc loc;
};

class ElementDecl : public Decl {
public:
  struct Field {
    std::string name;
    SMLoc loc;
    std::unique_ptr<TypeExpr> typeExpr;
    TypePtr type;
  };
  ElementDecl(std::string name, SMLoc loc)
      : Decl(Kind::Element, std::move(name), loc) {}
  static bool classof(const Decl *d) { return d->getKind() == Kind::Element; }

  /// The index of field `name`, or -1.
  int fieldIndex(const std::string &fieldName) const {
    for (size_t i = 0; i < fields.size(); ++i)
      if (fields[i].name == fieldName)
        return i;
    return -1;
  }

  std::vector<Field> fields;
};

class VarDecl : public Decl {
public:
  enum class Role {
    Extern,      // host-bound global (set, grid or tensor)
    GlobalConst, // top-level const
    Param,
    Result,
    Var,         // local var
    Const,       // local const
    Implicit,    // declared by its first assignment
    LoopVar,     // for variable
    IndexVar,    // ivar
  };
  VarDecl(Role role, std::string name, SMLoc loc)
      : Decl(Kind::Var, std::move(name), loc), role(role) {}
  static bool classof(const Decl *d) { return d->getKind() == Kind::Var; }

  bool isGlobal() const {
    return role == Role::Extern || role == Role::GlobalConst;
  }

  Role role;
  bool inout = false;
  std::unique_ptr<TypeExpr> typeExpr; // null when inferred
  ExprPtr init;                       // const initialiser (global or local)
  TypePtr type;
};

class GenericParamDecl : public Decl {
public:
  GenericParamDecl(std::string name, SMLoc loc, bool isRange, unsigned index)
      : Decl(Kind::Generic, std::move(name), loc), isRange(isRange),
        index(index) {}
  static bool classof(const Decl *d) { return d->getKind() == Kind::Generic; }

  bool isRange; // declared `0:N`: a range only, usable as an int
  unsigned index;
};

/// Where an element value's origin is inferred from: a parameter, and for
/// named tuples the member (-1: the element itself or every member of an
/// unnamed tuple).
using OriginKey = std::pair<const VarDecl *, int>;

class Block;

class FuncDecl : public Decl {
public:
  FuncDecl(std::string name, SMLoc loc)
      : Decl(Kind::Func, std::move(name), loc) {}
  static bool classof(const Decl *d) { return d->getKind() == Kind::Func; }
  ~FuncDecl() override;

  bool isGeneric() const { return !generics.empty() && !genericOrigin; }
  bool isInstance() const { return genericOrigin != nullptr; }

  bool isExport = false;
  bool isExtern = false;
  bool isIntrinsic = false;
  std::vector<std::unique_ptr<GenericParamDecl>> generics;
  std::vector<std::unique_ptr<VarDecl>> params;
  std::vector<std::unique_ptr<VarDecl>> results;
  std::unique_ptr<Block> body; // null for extern functions
  /// The declaration's source text, to re-parse a copy per instance.
  llvm::StringRef source;

  // Sema.
  unsigned order = 0; // position among top-level declarations
  /// Origins of element and tuple parameters learnt from the body.
  std::map<OriginKey, const VarDecl *> inferredOrigins;
  /// Generic parameters indexed by an element parameter (binding them to the
  /// element's origin set at calls and maps).
  std::map<const GenericParamDecl *, OriginKey> genericFromOrigin;
  /// Instances of a generic function, one per binding (checked).
  std::vector<std::unique_ptr<FuncDecl>> instances;
  const FuncDecl *genericOrigin = nullptr; // instance: its generic function
  /// The functions its calls and maps use (their instances for generics).
  std::vector<const FuncDecl *> callees;
  std::vector<Dim> binding;                // instance: one Dim per generic
  std::string mangledName;                 // instance: unique symbol name
};

//===----------------------------------------------------------------------===//
// Expressions
//===----------------------------------------------------------------------===//

enum class Intrinsic {
  None, Mod, Sin, Cos, Tan, Asin, Acos, Sqrt, Cbrt, Log, Exp, Abs, Atan2,
  Pow, Max, Min, Det, Det2, Det4, Inv, Inv2, Inv4, Cross, Norm, Dot, Lu,
  Chol, LuSolve, LltSolve, LuMatSolve, LltMatSolve, LuFree, CholFree,
  TriangularSolve, CreateComplex, ComplexNorm, ComplexGetReal,
  ComplexGetImag, ComplexConj, Clock, StoreTime,
};

class Expr {
public:
  enum class Kind {
    IntLit, FloatLit, BoolLit, StringLit, ComplexLit, DenseLit, Name, Call,
    Read, TupleRead, Field, SetRead, Unary, Binary, Compare, Transpose, Map,
  };
  Expr(Kind kind, SMLoc loc) : kind(kind), loc(loc) {}
  virtual ~Expr() = default;
  Kind getKind() const { return kind; }

  const Kind kind;
  SMLoc loc;
  TypePtr type; // set by sema
  bool parenthesized = false;
  /// The longest path to a leaf, counting this node; the parser bounds it
  /// so that the recursive walks of sema and IR generation cannot exhaust
  /// the stack.
  unsigned height = 1;
};

class IntLiteral : public Expr {
public:
  IntLiteral(SMLoc loc, int64_t value) : Expr(Kind::IntLit, loc), value(value) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::IntLit; }
  int64_t value;
};

class FloatLiteral : public Expr {
public:
  FloatLiteral(SMLoc loc, double value)
      : Expr(Kind::FloatLit, loc), value(value) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::FloatLit; }
  double value;
};

class BoolLiteral : public Expr {
public:
  BoolLiteral(SMLoc loc, bool value) : Expr(Kind::BoolLit, loc), value(value) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::BoolLit; }
  bool value;
};

class StringLiteral : public Expr {
public:
  StringLiteral(SMLoc loc, std::string value)
      : Expr(Kind::StringLit, loc), value(std::move(value)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::StringLit; }
  std::string value;
};

class ComplexLiteral : public Expr {
public:
  ComplexLiteral(SMLoc loc, double re, double im)
      : Expr(Kind::ComplexLit, loc), re(re), im(im) {}
  static bool classof(const Expr *e) {
    return e->getKind() == Kind::ComplexLit;
  }
  double re, im;
};

/// `[1, 2; 3, 4]`, nested `[[...], [...]]`. Values are row-major; a
/// one-dimensional literal is a row vector unless transposed.
class DenseLiteral : public Expr {
public:
  explicit DenseLiteral(SMLoc loc) : Expr(Kind::DenseLit, loc) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::DenseLit; }

  ScalarKind component = ScalarKind::Int;
  std::vector<int64_t> shape;
  std::vector<int64_t> intValues;
  std::vector<double> floatValues;  // Float
  std::vector<double> complexValues; // Complex: re, im pairs
  bool column = false;               // a transposed 1-D literal
};

/// A name use: a variable, a set, or a `0:` generic parameter used as an int.
class NameExpr : public Expr {
public:
  NameExpr(SMLoc loc, std::string name)
      : Expr(Kind::Name, loc), name(std::move(name)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Name; }
  std::string name;
  const Decl *decl = nullptr; // VarDecl or GenericParamDecl
};

class CallExpr : public Expr {
public:
  CallExpr(SMLoc loc, std::string callee)
      : Expr(Kind::Call, loc), callee(std::move(callee)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Call; }
  std::string callee;
  bool hasGenericArgs = false;
  std::vector<DimExpr> genericArgs;
  std::vector<ExprPtr> args;

  // Sema.
  const FuncDecl *func = nullptr; // the instance for generic functions
  Intrinsic intrinsic = Intrinsic::None;
  std::vector<Dim> binding; // generic binding (also kept for instances)
};

/// `A(i, j)`, `A(:, j)`, `K(p,q)(0,1)`: a tensor component, block or slice.
/// Parsed for every `x(...)`; sema turns calls and tuple reads into their own
/// nodes.
class ReadExpr : public Expr {
public:
  ReadExpr(SMLoc loc, ExprPtr base) : Expr(Kind::Read, loc), base(std::move(base)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Read; }
  ExprPtr base;
  std::vector<ExprPtr> indices; // null entries are `:` slices
  std::vector<SMLoc> indexLocs;
  bool isSlice() const {
    for (const ExprPtr &i : indices)
      if (!i)
        return true;
    return false;
  }
};

/// `t(i)` on an unnamed tuple or `t.name` on a named one.
class TupleReadExpr : public Expr {
public:
  TupleReadExpr(SMLoc loc, ExprPtr base)
      : Expr(Kind::TupleRead, loc), base(std::move(base)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::TupleRead; }
  ExprPtr base;
  ExprPtr index;      // unnamed tuples
  std::string member; // named tuples
  int memberIndex = -1; // the member when known statically
};

/// `e.f` (an element's field) or `S.f` (a set field as a global vector).
class FieldExpr : public Expr {
public:
  FieldExpr(SMLoc loc, ExprPtr base, std::string field, SMLoc fieldLoc)
      : Expr(Kind::Field, loc), base(std::move(base)), field(std::move(field)),
        fieldLoc(fieldLoc) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Field; }
  ExprPtr base;
  std::string field;
  SMLoc fieldLoc;
  bool isSetField = false;
  int fieldIndex = -1;
  const ElementDecl *element = nullptr;
};

/// `g[o1,...;s1,...]` (a grid edge) or `P[k1,...]` (a grid point).
class SetReadExpr : public Expr {
public:
  SetReadExpr(SMLoc loc, ExprPtr base)
      : Expr(Kind::SetRead, loc), base(std::move(base)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::SetRead; }
  ExprPtr base;
  std::vector<ExprPtr> offsets;
  std::vector<ExprPtr> directions;
  bool hasDirections = false;
  const VarDecl *grid = nullptr; // the grid parameter read through
};

class UnaryExpr : public Expr {
public:
  enum class Op { Neg, Plus, Not };
  UnaryExpr(SMLoc loc, Op op, ExprPtr operand)
      : Expr(Kind::Unary, loc), op(op), operand(std::move(operand)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Unary; }
  Op op;
  ExprPtr operand;
};

class BinaryExpr : public Expr {
public:
  enum class Op {
    Add, Sub, Mul, Div, LeftDiv, ElemMul, ElemDiv, Pow, And, Or, Xor,
  };
  BinaryExpr(SMLoc loc, Op op, ExprPtr lhs, ExprPtr rhs)
      : Expr(Kind::Binary, loc), op(op), lhs(std::move(lhs)),
        rhs(std::move(rhs)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Binary; }
  Op op;
  ExprPtr lhs, rhs;
  /// Sema: for Mul, what kind of product this is. BlockRowVec: a row of
  /// matrix blocks (`A(p,:)` of a blocked matrix) times a column vector.
  enum class MulKind {
    None, Scale, Inner, Outer, MatVec, VecMat, MatMat, BlockRowVec,
  };
  MulKind mulKind = MulKind::None;
};

const char *binaryOpSpelling(BinaryExpr::Op op);

/// `a < b <= c`: operands evaluated once, results and-ed.
class CompareExpr : public Expr {
public:
  enum class Op { Eq, Ne, Lt, Gt, Le, Ge };
  explicit CompareExpr(SMLoc loc) : Expr(Kind::Compare, loc) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Compare; }
  std::vector<ExprPtr> operands;
  std::vector<Op> ops;
  std::vector<SMLoc> opLocs;
};

const char *compareOpSpelling(CompareExpr::Op op);

class TransposeExpr : public Expr {
public:
  TransposeExpr(SMLoc loc, ExprPtr operand)
      : Expr(Kind::Transpose, loc), operand(std::move(operand)) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Transpose; }
  ExprPtr operand;
};

/// `map f<G>(x...) to S through Gr reduce +`; also the body of `apply`.
class MapExpr : public Expr {
public:
  explicit MapExpr(SMLoc loc) : Expr(Kind::Map, loc) {}
  static bool classof(const Expr *e) { return e->getKind() == Kind::Map; }
  std::string funcName;
  SMLoc funcLoc;
  bool hasGenericArgs = false;
  std::vector<DimExpr> genericArgs;
  std::vector<ExprPtr> args;
  std::string target;
  SMLoc targetLoc;
  std::string through;
  SMLoc throughLoc;
  bool reduce = false;

  // Sema.
  enum class EndpointForm { None, Unnamed, Named };
  const FuncDecl *func = nullptr; // the instance for generic functions
  std::vector<Dim> binding;
  const VarDecl *targetSet = nullptr;
  const VarDecl *grid = nullptr;
  EndpointForm endpointForm = EndpointForm::None;
};

//===----------------------------------------------------------------------===//
// Statements
//===----------------------------------------------------------------------===//

class Block {
public:
  SMLoc loc;
  std::vector<StmtPtr> stmts;
};

class Stmt {
public:
  enum class Kind {
    VarDecl, IVarDecl, Assign, Expr, If, While, DoWhile, For, Print, Apply,
  };
  Stmt(Kind kind, SMLoc loc) : kind(kind), loc(loc) {}
  virtual ~Stmt() = default;
  Kind getKind() const { return kind; }
  const Kind kind;
  SMLoc loc;
};

/// `var x : T = e;`, `var x = e;`, local `const x : T = e;` (initialiser in
/// the declaration's `init`).
class VarDeclStmt : public Stmt {
public:
  VarDeclStmt(SMLoc loc, std::unique_ptr<VarDecl> var)
      : Stmt(Kind::VarDecl, loc), var(std::move(var)) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::VarDecl; }
  std::unique_ptr<VarDecl> var;
};

class IVarDeclStmt : public Stmt {
public:
  IVarDeclStmt(SMLoc loc, std::unique_ptr<VarDecl> var)
      : Stmt(Kind::IVarDecl, loc), var(std::move(var)) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::IVarDecl; }
  std::unique_ptr<VarDecl> var;
};

/// `t1, ..., tk = e;` — also an index expression when ivars occur.
class AssignStmt : public Stmt {
public:
  explicit AssignStmt(SMLoc loc) : Stmt(Kind::Assign, loc) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::Assign; }
  std::vector<ExprPtr> targets;
  ExprPtr value;
  /// Implicit declarations made by this assignment (targets refer to them).
  std::vector<std::unique_ptr<VarDecl>> implicitDecls;
  bool isIndexExpr = false;
  std::vector<const VarDecl *> freeIndexVars;      // on the left
  std::vector<const VarDecl *> reductionIndexVars; // only on the right
};

class ExprStmt : public Stmt {
public:
  ExprStmt(SMLoc loc, ExprPtr expr) : Stmt(Kind::Expr, loc), expr(std::move(expr)) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::Expr; }
  ExprPtr expr;
};

class IfStmt : public Stmt {
public:
  explicit IfStmt(SMLoc loc) : Stmt(Kind::If, loc) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::If; }
  std::vector<ExprPtr> conditions; // if, then each elif
  std::vector<std::unique_ptr<Block>> blocks;
  std::unique_ptr<Block> elseBlock; // may be null
};

class WhileStmt : public Stmt {
public:
  explicit WhileStmt(SMLoc loc) : Stmt(Kind::While, loc) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::While; }
  ExprPtr condition;
  std::unique_ptr<Block> body;
};

class DoWhileStmt : public Stmt {
public:
  explicit DoWhileStmt(SMLoc loc) : Stmt(Kind::DoWhile, loc) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::DoWhile; }
  std::unique_ptr<Block> body;
  ExprPtr condition;
};

/// `for i in lo:hi` or `for p in S` (S a set or a generic parameter).
class ForStmt : public Stmt {
public:
  explicit ForStmt(SMLoc loc) : Stmt(Kind::For, loc) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::For; }
  std::unique_ptr<VarDecl> var;
  ExprPtr lower, upper; // range form
  std::string domain;   // set form
  SMLoc domainLoc;
  std::unique_ptr<Block> body;

  bool isRange() const { return lower != nullptr; }
  // Sema, set form: the set iterated, or the generic parameter (in generic
  // bodies; an instance resolves it to its bound set or range).
  const VarDecl *set = nullptr;
  const GenericParamDecl *generic = nullptr;
  Dim domainDim; // set form: the resolved domain
};

class PrintStmt : public Stmt {
public:
  PrintStmt(SMLoc loc, bool newline)
      : Stmt(Kind::Print, loc), newline(newline) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::Print; }
  bool newline;
  std::vector<ExprPtr> args;
};

class ApplyStmt : public Stmt {
public:
  ApplyStmt(SMLoc loc, std::unique_ptr<MapExpr> map)
      : Stmt(Kind::Apply, loc), map(std::move(map)) {}
  static bool classof(const Stmt *s) { return s->getKind() == Kind::Apply; }
  std::unique_ptr<MapExpr> map;
};

//===----------------------------------------------------------------------===//
// Program
//===----------------------------------------------------------------------===//

/// `%! f(a...) == expected;`
struct TestLine {
  SMLoc loc;
  unsigned line = 0; // within the program's buffer
  std::string funcName;
  SMLoc funcLoc;
  std::vector<ExprPtr> args;
  ExprPtr expected;
  const FuncDecl *func = nullptr; // sema, when it names a function
};

class Program {
public:
  std::vector<std::unique_ptr<ElementDecl>> elements;
  std::vector<std::unique_ptr<VarDecl>> globals; // externs and constants
  std::vector<std::unique_ptr<FuncDecl>> funcs;
  std::vector<TestLine> tests;
  /// Intrinsic function declarations (calls may point at them).
  std::vector<std::unique_ptr<FuncDecl>> intrinsics;
  /// Every top-level declaration in source order.
  std::vector<Decl *> order;
};

} // namespace simit::frontend

#endif // SIMIT_FRONTEND_AST_H
