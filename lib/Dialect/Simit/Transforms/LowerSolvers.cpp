//===- LowerSolvers.cpp - Solves and factorisations -----------------------===//
//
// simit.solve, simit.factorize, simit.factor_solve, simit.factor_free,
// simit.triangular_solve and simit.woodbury as calls of the runtime, on
// system tensors and on local matrices.
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"
#include "simit/Dialect/Simit/IR/SourcePosition.h"

#include <functional>

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

func::FuncOp FunctionLowering::declareRuntime(Location loc, StringRef name,
                                              FunctionType type) {
  auto callee = module.lookupSymbol<func::FuncOp>(name);
  if (callee)
    return callee.getFunctionType() == type ? callee : func::FuncOp();
  OpBuilder::InsertionGuard guard(b);
  b.setInsertionPointToEnd(module.getBody());
  callee = func::FuncOp::create(b, loc, name, type);
  callee.setPrivate();
  callee->setAttr("llvm.emit_c_interface", UnitAttr::get(b.getContext()));
  return callee;
}

Value FunctionLowering::asRuntimeBlocks(Location loc, Value array,
                                        MemRefType target) {
  // memref<?xf64> becomes memref<?x1xf64> or memref<?x1x1xf64>.
  auto type = cast<MemRefType>(array.getType());
  int64_t rank = target.getRank();
  if (type.getRank() == 1 && rank > 1) {
    SmallVector<int64_t> shape(rank, 1);
    shape[0] = ShapedType::kDynamic;
    SmallVector<OpFoldResult> sizes(rank, b.getIndexAttr(1));
    sizes[0] = memref::DimOp::create(b, loc, array, 0).getResult();
    ReassociationIndices all(rank);
    std::iota(all.begin(), all.end(), 0);
    array = memref::ExpandShapeOp::create(
        b, loc, MemRefType::get(shape, type.getElementType()), array,
        ArrayRef<ReassociationIndices>{all}, sizes);
  }
  return memref::CastOp::create(b, loc, target, array);
}

Value FunctionLowering::allocLike(Location loc, Value array, Type element) {
  auto type = cast<MemRefType>(array.getType());
  SmallVector<Value> sizes;
  for (int64_t d = 0; d < type.getRank(); ++d)
    if (type.isDynamicDim(d))
      sizes.push_back(memref::DimOp::create(b, loc, array, d));
  return memref::AllocOp::create(
      b, loc, MemRefType::get(type.getShape(), element), sizes);
}

void FunctionLowering::copyConverted(Location loc, Value from, Value to) {
  int64_t rank = cast<MemRefType>(from.getType()).getRank();
  auto target =
      cast<FloatType>(cast<MemRefType>(to.getType()).getElementType());
  SmallVector<Value> at;
  std::function<void(int64_t)> nest = [&](int64_t d) {
    if (d == rank) {
      Value v = memref::LoadOp::create(b, loc, from, at);
      unsigned width = cast<FloatType>(v.getType()).getWidth();
      if (target.getWidth() > width)
        v = arith::ExtFOp::create(b, loc, target, v);
      else if (target.getWidth() < width)
        v = arith::TruncFOp::create(b, loc, target, v);
      memref::StoreOp::create(b, loc, v, to, at);
      return;
    }
    forLoop(loc, memref::DimOp::create(b, loc, from, d), [&](Value i) {
      at.push_back(i);
      nest(d + 1);
      at.pop_back();
    });
  };
  nest(0);
}

