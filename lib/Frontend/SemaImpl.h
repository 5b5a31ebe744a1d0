//===- SemaImpl.h - Semantic analysis internals -----------------*- C++ -*-===//
//
// The checker shared by Sema.cpp (declarations, statements), SemaExpr.cpp
// (expressions) and SemaCall.cpp (calls, maps, generic instances).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_FRONTEND_SEMAIMPL_H
#define SIMIT_LIB_FRONTEND_SEMAIMPL_H

#include "simit/Frontend/AST.h"
#include "simit/Frontend/Diagnostics.h"

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace simit::frontend {

class Sema {
public:
  Sema(Program &program, DiagnosticEngine &diags)
      : program(program), diags(diags) {}

  bool run();

  // Declarations (Sema.cpp).
  void declareIntrinsics();
  void checkElement(ElementDecl &element, unsigned order);
  void checkGlobal(VarDecl &var, unsigned order);
  void checkFunctionDecl(FuncDecl &func, unsigned order);
  void checkFunctionBody(FuncDecl &func);
  void checkTestLine(TestLine &test);
  TypePtr resolveType(const TypeExpr &type);
  std::optional<Dim> resolveDim(const DimExpr &dim, bool forGenericArg);
  /// Reports a repeat count (`S*n`, `(E*n)`, `grid[n]`) too large to
  /// represent; `what` names it.
  bool checkRepeatBound(const TypeExpr &type, llvm::StringRef what);

  // Statements (Sema.cpp).
  void checkBlock(Block &block);
  void checkStmt(Stmt &stmt);
  void checkVarDecl(VarDecl &var);
  void checkAssign(AssignStmt &stmt);
  void checkAssignTarget(AssignStmt &stmt, ExprPtr &target,
                         const TypePtr &value, SMLoc valueLoc);
  void checkCondition(ExprPtr &cond);
  void checkFor(ForStmt &stmt);
  bool checkAssignable(const TypePtr &target, const TypePtr &value,
                       SMLoc loc, const char *what);

  // Expressions (SemaExpr.cpp).
  TypePtr checkExpr(ExprPtr &expr);
  TypePtr checkName(NameExpr &name);
  TypePtr checkRead(ExprPtr &expr);
  TypePtr checkTensorRead(ReadExpr &read);
  TypePtr checkTupleRead(TupleReadExpr &read);
  TypePtr checkField(ExprPtr &expr);
  TypePtr checkSetRead(SetReadExpr &read);
  TypePtr checkUnary(ExprPtr &expr);
  TypePtr checkBinary(BinaryExpr &binary);
  TypePtr checkProduct(BinaryExpr &binary, const TypePtr &a, const TypePtr &b);
  TypePtr checkCompare(CompareExpr &cmp);
  TypePtr checkTranspose(ExprPtr &expr);
  bool checkIndex(ExprPtr &index, const Dim &dim, SMLoc loc);
  void checkElementOrigin(const Expr &element, const VarDecl *set, SMLoc loc);

  // Calls, maps and generics (SemaCall.cpp).
  TypePtr checkCall(CallExpr &call);
  TypePtr checkNormOrDot(CallExpr &call);
  TypePtr checkMap(MapExpr &map, bool isApply);
  bool inferBinding(const FuncDecl &callee, std::vector<std::optional<Dim>> &binding,
                    const std::vector<DimExpr> &explicitArgs, bool hasExplicit,
                    SMLoc loc);
  void unify(const FuncDecl &callee, const TypePtr &param, const TypePtr &arg,
             std::vector<std::optional<Dim>> &binding);
  const FuncDecl *instantiate(FuncDecl &generic, const std::vector<Dim> &binding);
  TypePtr resultTypeOf(const FuncDecl &callee, const std::vector<Dim> &binding);
  bool checkArgument(const FuncDecl &callee, unsigned i, ExprPtr &arg,
                     const TypePtr &paramType, const std::string &what);

  // Scopes and lookup.
  const FuncDecl *lookupFunction(const std::string &name) const;
  const Decl *lookupVariable(const std::string &name) const;
  const ElementDecl *lookupElement(const std::string &name) const;
  bool declareLocal(const Decl *decl);
  void pushScope() { scopes.emplace_back(); }
  void popScope() { scopes.pop_back(); }

  // Element origins.
  const VarDecl *originOf(const Expr &e, std::optional<OriginKey> *key) const;
  std::vector<const VarDecl *> tupleOriginsOf(const Expr &e) const;

  // Writability of targets and inout arguments.
  bool isWritable(const Expr &e) const;
  bool isWritableElement(const Expr &e) const;

  // Current generic binding.
  std::optional<Dim> boundDim(const GenericParamDecl *param) const;

  Program &program;
  DiagnosticEngine &diags;

  // Global namespaces with each name's declaration position; a function
  // sees only what precedes it.
  std::map<std::string, std::pair<const ElementDecl *, unsigned>> elements;
  std::map<std::string, std::pair<const VarDecl *, unsigned>> globals;
  std::map<std::string, std::pair<FuncDecl *, unsigned>> functions;
  std::set<std::string> allFunctionNames;

  /// The function being checked, its visibility limit and binding.
  struct Context {
    FuncDecl *func = nullptr;
    unsigned visibleBefore = ~0u;
    bool genericMode = false; // checking a generic body with free parameters
    // Index expressions: whether ivars may appear, and what was used.
    bool inAssignment = false;
    bool inIndexPosition = false;
    bool inIndexExpr = false; // the statement uses ivars
    std::set<const VarDecl *> ivarsSeen;
    std::map<const VarDecl *, std::vector<Dim>> ivarRanges;
  };
  Context ctx;
  std::vector<std::map<std::string, const Decl *>> scopes;
  std::vector<std::unique_ptr<Block>> preludeBodies;
};

/// Folds unary `-`/`+` and `'` applied to literals into literals.
void foldLiteral(ExprPtr &expr);

/// The declaration a name expression refers to, if any.
inline const VarDecl *varOf(const Expr &e) {
  if (auto *name = llvm::dyn_cast<NameExpr>(&e))
    return llvm::dyn_cast_or_null<VarDecl>(name->decl);
  return nullptr;
}

} // namespace simit::frontend

#endif // SIMIT_LIB_FRONTEND_SEMAIMPL_H
