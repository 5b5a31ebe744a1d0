//===- IRGenImpl.h - The IR generator's internal interface ------*- C++ -*-===//
//
// One IRGenerator translates one checked program. Its parts live in
// IRGen.cpp (module, globals, functions, runtime declarations),
// IRGenTypes.cpp (types, locations, literals), IRGenExpr.cpp (expressions),
// IRGenCall.cpp (calls, intrinsics, maps), IRGenStmt.cpp (statements and
// assignment targets) and IRGenIndexExpr.cpp (ivar assignments).
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_LIB_FRONTEND_IRGENIMPL_H
#define SIMIT_LIB_FRONTEND_IRGENIMPL_H

#include "simit/ABI/RuntimeFunctionNames.h"
#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Frontend/IRGen.h"

#include "mlir/Dialect/Func/IR/FuncOps.h"
#include "mlir/IR/Builders.h"
#include "llvm/ADT/DenseMap.h"
#include "llvm/ADT/SmallPtrSet.h"
#include "llvm/ADT/StringMap.h"

#include <complex>
#include <functional>
#include <optional>

namespace simit::frontend {

/// How a variable is held while its function is generated: in a slot
/// (`!simit.ref`, for `var`s, results, `inout` tensor parameters) or as an SSA
/// value (other parameters, implicit locals, constants, loop variables).
struct Binding {
  mlir::Value value;
  bool isSlot = false;
};

/// The printed form of an IR type, for messages.
inline std::string typeString(mlir::Type type) {
  std::string text;
  llvm::raw_string_ostream os(text);
  os << type;
  return text;
}

using ExprVisitor = std::function<void(const Expr &)>;

/// Calls `visit` on `e` (if not null) and every expression inside it,
/// outer first.
void walkExpr(const Expr *e, const ExprVisitor &visit);

struct IndexExprState;

/// A literal after folding unary `-`/`+` and `'`: its values row-major.
struct FoldedLiteral {
  ScalarKind kind = ScalarKind::Int;
  std::vector<int64_t> shape; // empty for a scalar
  std::vector<int64_t> ints;  // Int and Bool
  std::vector<double> floats;
  std::vector<std::complex<double>> complexes;
  std::string string;
};

class IRGenerator {
public:
  IRGenerator(const Program &program, DiagnosticEngine &diags,
              mlir::MLIRContext &context, const IRGenOptions &options);

  mlir::OwningOpRef<mlir::ModuleOp> generate();

private:
  //===--- IRGen.cpp ------------------------------------------------------===//
  void genExtern(const VarDecl &global);
  /// Generates `func`; with `inoutResults` (positions of `inout` tensor
  /// parameters), its variant for a map passing them as extra arguments:
  /// each such parameter is a leading result, which the map starts from
  /// the argument's value. With `accumulateResults` (the variant for a map
  /// with `reduce +`), every assignment to one of func's own results adds
  /// to what it writes, so that the map, which stores, reduces them.
  void genFunction(const FuncDecl &func,
                   llvm::ArrayRef<unsigned> inoutResults = {},
                   bool accumulateResults = false);
  /// The symbol of the variant of `func` for maps with `inout` extra
  /// arguments, with `reduce +` or without.
  std::string inoutVariantOf(const FuncDecl &func, bool reduce) const;
  /// The result of the function being generated that an assignment to
  /// `target` adds to (genFunction's accumulateResults), or null.
  const VarDecl *accumulatedResultOf(const Expr &target) const;
  /// The symbol of a function (its instance name for generic instances).
  std::string symbolOf(const FuncDecl &func) const;
  mlir::FunctionType functionType(const FuncDecl &func);
  /// A private declaration `@<base>` (`@<base>_<k>` when `@<base>` exists
  /// with another type) tagged with the Simit name it implements.
  mlir::func::FuncOp declareRuntimeFunction(llvm::StringRef base,
                                            llvm::StringRef simitName,
                                            mlir::FunctionType type);
  /// Erases dead side-effect-free operations and merges repeated ones.
  void simplify();
  SMLoc sourceLoc(mlir::Location where);
  bool checkResultWrites();
  bool verifyModule();