// A diagonal or dense matrix seen as BCSR: row r holds the block at column
// r, or the blocks at every column (r * n + c is the dense layout's block
// (r, c)).
std::pair<Value, Value>
FunctionLowering::bcsrIndexArrays(Location loc, const Storage &storage) {
  if (storage.isBCSR())
    return {rowPointers(storage), columnIndices(storage)};
  if (storage.kind == Storage::Kind::Stencil) {
    std::array<Value, 3> pattern = stencilPattern(storage);
    return {pattern[0], pattern[1]};
  }
  FunctionLowering &l = *this;
  bool dense = storage.kind == Storage::Kind::DenseMatrix;
  Value n = l.getSetSize(storage.rows);
  Value one = l.indexConstant(1);
  auto array = MemRefType::get({ShapedType::kDynamic}, b.getI32Type());
  Value rowPtr = memref::AllocOp::create(
      b, loc, array, ValueRange{arith::AddIOp::create(b, loc, n, one)});
  Value colIdx = memref::AllocOp::create(
      b, loc, array,
      ValueRange{dense ? arith::MulIOp::create(b, loc, n, n).getResult() : n});
  auto i32 = [&](OpBuilder &nb, Value index) -> Value {
    return arith::IndexCastOp::create(nb, loc, nb.getI32Type(), index);
  };
  scf::ForOp::create(
      b, loc, l.indexConstant(0), arith::AddIOp::create(b, loc, n, one), one,
      ValueRange{}, [&](OpBuilder &nb, Location, Value r, ValueRange) {
        Value first =
            dense ? arith::MulIOp::create(nb, loc, r, n).getResult() : r;
        Value first32 = i32(nb, first);
        memref::StoreOp::create(nb, loc, first32, rowPtr, ValueRange{r});
        Value inRange =
            arith::CmpIOp::create(nb, loc, arith::CmpIPredicate::slt, r, n);
        scf::IfOp::create(nb, loc, inRange, [&](OpBuilder &ib, Location) {
          if (dense)
            scf::ForOp::create(
                ib, loc, l.indexConstant(0), n, one, ValueRange{},
                [&](OpBuilder &cb, Location, Value c, ValueRange) {
                  memref::StoreOp::create(
                      cb, loc, i32(cb, c), colIdx,
                      ValueRange{arith::AddIOp::create(cb, loc, first, c)});
                  scf::YieldOp::create(cb, loc);
                });
          else
            memref::StoreOp::create(ib, loc, first32, colIdx, ValueRange{r});
          scf::YieldOp::create(ib, loc);
        });
        scf::YieldOp::create(nb, loc);
      });
  return {rowPtr, colIdx};
}

/// Whether the runtime's sparse solvers take a matrix stored as `s` (a
/// stencil through its bind-time BCSR pattern): square over one set, or a
/// BCSR matrix over two sets (`matrix[Q,V]`) whose sizes assertSquare
/// compares at run time.
static bool isSparseSquare(const Storage &s) {
  return hasBCSRView(s) && (s.rows == s.cols || s.isBCSR());
}

void FunctionLowering::assertSquare(Operation *op, const Storage &storage,
                                    StringRef what) {
  if (storage.rows == storage.cols)
    return;
  Location loc = op->getLoc();
  Value same =
      arith::CmpIOp::create(b, loc, arith::CmpIPredicate::eq,
                            getSetSize(storage.rows), getSetSize(storage.cols));
  cf::AssertOp::create(
      b, loc, same,
      (what + ": the matrix over ('" + storage.rows.getValue() + "', '" +
       storage.cols.getValue() + "') is not square (its sets differ in size)" +
       sourcePositionSuffix(op))
          .str());
}

bool mlir::simit::loops::hasBCSRView(const Storage &s) {
  return s.isBCSR() || ((s.kind == Storage::Kind::Diagonal ||
                         s.kind == Storage::Kind::Stencil ||
                         s.kind == Storage::Kind::DenseMatrix) &&
                        s.rows == s.cols);
}

std::array<Value, 3> FunctionLowering::bcsrArrays(Location loc,
                                                  const Storage &storage,
                                                  Value matrix) {
  if (storage.kind == Storage::Kind::Stencil)
    return stencilAsBCSR(loc, storage, lookup(matrix));
  auto [rowPtr, colIdx] = bcsrIndexArrays(loc, storage);
  return {rowPtr, colIdx, lookup(matrix)};
}

