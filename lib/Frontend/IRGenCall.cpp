//===- IRGenCall.cpp - Calls, intrinsics and maps -------------------------===//
//
// User functions are func.call; an `inout` tensor argument passes its
// variable's slot, or a temporary slot copied back into the argument (a
// component, block or field) after the call. Intrinsics become math,
// arith, complex and simit ops (factorisations and solves included), or
// calls of the runtime (see IRGen.cpp).
// `map` is simit.assemble with `reduce +` and simit.map otherwise.
//
//===----------------------------------------------------------------------===//

#include "IRGenImpl.h"

#include "mlir/Dialect/Arith/IR/Arith.h"
#include "mlir/Dialect/Complex/IR/Complex.h"
#include "mlir/Dialect/Math/IR/Math.h"
#include "llvm/Support/MathExtras.h"

using namespace simit::frontend;
using namespace mlir;
namespace dialect = mlir::simit;
namespace frontend = ::simit::frontend;

SmallVector<Value> IRGenerator::genValues(const Expr &e) {
  if (auto *call = dyn_cast<CallExpr>(&e))
    return genCall(*call);
  if (auto *map = dyn_cast<MapExpr>(&e))
    return genMap(*map);
  return {genExpr(e)};
}

SmallVector<Value> IRGenerator::genCall(const CallExpr &e) {
  switch (e.intrinsic) {
  case Intrinsic::None:
    return genUserCall(e);
  case Intrinsic::Lu:
  case Intrinsic::Chol:
  case Intrinsic::LuSolve:
  case Intrinsic::LltSolve:
  case Intrinsic::LuMatSolve:
  case Intrinsic::LltMatSolve:
  case Intrinsic::LuFree:
  case Intrinsic::CholFree:
  case Intrinsic::TriangularSolve:
    return genSolverIntrinsic(e);
  case Intrinsic::Clock:
    return genRuntimeCall(e, ::simit::abi::RuntimeFunction::Clock, "clock");
  case Intrinsic::StoreTime:
    return genRuntimeCall(e, ::simit::abi::RuntimeFunction::StoreTime,
                          "storeTime");
  default:
    return {genIntrinsic(e)};
  }
}

SmallVector<mlir::Type> IRGenerator::convertResultTypes(const Expr &e) {
  SmallVector<mlir::Type> types;
  if (e.type->isResults()) {
    for (const TypePtr &t : e.type->results)
      types.push_back(convertType(t, e.loc));
  } else if (!e.type->isVoid()) {
    types.push_back(convertType(e.type, e.loc));
  }
  return types;
}

SmallVector<Value> IRGenerator::genSolverIntrinsic(const CallExpr &e) {
  SmallVector<Value> args;
  for (const ExprPtr &arg : e.args)
    args.push_back(genExpr(*arg));
  SmallVector<mlir::Type> results = convertResultTypes(e);
  mlir::Location l = loc(e.loc);
  bool lu = llvm::is_contained({Intrinsic::Lu, Intrinsic::LuSolve,
                                Intrinsic::LuMatSolve, Intrinsic::LuFree},
                               e.intrinsic);
  auto kind = lu ? dialect::FactorizationKind::LU
                 : dialect::FactorizationKind::Cholesky;
  switch (e.intrinsic) {
  case Intrinsic::Lu:
  case Intrinsic::Chol:
    return {dialect::FactorizeOp::create(builder, l, results[0], kind, args[0])};
  case Intrinsic::LuFree:
  case Intrinsic::CholFree:
    dialect::FactorFreeOp::create(builder, l, kind, args[0]);
    return {};
  case Intrinsic::TriangularSolve:
    return {dialect::TriangularSolveOp::create(builder, l, results[0], args[0],
                                               args[1])};
  default:
    return {dialect::FactorSolveOp::create(builder, l, results[0], kind,
                                           args[0], args[1])};
  }
}

