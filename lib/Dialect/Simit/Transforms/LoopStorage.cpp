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

/// The names a chain is made of, in order: factors' edge sets, then mids.
static SmallVector<StringRef> chainNames(const ProductChain &chain) {
  SmallVector<StringRef> names;
  for (const SmallVector<StringAttr, 2> &factor : chain.factors) {
    for (StringAttr set : factor)
      names.push_back(set.getValue());
    names.push_back("*");
  }
  for (StringAttr mid : chain.mids)
    names.push_back(mid.getValue());
  return names;
}

bool ProductChain::operator<(const ProductChain &o) const {
  return chainNames(*this) < chainNames(o);
}

SmallVector<StringAttr, 2> Storage::patternSets() const {
  if (kind == Kind::Pattern)
    return {edges};
  return members;
}

/// The offsets of a stencil storage.
static SmallVector<SmallVector<int64_t>> offsetsOf(const Storage &s) {
  return llvm::map_to_vector(s.offsets, [](Attribute o) {
    return llvm::to_vector(cast<DenseI64ArrayAttr>(o).asArrayRef());
  });
}

/// The stencil of `grid` over `points` with `offsets`, sorted and unique as
/// the encoding keeps them.
static Storage stencilWith(StringAttr grid, StringAttr points,
                           SmallVector<SmallVector<int64_t>> offsets) {
  llvm::sort(offsets);
  offsets.erase(llvm::unique(offsets), offsets.end());
  MLIRContext *ctx = grid.getContext();
  SmallVector<Attribute> attrs = llvm::map_to_vector(
      offsets, [&](ArrayRef<int64_t> o) -> Attribute {
        return DenseI64ArrayAttr::get(ctx, o);
      });
  return Storage::stencil(grid, points, ArrayAttr::get(ctx, attrs));
}

bool Storage::contains(const Storage &o) const {
  if (*this == o)
    return true;
  if (kind == Kind::Stencil && o.kind == Kind::Stencil)
    return edges == o.edges && rows == o.rows &&
           llvm::all_of(o.offsets, [&](Attribute offset) {
             return llvm::is_contained(offsets, offset);
           });
  if (kind == Kind::DenseMatrix)
    return o.isMatrix() && rows == o.rows && cols == o.cols;
  // An edge pattern over (V, V) holds every diagonal block of V, and so do
  // a stencil (it always stores offset 0) and a union of patterns.
  if (o.kind == Kind::Diagonal)
    return (kind == Kind::Pattern || kind == Kind::Stencil ||
            kind == Kind::Union || kind == Kind::Product) &&
           rows == cols && rows == o.rows;
  // A product holds its chains; one of a single factor holds that
  // factor's patterns.
  if (kind == Kind::Product && rows == o.rows && cols == o.cols) {
    if (o.kind == Kind::Product)
      return llvm::all_of(o.chains, [&](const ProductChain &chain) {
        return llvm::is_contained(chains, chain);
      });
    if (o.kind != Kind::Pattern && o.kind != Kind::Union)
      return false;
    return llvm::any_of(chains, [&](const ProductChain &chain) {
      return chain.factors.size() == 1 &&
             llvm::all_of(o.patternSets(), [&](StringAttr e) {
               return llvm::is_contained(chain.factors.front(), e);
             });
    });
  }
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
  case Storage::Kind::DenseMatrix:
    return Storage::denseMatrix(s.cols, s.rows);
  case Storage::Kind::Stencil: {
    // The stencil of the negated offsets (storage::transpose).
    SmallVector<SmallVector<int64_t>> negated = offsetsOf(s);
    for (SmallVector<int64_t> &offset : negated)
      for (int64_t &v : offset)
        v = -v;
    return stencilWith(s.edges, s.rows, negated);
  }
  case Storage::Kind::Product:
  case Storage::Kind::Incidence:
  case Storage::Kind::Host:
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
  // Stencils of one grid join into the stencil of all their offsets.
  if (a.kind == Storage::Kind::Stencil && b.kind == Storage::Kind::Stencil &&
      a.edges == b.edges && a.rows == b.rows) {
    SmallVector<SmallVector<int64_t>> offsets = offsetsOf(a);
    llvm::append_range(offsets, offsetsOf(b));
    return stencilWith(a.edges, a.rows, offsets);
  }
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
  case Kind::DenseMatrix:
    return ("dense matrix over ('" + rows.getValue() + "', '" +
            cols.getValue() + "')")
        .str();
  case Kind::Product: {
    if (chains.size() > 1)
      return ("sum of " + Twine(chains.size()) +
              " products of matrices over ('" + rows.getValue() + "', '" +
              cols.getValue() + "')")
          .str();
    std::string over = "('" + rows.getValue().str();
    for (StringAttr mid : chains.front().mids)
      over += "', '" + mid.getValue().str();
    return "product of matrices over " + over + "', '" +
           cols.getValue().str() + "')";
  }
  case Kind::Host:
    if (edges)
      return ("matrix returned by host function '" + edges.getValue() + "'")
          .str();
    return "pattern built at run time (" + runtimeEncoding.str() + ")";
  }
  llvm_unreachable("storage kind");
}

