//===- LoopStorage.cpp - Storages of system tensors -----------------------===//
//
// What a Storage holds, and how storages contain, join and transpose
// (LoopsLowering.h).
//
//===----------------------------------------------------------------------===//

#include "LoopsLowering.h"

using namespace mlir;
using namespace mlir::simit;
using namespace mlir::simit::loops;

Storage Storage::unionOf(ArrayRef<StringAttr> edgeSets, StringAttr rows,
                         StringAttr cols) {
  SmallVector<StringAttr, 2> sorted(edgeSets);
  llvm::sort(sorted, [](StringAttr a, StringAttr b) {
    return a.getValue() < b.getValue();
  });
  sorted.erase(llvm::unique(sorted), sorted.end());
  if (sorted.size() == 1)
    return pattern(sorted.front(), rows, cols);
  Storage result{Kind::Union, nullptr, rows, cols};
  result.members = std::move(sorted);
  return result;
}

SmallVector<StringAttr, 2> Storage::patternSets() const {
  if (kind == Kind::Pattern)
    return {edges};
  return members;
}

bool Storage::contains(const Storage &o) const {
  if (*this == o)
    return true;
  // An edge pattern over (V, V) holds every diagonal block of V, and so do
  // a stencil (it always stores offset 0) and a union of patterns.
  if (o.kind == Kind::Diagonal)
    return (kind == Kind::Pattern || kind == Kind::Stencil ||
            kind == Kind::Union || kind == Kind::Product) &&
           rows == cols && rows == o.rows;
  // A union holds the patterns of its members over its sets.
  return kind == Kind::Union &&
         (o.kind == Kind::Pattern || o.kind == Kind::Union) && rows == o.rows &&
         cols == o.cols && llvm::all_of(o.patternSets(), [&](StringAttr e) {
           return llvm::is_contained(members, e);
         });
}

std::optional<Storage> mlir::simit::loops::transposedStorage(const Storage &s) {
  switch (s.kind) {
  case Storage::Kind::Dense:
  case Storage::Kind::Diagonal:
    return s;
  case Storage::Kind::Pattern:
    return Storage::pattern(s.edges, s.cols, s.rows);
  case Storage::Kind::Union:
    return Storage::unionOf(s.members, s.cols, s.rows);
  case Storage::Kind::Product:
  case Storage::Kind::Stencil:
  case Storage::Kind::Incidence:
    return std::nullopt;
  }
  llvm_unreachable("storage kind");
}

std::optional<Storage> mlir::simit::loops::joinStorages(const Storage &a,
                                                        const Storage &b) {
  if (a.contains(b))
    return a;
  if (b.contains(a))
    return b;
  // Patterns over the same sets join into their union; a diagonal joins
  // into any square one.
  auto combinable = [&](const Storage &s) {
    return s.kind == Storage::Kind::Pattern || s.kind == Storage::Kind::Union ||
           (s.kind == Storage::Kind::Diagonal && s.rows == s.cols);
  };
  if (!combinable(a) || !combinable(b) || a.rows != b.rows || a.cols != b.cols)
    return std::nullopt;
  SmallVector<StringAttr, 4> sets(a.patternSets());
  llvm::append_range(sets, b.patternSets());
  return Storage::unionOf(sets, a.rows, a.cols);
}

std::string Storage::describe() const {
  switch (kind) {
  case Kind::Dense:
    return "dense";
  case Kind::Diagonal:
    return ("diagonal of '" + rows.getValue() + "'").str();
  case Kind::Pattern:
    return ("pattern of '" + edges.getValue() + "' over ('" +
            rows.getValue() + "', '" + cols.getValue() + "')")
        .str();
  case Kind::Stencil:
    return ("stencil of grid '" + edges.getValue() + "' with " +
            Twine(offsets.size()) + " offsets")
        .str();
  case Kind::Incidence:
    return ((transposed ? "transposed incidence of '" : "incidence of '") +
            edges.getValue() + "' over ('" + rows.getValue() + "', '" +
            cols.getValue() + "')")
        .str();
  case Kind::Union: {
    std::string names;
    for (StringAttr member : members)
      names += (names.empty() ? "'" : ", '") + member.getValue().str() + "'";
    return ("union of the patterns of " + names + " over ('" +
            rows.getValue() + "', '" + cols.getValue() + "')")
        .str();
  }
  case Kind::Product:
    return ("product of matrices over ('" + rows.getValue() + "', '" +
            mid.getValue() + "') and ('" + mid.getValue() + "', '" +
            cols.getValue() + "')")
        .str();
  }
  llvm_unreachable("storage kind");
}