/// `\`: the runtime's SolveSession (lib/ABI/SystemSolves.cpp).
LogicalResult FunctionLowering::lowerSolve(SolveOp op) {
  // The solves of simit-sherman-morrison say which they are.
  std::string what = "solve";
  if (auto note = op->getAttrOfType<StringAttr>("simit.solve_note"))
    what += (" [" + note.getValue() + "]").str();
  return lowerSystemSolve(op, op.getMatrix(), op.getRhs(),
                          ::simit::abi::SystemSolve::Solve, what);
}

LogicalResult FunctionLowering::lowerSystemSolve(Operation *op, Value matrix,
                                                 ValueRange vectors,
                                                 ::simit::abi::SystemSolve method,
                                                 StringRef what,
                                                 unsigned rank) {
  Location loc = op->getLoc();
  Storage storage = storageOf(matrix);
  auto matrixType = cast<SystemTensorType>(matrix.getType());
  // `\` also takes block diagonal matrices.
  bool diagonal = storage.kind == Storage::Kind::Diagonal &&
                  method == ::simit::abi::SystemSolve::Solve;
  if (!isSparseSquare(storage))
    return op->emitError("solves are supported for square matrices "
                         "assembled from a set; this matrix is stored as ")
           << storage.describe();
  assertSquare(op, storage, what);
  SmallVector<int64_t> block = matrixType.getBlockShape();
  // Scalar blocks are 1x1 blocks to the runtime.
  if (block.empty())
    block = {1, 1};
  Type component = matrixType.getComponentType();
  if (!component.isF64() && !component.isF32())
    return op->emitError("the runtime solver takes f64 or f32 matrices");
  if (block.size() != 2 || block[0] != block[1])
    return op->emitError("the runtime solver takes matrices of scalars or of "
                         "square blocks");

  // func.func private @simit_rt_<method>_{bcsr,diag}[_f32]([rowptr,
  //     colidx,] values, vectors..., x, where), declared once. The runtime ends the
  // run with `where` in its message when the solve fails.
  MLIRContext *ctx = b.getContext();
  int64_t dyn = ShapedType::kDynamic;
  Type indexArray = MemRefType::get({dyn}, b.getI32Type());
  auto values = MemRefType::get({dyn, dyn, dyn}, component);
  auto vector = MemRefType::get({dyn, dyn}, component);
  SmallVector<Type> argTypes;
  if (!diagonal)
    argTypes.append({indexArray, indexArray});
  argTypes.push_back(values);
  argTypes.append(vectors.size() + 1, vector);
  argTypes.push_back(LLVM::LLVMPointerType::get(ctx));
  std::optional<::simit::abi::RuntimeFunction> function =
      ::simit::abi::systemSolveFunction(
          diagonal ? ::simit::abi::SystemSolve::Diagonal : method,
          component.isF32(), rank);
  if (!function)
    return op->emitError("the runtime has no solve of rank ") << rank;
  StringRef solver = runtimeName(*function);
  func::FuncOp callee =
      declareRuntime(loc, solver, FunctionType::get(ctx, argTypes, {}));
  if (!callee)
    return op->emitError("@") << solver << " is declared with another type";

  Value result = op->getResult(0);
  Value x = allocSystem(loc, result.getType(), Storage::dense(),
                        /*zeroFill=*/false);
  SmallVector<Value> args;
  if (diagonal) {
    args.push_back(asRuntimeBlocks(loc, lookup(matrix), values));
  } else {
    auto [rowPtr, colIdx, blocks] = bcsrArrays(loc, storage, matrix);
    args.append({rowPtr, colIdx, asRuntimeBlocks(loc, blocks, values)});
  }
  for (Value input : vectors)
    args.push_back(asRuntimeBlocks(loc, lookup(input), vector));
  args.append({asRuntimeBlocks(loc, x, vector),
               stringConstant(loc, what.str() + sourcePositionSuffix(op))});
  func::CallOp::create(b, loc, callee, args);
  map(result, x);
  return success();
}

