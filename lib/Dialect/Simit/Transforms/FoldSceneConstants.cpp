//===- FoldSceneConstants.cpp - Constants the scene fixes into the code ---===//
//
// A scene fixes values the program reads as data: externs it marks constant
// and fields with one value over their whole set. Folded, they are
// immediates the optimiser can use (h * h computed once, a branch on a
// constant flag gone) and arguments the host no longer binds.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/SymbolTable.h"
#include "mlir/Transforms/GreedyPatternRewriteDriver.h"

#include <optional>

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITFOLDSCENECONSTANTS
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

static constexpr llvm::StringLiteral kConstantAttr = "simit.constant";
static constexpr llvm::StringLiteral kUniformFieldsAttr =
    "simit.uniform_fields";

/// Replaces every load of a constant extern's slot, unless something else
/// uses the slot (a store).
static void foldConstantExterns(ModuleOp module) {
  DenseMap<StringAttr, TypedAttr> constants;
  for (auto global : module.getOps<ExternOp>())
    if (auto value = global->getAttrOfType<TypedAttr>(kConstantAttr))
      if (value.getType() == global.getType())
        constants[global.getSymNameAttr()] = value;
  if (constants.empty())
    return;
  SmallVector<ExternRefOp> refs;
  module.walk([&](ExternRefOp ref) {
    StringAttr name = ref.getGlobalAttr().getAttr();
    if (!constants.count(name))
      return;
    if (llvm::all_of(ref->getUsers(),
                     [](Operation *user) { return isa<LoadOp>(user); }))
      refs.push_back(ref);
    else
      constants.erase(name); // written: the slot changes while it runs
  });
  for (ExternRefOp ref : refs) {
    auto it = constants.find(ref.getGlobalAttr().getAttr());
    if (it == constants.end())
      continue;
    for (Operation *user : llvm::make_early_inc_range(ref->getUsers())) {
      OpBuilder builder(user);
      Value constant =
          arith::ConstantOp::create(builder, user->getLoc(), it->second);
      user->getResult(0).replaceAllUsesWith(constant);
      user->erase();
    }
  }
}

namespace {
/// The uniform fields of the module's sets and what may fold them.
class UniformFields {
public:
  explicit UniformFields(ModuleOp module) : module(module) {
    for (auto global : module.getOps<ExternOp>()) {
      auto set = dyn_cast<SetType>(global.getType());
      auto fields = global->getAttrOfType<DictionaryAttr>(kUniformFieldsAttr);
      if (set && fields)
        uniform[set.getName()] = fields;
    }
    module.walk([&](Operation *op) {
      if (auto write = dyn_cast<ElemWriteOp>(op))
        writtenByElement.insert(
            {write.getElement().getType(), write.getFieldAttr()});
      else if (auto write = dyn_cast<FieldWriteOp>(op))
        writtenBySet.insert({cast<SetType>(write.getSet().getType()).getName(),
                             write.getFieldAttr()});
    });
  }

  bool empty() const { return uniform.empty(); }

  /// The value every element of `read`'s element has in the field, if the
  /// set the element comes from is known and the field is uniform there.
  TypedAttr valueOf(ElemReadOp read) {
    std::optional<StringAttr> set = setOf(read.getElement());
    if (!set)
      return nullptr;
    auto fields = uniform.lookup(*set);
    if (!fields ||
        writtenByElement.contains({read.getElement().getType(),
                                   read.getFieldAttr()}) ||
        writtenBySet.contains({*set, read.getFieldAttr()}))
      return nullptr;
    auto value = fields.getAs<TypedAttr>(read.getField());
    return value && value.getType() == read.getType() ? value : nullptr;
  }

private:
  /// The one set the element always comes from: the element argument of an
  /// element function, or a component of its endpoint tuple, when every
  /// map and assembly calling the function agrees.
  std::optional<StringAttr> setOf(Value element) {
    std::optional<unsigned> endpoint;
    if (auto get = element.getDefiningOp<TupleGetOp>()) {
      endpoint = get.getIndex();
      element = get.getTuple();
    }
    auto argument = dyn_cast<BlockArgument>(element);
    if (!argument)
      return std::nullopt;
    auto function = dyn_cast<func::FuncOp>(argument.getOwner()->getParentOp());
    if (!function || argument.getOwner() != &function.getBody().front())
      return std::nullopt;
    std::optional<SymbolTable::UseRange> uses =
        SymbolTable::getSymbolUses(function, module);
    if (!uses || uses->empty())
      return std::nullopt;
    std::optional<StringAttr> found;
    for (const SymbolTable::SymbolUse &use : *uses) {
      Operation *user = use.getUser();
      if (!isa<MapOp, AssembleOp>(user))
        return std::nullopt;
      unsigned extras = isa<MapOp>(user)
                            ? cast<MapOp>(user).getExtras().size()
                            : cast<AssembleOp>(user).getExtras().size();
      auto set = cast<SetType>(
          (isa<MapOp>(user) ? cast<MapOp>(user).getSet()
                            : cast<AssembleOp>(user).getSet())
              .getType());
      unsigned position = argument.getArgNumber();
      StringAttr name;
      if (!endpoint && position == extras)
        name = set.getName();
      else if (endpoint && position == extras + 1 &&
               *endpoint < set.getCardinality())
        name = set.getEndpoint(*endpoint);
      else
        return std::nullopt;
      if (found && *found != name)
        return std::nullopt;
      found = name;
    }
    return found;
  }

  ModuleOp module;
  DenseMap<StringAttr, DictionaryAttr> uniform;
  DenseSet<std::pair<Type, StringAttr>> writtenByElement;
  DenseSet<std::pair<StringAttr, StringAttr>> writtenBySet;
};
} // namespace

static void foldUniformFields(ModuleOp module) {
  UniformFields fields(module);
  if (fields.empty())
    return;
  SmallVector<std::pair<ElemReadOp, TypedAttr>> folds;
  module.walk([&](ElemReadOp read) {
    if (TypedAttr value = fields.valueOf(read))
      folds.push_back({read, value});
  });
  for (auto [read, value] : folds) {
    OpBuilder builder(read);
    read.replaceAllUsesWith(
        arith::ConstantOp::create(builder, read.getLoc(), value).getResult());
    read.erase();
  }
}

namespace {
struct FoldSceneConstants
    : public simit::impl::SimitFoldSceneConstantsBase<FoldSceneConstants> {
  void runOnOperation() override {
    ModuleOp module = getOperation();
    foldConstantExterns(module);
    foldUniformFields(module);
    // Arithmetic on the constants folds (the driver folds every op), and
    // branches on them resolve; the blocks of regions stay as they are.
    RewritePatternSet patterns(&getContext());
    scf::IfOp::getCanonicalizationPatterns(patterns, &getContext());
    GreedyRewriteConfig config;
    config.setRegionSimplificationLevel(GreedySimplifyRegionLevel::Disabled);
    if (failed(applyPatternsGreedily(module, std::move(patterns), config)))
      signalPassFailure();
  }
};
} // namespace
