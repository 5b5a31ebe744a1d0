//===- SimitStorage.cpp - Storage encodings of system matrices ------------===//
//
// `#simit.storage`: its syntax, its verifier (which accepts canonical
// encodings only), the canonicalising builders, containment and join.
//
//===----------------------------------------------------------------------===//

#include "simit/Dialect/Simit/IR/SimitStorage.h"

#include "mlir/IR/DialectImplementation.h"
#include "llvm/ADT/MapVector.h"
#include "llvm/ADT/STLExtras.h"

#include <functional>

using namespace mlir;
using namespace mlir::simit;

//===----------------------------------------------------------------------===//
// Syntax
//===----------------------------------------------------------------------===//

static void printPositions(raw_ostream &os, ArrayRef<int64_t> positions) {
  os << "[";
  llvm::interleaveComma(positions, os);
  os << "]";
}

void StorageAttr::printBody(raw_ostream &os) const {
  os << stringifyStorageKind(getKind());
  switch (getKind()) {
  case StorageKind::Dense:
  case StorageKind::Empty:
    return;
  case StorageKind::Diag:
    os << "(\"" << getSet().getValue() << "\")";
    return;
  case StorageKind::Pattern:
    os << "(\"" << getSet().getValue() << "\", rows ";
    printPositions(os, getRows());
    os << ", cols ";
    printPositions(os, getCols());
    os << ")";
    return;
  case StorageKind::Incidence:
    os << "(\"" << getSet().getValue() << "\", cols ";
    printPositions(os, getCols());
    os << ")";
    return;
  case StorageKind::Stencil:
    os << "(\"" << getSet().getValue() << "\", [";
    llvm::interleaveComma(getOffsets(), os, [&](DenseI64ArrayAttr offset) {
      printPositions(os, offset.asArrayRef());
    });
    os << "])";
    return;
  case StorageKind::LowRank:
    os << "(";
    getOperand().printBody(os);
    os << ", " << getRank() << ")";
    return;
  case StorageKind::Host:
    os << "(\"" << getSet().getValue() << "\", " << getCall() << ")";
    return;
  case StorageKind::Transpose:
  case StorageKind::Union:
  case StorageKind::Product:
    os << "(";
    llvm::interleaveComma(getMembers(), os, [&](Attribute member) {
      cast<StorageAttr>(member).printBody(os);
    });
    os << ")";
    return;
  }
  llvm_unreachable("storage kind");
}

std::string StorageAttr::str() const {
  std::string text;
  llvm::raw_string_ostream os(text);
  printBody(os);
  return text;
}

void StorageAttr::print(AsmPrinter &printer) const {
  printer << "<";
  printBody(printer.getStream());
  printer << ">";
}

static ParseResult parsePositions(AsmParser &parser,
                                  SmallVectorImpl<int64_t> &positions) {
  return parser.parseCommaSeparatedList(
      AsmParser::Delimiter::Square, [&]() -> ParseResult {
        return parser.parseInteger(positions.emplace_back());
      });
}