/// What a factorisation or solve op calls: the language's intrinsic (lu,
/// lusolve, triangularSolve, ...; the statement messages name) and the
/// runtime function, on a system matrix (`system`: BCSR arrays) or on
/// dense local tensors.
struct SolverCall {
  StringRef intrinsic;
  ::simit::abi::RuntimeFunction function;
};
static SolverCall solverCallOf(Operation *op, bool system) {
  using F = ::simit::abi::RuntimeFunction;
  auto lu = [](FactorizationKind kind) {
    return kind == FactorizationKind::LU;
  };
  if (auto factorize = dyn_cast<FactorizeOp>(op)) {
    if (lu(factorize.getKind()))
      return {"lu", system ? F::LUBCSR : F::LU};
    return {"chol", system ? F::CholBCSR : F::Chol};
  }
  if (auto free = dyn_cast<FactorFreeOp>(op))
    return lu(free.getKind()) ? SolverCall{"lufree", F::LUFree}
                              : SolverCall{"cholfree", F::CholFree};
  if (auto solve = dyn_cast<FactorSolveOp>(op)) {
    bool isLU = lu(solve.getKind());
    StringRef name = solve.getIntrinsicName();
    if (system)
      return {name, isLU ? F::LUSolveBCSR : F::LLTSolveBCSR};
    if (getTensorOrder(solve.getRhs().getType()) == 2)
      return {name, isLU ? F::LUMatSolve : F::LLTMatSolve};
    return {name, isLU ? F::LUSolve : F::LLTSolve};
  }
  return {"triangularSolve", F::TriangularSolve};
}

LogicalResult FunctionLowering::lowerWoodbury(WoodburyOp op) {
  // (A, u_1..u_k, v_1..v_k, b, w_1..w_k, c) -> x: the runtime's
  // simit_rt_sherman_morrison_bcsr for k = 1, simit_rt_woodbury<k>_bcsr.
  unsigned k = op.getRank();
  if (k > WoodburyOp::kMaxRank)
    return op.emitError("the runtime's Woodbury solve takes at most ")
           << WoodburyOp::kMaxRank << " outer products, not " << k;
  SmallVector<Value> vectors(op.getUs());
  llvm::append_range(vectors, op.getVs());
  vectors.push_back(op.getRhs());
  llvm::append_range(vectors, op.getWs());
  vectors.push_back(op.getSolution());
  if (k == 1)
    return lowerSystemSolve(op, op.getMatrix(), vectors,
                            ::simit::abi::SystemSolve::LowRank,
                            "Sherman-Morrison", k);
  return lowerSystemSolve(op, op.getMatrix(), vectors,
                          ::simit::abi::SystemSolve::LowRank, "Woodbury", k);
}

