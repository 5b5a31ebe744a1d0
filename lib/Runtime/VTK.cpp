//===--- VTK.cpp - ASCII VTK unstructured grid (.vtu) output --------------===//

#include "simit/Runtime/VTK.h"

#include "AtomicFile.h"
#include "FieldText.h"


using namespace simit;

int simit::vtkCellType(int cardinality) {
  switch (cardinality) {
  case 1:
    return 1; // VTK_VERTEX
  case 2:
    return 3; // VTK_LINE
  case 3:
    return 5; // VTK_TRIANGLE
  case 4:
    return 10; // VTK_TETRA
  default:
    return -1;
  }
}

static const char *vtkTypeName(ComponentType type) {
  switch (type) {
  case ComponentType::Float64:
    return "Float64";
  case ComponentType::Float32:
    return "Float32";
  case ComponentType::Int32:
    return "Int32";
  case ComponentType::Bool:
    return "UInt8";
  }
  return "Float64";
}

llvm::Error simit::checkVTKOptions(const Set &points,
                                   const VTKOptions &options) {
  std::string where = "VTK output of set '" + points.name().str() + "'";
  const FieldDescriptor *position =
      points.fieldDescriptor(options.positionField);
  if (!position)
    return llvm::createStringError(where + ": no position field '" +
                                   options.positionField + "'");
  if (position->shape != std::vector<int>{3} ||
      (position->type != ComponentType::Float64 &&
       position->type != ComponentType::Float32))
    return llvm::createStringError(where + ": the position field '" +
                                   options.positionField +
                                   "' is not a float vector of 3");
  for (const Set *cells : options.cellSets) {
    if (vtkCellType(cells->cardinality()) < 0)
      return llvm::createStringError(
          where + ": set '" + cells->name() + "' has cardinality " +
          llvm::Twine(cells->cardinality()) + ", expected 1 to 4");
    for (Set *endpointSet : cells->endpointSetList())
      if (endpointSet != &points)
        return llvm::createStringError(where + ": set '" + cells->name() +
                                       "' is not an edge set over it");
  }
  for (const std::string &field : options.pointFields)
    if (!points.fieldDescriptor(field))
      return llvm::createStringError(where + ": no point field '" + field +
                                     "'");
  if (!options.cellFields.empty() && options.cellSets.size() != 1)
    return llvm::createStringError(where + ": cell fields need exactly one "
                                           "cell set");
  for (const std::string &field : options.cellFields)
    if (!options.cellSets[0]->fieldDescriptor(field))
      return llvm::createStringError(where + ": no cell field '" + field +
                                     "' on set '" +
                                     options.cellSets[0]->name() + "'");
  return llvm::Error::success();
}

/// One <DataArray> holding a whole field.
static void writeFieldArray(llvm::raw_ostream &os, const Set &set,
                            llvm::StringRef name, bool named) {
  const FieldDescriptor *field = set.fieldDescriptor(name);
  size_t blockSize = field->blockSize();
  os << "        <DataArray type=\"" << vtkTypeName(field->type) << "\"";
  if (named)
    os << " Name=\"" << name << "\"";
  os << " NumberOfComponents=\"" << blockSize << "\" format=\"ascii\">\n";
  const void *data = set.fieldData(name);
  for (int e = 0; e < set.size(); ++e) {
    os << "         ";
    for (size_t i = 0; i < blockSize; ++i) {
      os << ' ';
      detail::writeComponent(os, data, field->type, e * blockSize + i);
    }
    os << '\n';
  }
  os << "        </DataArray>\n";
}

llvm::Error simit::writeVTU(llvm::raw_ostream &os, const Set &points,
                            const VTKOptions &options) {
  if (llvm::Error err = checkVTKOptions(points, options))
    return err;
  size_t numCells = 0;
  for (const Set *cells : options.cellSets)
    numCells += cells->size();

  os << "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
        "byte_order=\"LittleEndian\">\n"
        "  <UnstructuredGrid>\n"
     << "    <Piece NumberOfPoints=\"" << points.size()
     << "\" NumberOfCells=\"" << numCells << "\">\n";

  os << "      <PointData>\n";
  for (const std::string &field : options.pointFields)
    writeFieldArray(os, points, field, true);
  os << "      </PointData>\n";
  os << "      <CellData>\n";
  for (const std::string &field : options.cellFields)
    writeFieldArray(os, *options.cellSets[0], field, true);
  os << "      </CellData>\n";

  os << "      <Points>\n";
  writeFieldArray(os, points, options.positionField, false);
  os << "      </Points>\n";

  os << "      <Cells>\n"
        "        <DataArray type=\"Int32\" Name=\"connectivity\" "
        "format=\"ascii\">\n";
  for (const Set *cells : options.cellSets)
    for (int e = 0; e < cells->size(); ++e) {
      os << "         ";
      for (int32_t p : cells->endpointsOf(e))
        os << ' ' << p;
      os << '\n';
    }
  os << "        </DataArray>\n"
        "        <DataArray type=\"Int32\" Name=\"offsets\" "
        "format=\"ascii\">\n";
  long long offset = 0;
  for (const Set *cells : options.cellSets)
    for (int e = 0; e < cells->size(); ++e) {
      offset += cells->cardinality();
      os << "          " << offset << '\n';
    }
  os << "        </DataArray>\n"
        "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (const Set *cells : options.cellSets)
    for (int e = 0; e < cells->size(); ++e)
      os << "          " << vtkCellType(cells->cardinality()) << '\n';
  os << "        </DataArray>\n"
        "      </Cells>\n"
        "    </Piece>\n"
        "  </UnstructuredGrid>\n"
        "</VTKFile>\n";
  return llvm::Error::success();
}

llvm::Error simit::writeVTU(llvm::StringRef path, const Set &points,
                            const VTKOptions &options) {
  if (llvm::Error err = checkVTKOptions(points, options))
    return err;
  return detail::writeFileAtomically(path, [&](llvm::raw_ostream &os) {
    return writeVTU(os, points, options);
  });
}