/// Parses an encoding body (`diag("points")`, `union(...)`, ...); the
/// result is verified but not canonicalised.
static StorageAttr parseBody(AsmParser &parser) {
  MLIRContext *ctx = parser.getContext();
  SMLoc loc = parser.getCurrentLocation();
  StringRef keyword;
  if (parser.parseKeyword(&keyword))
    return {};
  std::optional<StorageKind> kind = symbolizeStorageKind(keyword);
  if (!kind) {
    parser.emitError(loc, "unknown storage kind '") << keyword << "'";
    return {};
  }
  StringAttr set;
  SmallVector<int64_t> rows, cols;
  SmallVector<DenseI64ArrayAttr> offsets;
  SmallVector<Attribute> members;
  int64_t rank = 0, call = 0;
  auto parseSet = [&]() -> ParseResult {
    std::string name;
    if (parser.parseString(&name))
      return failure();
    set = StringAttr::get(ctx, name);
    return success();
  };
  auto parseMember = [&]() -> ParseResult {
    StorageAttr member = parseBody(parser);
    if (!member)
      return failure();
    members.push_back(member);
    return success();
  };
  ParseResult result = success();
  switch (*kind) {
  case StorageKind::Dense:
  case StorageKind::Empty:
    break;
  case StorageKind::Diag:
    result = failure(parser.parseLParen() || parseSet() ||
                     parser.parseRParen());
    break;
  case StorageKind::Pattern:
    result = failure(parser.parseLParen() || parseSet() ||
                     parser.parseComma() || parser.parseKeyword("rows") ||
                     parsePositions(parser, rows) || parser.parseComma() ||
                     parser.parseKeyword("cols") ||
                     parsePositions(parser, cols) || parser.parseRParen());
    break;
  case StorageKind::Incidence:
    result = failure(parser.parseLParen() || parseSet() ||
                     parser.parseComma() || parser.parseKeyword("cols") ||
                     parsePositions(parser, cols) || parser.parseRParen());
    break;
  case StorageKind::Stencil:
    result = failure(
        parser.parseLParen() || parseSet() || parser.parseComma() ||
        parser.parseCommaSeparatedList(
            AsmParser::Delimiter::Square,
            [&]() -> ParseResult {
              SmallVector<int64_t> offset;
              if (parsePositions(parser, offset))
                return failure();
              offsets.push_back(DenseI64ArrayAttr::get(ctx, offset));
              return success();
            }) ||
        parser.parseRParen());
    break;
  case StorageKind::LowRank:
    result = failure(parser.parseLParen() || parseMember() ||
                     parser.parseComma() || parser.parseInteger(rank) ||
                     parser.parseRParen());
    break;
  case StorageKind::Host:
    result =
        failure(parser.parseLParen() || parseSet() || parser.parseComma() ||
                parser.parseInteger(call) || parser.parseRParen());
    break;
  case StorageKind::Transpose:
  case StorageKind::Union:
  case StorageKind::Product:
    result = parser.parseCommaSeparatedList(AsmParser::Delimiter::Paren,
                                            parseMember);
    break;
  }
  if (failed(result))
    return {};
  return StorageAttr::getChecked([&] { return parser.emitError(loc); }, ctx,
                                 *kind, set, ArrayRef<int64_t>(rows),
                                 ArrayRef<int64_t>(cols),
                                 ArrayRef<DenseI64ArrayAttr>(offsets),
                                 ArrayRef<Attribute>(members), rank, call);
}

Attribute StorageAttr::parse(AsmParser &parser, Type) {
  if (parser.parseLess())
    return {};
  StorageAttr body = parseBody(parser);
  if (!body || parser.parseGreater())
    return {};
  return body;
}

//===----------------------------------------------------------------------===//
// Verifier: structure and canonical form
//===----------------------------------------------------------------------===//

static bool isSortedUnique(ArrayRef<int64_t> values) {
  return llvm::is_sorted(values) &&
         std::adjacent_find(values.begin(), values.end()) == values.end();
}

/// The order of union members: by printed body, which is deterministic.
static bool precedes(StorageAttr a, StorageAttr b) { return a.str() < b.str(); }

static bool isTransposedIncidence(StorageAttr x) {
  return x.getKind() == StorageKind::Transpose &&
         x.getOperand().getKind() == StorageKind::Incidence;
}

/// Whether factors `a` then `b` compose to a pattern (product canonicalises
/// them into one).
static bool composesToPattern(StorageAttr a, StorageAttr b) {
  return isTransposedIncidence(a) && b.getKind() == StorageKind::Incidence &&
         a.getOperand().getSet() == b.getSet();
}