LogicalResult FunctionLowering::lowerSystemFactorisation(Operation *op) {
  Location loc = op->getLoc();
  if (auto solve = dyn_cast<TriangularSolveOp>(op))
    return lowerSystemSolve(op, solve.getMatrix(), solve.getRhs(),
                            ::simit::abi::SystemSolve::Triangular,
                            "triangularSolve");
  SolverCall call = solverCallOf(op, /*system=*/true);
  std::string name = call.intrinsic.str();
  auto factorize = dyn_cast<FactorizeOp>(op);
  auto solve = dyn_cast<FactorSolveOp>(op);
  Value matrix = factorize ? factorize.getMatrix() : Value();
  Storage storage = matrix ? storageOf(matrix) : Storage();
  // f32 arrays (a float32 program) are widened for the runtime and its
  // solutions narrowed back.
  auto f64Blocks = [](Type t, unsigned order) {
    auto type = dyn_cast<SystemTensorType>(t);
    if (!type || !type.isSystem() || type.getOrder() != order ||
        !(type.getComponentType().isF64() || type.getComponentType().isF32()))
      return false;
    SmallVector<int64_t> block = type.getBlockShape();
    return block.empty() || (order == 2 && block.size() == 2 &&
                             block[0] == block[1]) ||
           (order == 1 && block.size() == 1);
  };
  if (factorize &&
      !(f64Blocks(matrix.getType(), 2) && isSparseSquare(storage)))
    return op->emitError("'")
           << name
           << "' on a system matrix needs a square float matrix of scalars or "
              "square blocks assembled from a set; this one is stored as "
           << storage.describe();
  auto scalarMatrix = [&](Type t) {
    auto type = dyn_cast<SystemTensorType>(t);
    return f64Blocks(t, 2) && type.getBlockShape().empty();
  };
  bool matrixSolve = solve && scalarMatrix(solve.getRhs().getType()) &&
                     scalarMatrix(solve.getType());
  if (solve && !matrixSolve &&
      !(f64Blocks(solve.getRhs().getType(), 1) &&
        solve.getType() == solve.getRhs().getType()))
    return op->emitError("'") << name
                              << "' on system tensors needs a float vector "
                                 "right-hand side, solved to its own type, "
                                 "or a float matrix of scalars";
  if (!factorize && !solve)
    return op->emitError("'") << name
                              << "' is not supported on system tensors by "
                                 "the loop lowering";

  MLIRContext *ctx = b.getContext();
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  int64_t dyn = ShapedType::kDynamic;
  auto indexArray = MemRefType::get({dyn}, b.getI32Type());
  auto values = MemRefType::get({dyn, dyn, dyn}, b.getF64Type());
  auto vector = MemRefType::get({dyn, dyn}, b.getF64Type());
  StringRef runtimeName = mlir::simit::runtimeName(call.function);
  // The runtime ends the run with `where` ("chol (file:line:col)") when the
  // factorisation or solve fails, and names the statement in statistics.
  Value where = stringConstant(loc, name + sourcePositionSuffix(op));
  if (factorize) {
    auto type =
        FunctionType::get(ctx, {indexArray, indexArray, values, ptr}, {ptr});
    func::FuncOp callee = declareRuntime(loc, runtimeName, type);
    if (!callee)
      return op->emitError("@") << runtimeName
                                << " is declared with another type";
    auto [rowPtr, colIdx, blocks] = bcsrArrays(loc, storage, matrix);
    if (!cast<MemRefType>(blocks.getType()).getElementType().isF64()) {
      Value wide = allocLike(loc, blocks, b.getF64Type());
      copyConverted(loc, blocks, wide);
      blocks = wide;
    }
    auto lowered = func::CallOp::create(
        b, loc, callee,
        ValueRange{rowPtr, colIdx, asRuntimeBlocks(loc, blocks, values),
                   where});
    map(factorize.getResult(), lowered.getResult(0));
    return success();
  }
  auto type = FunctionType::get(ctx, {ptr, vector, vector, ptr}, {});
  func::FuncOp callee = declareRuntime(loc, runtimeName, type);
  if (!callee)
    return op->emitError("@") << runtimeName
                              << " is declared with another type";
  if (matrixSolve)
    return lowerFactorMatrixSolve(solve, callee, where);
  Value x = allocSystem(loc, solve.getType(), Storage::dense(),
                        /*zeroFill=*/false);
  Value rhs = lookup(solve.getRhs()), solution = x;
  if (!cast<MemRefType>(x.getType()).getElementType().isF64()) {
    Value wide = allocLike(loc, rhs, b.getF64Type());
    copyConverted(loc, rhs, wide);
    rhs = wide;
    solution = allocLike(loc, x, b.getF64Type());
  }
  func::CallOp::create(b, loc, callee,
                       ValueRange{lookup(solve.getFactorization()),
                                  asRuntimeBlocks(loc, rhs, vector),
                                  asRuntimeBlocks(loc, solution, vector),
                                  where});
  if (solution != x)
    copyConverted(loc, solution, x);
  map(solve.getResult(), x);
  return success();
}

