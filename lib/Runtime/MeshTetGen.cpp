//===--- MeshTetGen.cpp - TetGen .node/.ele/.edge/.face loader ------------===//

#include "simit/Runtime/Mesh.h"

#include "TextReader.h"

#include "llvm/Support/FileSystem.h"

#include <algorithm>
#include <optional>

using namespace simit;
using namespace simit::detail;

namespace {

/// Reads the record index that starts every TetGen line. The first record
/// of the .node file fixes the mesh's numbering base (0 or 1); every record
/// of every file follows it in order, and vertex references use it too.
llvm::Error readRecordIndex(const TextReader &reader, llvm::StringRef token,
                            size_t position, std::optional<int> &base) {
  auto index = reader.parseInt(token, "the record index");
  if (!index)
    return index.takeError();
  if (!base) {
    if (*index != 0 && *index != 1)
      return reader.error("expected the first record index to be 0 or 1, "
                          "found " +
                          llvm::Twine(*index));
    base = static_cast<int>(*index);
    return llvm::Error::success();
  }
  if (*index == *base + static_cast<long long>(position))
    return llvm::Error::success();
  if (position == 0)
    return reader.error("expected the first record index to be " +
                        llvm::Twine(*base) +
                        ", the numbering of the .node file, found " +
                        llvm::Twine(*index));
  if (*index >= *base && *index < *base + static_cast<long long>(position))
    return reader.error("duplicated record index " + llvm::Twine(*index));
  return reader.error("expected record index " +
                      llvm::Twine(*base + position) + ", found " +
                      llvm::Twine(*index));
}

/// Reads the header line and checks it has between `minFields` and
/// `maxFields` non-negative integers; missing optional fields read as 0.
llvm::Error readHeader(TextReader &reader, unsigned minFields,
                       unsigned maxFields, llvm::StringRef description,
                       llvm::SmallVectorImpl<long long> &fields) {
  llvm::SmallVector<llvm::StringRef, 8> tokens;
  if (auto err = reader.requireTokens(tokens, "a header line (" +
                                                  description + ")"))
    return err;
  if (tokens.size() < minFields || tokens.size() > maxFields)
    return reader.error("expected a header line (" + description + ")");
  fields.assign(maxFields, 0);
  for (size_t i = 0; i < tokens.size(); ++i) {
    auto value = reader.parseInt(tokens[i], "header field " +
                                                llvm::Twine(i + 1) + " (" +
                                                description + ")");
    if (!value)
      return value.takeError();
    if (*value < 0)
      return reader.error("expected a non-negative header field " +
                          llvm::Twine(i + 1) + " (" + description + ")");
    fields[i] = *value;
  }
  return llvm::Error::success();
}

/// Reads the points and returns the file's dimension (2 or 3); `base`
/// receives the numbering base of its records.
llvm::Expected<int> readNodes(llvm::StringRef path, Mesh &mesh,
                              std::optional<int> &base) {
  auto reader = TextReader::open(path);
  if (!reader)
    return reader.takeError();
  llvm::SmallVector<long long, 4> header;
  if (auto err = readHeader(*reader, 1, 4,
                            "<#points> <dimension> <#attributes> "
                            "<#boundary markers>",
                            header))
    return err;
  long long count = header[0], dimension = header[1] ? header[1] : 3;
  if (dimension != 2 && dimension != 3)
    return reader->error("expected dimension 2 or 3, found " +
                         llvm::Twine(dimension));
  if (header[3] > 1)
    return reader->error("expected 0 or 1 boundary marker columns, found " +
                         llvm::Twine(header[3]));
  size_t columns = 1 + dimension + header[2] + header[3];
  mesh.points.reserve(
      std::min<size_t>(count, reader->recordCapacity(columns)));
  llvm::SmallVector<llvm::StringRef, 16> tokens;
  for (long long i = 0; i < count; ++i) {
    if (auto err = reader->requireTokens(
            tokens, "point " + llvm::Twine(i + 1) + " of " +
                        llvm::Twine(count)))
      return std::move(err);
    if (tokens.size() != columns)
      return reader->error("expected " + llvm::Twine(columns) +
                           " values (index, " + llvm::Twine(dimension) +
                           " coordinates, " + llvm::Twine(header[2]) +
                           " attributes, " + llvm::Twine(header[3]) +
                           " markers), found " + llvm::Twine(tokens.size()));
    if (auto err = readRecordIndex(*reader, tokens[0], i, base))
      return std::move(err);
    std::array<double, 3> point = {0, 0, 0};
    for (long long d = 0; d < dimension; ++d) {
      auto value = reader->parseFiniteDouble(tokens[1 + d], "a coordinate");
      if (!value)
        return value.takeError();
      point[d] = *value;
    }
    mesh.points.push_back(point);
  }
  if (reader->nextTokens(tokens))
    return reader->error("expected the end of the file after " +
                         llvm::Twine(count) + " points");
  return static_cast<int>(dimension);
}

/// Reads the records of an .ele/.edge/.face file: `arity` vertex references
/// after the index (of `stored` present), then `extra` columns to skip.
template <size_t N>
llvm::Error readSimplices(TextReader &reader, long long count, size_t stored,
                          size_t extra, size_t numPoints, int base,
                          llvm::StringRef what,
                          std::vector<std::array<int, N>> &out) {
  size_t columns = 1 + stored + extra;
  out.reserve(std::min<size_t>(count, reader.recordCapacity(columns)));
  llvm::SmallVector<llvm::StringRef, 16> tokens;
  std::optional<int> recordBase = base;
  for (long long i = 0; i < count; ++i) {
    if (auto err = reader.requireTokens(
            tokens, what + " " + llvm::Twine(i + 1) + " of " +
                        llvm::Twine(count)))
      return err;
    if (tokens.size() != columns)
      return reader.error("expected " + llvm::Twine(columns) +
                          " values (index, " + llvm::Twine(stored) +
                          " vertices, " + llvm::Twine(extra) +
                          " attributes/markers), found " +
                          llvm::Twine(tokens.size()));
    if (auto err = readRecordIndex(reader, tokens[0], i, recordBase))
      return err;
    std::array<int, N> &element = out.emplace_back();
    for (size_t k = 0; k < N; ++k) {
      auto vertex = reader.parseInt(tokens[1 + k], "a vertex index");
      if (!vertex)
        return vertex.takeError();
      long long zeroBased = *vertex - base;
      if (zeroBased < 0 || zeroBased >= static_cast<long long>(numPoints))
        return reader.error("vertex index " + llvm::Twine(*vertex) +
                            " is out of range (" + llvm::Twine(base) + ".." +
                            llvm::Twine(base + (long long)numPoints - 1) +
                            ")");
      element[k] = static_cast<int>(zeroBased);
    }
  }
  if (reader.nextTokens(tokens))
    return reader.error("expected the end of the file after " +
                        llvm::Twine(count) + " records");
  return llvm::Error::success();
}

llvm::Error readElements(llvm::StringRef path, int base, Mesh &mesh) {
  auto reader = TextReader::open(path);
  if (!reader)
    return reader.takeError();
  llvm::SmallVector<long long, 3> header;
  if (auto err = readHeader(*reader, 2, 3,
                            "<#tetrahedra> <nodes per tetrahedron> "
                            "<#attributes>",
                            header))
    return err;
  if (header[1] != 4 && header[1] != 10)
    return reader->error("expected 4 or 10 nodes per tetrahedron, found " +
                         llvm::Twine(header[1]));
  return readSimplices<4>(*reader, header[0], header[1], header[2],
                          mesh.points.size(), base, "tetrahedron", mesh.tets);
}

template <size_t N>
llvm::Error readFacets(llvm::StringRef path, llvm::StringRef what,
                       size_t numPoints, int base,
                       std::vector<std::array<int, N>> &out) {
  auto reader = TextReader::open(path);
  if (!reader)
    return reader.takeError();
  llvm::SmallVector<long long, 2> header;
  if (auto err = readHeader(*reader, 1, 2,
                            "<#" + what.str() + "s> <boundary marker>",
                            header))
    return err;
  if (header[1] > 1)
    return reader->error("expected a boundary marker flag of 0 or 1, "
                         "found " +
                         llvm::Twine(header[1]));
  return readSimplices<N>(*reader, header[0], N, header[1], numPoints, base,
                          what, out);
}

} // namespace

llvm::Expected<Mesh> simit::loadTetGen(llvm::StringRef basePath) {
  Mesh mesh;
  std::string base = basePath.str();
  std::optional<int> numbering;
  auto dimension = readNodes(base + ".node", mesh, numbering);
  if (!dimension)
    return dimension.takeError();
  // An empty .node file has no first index; its elements could only be
  // out of range anyway.
  int firstIndex = numbering.value_or(0);
  if (llvm::sys::fs::exists(base + ".ele")) {
    if (*dimension != 3)
      return llvm::createStringError(
          base + ".node: expected 3-D points for the tetrahedra of " + base +
          ".ele, found dimension " + llvm::Twine(*dimension));
    if (auto err = readElements(base + ".ele", firstIndex, mesh))
      return err;
  }
  if (llvm::sys::fs::exists(base + ".edge"))
    if (auto err = readFacets<2>(base + ".edge", "edge", mesh.points.size(),
                                 firstIndex, mesh.edges))
      return err;
  if (llvm::sys::fs::exists(base + ".face"))
    if (auto err = readFacets<3>(base + ".face", "face", mesh.points.size(),
                                 firstIndex, mesh.triangles))
      return err;
  return mesh;
}