SmallVector<Value>
IRGenerator::genRuntimeCall(const CallExpr &e,
                            ::simit::abi::RuntimeFunction function,
                            StringRef name) {
  SmallVector<Value> args;
  for (const ExprPtr &arg : e.args)
    args.push_back(genExpr(*arg));
  SmallVector<mlir::Type> results = convertResultTypes(e);
  func::FuncOp callee = declareRuntimeFunction(
      ::simit::abi::runtimeFunctionName(function), name,
      builder.getFunctionType(ValueRange(args).getTypes(), results));
  auto call = func::CallOp::create(builder, loc(e.loc), callee, args);
  return SmallVector<Value>(call.getResults());
}

SmallVector<Value> IRGenerator::genUserCall(const CallExpr &e) {
  const FuncDecl &callee = *e.func;
  struct CopyBack {
    const Expr *argument;
    Value slot;
  };
  SmallVector<CopyBack> copyBacks;
  SmallVector<Value> args;
  for (auto [param, arg] : llvm::zip(callee.params, e.args)) {
    if (!isSlotParam(*param)) {
      args.push_back(genExpr(*arg));
      continue;
    }
    if (accumulatedResultOf(*arg))
      return {unsupported(arg->loc,
                          "a result passed as an inout argument in a "
                          "function mapped with reduce and inout extra "
                          "arguments")};
    // Pass a variable's own slot; anything else through a temporary.
    if (auto *name = dyn_cast<NameExpr>(arg.get())) {
      auto *var = dyn_cast<VarDecl>(name->decl);
      auto it = var ? bindings.find(var) : bindings.end();
      if (var && var->role == VarDecl::Role::Extern) {
        args.push_back(slotOf(*var, arg->loc));
        continue;
      }
      if (it != bindings.end() && it->second.isSlot) {
        args.push_back(it->second.value);
        continue;
      }
    }
    Value value = genExpr(*arg);
    Value slot = dialect::AllocOp::create(
        builder, loc(arg->loc), dialect::RefType::get(&context, value.getType()));
    dialect::StoreOp::create(builder, loc(arg->loc), value, slot);
    args.push_back(slot);
    copyBacks.push_back({arg.get(), slot});
  }

  func::CallOp call;
  if (callee.isExtern) {
    SmallVector<mlir::Type> results = convertResultTypes(e);
    func::FuncOp decl = declareRuntimeFunction(
        callee.name, callee.name,
        builder.getFunctionType(ValueRange(args).getTypes(), results));
    call = func::CallOp::create(builder, loc(e.loc), decl, args);
  } else {
    auto function = module.lookupSymbol<func::FuncOp>(symbolOf(callee));
    if (!function)
      return {unsupported(e.loc, "a call of '" + callee.name +
                                     "' before its definition")};
    call = func::CallOp::create(builder, loc(e.loc), function, args);
  }
  for (const CopyBack &copy : copyBacks)
    writeTarget(*copy.argument,
                dialect::LoadOp::create(builder, loc(copy.argument->loc),
                                      copy.slot),
                copy.argument->loc);
  return SmallVector<Value>(call.getResults());
}

/// A local int tensor with its components converted to `real`.
static Value toFloats(OpBuilder &builder, Location l, Value local,
                      mlir::Type real) {
  auto type = cast<RankedTensorType>(local.getType());
  return arith::SIToFPOp::create(builder, l, type.clone(real), local);
}

/// atan2(y, x), with C's values at y = x = 0 (±0 or ±pi by the signs):
/// MLIR folds math.atan2 of two constant zeros to NaN, which the same call
/// at run time never gives.
Value IRGenerator::genAtan2(Value y, Value x, Location l) {
  mlir::Type type = y.getType();
  auto constant = [&](double value) -> Value {
    return arith::ConstantOp::create(builder, l, type,
                                     builder.getFloatAttr(type, value));
  };
  Value angle = math::Atan2Op::create(builder, l, y, x);
  Value zero = constant(0.0);
  Value bothZero = arith::AndIOp::create(
      builder, l,
      arith::CmpFOp::create(builder, l, arith::CmpFPredicate::OEQ, y, zero),
      arith::CmpFOp::create(builder, l, arith::CmpFPredicate::OEQ, x, zero));
  Value xNegative = arith::CmpFOp::create(
      builder, l, arith::CmpFPredicate::OLT,
      math::CopySignOp::create(builder, l, constant(1.0), x), zero);
  Value magnitude = arith::SelectOp::create(builder, l, xNegative,
                                            constant(llvm::numbers::pi), zero);
  Value atZero = math::CopySignOp::create(builder, l, magnitude, y);
  return arith::SelectOp::create(builder, l, bothZero, atZero, angle);
}