LogicalResult FunctionLowering::lowerFactorMatrixSolve(FactorSolveOp solve,
                                                      func::FuncOp vectorSolve,
                                                      Value where) {
  // X = A^-1 B column by column: column j of B gathered into a vector (zero
  // where B stores no block), solved with the factorisation, and written
  // into column j of X, which is dense.
  Location loc = solve.getLoc();
  auto rhsType = cast<SystemTensorType>(solve.getRhs().getType());
  auto resultType = cast<SystemTensorType>(solve.getType());
  Storage rhs = storageOf(solve.getRhs());
  Storage result = storageOf(solve);
  if (result.kind != Storage::Kind::DenseMatrix)
    return solve.emitError("the solution of '")
           << solve.getIntrinsicName() << "' must be stored as a dense "
           << "matrix; it is stored as " << result.describe();
  Value rhsRows = getSetSize(cast<StringAttr>(rhsType.getDims()[0]));
  Value cols = getSetSize(cast<StringAttr>(rhsType.getDims()[1]));
  Value resultRows = getSetSize(cast<StringAttr>(resultType.getDims()[0]));
  auto vectorType = MemRefType::get({ShapedType::kDynamic}, b.getF64Type());
  auto runtimeVector = MemRefType::get(
      {ShapedType::kDynamic, ShapedType::kDynamic}, b.getF64Type());
  Value column = memref::AllocOp::create(b, loc, vectorType, rhsRows);
  Value solution = memref::AllocOp::create(b, loc, vectorType, resultRows);
  Value x = allocSystem(loc, resultType, result, /*zeroFill=*/false);
  Value bValues = lookup(solve.getRhs());
  Value zero = zeroOf(b.getF64Type());
  forLoop(loc, cols, [&](Value j) {
    forLoop(loc, rhsRows, [&](Value r) {
      Value position = findBlock(loc, rhs, r, j);
      Value present = arith::CmpIOp::create(b, loc, arith::CmpIPredicate::sge,
                                            position, indexConstant(0));
      Value at =
          arith::SelectOp::create(b, loc, present, position, indexConstant(0));
      Value stored = memref::LoadOp::create(b, loc, bValues, at);
      if (!stored.getType().isF64())
        stored = arith::ExtFOp::create(b, loc, b.getF64Type(), stored);
      memref::StoreOp::create(
          b, loc, arith::SelectOp::create(b, loc, present, stored, zero),
          column, r);
    });
    func::CallOp::create(b, loc, vectorSolve,
                         ValueRange{lookup(solve.getFactorization()),
                                    asRuntimeBlocks(loc, column, runtimeVector),
                                    asRuntimeBlocks(loc, solution,
                                                    runtimeVector),
                                    where});
    forLoop(loc, resultRows, [&](Value r) {
      Value at = findBlock(loc, result, r, j);
      Value component = memref::LoadOp::create(b, loc, solution, r);
      if (resultType.getComponentType() != component.getType())
        component = arith::TruncFOp::create(
            b, loc, resultType.getComponentType(), component);
      memref::StoreOp::create(b, loc, component, x, at);
    });
  });
  // The buffer deallocation passes free the two vectors.
  map(solve.getResult(), x);
  return success();
}