namespace {
/// Reads encodings into the loop lowering's storages.
struct EncodingReader {
  const DenseMap<StringAttr, SetType> &sets;

  /// The endpoint set at `position` of edge set `edges`.
  StringAttr endpointSet(StringAttr edges, int64_t position) {
    SetType set = sets.lookup(edges);
    if (!set || position < 0 ||
        position >= static_cast<int64_t>(set.getCardinality()))
      return nullptr;
    return set.getEndpoint(position);
  }

  /// The column set of a matrix stored as `e` (its row set with
  /// `rowsOf`); null when the encoding does not say.
  StringAttr colSet(StorageAttr e, bool rowsOf = false) {
    switch (e.getKind()) {
    case StorageKind::Diag:
      return e.getSet();
    case StorageKind::Pattern: {
      ArrayRef<int64_t> positions = rowsOf ? e.getRows() : e.getCols();
      return positions.empty() ? nullptr
                               : endpointSet(e.getSet(), positions.front());
    }
    case StorageKind::Incidence:
      return rowsOf ? e.getSet()
                    : (e.getCols().empty()
                           ? nullptr
                           : endpointSet(e.getSet(), e.getCols().front()));
    case StorageKind::Transpose:
      return colSet(e.getOperand(), !rowsOf);
    case StorageKind::Union:
    case StorageKind::LowRank:
      return colSet(e.getMember(0), rowsOf);
    case StorageKind::Product:
      return colSet(e.getMember(rowsOf ? 0 : e.getMembers().size() - 1),
                    rowsOf);
    default:
      return nullptr;
    }
  }

  /// The edge sets of a pattern, a union of patterns or their transposes
  /// (whose pattern over (C, R) is the same edges' endpoint pairs,
  /// swapped); none for other encodings.
  std::optional<SmallVector<StringAttr, 2>> patternSets(StorageAttr e) {
    switch (e.getKind()) {
    case StorageKind::Pattern:
      return SmallVector<StringAttr, 2>{e.getSet()};
    case StorageKind::Transpose:
      return patternSets(e.getOperand());
    case StorageKind::Union: {
      SmallVector<StringAttr, 2> all;
      for (unsigned i = 0, n = e.getMembers().size(); i < n; ++i) {
        // A diagonal member is held by any square pattern.
        if (e.getMember(i).getKind() == StorageKind::Diag)
          continue;
        std::optional<SmallVector<StringAttr, 2>> part =
            patternSets(e.getMember(i));
        if (!part)
          return std::nullopt;
        llvm::append_range(all, *part);
      }
      if (all.empty())
        return std::nullopt;
      return all;
    }
    default:
      return std::nullopt;
    }
  }

  /// The edge sets of a product's factor: patternSets, or the edge set of
  /// an incidence or its transpose (the runtime reads the pattern of E over
  /// (E, V) or (V, E) as the incidence's).
  std::optional<SmallVector<StringAttr, 2>> factorSets(StorageAttr e) {
    StorageAttr inner =
        e.getKind() == StorageKind::Transpose ? e.getOperand() : e;
    if (inner.getKind() == StorageKind::Incidence)
      return SmallVector<StringAttr, 2>{inner.getSet()};
    return patternSets(e);
  }

