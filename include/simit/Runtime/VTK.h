//===--- VTK.h - ASCII VTK unstructured grid (.vtu) output ------*- C++ -*-===//
//
// Writes a vertex set with a position field as the points of an
// UnstructuredGrid, the elements of edge sets over it as cells (VTK types
// 1 vertex, 3 line, 5 triangle, 10 tetra, by cardinality), and chosen
// fields as point and cell data. ParaView and the `vtk` Python module read
// the result.
//
//===----------------------------------------------------------------------===//

#ifndef SIMIT_RUNTIME_VTK_H
#define SIMIT_RUNTIME_VTK_H

#include "simit/Runtime/Set.h"

#include "llvm/Support/Error.h"
#include "llvm/Support/raw_ostream.h"

#include <string>
#include <vector>

namespace simit {

struct VTKOptions {
  /// A float64 or float32 field of shape [3] on the point set.
  std::string positionField = "x";
  /// Edge sets whose endpoints are all the point set, written as cells in
  /// this order.
  std::vector<const Set *> cellSets;
  /// Fields of the point set written as point data.
  std::vector<std::string> pointFields;
  /// Fields written as cell data; needs exactly one cell set.
  std::vector<std::string> cellFields;
};

/// The VTK cell type of a simplex with `cardinality` vertices, or -1.
int vtkCellType(int cardinality);

/// Checks the options against the sets; the error names the problem.
llvm::Error checkVTKOptions(const Set &points, const VTKOptions &options);

llvm::Error writeVTU(llvm::raw_ostream &os, const Set &points,
                     const VTKOptions &options);
/// Writes `path` under a temporary name, renamed to `path` when complete.
llvm::Error writeVTU(llvm::StringRef path, const Set &points,
                     const VTKOptions &options);

} // namespace simit

#endif // SIMIT_RUNTIME_VTK_H