  //===--- IRGenTypes.cpp -------------------------------------------------===//
  mlir::Location loc(SMLoc where);
  mlir::Type floatType();
  mlir::Type scalarType(ScalarKind kind);
  /// The IR type of a tensor, element, tuple or opaque value.
  mlir::Type convertType(const TypePtr &type, SMLoc where);
  mlir::simit::ElementType elementType(const ElementDecl *element);
  /// The type of a set variable (extern or parameter).
  mlir::simit::SetType setType(const VarDecl *set);
  /// The IR name of a set: an extern's own name; for a set parameter, the
  /// one extern of its type (sets are identified by name in the IR, so a
  /// grid parameter must name the grid the function is mapped through), or
  /// the parameter's name when there is no such single extern.
  std::string setName(const VarDecl *set);
  mlir::Attribute dimAttr(const Dim &dim, SMLoc where);
  /// The type a parameter has in the function signature.
  mlir::Type paramType(const VarDecl &param);
  /// Parameters passed by reference: `inout` tensors and opaque handles.
  static bool isSlotParam(const VarDecl &param);

  std::optional<FoldedLiteral> foldLiteral(const Expr &e);
  /// The constant `literal` reshaped to `type` (a scalar or builtin tensor
  /// with as many components).
  mlir::Value genConstant(const FoldedLiteral &literal, mlir::Type type,
                          SMLoc where);
  mlir::Value intConstant(int64_t value, SMLoc where);
  mlir::Value indexConstant(int64_t value, SMLoc where);

  //===--- IRGenExpr.cpp --------------------------------------------------===//
  mlir::Value genExpr(const Expr &e);
  mlir::Value genName(const NameExpr &e);
  mlir::Value genVarValue(const VarDecl &var, SMLoc where);
  mlir::Value genUnary(const UnaryExpr &e);
  mlir::Value genBinary(const BinaryExpr &e);
  mlir::Value genElementwise(BinaryExpr::Op op, mlir::Value a, mlir::Value b,
                             mlir::Type resultType, SMLoc where);
  mlir::Value genProduct(const BinaryExpr &e, mlir::Value a, mlir::Value b);
  mlir::Value genBlockRowProduct(const BinaryExpr &e);
  mlir::Value genCompare(const CompareExpr &e);
  mlir::Value genScalarCompare(CompareExpr::Op op, mlir::Value a,
                               mlir::Value b, ScalarKind kind, SMLoc where);
  mlir::Value genTranspose(const TransposeExpr &e);
  mlir::Value genRead(const ReadExpr &e);
  mlir::Value genIndex(const Expr &index);
  mlir::Value genTupleRead(const TupleReadExpr &e);
  mlir::Value genField(const FieldExpr &e);
  mlir::Value genSetRead(const SetReadExpr &e);
  /// The set a set-typed variable holds.
  mlir::Value genSet(const VarDecl *set, SMLoc where);
  /// `value` as a value of `type`: broadcasts a scalar into a tensor.
  mlir::Value coerce(mlir::Value value, mlir::Type type, SMLoc where);
  std::optional<int64_t> constantInt(mlir::Value value);
  mlir::Value toIndex(mlir::Value value, SMLoc where);

  //===--- IRGenCall.cpp --------------------------------------------------===//
  /// Every value of a call or map (none for void ones).
  llvm::SmallVector<mlir::Value> genValues(const Expr &e);
  llvm::SmallVector<mlir::Value> genCall(const CallExpr &e);
  /// The IR types of a call's results.
  llvm::SmallVector<mlir::Type> convertResultTypes(const Expr &e);
  llvm::SmallVector<mlir::Value> genUserCall(const CallExpr &e);
  mlir::Value genIntrinsic(const CallExpr &e);
  mlir::Value genAtan2(mlir::Value y, mlir::Value x, mlir::Location l);
  /// lu, chol, their solves and frees, and triangularSolve as simit ops.
  llvm::SmallVector<mlir::Value> genSolverIntrinsic(const CallExpr &e);
  /// A call of the runtime's `function`, the language's `name`.
  llvm::SmallVector<mlir::Value>
  genRuntimeCall(const CallExpr &e, ::simit::abi::RuntimeFunction function,
                 llvm::StringRef name);
  llvm::SmallVector<mlir::Value> genMap(const MapExpr &e);

