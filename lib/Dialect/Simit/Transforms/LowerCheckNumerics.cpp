//===- LowerCheckNumerics.cpp - Scans of results for NaN and infinity -----===//
//
// After an op that simit-check-numerics marked, each float system tensor
// result is handed to the runtime's scan together with what the runtime
// needs to name an element: the layout of the blocks in the array (how the
// storage maps a block to its row and column), the pattern's index arrays,
// and the source description the pass wrote. The runtime function is
// simit_rt_check_numerics_f64/_f32 (lib/ABI/CheckNumerics.cpp).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

// The layout codes are shared with the runtime that reads them (a header
// of plain declarations; nothing of the engine is linked).
#include "simit/ABI/NumericsLayout.h"
#include "simit/ABI/RuntimeFunctionNames.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

namespace {
/// The row set of a vector: its first set dimension.
StringAttr firstSet(SystemTensorType type) {
  for (Attribute dim : type.getDims())
    if (auto set = dyn_cast<StringAttr>(dim))
      return set;
  return {};
}

SimitNumericsLayout layoutOf(const Storage &storage) {
  switch (storage.kind) {
  case Storage::Kind::Dense:
    return SIMIT_NUMERICS_VECTOR;
  case Storage::Kind::Diagonal:
    return SIMIT_NUMERICS_DIAGONAL;
  case Storage::Kind::Pattern:
  case Storage::Kind::Union:
  case Storage::Kind::Product:
  case Storage::Kind::Host:
    return SIMIT_NUMERICS_PATTERN;
  case Storage::Kind::Incidence:
    return SIMIT_NUMERICS_FIXED_ROWS;
  case Storage::Kind::Stencil:
    return SIMIT_NUMERICS_STENCIL;
  case Storage::Kind::DenseMatrix:
    return SIMIT_NUMERICS_DENSE;
  }
  llvm_unreachable("storage kind");
}
} // namespace