LogicalResult FunctionLowering::lowerFactorisation(Operation *op) {
  Location loc = op->getLoc();
  if (llvm::any_of(op->getOperandTypes(), isSystem))
    return lowerSystemFactorisation(op);
  MLIRContext *ctx = b.getContext();
  SolverCall call = solverCallOf(op, /*system=*/false);
  std::string name = call.intrinsic.str();
  Type f64 = b.getF64Type();
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  Type flat = MemRefType::get({ShapedType::kDynamic}, f64);
  bool factorise = isa<FactorizeOp>(op);
  bool free = isa<FactorFreeOp>(op);
  bool triangular = isa<TriangularSolveOp>(op);
  bool matSolve = !factorise && !free && !triangular &&
                  getTensorOrder(op->getOperand(1).getType()) == 2;

  // The runtime takes f64 matrices and vectors of static shapes; the op's
  // verifier has checked the rest. With float32 (language.md 4.1) the
  // operands are widened and the result rounded back: the runtime's
  // factorisations and solves run in f64.
  auto floatOf = [](Type t) -> Type {
    auto tensor = dyn_cast<RankedTensorType>(t);
    return tensor ? tensor.getElementType() : Type();
  };
  Type precision;
  bool supported = true;
  for (Type t :
       llvm::concat<const Type>(op->getOperandTypes(), op->getResultTypes())) {
    if (isa<OpaqueType>(t))
      continue;
    auto tensor = dyn_cast<RankedTensorType>(t);
    supported &= tensor && tensor.hasStaticShape() &&
                 (floatOf(t).isF64() || floatOf(t).isF32()) &&
                 (!precision || precision == floatOf(t));
    precision = floatOf(t);
  }
  if (!supported || (!factorise && !free && !triangular &&
                     op->getResult(0).getType() != op->getOperand(1).getType()))
    return op->emitError("'")
           << name
           << "' is supported by the loop lowering on dense local float "
              "matrices and vectors of static shapes, its result of the "
              "right-hand side's type";

  // A lower triangle to solve with is square.
  if (triangular) {
    ArrayRef<int64_t> matrix =
        cast<RankedTensorType>(op->getOperand(0).getType()).getShape();
    if (matrix[0] != matrix[1])
      return op->emitError("'triangularSolve' solves with the lower triangle "
                           "of a square matrix; this one is ")
             << matrix[0] << " x " << matrix[1];
  }

  // Local tensors (vectors) are stored to a stack buffer passed as
  // memref<?xf64>; tensor results come back through one.
  SmallVector<Value> args;
  SmallVector<Type> argTypes;
  for (Value operand : op->getOperands()) {
    Value value = lookup(operand);
    if (isa<OpaqueType>(operand.getType())) {
      args.push_back(value);
      argTypes.push_back(ptr);
      continue;
    }
    args.push_back(denseRuntimeBuffer(loc, value));
    argTypes.push_back(flat);
  }
  Value resultSlot;
  SmallVector<Type> resultTypes;
  if (factorise) {
    resultTypes.push_back(ptr);
  } else if (!free) {
    auto resultType = cast<RankedTensorType>(op->getResult(0).getType());
    resultSlot = denseRuntimeBuffer(loc, resultType.getNumElements());
    args.push_back(resultSlot);
    argTypes.push_back(flat);
  }
  // Sizes: n of a factorised or triangular matrix, the columns of a
  // matrix right-hand side.
  auto sizeArg = [&](int64_t size) {
    args.push_back(arith::ConstantOp::create(b, loc, b.getI64IntegerAttr(size)));
    argTypes.push_back(b.getI64Type());
  };
  auto shape = [&](unsigned operand) {
    return cast<RankedTensorType>(op->getOperand(operand).getType()).getShape();
  };
  if (factorise || triangular)
    sizeArg(shape(0)[0]);
  else if (matSolve)
    sizeArg(shape(1)[1]);
  // The runtime ends the run naming `where` ("lusolve (file:line:col)")
  // when a size, the matrix or the handle is wrong.
  args.push_back(stringConstant(loc, name + sourcePositionSuffix(op)));
  argTypes.push_back(ptr);

  StringRef runtimeName = mlir::simit::runtimeName(call.function);
  if (free) {
    callRuntime(loc, runtimeName, {}, args);
    return success();
  }
  // The JIT binds the C interface, _mlir_ciface_<name>, of functions with
  // memrefs.
  func::FuncOp callee = declareRuntime(
      loc, runtimeName, FunctionType::get(ctx, argTypes, resultTypes));
  if (!callee)
    return op->emitError("@") << runtimeName
                              << " is declared with another type";
  auto lowered = func::CallOp::create(b, loc, callee, args);
  if (factorise) {
    map(op->getResult(0), lowered.getResult(0));
    return success();
  }
  map(op->getResult(0),
      loadDenseRuntimeBuffer(
          loc, resultSlot,
          cast<VectorType>(convertType(op->getResult(0).getType()))));
  return success();
}