  /// The chain of factors of a product encoding over (rows, cols).
  std::optional<ProductChain> productChain(StorageAttr e, StringAttr rows,
                                           StringAttr cols) {
    ProductChain chain;
    unsigned n = e.getMembers().size();
    for (unsigned i = 0; i + 1 < n; ++i) {
      StringAttr mid = colSet(e.getMember(i));
      if (!mid)
        return std::nullopt;
      chain.mids.push_back(mid);
    }
    for (unsigned i = 0; i < n; ++i) {
      std::optional<SmallVector<StringAttr, 2>> sets =
          factorSets(e.getMember(i));
      if (!sets)
        return std::nullopt;
      StringAttr from = i == 0 ? rows : chain.mids[i - 1];
      StringAttr to = i + 1 == n ? cols : chain.mids[i];
      chain.factors.push_back(Storage::unionOf(*sets, from, to).patternSets());
    }
    return chain;
  }

  /// A union with products among its members: a product storage of their
  /// chains, each pattern, union or incidence member a chain of one factor
  /// (a square chain holds the diagonal, so a diagonal member adds nothing
  /// there).
  std::optional<Storage> sumOfProducts(StorageAttr e, StringAttr rows,
                                       StringAttr cols) {
    Storage sum{Storage::Kind::Product, nullptr, rows, cols};
    for (unsigned i = 0, n = e.getMembers().size(); i < n; ++i) {
      StorageAttr member = e.getMember(i);
      if (member.getKind() == StorageKind::Diag && rows == cols)
        continue;
      std::optional<Storage> part = read(member, rows, cols);
      if (!part)
        return std::nullopt;
      if (part->kind == Storage::Kind::Product) {
        llvm::append_range(sum.chains, part->chains);
      } else if (part->hasGatherMaps() ||
                 part->kind == Storage::Kind::Incidence) {
        // The runtime reads an edge set E over (E, V) or (V, E) as the
        // pattern of its incidence or of the transpose.
        ProductChain single;
        single.factors.push_back(part->kind == Storage::Kind::Incidence
                                     ? SmallVector<StringAttr, 2>{part->edges}
                                     : part->patternSets());
        sum.chains.push_back(std::move(single));
      } else {
        return std::nullopt;
      }
    }
    llvm::sort(sum.chains);
    sum.chains.erase(llvm::unique(sum.chains), sum.chains.end());
    if (sum.chains.empty())
      return std::nullopt;
    return sum;
  }

  /// A pattern built at run time: a union of members that are all stored
  /// BCSR, block diagonal or as a stencil (its pattern comes from theirs,
  /// a stencil's through its bind-time BCSR pattern), the transpose
  /// of a BCSR one, or any product (the product's comes from its
  /// operands').
  std::optional<Storage> runtimePattern(StorageAttr e, StringAttr rows,
                                        StringAttr cols) {
    if (e.getKind() == StorageKind::Union)
      for (unsigned i = 0, n = e.getMembers().size(); i < n; ++i) {
        std::optional<Storage> member = read(e.getMember(i), rows, cols);
        if (!member || !hasBCSRView(*member) ||
            member->kind == Storage::Kind::DenseMatrix)
          return std::nullopt;
      }
    if (e.getKind() == StorageKind::Transpose) {
      std::optional<Storage> inner = read(e.getOperand(), cols, rows);
      if (!inner || !inner->isBCSR())
        return std::nullopt;
    }
    if (e.getKind() != StorageKind::Host && e.getKind() != StorageKind::Union &&
        e.getKind() != StorageKind::Product &&
        e.getKind() != StorageKind::Transpose)
      return std::nullopt;
    return Storage::runtimePattern(e, rows, cols);
  }

  /// Whether a union or product has a stencil among its members, whose
  /// pattern the runtime then combines with the others'.
  static bool hasStencilMember(StorageAttr e) {
    return llvm::any_of(e.getMembers(), [](Attribute member) {
      return cast<StorageAttr>(member).getKind() == StorageKind::Stencil;
    });
  }