LogicalResult
StorageAttr::verify(function_ref<InFlightDiagnostic()> emitError,
                    StorageKind kind, StringAttr set, ArrayRef<int64_t> rows,
                    ArrayRef<int64_t> cols, ArrayRef<DenseI64ArrayAttr> offsets,
                    ArrayRef<Attribute> members, int64_t rank, int64_t call) {
  StringRef name = stringifyStorageKind(kind);
  bool wantsSet = kind == StorageKind::Diag || kind == StorageKind::Pattern ||
                  kind == StorageKind::Incidence ||
                  kind == StorageKind::Stencil || kind == StorageKind::Host;
  if (wantsSet != static_cast<bool>(set) || (set && set.getValue().empty()))
    return emitError() << "'" << name << "' "
                       << (wantsSet ? "needs a set name" : "takes no set");
  if (!rows.empty() && kind != StorageKind::Pattern)
    return emitError() << "'" << name << "' takes no row positions";
  if (!cols.empty() && kind != StorageKind::Pattern &&
      kind != StorageKind::Incidence)
    return emitError() << "'" << name << "' takes no column positions";
  if (!offsets.empty() && kind != StorageKind::Stencil)
    return emitError() << "'" << name << "' takes no offsets";
  if (rank != 0 && kind != StorageKind::LowRank)
    return emitError() << "'" << name << "' takes no rank";
  if (call != 0 && kind != StorageKind::Host)
    return emitError() << "'" << name << "' takes no call number";
  for (Attribute member : members)
    if (!isa<StorageAttr>(member))
      return emitError() << "members of '" << name
                         << "' must be storage encodings";
  auto member = [&](unsigned i) { return cast<StorageAttr>(members[i]); };
  auto checkPositions = [&](ArrayRef<int64_t> positions,
                            StringRef what) -> LogicalResult {
    if (positions.empty() || positions.front() < 0 ||
        !isSortedUnique(positions))
      return emitError() << "'" << name << "' " << what
                         << " positions must be non-negative, sorted, unique "
                            "and not empty";
    return success();
  };

  switch (kind) {
  case StorageKind::Dense:
  case StorageKind::Empty:
  case StorageKind::Diag:
    if (!members.empty())
      return emitError() << "'" << name << "' has no members";
    return success();
  case StorageKind::Host:
    if (!members.empty())
      return emitError() << "'host' has no members";
    if (call < 0)
      return emitError() << "'host' needs a non-negative call number";
    return success();
  case StorageKind::Pattern:
    if (!members.empty())
      return emitError() << "'pattern' has no members";
    return failure(failed(checkPositions(rows, "row")) ||
                   failed(checkPositions(cols, "column")));
  case StorageKind::Incidence:
    if (!members.empty())
      return emitError() << "'incidence' has no members";
    return checkPositions(cols, "column");
  case StorageKind::Stencil: {
    if (!members.empty())
      return emitError() << "'stencil' has no members";
    if (offsets.empty() || offsets.front().empty())
      return emitError() << "'stencil' needs offsets of a positive rank";
    size_t gridRank = offsets.front().size();
    if (llvm::any_of(offsets, [&](DenseI64ArrayAttr o) {
          return static_cast<size_t>(o.size()) != gridRank;
        }))
      return emitError() << "'stencil' offsets must all have rank "
                         << gridRank;
    auto isSmaller = [](DenseI64ArrayAttr a, DenseI64ArrayAttr b) {
      return a.asArrayRef() < b.asArrayRef();
    };
    for (auto [a, b] : llvm::zip(offsets, offsets.drop_front()))
      if (!isSmaller(a, b))
        return emitError() << "'stencil' offsets must be sorted and unique";
    if (llvm::none_of(offsets, [](DenseI64ArrayAttr o) {
          return llvm::all_of(o.asArrayRef(), [](int64_t c) { return c == 0; });
        }))
      return emitError() << "'stencil' offsets must hold offset 0";
    return success();
  }
  case StorageKind::Transpose: {
    if (members.size() != 1)
      return emitError() << "'transpose' has one member";
    StorageKind inner = member(0).getKind();
    if (inner == StorageKind::Transpose || inner == StorageKind::Diag ||
        inner == StorageKind::Empty || inner == StorageKind::LowRank ||
        inner == StorageKind::Product)
      return emitError() << "'transpose(" << member(0).str()
                         << ")' is not canonical";
    return success();
  }
  case StorageKind::LowRank:
    if (members.size() != 1)
      return emitError() << "'lowrank' has one member";
    if (rank <= 0)
      return emitError() << "'lowrank' needs a positive rank";
    if (member(0).getKind() == StorageKind::LowRank)
      return emitError() << "'lowrank' of 'lowrank' is not canonical";
    return success();
  case StorageKind::Union: {
    if (members.size() < 2)
      return emitError() << "'union' needs two members or more";
    for (unsigned i = 0; i < members.size(); ++i) {
      StorageKind k = member(i).getKind();
      if (k == StorageKind::Union || k == StorageKind::Empty ||
          k == StorageKind::Dense || k == StorageKind::LowRank)
        return emitError() << "a union member cannot be '"
                           << stringifyStorageKind(k) << "'";
      if (i > 0 && !precedes(member(i - 1), member(i)))
        return emitError() << "union members must be sorted and unique";
      for (unsigned j = 0; j < members.size(); ++j) {
        if (i == j)
          continue;
        if (k == StorageKind::Stencil &&
            member(j).getKind() == StorageKind::Stencil &&
            member(i).getSet() == member(j).getSet())
          return emitError() << "a union holds one stencil per grid";
        if (storage::contains(member(j), member(i)))
          return emitError() << "union member '" << member(i).str()
                             << "' is contained in '" << member(j).str()
                             << "'";
      }
    }
    return success();
  }
  case StorageKind::Product: {
    if (members.size() < 2)
      return emitError() << "'product' needs two factors or more";
    for (unsigned i = 0; i < members.size(); ++i) {
      StorageKind k = member(i).getKind();
      if (k == StorageKind::Product || k == StorageKind::Empty ||
          k == StorageKind::Diag || k == StorageKind::LowRank)
        return emitError() << "a product factor cannot be '"
                           << stringifyStorageKind(k) << "'";
      if (i > 0 && composesToPattern(member(i - 1), member(i)))
        return emitError() << "the factors '" << member(i - 1).str()
                           << "', '" << member(i).str()
                           << "' compose to a pattern";
    }
    return success();
  }
  }
  llvm_unreachable("storage kind");
}