  //===--- IRGenStmt.cpp --------------------------------------------------===//
  void genBlock(const Block &block);
  void genStmt(const Stmt &stmt);
  void genVarDecl(const VarDecl &var);
  void genAssign(const AssignStmt &stmt);
  void genIf(const IfStmt &stmt, size_t branch);
  void genWhile(const WhileStmt &stmt);
  void genDoWhile(const DoWhileStmt &stmt);
  void genFor(const ForStmt &stmt);
  void genRangeFor(const ForStmt &stmt, mlir::Value lower, mlir::Value upper);
  void genPrint(const PrintStmt &stmt);
  /// A zero-initialised slot for `var`, bound to it.
  mlir::Value allocSlot(const VarDecl &var);
  /// The slot a writable variable is held in.
  mlir::Value slotOf(const VarDecl &var, SMLoc where);
  /// Writes `value` to an assignment target (copies back through reads and
  /// fields: load, simit.insert, store).
  void writeTarget(const Expr &target, mlir::Value value, SMLoc where);
  /// Runs `write` once per position of the tuple `pick` reads, under a test
  /// of `position`, with `pick` fixed to that position.
  void writeAtEachEndpoint(const TupleReadExpr &pick, mlir::Value position,
                           llvm::function_ref<void()> write);
  /// Ends the run with the source position unless the computed `position`
  /// names one of a tuple's `size` endpoints (one unsigned compare also
  /// rejects negative positions).
  void checkEndpointPosition(mlir::Value position, unsigned size, SMLoc where);

  //===--- IRGenIndexExpr.cpp ---------------------------------------------===//
  void genIndexAssign(const AssignStmt &stmt);
  /// Evaluates the operands of an index expression outside it: reads with
  /// index variables and scalar subexpressions without them.
  void collectIndexInputs(const Expr &e, IndexExprState &state);
  /// The scalar component `e` computes inside the index expression's body.
  mlir::Value genIndexBody(const Expr &e, IndexExprState &state);
  mlir::Value genIndexBodyOp(const Expr &e, IndexExprState &state);
  /// Writes a computed value over distinct free variables to a target that
  /// repeats variables or mixes in fixed indices (`B(i,i)`, `B(i,0)`).
  void writeIndexedTarget(const ReadExpr &target, mlir::Value value,
                          IndexExprState &state);

  //===--- Errors ---------------------------------------------------------===//
  /// Reports a construct the generator does not support and returns a
  /// placeholder of `type` so generation can go on.
  mlir::Value unsupported(SMLoc where, const llvm::Twine &what,
                          mlir::Type type = {});

  const Program &program;
  DiagnosticEngine &diags;
  mlir::MLIRContext &context;
  IRGenOptions options;
  mlir::OpBuilder builder;
  mlir::ModuleOp module;
  mlir::StringAttr fileName;
  bool failed = false;

  llvm::DenseMap<const ElementDecl *, mlir::simit::ElementType> elementTypes;
  llvm::StringMap<mlir::func::FuncOp> runtimeFunctions;

  // The function being generated.
  const FuncDecl *currentFunc = nullptr;
  /// Its results that assignments add to (genFunction).
  llvm::SmallPtrSet<const VarDecl *, 4> accumulatedResults;
  llvm::DenseMap<const VarDecl *, Binding> bindings;
  /// Tuple reads fixed to one position while a write is generated per
  /// endpoint.
  llvm::DenseMap<const TupleReadExpr *, int64_t> endpointPositions;
};

} // namespace simit::frontend

#endif // SIMIT_LIB_FRONTEND_IRGENIMPL_H