  std::optional<Storage> read(StorageAttr e, StringAttr rows,
                              StringAttr cols) {
    switch (e.getKind()) {
    case StorageKind::Diag:
      return Storage::diagonal(e.getSet());
    case StorageKind::Pattern:
      // Runtime patterns hold every endpoint pair of the rows' and columns'
      // sets, which is what simit-assign-storage derives from set types.
      return Storage::pattern(e.getSet(), rows, cols);
    case StorageKind::Stencil: {
      SmallVector<Attribute> offsets(e.getOffsets().begin(),
                                     e.getOffsets().end());
      return Storage::stencil(e.getSet(), rows,
                              ArrayAttr::get(e.getContext(), offsets));
    }
    case StorageKind::Incidence: {
      // The layout holds a block per endpoint position in `cols` of each
      // edge.
      SetType set = sets.lookup(e.getSet());
      if (!set || e.getCols().empty())
        return std::nullopt;
      return Storage::incidence(e.getSet(), cols, set.getCardinality(),
                                e.getCols());
    }
    case StorageKind::Transpose: {
      StorageAttr inner = e.getOperand();
      // A host function's matrix transposed is stored on its transposed
      // pattern, built at run time.
      if (storage::findHost(inner))
        return runtimePattern(e, rows, cols);
      if (inner.getKind() == StorageKind::Incidence) {
        std::optional<Storage> stored = read(inner, cols, rows);
        if (!stored)
          return std::nullopt;
        return Storage::incidenceTransposed(*stored);
      }
      std::optional<Storage> stored = read(inner, cols, rows);
      return stored ? transposedStorage(*stored) : std::nullopt;
    }
    case StorageKind::Union: {
      // With a host function's matrix in it, the pattern is built at run
      // time from the members' (all BCSR).
      if (storage::findHost(e))
        return runtimePattern(e, rows, cols);
      // A square pattern, union, product or stencil stores the diagonal
      // (runtime patterns over one set hold every (r, r)): a diagonal
      // member next to one other member adds nothing.
      if (e.getMembers().size() == 2 && rows == cols) {
        for (unsigned d = 0; d < 2; ++d) {
          if (e.getMember(d).getKind() != StorageKind::Diag)
            continue;
          std::optional<Storage> other = read(e.getMember(1 - d), rows, cols);
          if (other && other->contains(Storage::diagonal(rows)))
            return other;
        }
      }
      if (std::optional<SmallVector<StringAttr, 2>> members = patternSets(e))
        return Storage::unionOf(*members, rows, cols);
      // A stencil next to other patterns: their union is built at run
      // time from the stencil's bind-time pattern and theirs.
      if (hasStencilMember(e))
        return runtimePattern(e, rows, cols);
      return sumOfProducts(e, rows, cols);
    }
    case StorageKind::Product: {
      // A stencil factor next to others: the product's pattern is built at
      // run time from the stencil's bind-time BCSR pattern and theirs.
      if (storage::findHost(e) || hasStencilMember(e))
        return runtimePattern(e, rows, cols);
      std::optional<ProductChain> chain = productChain(e, rows, cols);
      if (!chain)
        return std::nullopt;
      Storage product{Storage::Kind::Product, nullptr, rows, cols};
      product.chains.push_back(std::move(*chain));
      return product;
    }
    case StorageKind::Dense:
      return Storage::denseMatrix(rows, cols);
    case StorageKind::Empty:
      // A matrix nothing writes (a variable only declared) is zero; it is
      // stored zero-filled in the smallest layout that needs no pattern.
      return rows == cols ? Storage::diagonal(rows)
                          : Storage::denseMatrix(rows, cols);
    case StorageKind::Host:
      return Storage::runtimePattern(e, rows, cols);
    case StorageKind::LowRank:
      return std::nullopt;
    }
    llvm_unreachable("storage kind");
  }
};
} // namespace

std::optional<Storage>
mlir::simit::loops::storageOfEncoding(StorageAttr encoding, StringAttr rows,
                                      StringAttr cols,
                                      const DenseMap<StringAttr, SetType> &sets) {
  return EncodingReader{sets}.read(encoding, rows, cols);
}