//===----------------------------------------------------------------------===//
// Builders
//===----------------------------------------------------------------------===//

static StorageAttr make(MLIRContext *ctx, StorageKind kind, StringAttr set = {},
                        ArrayRef<int64_t> rows = {},
                        ArrayRef<int64_t> cols = {},
                        ArrayRef<DenseI64ArrayAttr> offsets = {},
                        ArrayRef<StorageAttr> members = {}, int64_t rank = 0,
                        int64_t call = 0) {
  SmallVector<Attribute> memberAttrs(members.begin(), members.end());
  return StorageAttr::get(ctx, kind, set, rows, cols, offsets,
                          ArrayRef<Attribute>(memberAttrs), rank, call);
}

static SmallVector<int64_t> sortedUnique(ArrayRef<int64_t> values) {
  SmallVector<int64_t> result(values);
  llvm::sort(result);
  result.erase(llvm::unique(result), result.end());
  return result;
}

StorageAttr storage::dense(MLIRContext *ctx) {
  return make(ctx, StorageKind::Dense);
}

StorageAttr storage::empty(MLIRContext *ctx) {
  return make(ctx, StorageKind::Empty);
}

StorageAttr storage::diag(StringAttr set) {
  return make(set.getContext(), StorageKind::Diag, set);
}

StorageAttr storage::pattern(StringAttr edges, ArrayRef<int64_t> rows,
                             ArrayRef<int64_t> cols) {
  return make(edges.getContext(), StorageKind::Pattern, edges,
              sortedUnique(rows), sortedUnique(cols));
}

StorageAttr storage::incidence(StringAttr edges, ArrayRef<int64_t> cols) {
  return make(edges.getContext(), StorageKind::Incidence, edges, {},
              sortedUnique(cols));
}

StorageAttr storage::stencil(StringAttr grid,
                             ArrayRef<SmallVector<int64_t>> offsets) {
  assert(!offsets.empty() && "a stencil needs the grid rank");
  SmallVector<SmallVector<int64_t>> sorted(offsets);
  sorted.emplace_back(offsets.front().size(), 0);
  llvm::sort(sorted);
  sorted.erase(llvm::unique(sorted), sorted.end());
  MLIRContext *ctx = grid.getContext();
  SmallVector<DenseI64ArrayAttr> attrs = llvm::map_to_vector(
      sorted, [&](ArrayRef<int64_t> o) { return DenseI64ArrayAttr::get(ctx, o); });
  return make(ctx, StorageKind::Stencil, grid, {}, {}, attrs);
}

StorageAttr storage::host(StringAttr function, int64_t call) {
  return make(function.getContext(), StorageKind::Host, function, {}, {}, {},
              {}, 0, call);
}

StorageAttr storage::transpose(StorageAttr x) {
  switch (x.getKind()) {
  case StorageKind::Transpose:
    return x.getOperand();
  case StorageKind::Diag:
  case StorageKind::Empty:
  case StorageKind::Dense:
    return x;
  case StorageKind::LowRank:
    return lowRank(transpose(x.getOperand()), x.getRank());
  case StorageKind::Stencil: {
    // Block (r, r + o) of a periodic stencil is (c - o, c) of its
    // transpose: the stencil of the negated offsets.
    SmallVector<SmallVector<int64_t>> negated;
    for (DenseI64ArrayAttr o : x.getOffsets())
      negated.push_back(llvm::map_to_vector(
          o.asArrayRef(), [](int64_t v) { return -v; }));
    return stencil(x.getSet(), negated);
  }
  case StorageKind::Product: {
    // (F1 ... Fk)' = Fk' ... F1': a product pattern of its own, built at
    // bind time like any other (the union over associations transposes
    // into the union over the reversed associations).
    SmallVector<StorageAttr> reversed;
    for (unsigned i = x.getMembers().size(); i-- > 0;)
      reversed.push_back(transpose(x.getMember(i)));
    return product(reversed);
  }
  default:
    return make(x.getContext(), StorageKind::Transpose, {}, {}, {}, {}, {x});
  }
}