LogicalResult FunctionLowering::scanForNonFinite(Operation *op) {
  auto marks = op->getAttrOfType<DictionaryAttr>(kCheckNumericsAttr);
  auto what = marks.getAs<StringAttr>("op");
  auto names = marks.getAs<ArrayAttr>("results");
  Location loc = op->getLoc();
  MLIRContext *ctx = b.getContext();
  int64_t dyn = ShapedType::kDynamic;
  auto indexArray = MemRefType::get({dyn}, b.getI32Type());
  SetType mapped;
  if (isa<MapOp, AssembleOp>(op))
    mapped = cast<SetType>((isa<MapOp>(op) ? cast<MapOp>(op).getSet()
                                           : cast<AssembleOp>(op).getSet())
                               .getType());

  // One call of the runtime's scan; mapCardinality 0 names no elements of
  // the mapped set.
  auto scan = [&](Value array, Type component, SimitNumericsLayout layout,
                  Value perRow, Value rowptr, Value colidx, StringRef name,
                  StringAttr rowSet, StringAttr colSet, Value mapEndpoints,
                  int64_t mapCardinality, StringAttr mapSet) -> LogicalResult {
    Type ptr = LLVM::LLVMPointerType::get(ctx);
    auto values = UnrankedMemRefType::get(component, Attribute());
    auto calleeType = FunctionType::get(
        ctx,
        {values, b.getI32Type(), b.getI64Type(), indexArray, indexArray, ptr,
         ptr, ptr, ptr, indexArray, b.getI64Type(), ptr},
        {});
    StringRef calleeName = runtimeName(
        component.isF64() ? ::simit::abi::RuntimeFunction::CheckNumericsF64
                          : ::simit::abi::RuntimeFunction::CheckNumericsF32);
    func::FuncOp callee = declareRuntime(loc, calleeName, calleeType);
    if (!callee)
      return op->emitError("@") << calleeName
                                << " is declared with another type";
    SmallVector<Value> args{
        array,
        arith::ConstantIntOp::create(b, loc, b.getI32Type(), layout),
        perRow ? perRow
               : arith::ConstantIntOp::create(b, loc, b.getI64Type(), 0)
                     .getResult(),
        rowptr ? rowptr : emptyIndexArray(),
        colidx ? colidx : emptyIndexArray(),
        stringConstant(loc, what.getValue()),
        stringConstant(loc, name),
        stringConstant(loc, rowSet ? rowSet.getValue() : ""),
        stringConstant(loc, colSet ? colSet.getValue() : ""),
        mapEndpoints ? mapEndpoints : emptyIndexArray(),
        arith::ConstantIntOp::create(b, loc, b.getI64Type(), mapCardinality),
        stringConstant(loc, mapSet ? mapSet.getValue() : "")};
    // The unranked descriptor of the values is a stack slot made where it
    // is cast: the scope frees it after the call, so a scan in a loop does
    // not grow the stack with every iteration.
    auto scope = memref::AllocaScopeOp::create(b, loc, TypeRange{});
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(&scope.getBodyRegion().emplaceBlock());
    args.front() = memref::CastOp::create(b, loc, values, array);
    func::CallOp::create(b, loc, callee, args);
    memref::AllocaScopeReturnOp::create(b, loc, ValueRange{});
    return success();
  };

  for (auto [index, result] : llvm::enumerate(op->getResults())) {
    auto type = dyn_cast<SystemTensorType>(result.getType());
    Value array = lookup(result);
    if (!type || !type.isSystem() || !array ||
        !isa<Float64Type, Float32Type>(type.getComponentType()))
      continue;
    Storage storage = storageOf(result);
    SimitNumericsLayout layout = layoutOf(storage);
    Value rowptr, colidx;
    Value perRow;
    auto constantPerRow = [&](int64_t n) {
      return arith::ConstantIntOp::create(b, loc, b.getI64Type(), n);
    };
    if (layout == SIMIT_NUMERICS_PATTERN) {
      rowptr = rowPointers(storage);
      colidx = columnIndices(storage);
    } else if (layout == SIMIT_NUMERICS_FIXED_ROWS) {
      // The edge set's endpoint array is the column index, row by row.
      perRow = constantPerRow(storage.cardinality);
      ReassociationIndices both = {0, 1};
      colidx =
          memref::CollapseShapeOp::create(b, loc, incidenceEndpoints(storage),
                                          ArrayRef<ReassociationIndices>{both});
    } else if (layout == SIMIT_NUMERICS_STENCIL) {
      perRow = constantPerRow(storage.offsets.size());
    } else if (layout == SIMIT_NUMERICS_DENSE) {
      perRow = arith::IndexCastOp::create(b, loc, b.getI64Type(),
                                          getSetSize(storage.cols));
    }
    if (!rowptr)
      rowptr = emptyIndexArray();
    if (!colidx)
      colidx = emptyIndexArray();
    StringAttr rowSet = storage.isMatrix() ? storage.rows : firstSet(type);
    StringAttr colSet = storage.isMatrix() ? storage.cols : StringAttr();

    // An assembly over an edge set whose endpoints are the result's row (and
    // column) set: its endpoint array lets the runtime name the elements
    // that assembled the bad block (a tet, not only one of its vertices).
    Value mapEndpoints;
    int64_t mapCardinality = 0;
    StringAttr mapSet;
    if (mapped && !mapped.isGrid() && mapped.getCardinality() > 0 &&
        mapped.isHomogeneous() && mapped.getEndpoint(0) == rowSet &&
        (!colSet || colSet == rowSet) && layout != SIMIT_NUMERICS_STENCIL) {
      mapCardinality = mapped.getCardinality();
      mapSet = mapped.getName();
      ReassociationIndices both = {0, 1};
      mapEndpoints = memref::CollapseShapeOp::create(
          b, loc, getEndpoints(mapped), ArrayRef<ReassociationIndices>{both});
    }
    auto name = index < names.size() ? cast<StringAttr>(names[index])
                                     : StringAttr::get(ctx, "");
    if (failed(scan(array, type.getComponentType(), layout, perRow, rowptr,
                    colidx, name.getValue(), rowSet, colSet, mapEndpoints,
                    mapCardinality, mapSet)))
      return failure();
  }

  // The float fields the element function writes (an `inout` element, as
  // in `t.B = inv(Dm)`): a NaN stored there is named with this statement
  // rather than found later by the scan of the state after the function.
  if (auto fields = marks.getAs<ArrayAttr>("fields")) {
    for (auto field : fields.getAsRange<StringAttr>()) {
      Type fieldType = mapped.getElement().getFieldType(field.getValue());
      Value array = getField(mapped.getName(), field, fieldType);
      std::string name =
          (mapped.getName().getValue() + "." + field.getValue()).str();
      if (failed(scan(array, getComponentType(fieldType),
                      SIMIT_NUMERICS_VECTOR, {}, {}, {}, name,
                      mapped.getName(), {}, {}, 0, {})))
        return failure();
    }
  }
  return success();
}
