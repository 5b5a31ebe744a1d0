//===--- BindingKind.h - Kinds of arguments of lowered functions -*- C++ -*-===//
//
// Every argument of a lowered exported function after its own parameters is
// a binding: data of the scene the function touches (a set's size, a field,
// a sparsity pattern's index arrays, ...). The loop lowering records each in
// the function's `simit.bindings` attribute as a dictionary whose "kind" is
// one of these spellings; the engine reads them back to pass the arguments.
// One definition serves both sides. This header depends on nothing but the
// C++ standard library, so the runtime and other hosts can include it too.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_ABI_BINDINGKIND_H
#define SIMIT_ABI_BINDINGKIND_H

#include <optional>
#include <string_view>

namespace simit {
namespace abi {

/// The attributes a lowered exported function carries to the engine, on
/// its func.func and, after the conversion to LLVM, on its llvm.func:
/// one binding dictionary per argument; the function's type at the host
/// boundary (memrefs, scalars, vectors), which the LLVM signature no longer
/// shows; and how its memref arguments are passed (simit-record-host-abi).
constexpr std::string_view kBindingsAttr = "simit.bindings";
constexpr std::string_view kHostTypeAttr = "simit.host_type";
constexpr std::string_view kMemRefConventionAttr = "simit.memref_convention";
/// The declared shape of each result (empty for a scalar or a system
/// tensor), when a result is a local tensor of rank 2 or more, which the
/// lowering flattens to a vector.
constexpr std::string_view kResultShapesAttr = "simit.result_shapes";
/// The spellings of kMemRefConventionAttr: a memref passed as its exploded
/// descriptor (MLIR's default), or as a bare pointer to its data.
constexpr std::string_view kDescriptorConvention = "descriptor";
constexpr std::string_view kBarePointerConvention = "bare_pointer";

/// What one argument of a lowered function carries (docs/lowering.md,
/// "Host ABI of an entry point").
enum class BindingKind {
  SetSize,            // index: the number of elements of `set`
  GridDims,           // memref<d x i32>: the extents of grid `set`
  Field,              // memref<?x b...>: field `field` of `set`
  Endpoints,          // memref<?xc x i32>: the endpoints of edge set `set`
  PatternRowPtr,      // memref<?xi32>: BCSR row pointers of (set; rows, cols)
  PatternColIdx,      // memref<?xi32>: BCSR block columns
  PatternLocations,   // memref<?x(c*c)xi32>: per-edge block locations
  UnionRowPtr,        // memref<?xi32>: BCSR row pointers of the union of the
                      // patterns of the '+'-joined `set` over (rows, cols)
  UnionColIdx,        // memref<?xi32>: its block columns
  UnionGather,        // memref<?xi32>: per union block, its position in the
                      // pattern (or union) `part` ('~' first: read
                      // transposed), or -1
  ProductRowPtr,      // memref<?xi32>: BCSR row pointers of the product of
                      // the patterns `left*right` over (rows, mid, cols)
  ProductColIdx,      // memref<?xi32>: its block columns
  IncidenceRowPtr,    // memref<?xi32>: per row of the incidence of edge set
                      // `set` over (rows, cols) (one of them the edge set
                      // itself), its first block (simit::IncidenceView)
  IncidenceColIdx,    // memref<?xi32>: per block, its column
  IncidencePositions, // memref<?xi32>: per block, its value position
  IncidenceEndpoints, // memref<?xm x i32>: per edge of `set`, its m
                      // endpoints in `cols` (rows == set), at the
                      // positions whose endpoint set is `cols`
  StencilRowPtr,      // memref<?xi32>: BCSR row pointers of the stencil of
                      // grid `set` with `offsets` (simit::StencilPattern)
  StencilColIdx,      // memref<?xi32>: its block columns
  StencilPositions,   // memref<?xi32>: per stencil block, its BCSR position
  ElementColours,     // memref<?xi32>: the colouring of edge set `set` in
                      // chunks of `chunk` elements
  Extern,             // an extern tensor `name`
  Parameter,          // the function's own parameter number `index`
};

/// The kinds in the order of their spellings' table.
inline constexpr BindingKind kBindingKinds[] = {BindingKind::SetSize,
                                                BindingKind::GridDims,
                                                BindingKind::Field,
                                                BindingKind::Endpoints,
                                                BindingKind::PatternRowPtr,
                                                BindingKind::PatternColIdx,
                                                BindingKind::PatternLocations,
                                                BindingKind::UnionRowPtr,
                                                BindingKind::UnionColIdx,
                                                BindingKind::UnionGather,
                                                BindingKind::ProductRowPtr,
                                                BindingKind::ProductColIdx,
                                                BindingKind::IncidenceRowPtr,
                                                BindingKind::IncidenceColIdx,
                                                BindingKind::IncidencePositions,
                                                BindingKind::IncidenceEndpoints,
                                                BindingKind::StencilRowPtr,
                                                BindingKind::StencilColIdx,
                                                BindingKind::StencilPositions,
                                                BindingKind::ElementColours,
                                                BindingKind::Extern,
                                                BindingKind::Parameter};

/// The spelling of `kind` in `simit.bindings`.
constexpr std::string_view spelling(BindingKind kind) {
  switch (kind) {
  case BindingKind::SetSize:
    return "set_size";
  case BindingKind::GridDims:
    return "grid_dims";
  case BindingKind::Field:
    return "field";
  case BindingKind::Endpoints:
    return "endpoints";
  case BindingKind::PatternRowPtr:
    return "pattern_rowptr";
  case BindingKind::PatternColIdx:
    return "pattern_colidx";
  case BindingKind::PatternLocations:
    return "pattern_locations";
  case BindingKind::UnionRowPtr:
    return "union_rowptr";
  case BindingKind::UnionColIdx:
    return "union_colidx";
  case BindingKind::UnionGather:
    return "union_gather";
  case BindingKind::ProductRowPtr:
    return "product_rowptr";
  case BindingKind::ProductColIdx:
    return "product_colidx";
  case BindingKind::IncidenceRowPtr:
    return "incidence_rowptr";
  case BindingKind::IncidenceColIdx:
    return "incidence_colidx";
  case BindingKind::IncidencePositions:
    return "incidence_positions";
  case BindingKind::IncidenceEndpoints:
    return "incidence_endpoints";
  case BindingKind::StencilRowPtr:
    return "stencil_rowptr";
  case BindingKind::StencilColIdx:
    return "stencil_colidx";
  case BindingKind::StencilPositions:
    return "stencil_positions";
  case BindingKind::ElementColours:
    return "element_colours";
  case BindingKind::Extern:
    return "extern";
  case BindingKind::Parameter:
    return "param";
  }
  return {};
}

/// The kind spelled `text`, if any.
constexpr std::optional<BindingKind> parseBindingKind(std::string_view text) {
  for (BindingKind kind : kBindingKinds)
    if (spelling(kind) == text)
      return kind;
  return std::nullopt;
}

} // namespace abi
} // namespace simit

#endif // SIMIT_ABI_BINDINGKIND_H