StorageAttr storage::lowRank(StorageAttr x, int64_t rank) {
  assert(rank >= 0 && "a negative number of rank-one terms");
  if (rank == 0)
    return x;
  if (x.getKind() == StorageKind::LowRank)
    return lowRank(x.getOperand(), x.getRank() + rank);
  return make(x.getContext(), StorageKind::LowRank, {}, {}, {}, {}, {x},
              rank);
}

StorageAttr storage::unionOf(ArrayRef<StorageAttr> members) {
  assert(!members.empty() && "a union needs its context from a member");
  MLIRContext *ctx = members.front().getContext();
  // Flatten, hoisting rank-one terms (a union stores the blocks of the
  // largest) and merging the offsets of stencils of one grid.
  SmallVector<StorageAttr> flat;
  int64_t rank = 0;
  llvm::MapVector<StringAttr, SmallVector<SmallVector<int64_t>>> stencils;
  std::function<void(StorageAttr)> add = [&](StorageAttr m) {
    switch (m.getKind()) {
    case StorageKind::Union:
      for (unsigned i = 0, e = m.getMembers().size(); i < e; ++i)
        add(m.getMember(i));
      return;
    case StorageKind::LowRank:
      rank = std::max(rank, m.getRank());
      add(m.getOperand());
      return;
    case StorageKind::Empty:
      return;
    case StorageKind::Stencil:
      for (DenseI64ArrayAttr o : m.getOffsets())
        stencils[m.getSet()].push_back(llvm::to_vector(o.asArrayRef()));
      return;
    default:
      flat.push_back(m);
    }
  };
  for (StorageAttr m : members)
    add(m);
  for (auto &[grid, offsets] : stencils)
    flat.push_back(stencil(grid, offsets));
  StorageAttr result;
  if (llvm::any_of(flat, [](StorageAttr m) {
        return m.getKind() == StorageKind::Dense;
      })) {
    result = dense(ctx);
  } else {
    llvm::sort(flat, precedes);
    flat.erase(llvm::unique(flat), flat.end());
    SmallVector<StorageAttr> kept;
    for (StorageAttr m : flat)
      if (llvm::none_of(flat, [&](StorageAttr other) {
            return other != m && contains(other, m);
          }))
        kept.push_back(m);
    if (kept.empty())
      result = empty(ctx);
    else if (kept.size() == 1)
      result = kept.front();
    else
      result = make(ctx, StorageKind::Union, {}, {}, {}, {}, kept);
  }
  return lowRank(result, rank);
}

StorageAttr storage::product(ArrayRef<StorageAttr> factors) {
  assert(!factors.empty() && "a product needs its context from a factor");
  MLIRContext *ctx = factors.front().getContext();
  // Flatten; rank-one terms of any factor stay rank-one terms of the product
  // (u v' Y = u (Y' v)'), so the ranks add up outside it.
  SmallVector<StorageAttr> flat;
  int64_t rank = 0;
  std::function<void(StorageAttr)> add = [&](StorageAttr f) {
    if (f.getKind() == StorageKind::Product) {
      for (unsigned i = 0, e = f.getMembers().size(); i < e; ++i)
        add(f.getMember(i));
    } else if (f.getKind() == StorageKind::LowRank) {
      rank += f.getRank();
      add(f.getOperand());
    } else {
      flat.push_back(f);
    }
  };
  for (StorageAttr f : factors)
    add(f);
  if (llvm::any_of(flat, [](StorageAttr f) {
        return f.getKind() == StorageKind::Empty;
      }))
    return lowRank(empty(ctx), rank);
  // A dense factor fills in every block (A^-1 B times anything).
  if (llvm::any_of(flat, [](StorageAttr f) {
        return f.getKind() == StorageKind::Dense;
      }))
    return lowRank(dense(ctx), rank);
  SmallVector<StorageAttr> kept;
  for (StorageAttr f : flat) {
    if (f.getKind() == StorageKind::Diag)
      continue;
    if (!kept.empty() && composesToPattern(kept.back(), f)) {
      StorageAttr rows = kept.pop_back_val().getOperand();
      f = pattern(rows.getSet(), rows.getCols(), f.getCols());
    }
    // Stencils of one grid compose into the stencil of the sums of their
    // offsets (periodic: (r + a) + b = r + (a + b)).
    if (!kept.empty() && kept.back().getKind() == StorageKind::Stencil &&
        f.getKind() == StorageKind::Stencil &&
        kept.back().getSet() == f.getSet()) {
      SmallVector<SmallVector<int64_t>> sums;
      for (DenseI64ArrayAttr a : kept.pop_back_val().getOffsets())
        for (DenseI64ArrayAttr b : f.getOffsets())
          sums.push_back(llvm::to_vector(llvm::map_range(
              llvm::zip_equal(a.asArrayRef(), b.asArrayRef()),
              [](auto ab) { return std::get<0>(ab) + std::get<1>(ab); })));
      f = stencil(f.getSet(), sums);
    }
    kept.push_back(f);
  }
  StorageAttr result;
  if (kept.empty())
    result = flat.front(); // Every factor is the diagonal of one set.
  else if (kept.size() == 1)
    result = kept.front();
  else
    result = make(ctx, StorageKind::Product, {}, {}, {}, {}, kept);
  return lowRank(result, rank);
}