Value IRGenerator::genIntrinsic(const CallExpr &e) {
  SmallVector<Value> args;
  for (const ExprPtr &arg : e.args)
    args.push_back(genExpr(*arg));
  Location l = loc(e.loc);
  mlir::Type resultType = convertType(e.type, e.loc);
  switch (e.intrinsic) {
  case Intrinsic::Mod: return arith::RemSIOp::create(builder, l, args[0], args[1]);
  case Intrinsic::Sin: return math::SinOp::create(builder, l, args[0]);
  case Intrinsic::Cos: return math::CosOp::create(builder, l, args[0]);
  case Intrinsic::Tan: return math::TanOp::create(builder, l, args[0]);
  case Intrinsic::Asin: return math::AsinOp::create(builder, l, args[0]);
  case Intrinsic::Acos: return math::AcosOp::create(builder, l, args[0]);
  case Intrinsic::Sqrt: return math::SqrtOp::create(builder, l, args[0]);
  case Intrinsic::Cbrt: return math::CbrtOp::create(builder, l, args[0]);
  case Intrinsic::Log: return math::LogOp::create(builder, l, args[0]);
  case Intrinsic::Exp: return math::ExpOp::create(builder, l, args[0]);
  case Intrinsic::Abs: return math::AbsFOp::create(builder, l, args[0]);
  case Intrinsic::Atan2:
    return genAtan2(args[0], args[1], l);
  case Intrinsic::Pow: return math::PowFOp::create(builder, l, args[0], args[1]);
  case Intrinsic::Max: return arith::MaximumFOp::create(builder, l, args[0], args[1]);
  case Intrinsic::Min: return arith::MinimumFOp::create(builder, l, args[0], args[1]);
  case Intrinsic::Det:
  case Intrinsic::Det2:
  case Intrinsic::Det4:
    return dialect::DetOp::create(builder, l, resultType, args[0]);
  case Intrinsic::Inv:
  case Intrinsic::Inv2:
  case Intrinsic::Inv4:
    return dialect::InvOp::create(builder, l, args[0]);
  case Intrinsic::Cross: return dialect::CrossOp::create(builder, l, args[0], args[1]);
  case Intrinsic::Norm: {
    if (!isa<IntegerType>(dialect::getComponentType(args[0].getType())))
      return dialect::NormOp::create(builder, l, resultType, args[0]);
    // The norm of an int vector is a float. A local one is converted to
    // floats first (squares overflow 32 bits from 46341 on); a system one
    // takes the sqrt of its int dot product.
    if (isa<RankedTensorType>(args[0].getType()))
      return dialect::NormOp::create(builder, l, resultType,
                                     toFloats(builder, l, args[0], resultType));
    Value squares = dialect::DotOp::create(builder, l, builder.getI32Type(),
                                         args[0], args[0]);
    Value asFloat = arith::SIToFPOp::create(builder, l, resultType, squares);
    return math::SqrtOp::create(builder, l, asFloat);
  }
  case Intrinsic::Dot: {
    mlir::Type component = dialect::getComponentType(args[0].getType());
    if (!isa<IntegerType>(component))
      return dialect::DotOp::create(builder, l, resultType, args[0], args[1]);
    // The dot product of int vectors is a float (language.md 9): of local
    // ones converted to floats, of system ones the int sum converted.
    if (isa<RankedTensorType>(args[0].getType()))
      return dialect::DotOp::create(builder, l, resultType,
                                    toFloats(builder, l, args[0], resultType),
                                    toFloats(builder, l, args[1], resultType));
    Value sum = dialect::DotOp::create(builder, l, component, args[0], args[1]);
    return arith::SIToFPOp::create(builder, l, resultType, sum);
  }
  case Intrinsic::CreateComplex:
    return complex::CreateOp::create(builder, l, resultType, args[0], args[1]);
  case Intrinsic::ComplexNorm: return complex::AbsOp::create(builder, l, args[0]);
  case Intrinsic::ComplexGetReal: return complex::ReOp::create(builder, l, args[0]);
  case Intrinsic::ComplexGetImag: return complex::ImOp::create(builder, l, args[0]);
  case Intrinsic::ComplexConj: return complex::ConjOp::create(builder, l, args[0]);
  default:
    return unsupported(e.loc, "intrinsic '" + e.callee + "'", resultType);
  }
}