Value FunctionLowering::denseRuntimeBuffer(Location loc, int64_t size) {
  Type f64 = b.getF64Type();
  Value slot = allocaSlot(loc, MemRefType::get({size}, f64));
  return memref::CastOp::create(
      b, loc, MemRefType::get({ShapedType::kDynamic}, f64), slot);
}

Value FunctionLowering::denseRuntimeBuffer(Location loc, Value vector) {
  auto type = cast<VectorType>(vector.getType());
  int64_t size = type.getNumElements();
  Value buffer = denseRuntimeBuffer(loc, size);
  // The runtime's dense solvers run in f64 (language.md 4.1: float32
  // values are widened and their results rounded back).
  if (!type.getElementType().isF64())
    vector = arith::ExtFOp::create(
        b, loc, VectorType::get({size}, b.getF64Type()), vector);
  // Stored through the slot's static type, whose size the store shows.
  vector::StoreOp::create(b, loc, vector,
                          buffer.getDefiningOp<memref::CastOp>().getSource(),
                          ValueRange{indexConstant(0)});
  return buffer;
}

Value FunctionLowering::loadDenseRuntimeBuffer(Location loc, Value buffer,
                                               VectorType type) {
  buffer = buffer.getDefiningOp<memref::CastOp>().getSource();
  Value value = vector::LoadOp::create(
      b, loc, VectorType::get(type.getShape(), b.getF64Type()), buffer,
      ValueRange{indexConstant(0)});
  if (!type.getElementType().isF64())
    value = arith::TruncFOp::create(b, loc, type, value);
  return value;
}

using ::simit::abi::RuntimeFunction;

Value FunctionLowering::solveByDenseLU(Location loc, Operation *op,
                                       Value matrix, Value rhs, int64_t n) {
  MLIRContext *ctx = b.getContext();
  Type ptr = LLVM::LLVMPointerType::get(ctx);
  Value where = stringConstant(loc, "solve" + sourcePositionSuffix(op));
  auto call = [&](RuntimeFunction function, ArrayRef<Value> args,
                  TypeRange results) -> Value {
    StringRef name = mlir::simit::runtimeName(function);
    SmallVector<Type> types;
    for (Value arg : args)
      types.push_back(arg.getType());
    if (function == RuntimeFunction::LUFree)
      return callRuntime(loc, name, results, args);
    func::FuncOp callee =
        declareRuntime(loc, name, FunctionType::get(ctx, types, results));
    auto lowered = func::CallOp::create(b, loc, callee, args);
    return lowered.getNumResults() ? lowered.getResult(0) : Value();
  };
  Value n64 = arith::ConstantOp::create(b, loc, b.getI64IntegerAttr(n));
  Value handle = call(RuntimeFunction::LU,
                      {denseRuntimeBuffer(loc, matrix), n64, where}, {ptr});
  Value x = denseRuntimeBuffer(loc, n);
  call(RuntimeFunction::LUSolve,
       {handle, denseRuntimeBuffer(loc, rhs), x, where}, {});
  call(RuntimeFunction::LUFree, {handle, where}, {});
  return loadDenseRuntimeBuffer(loc, x, cast<VectorType>(rhs.getType()));
}
