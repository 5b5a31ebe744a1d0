//===--- MeshObj.cpp - Wavefront OBJ loader -------------------------------===//

#include "simit/Runtime/Mesh.h"

#include "TextReader.h"

using namespace simit;
using namespace simit::detail;

llvm::Expected<Mesh> simit::loadObj(llvm::StringRef path) {
  auto reader = TextReader::open(path);
  if (!reader)
    return reader.takeError();
  Mesh mesh;
  llvm::SmallVector<llvm::StringRef, 16> tokens;
  llvm::SmallVector<int, 8> polygon;
  while (reader->nextTokens(tokens)) {
    if (tokens[0] == "v") {
      // x y z and an optional weight w.
      if (tokens.size() != 4 && tokens.size() != 5)
        return reader->error("expected 'v x y z [w]'");
      std::array<double, 3> point;
      for (int d = 0; d < 3; ++d) {
        auto value = reader->parseFiniteDouble(tokens[1 + d], "a coordinate");
        if (!value)
          return value.takeError();
        point[d] = *value;
      }
      mesh.points.push_back(point);
    } else if (tokens[0] == "f") {
      if (tokens.size() < 4)
        return reader->error("expected a face of at least 3 vertices");
      polygon.clear();
      for (llvm::StringRef corner : llvm::ArrayRef(tokens).drop_front()) {
        // v, v/vt, v//vn or v/vt/vn: only the position index matters.
        auto index = reader->parseInt(corner.split('/').first,
                                      "a vertex index");
        if (!index)
          return index.takeError();
        long long count = mesh.points.size();
        long long zeroBased = *index > 0 ? *index - 1 : count + *index;
        if (*index == 0 || zeroBased < 0 || zeroBased >= count)
          return reader->error("vertex index " + llvm::Twine(*index) +
                               " is out of range (" + llvm::Twine(count) +
                               " vertices read so far)");
        polygon.push_back(static_cast<int>(zeroBased));
      }
      for (size_t k = 1; k + 1 < polygon.size(); ++k)
        mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
    }
    // vt, vn, g, o, s, usemtl, mtllib, l...: not part of the mesh model.
  }
  return mesh;
}