//===----------------------------------------------------------------------===//
// Containment and join
//===----------------------------------------------------------------------===//

static bool isSubset(ArrayRef<int64_t> inner, ArrayRef<int64_t> outer) {
  return llvm::all_of(inner,
                      [&](int64_t v) { return llvm::is_contained(outer, v); });
}

bool storage::contains(StorageAttr outer, StorageAttr inner) {
  if (outer == inner || inner.getKind() == StorageKind::Empty ||
      outer.getKind() == StorageKind::Dense)
    return true;
  StorageKind o = outer.getKind(), i = inner.getKind();
  if (i == StorageKind::Union)
    return llvm::all_of(inner.getMembers(), [&](Attribute m) {
      return contains(outer, cast<StorageAttr>(m));
    });
  if (i == StorageKind::LowRank)
    return o == StorageKind::LowRank && outer.getRank() >= inner.getRank() &&
           contains(outer.getOperand(), inner.getOperand());
  switch (o) {
  case StorageKind::Union:
    return llvm::any_of(outer.getMembers(), [&](Attribute m) {
      return contains(cast<StorageAttr>(m), inner);
    });
  case StorageKind::LowRank:
    return contains(outer.getOperand(), inner);
  case StorageKind::Transpose:
    // transpose(diag) is diag.
    return contains(outer.getOperand(), transpose(inner));
  case StorageKind::Pattern:
    // Over the same sets, a diagonal means a square pattern.
    if (i == StorageKind::Diag)
      return true;
    return i == StorageKind::Pattern && inner.getSet() == outer.getSet() &&
           isSubset(inner.getRows(), outer.getRows()) &&
           isSubset(inner.getCols(), outer.getCols());
  case StorageKind::Stencil:
    if (i == StorageKind::Diag)
      return true;
    return i == StorageKind::Stencil && inner.getSet() == outer.getSet() &&
           llvm::all_of(inner.getOffsets(), [&](DenseI64ArrayAttr offset) {
             return llvm::is_contained(outer.getOffsets(), offset);
           });
  case StorageKind::Incidence:
    return i == StorageKind::Incidence && inner.getSet() == outer.getSet() &&
           isSubset(inner.getCols(), outer.getCols());
  default:
    return false;
  }
}

StorageAttr storage::findHost(StorageAttr x) {
  if (x.getKind() == StorageKind::Host)
    return x;
  for (unsigned i = 0, e = x.getMembers().size(); i < e; ++i)
    if (StorageAttr host = findHost(x.getMember(i)))
      return host;
  return {};
}

StorageAttr storage::join(StorageAttr a, StorageAttr b) {
  if (contains(a, b))
    return a;
  if (contains(b, a))
    return b;
  return unionOf({a, b});
}

//===----------------------------------------------------------------------===//
// Types
//===----------------------------------------------------------------------===//

StorageAttr mlir::simit::getStorage(Type type) {
  auto tensor = dyn_cast<SystemTensorType>(type);
  return tensor ? tensor.getEncoding() : StorageAttr();
}

Type mlir::simit::withStorage(Type type, StorageAttr encoding) {
  return cast<SystemTensorType>(type).withEncoding(encoding);
}

bool mlir::simit::isSameUpToStorage(Type a, Type b) {
  if (a == b)
    return true;
  auto ta = dyn_cast<SystemTensorType>(a), tb = dyn_cast<SystemTensorType>(b);
  return ta && tb && ta.withEncoding({}) == tb.withEncoding({});
}
