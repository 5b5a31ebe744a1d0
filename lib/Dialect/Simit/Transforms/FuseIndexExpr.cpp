//===- FuseIndexExpr.cpp - Fuse chains of index expressions ---------------===//
//
// A producer index expression whose only use is an input of a consumer index
// expression is inlined into the consumer. The producer's result variables
// become the consumer's variables that index that input; its summed
// variables become new variables of the fused expression, summed by a
// simit.index_sum at the start of the consumer's body. `x + A * b` thus
// becomes one loop nest with a scalar temporary per row (Figure 10 of the
// paper), and an assembled matrix sum consumed by a product is never built.
//
// A producer with summed variables is fused only when the consumer visits
// each point of the producer's result once (every consumer variable indexes
// that input); otherwise the sum would be recomputed.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/Transforms/Passes.h"

#include "mlir/IR/IRMapping.h"
#include "llvm/ADT/StringSet.h"

namespace mlir {
namespace simit {
#define GEN_PASS_DEF_SIMITFUSEINDEXEXPR
#include "simit/Dialect/Simit/Transforms/Passes.h.inc"
} // namespace simit
} // namespace mlir

using namespace mlir;
using namespace mlir::simit;

namespace {
/// The variables of `op` summed around its whole body.
SmallVector<int64_t> topLevelSums(IndexExprOp op) {
  llvm::SmallDenseSet<int64_t> nested;
  op.walk([&](IndexSumOp sum) {
    for (int64_t v : sum.getVars())
      nested.insert(v);
  });
  SmallVector<int64_t> sums;
  for (int64_t v = 0, e = op.getIndexVars().size(); v < e; ++v)
    if (!llvm::is_contained(op.getResultIndices(), v) && !nested.contains(v))
      sums.push_back(v);
  return sums;
}

/// Whether fusing `producer` into input `input` of `consumer` is legal and
/// does not recompute sums.
bool canFuse(IndexExprOp producer, IndexExprOp consumer, unsigned input) {
  if (!producer->hasOneUse() || producer->getBlock() != consumer->getBlock())
    return false;
  if (getTensorOrder(producer.getType()) == 0)
    return false;
  bool hasSums =
      producer.getIndexVars().size() > producer.getResultIndices().size();
  if (!hasSums)
    return true;
  ArrayRef<int64_t> access = consumer.getInputIndexList(input);
  for (int64_t v = 0, e = consumer.getIndexVars().size(); v < e; ++v)
    if (!llvm::is_contained(access, v))
      return false;
  return true;
}

/// Clones `ops` at the builder, renumbering the variables of nested sums.
void cloneBody(OpBuilder &b, Block &body, IRMapping &mapping,
               ArrayRef<int64_t> varMap) {
  for (Operation &op : body.without_terminator()) {
    Operation *clone = b.clone(op, mapping);
    clone->walk([&](IndexSumOp sum) {
      SmallVector<int64_t> vars;
      for (int64_t v : sum.getVars())
        vars.push_back(varMap[v]);
      sum.setVars(vars);
    });
  }
}

/// Builds the fused expression of `producer` into input `q` of `consumer`.
IndexExprOp fuse(IndexExprOp producer, IndexExprOp consumer, unsigned q) {
  MLIRContext *ctx = consumer.getContext();
  OpBuilder b(consumer);
  SmallVector<Attribute> vars(consumer.getIndexVars().begin(),
                              consumer.getIndexVars().end());
  SmallVector<Attribute> domains(consumer.getDomains().begin(),
                                 consumer.getDomains().end());
  llvm::StringSet<> names;
  for (Attribute name : vars)
    names.insert(cast<StringAttr>(name).getValue());

  // The producer's variables in the fused expression.
  ArrayRef<int64_t> access = consumer.getInputIndexList(q);
  SmallVector<int64_t> varMap(producer.getIndexVars().size(), -1);
  for (auto [d, v] : llvm::enumerate(producer.getResultIndices()))
    varMap[v] = access[d];
  for (auto [v, name] : llvm::enumerate(producer.getIndexVars())) {
    if (varMap[v] >= 0)
      continue;
    std::string fresh = cast<StringAttr>(name).getValue().str();
    while (names.contains(fresh))
      fresh += "'";
    names.insert(fresh);
    varMap[v] = vars.size();
    vars.push_back(StringAttr::get(ctx, fresh));
    domains.push_back(producer.getDomain(v));
  }

  // Inputs: the consumer's but q, then the producer's.
  SmallVector<Value> inputs;
  SmallVector<SmallVector<int64_t>> lists;
  for (auto [i, input] : llvm::enumerate(consumer.getInputs()))
    if (i != q) {
      inputs.push_back(input);
      lists.emplace_back(consumer.getInputIndexList(i));
    }
  for (auto [i, input] : llvm::enumerate(producer.getInputs())) {
    inputs.push_back(input);
    SmallVector<int64_t> list;
    for (int64_t v : producer.getInputIndexList(i))
      list.push_back(varMap[v]);
    lists.push_back(list);
  }
  OperationState state(consumer.getLoc(), IndexExprOp::getOperationName());
  IndexExprOp::build(b, state, consumer.getType(), inputs,
                     b.getArrayAttr(vars), b.getArrayAttr(domains),
                     consumer.getResultIndices(), lists);
  for (NamedAttribute attr : consumer->getDiscardableAttrs())
    state.addAttribute(attr.getName(), attr.getValue());
  auto fused = cast<IndexExprOp>(b.create(state));
  Block &body = fused.getBody().front();
  Block &consumerBody = consumer.getBody().front();
  Block &producerBody = producer.getBody().front();

  IRMapping mapping;
  unsigned next = 0;
  for (auto [i, arg] : llvm::enumerate(consumerBody.getArguments()))
    if (i != q)
      mapping.map(arg, body.getArgument(next++));
  for (BlockArgument arg : producerBody.getArguments())
    mapping.map(arg, body.getArgument(next++));

  b.setInsertionPointToStart(&body);
  SmallVector<int64_t> sums = topLevelSums(producer);
  Value produced;
  auto producerYield = cast<YieldOp>(producerBody.getTerminator());
  if (sums.empty()) {
    cloneBody(b, producerBody, mapping, varMap);
    produced = mapping.lookupOrDefault(producerYield.getValue());
  } else {
    SmallVector<int64_t> fusedSums;
    for (int64_t v : sums)
      fusedSums.push_back(varMap[v]);
    auto sum = IndexSumOp::create(b, producer.getLoc(),
                                  producerYield.getValue().getType(),
                                  b.getDenseI64ArrayAttr(fusedSums));
    Block *sumBody = new Block();
    sum.getBody().push_back(sumBody);
    OpBuilder::InsertionGuard guard(b);
    b.setInsertionPointToStart(sumBody);
    cloneBody(b, producerBody, mapping, varMap);
    IndexSumYieldOp::create(b, producerYield.getLoc(),
                            mapping.lookupOrDefault(producerYield.getValue()));
    produced = sum.getResult();
  }
  mapping.map(consumerBody.getArgument(q), produced);
  SmallVector<int64_t> identity(consumer.getIndexVars().size());
  for (auto [v, slot] : llvm::enumerate(identity))
    slot = v;
  cloneBody(b, consumerBody, mapping, identity);
  auto consumerYield = cast<YieldOp>(consumerBody.getTerminator());
  YieldOp::create(b, consumerYield.getLoc(),
                  mapping.lookupOrDefault(consumerYield.getValue()));
  return fused;
}

struct FuseIndexExpr
    : public simit::impl::SimitFuseIndexExprBase<FuseIndexExpr> {
  void runOnOperation() override {
    // Fuse one pair at a time until no pair is left; each fusion removes an
    // index expression, so this terminates.
    while (true) {
      IndexExprOp producer, consumer;
      unsigned q = 0;
      getOperation().walk([&](IndexExprOp op) {
        for (auto [i, input] : llvm::enumerate(op.getInputs())) {
          auto def = input.getDefiningOp<IndexExprOp>();
          if (def && canFuse(def, op, i)) {
            producer = def;
            consumer = op;
            q = i;
            return WalkResult::interrupt();
          }
        }
        return WalkResult::advance();
      });
      if (!consumer)
        break;
      IndexExprOp fused = fuse(producer, consumer, q);
      consumer.getResult().replaceAllUsesWith(fused.getResult());
      consumer.erase();
      producer.erase();
    }
  }
};
} // namespace