SmallVector<Value> IRGenerator::genMap(const MapExpr &e) {
  const FuncDecl &callee = *e.func;
  auto function = module.lookupSymbol<func::FuncOp>(symbolOf(callee));
  if (!function)
    return {unsupported(e.funcLoc, "a map of '" + callee.name +
                                       "' before its definition")};
  SmallVector<Value> extras;
  // `inout` extra arguments: the map runs the variant of the function
  // that returns them as leading results, each starting from the
  // argument's value (reads inside see the map's accumulator, writes store
  // as in a map without reduce), and stores them back to the arguments.
  SmallVector<unsigned> inoutExtras;
  for (auto [i, arg] : llvm::enumerate(e.args)) {
    if (isSlotParam(*callee.params[i]))
      inoutExtras.push_back(i);
    extras.push_back(genExpr(*arg));
  }
  // With `reduce +` too, the variant adds at every write to its own
  // results, so that a map that stores (in set order, as the inout
  // arguments need) reduces them.
  bool reduces = e.reduce && !callee.results.empty();
  if (!inoutExtras.empty()) {
    function =
        module.lookupSymbol<func::FuncOp>(inoutVariantOf(callee, reduces));
    if (!function) {
      // Generated once, where the generation of the current function can
      // resume afterwards.
      auto savedBindings = std::move(bindings);
      const FuncDecl *savedFunc = currentFunc;
      OpBuilder::InsertionGuard guard(builder);
      builder.setInsertionPointToEnd(module.getBody());
      auto savedAccumulated = std::move(accumulatedResults);
      genFunction(callee, inoutExtras, reduces);
      bindings = std::move(savedBindings);
      currentFunc = savedFunc;
      accumulatedResults = std::move(savedAccumulated);
      function =
          module.lookupSymbol<func::FuncOp>(inoutVariantOf(callee, reduces));
    }
  }
  Value set = genSet(e.targetSet, e.targetLoc);
  Value grid = e.grid ? genSet(e.grid, e.throughLoc) : Value();
  TypeRange results = function.getResultTypes();
  Location l = loc(e.loc);
  // `reduce +` of a function without results (mapped as a statement) has
  // nothing to reduce: the map runs it for its effects.
  if (e.reduce && !results.empty() && inoutExtras.empty())
    return SmallVector<Value>(
        dialect::AssembleOp::create(builder, l, results, function.getSymName(),
                                    extras, set, grid,
                                    dialect::ReductionKind::Add)
            .getResults());
  auto map = dialect::MapOp::create(builder, l, results, function.getSymName(),
                                    extras, set, grid);
  if (inoutExtras.empty())
    return SmallVector<Value>(map.getResults());
  SmallVector<int64_t> inits(results.size(), -1);
  for (auto [r, i] : llvm::enumerate(inoutExtras)) {
    inits[r] = i;
    writeTarget(*e.args[i], map.getResult(r), e.args[i]->loc);
  }
  map.setResultInitsAttr(builder.getDenseI64ArrayAttr(inits));
  return SmallVector<Value>(map.getResults().drop_front(inoutExtras.size()));
}
