//===--- Specialise.cpp - A program made for the runs a host promises -----===//

#include "Specialise.h"

#include "simit/Dialect/Simit/IR/Simit.h"
#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/BuiltinAttributes.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/Format.h"

using namespace simit;

/// `values` as a constant of `type` (a scalar or a static tensor of
/// floats, integers or bools), or null when they do not fit.
static mlir::TypedAttr constantOf(mlir::Type type,
                                  llvm::ArrayRef<double> values) {
  auto tensor = llvm::dyn_cast<mlir::RankedTensorType>(type);
  mlir::Type scalar = tensor ? tensor.getElementType() : type;
  int64_t count = tensor ? tensor.getNumElements() : 1;
  if ((tensor && !tensor.hasStaticShape()) ||
      static_cast<int64_t>(values.size()) != count)
    return nullptr;
  llvm::SmallVector<mlir::Attribute> components;
  for (double value : values) {
    if (auto floatType = llvm::dyn_cast<mlir::FloatType>(scalar))
      components.push_back(mlir::FloatAttr::get(floatType, value));
    else if (auto intType = llvm::dyn_cast<mlir::IntegerType>(scalar))
      components.push_back(mlir::IntegerAttr::get(
          intType, intType.getWidth() == 1 ? value != 0
                                           : static_cast<int64_t>(value)));
    else
      return nullptr;
  }
  if (!tensor)
    return llvm::cast<mlir::TypedAttr>(components.front());
  return mlir::DenseElementsAttr::get(tensor, components);
}

void simit::specialiseModule(mlir::ModuleOp module,
                             const ProgramSpecialisation &specialisation) {
  // Functions the scene does not call are not compiled, unless it names one
  // the program does not export: its error then lists them all.
  auto exports = [&](llvm::StringRef name) {
    auto function = module.lookupSymbol<mlir::func::FuncOp>(name);
    return function && mlir::simit::isExportedFunction(function);
  };
  if (!specialisation.entryFunctions.empty() &&
      llvm::all_of(specialisation.entryFunctions, exports))
    for (auto function : module.getOps<mlir::func::FuncOp>())
      if (mlir::simit::isExportedFunction(function) &&
          !llvm::is_contained(specialisation.entryFunctions,
                              function.getSymName()))
        function->removeAttr("simit.export");
  mlir::MLIRContext *context = module.getContext();
  for (auto global : module.getOps<mlir::simit::ExternOp>()) {
    std::string name = global.getSymName().str();
    if (auto set = llvm::dyn_cast<mlir::simit::SetType>(global.getType())) {
      auto fields = specialisation.uniformFields.find(name);
      if (fields == specialisation.uniformFields.end())
        continue;
      llvm::SmallVector<mlir::NamedAttribute> values;
      for (const auto &[field, block] : fields->second)
        if (mlir::Type type = set.getElement().getFieldType(field))
          if (mlir::TypedAttr value = constantOf(type, block))
            values.emplace_back(mlir::StringAttr::get(context, field), value);
      if (!values.empty())
        global->setAttr("simit.uniform_fields",
                        mlir::DictionaryAttr::get(context, values));
      continue;
    }
    auto constant = specialisation.constantExterns.find(name);
    if (constant == specialisation.constantExterns.end())
      continue;
    if (mlir::TypedAttr value = constantOf(global.getType(), constant->second))
      global->setAttr("simit.constant", value);
  }
}

/// Exact: the components in hexadecimal floating point.
static void writeValues(llvm::raw_ostream &os, llvm::ArrayRef<double> values) {
  for (double value : values)
    os << " " << llvm::format("%a", value);
}

void simit::writeSpecialisationKey(
    llvm::raw_ostream &os, const ProgramSpecialisation &specialisation) {
  os << "\nentries " << llvm::join(specialisation.entryFunctions, ",");
  for (const auto &[name, values] : specialisation.constantExterns) {
    os << "\nconstant " << name;
    writeValues(os, values);
  }
  for (const auto &[set, fields] : specialisation.uniformFields)
    for (const auto &[field, values] : fields) {
      os << "\nuniform " << set << "." << field;
      writeValues(os, values);
    }
}
