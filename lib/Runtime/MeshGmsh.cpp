//===--- MeshGmsh.cpp - ASCII Gmsh .msh (formats 2 and 4) loader ----------===//

#include "simit/Runtime/Mesh.h"

#include "TextReader.h"

#include "llvm/ADT/DenseMap.h"

#include <algorithm>

using namespace simit;
using namespace simit::detail;

namespace {

using Tokens = llvm::SmallVector<llvm::StringRef, 16>;

/// Gmsh element types this loader keeps, with their node counts.
enum GmshElement { Line = 1, Triangle = 2, Tetrahedron = 4 };

class GmshReader {
public:
  GmshReader(TextReader &reader) : reader(reader) {}

  llvm::Error read(Mesh &mesh);

private:
  llvm::Error readFormat();
  llvm::Error readNodesV2(Mesh &mesh);
  llvm::Error readNodesV4(Mesh &mesh);
  llvm::Error readElementsV2(Mesh &mesh);
  llvm::Error readElementsV4(Mesh &mesh);
  llvm::Error skipSection(llvm::StringRef name);
  llvm::Error expectEnd(llvm::StringRef name);

  llvm::Expected<long long> intAt(const Tokens &tokens, size_t i,
                                  const llvm::Twine &what);
  llvm::Error addNode(long long tag, const Tokens &tokens, size_t first,
                      Mesh &mesh);
  /// Stores an element of `type` whose node tags are tokens[first...].
  llvm::Error addElement(long long type, const Tokens &tokens, size_t first,
                         Mesh &mesh);

  TextReader &reader;
  int major = 0, minor = 0;
  llvm::DenseMap<long long, int> nodeIndex;
};

llvm::Expected<long long> GmshReader::intAt(const Tokens &tokens, size_t i,
                                            const llvm::Twine &what) {
  if (i >= tokens.size())
    return reader.error("expected " + what + " in column " +
                        llvm::Twine(i + 1));
  return reader.parseInt(tokens[i], what);
}

llvm::Error GmshReader::expectEnd(llvm::StringRef name) {
  Tokens tokens;
  std::string end = ("$End" + name).str();
  if (auto err = reader.requireTokens(tokens, end))
    return err;
  if (tokens.size() != 1 || tokens[0] != end)
    return reader.error("expected " + end + ", found '" + tokens[0] + "'");
  return llvm::Error::success();
}

llvm::Error GmshReader::skipSection(llvm::StringRef name) {
  Tokens tokens;
  std::string end = ("$End" + name).str();
  while (true) {
    if (auto err = reader.requireTokens(tokens, end))
      return err;
    if (tokens[0] == end)
      return llvm::Error::success();
  }
}

llvm::Error GmshReader::readFormat() {
  Tokens tokens;
  if (auto err = reader.requireTokens(tokens, "<version> <file-type> "
                                              "<data-size>"))
    return err;
  if (tokens.size() != 3)
    return reader.error("expected <version> <file-type> <data-size>");
  auto [majorText, minorText] = tokens[0].split('.');
  if (majorText.getAsInteger(10, major) ||
      (!minorText.empty() && minorText.getAsInteger(10, minor)) ||
      (major != 2 && major != 4))
    return reader.error("expected format version 2.x or 4.x, found '" +
                        tokens[0] + "'");
  if (tokens[1] != "0")
    return reader.error("expected an ASCII file (file-type 0), found "
                        "file-type " +
                        tokens[1]);
  return expectEnd("MeshFormat");
}

llvm::Error GmshReader::addNode(long long tag, const Tokens &tokens,
                                size_t first, Mesh &mesh) {
  if (tokens.size() < first + 3)
    return reader.error("expected 3 coordinates");
  std::array<double, 3> point;
  for (int d = 0; d < 3; ++d) {
    auto value = reader.parseFiniteDouble(tokens[first + d], "a coordinate");
    if (!value)
      return value.takeError();
    point[d] = *value;
  }
  if (!nodeIndex.try_emplace(tag, mesh.points.size()).second)
    return reader.error("duplicated node tag " + llvm::Twine(tag));
  mesh.points.push_back(point);
  return llvm::Error::success();
}

llvm::Error GmshReader::readNodesV2(Mesh &mesh) {
  Tokens tokens;
  if (auto err = reader.requireTokens(tokens, "the number of nodes"))
    return err;
  auto count = intAt(tokens, 0, "the number of nodes");
  if (!count)
    return count.takeError();
  for (long long i = 0; i < *count; ++i) {
    if (auto err = reader.requireTokens(tokens, "node " + llvm::Twine(i + 1) +
                                                    " of " +
                                                    llvm::Twine(*count)))
      return err;
    if (tokens.size() != 4)
      return reader.error("expected <node-tag> <x> <y> <z>");
    auto tag = intAt(tokens, 0, "a node tag");
    if (!tag)
      return tag.takeError();
    if (auto err = addNode(*tag, tokens, 1, mesh))
      return err;
  }
  return expectEnd("Nodes");
}

llvm::Error GmshReader::readNodesV4(Mesh &mesh) {
  Tokens tokens;
  if (auto err = reader.requireTokens(tokens, "the nodes header"))
    return err;
  auto blocks = intAt(tokens, 0, "the number of entity blocks");
  if (!blocks)
    return blocks.takeError();
  for (long long b = 0; b < *blocks; ++b) {
    if (auto err = reader.requireTokens(tokens, "an entity block header"))
      return err;
    if (tokens.size() != 4)
      return reader.error("expected an entity block header of 4 integers");
    // 4.1: dim tag parametric count; 4.0: tag dim parametric count.
    auto parametric = intAt(tokens, 2, "the parametric flag");
    if (!parametric)
      return parametric.takeError();
    if (*parametric != 0)
      return reader.error("parametric node coordinates are not supported");
    auto count = intAt(tokens, 3, "the number of nodes in the block");
    if (!count)
      return count.takeError();
    if (minor == 0) {
      for (long long i = 0; i < *count; ++i) {
        if (auto err = reader.requireTokens(tokens, "<node-tag> <x> <y> <z>"))
          return err;
        if (tokens.size() != 4)
          return reader.error("expected <node-tag> <x> <y> <z>");
        auto tag = intAt(tokens, 0, "a node tag");
        if (!tag)
          return tag.takeError();
        if (auto err = addNode(*tag, tokens, 1, mesh))
          return err;
      }
      continue;
    }
    // 4.1 lists the block's tags first, then its coordinates: room for
    // the tags the file can hold, not for what the header says.
    std::vector<long long> tags;
    tags.reserve(std::min<size_t>(std::max(*count, 0LL),
                                  reader.recordCapacity(1)));
    for (long long i = 0; i < *count; ++i) {
      if (auto err = reader.requireTokens(tokens, "a node tag"))
        return err;
      if (tokens.size() != 1)
        return reader.error("expected one node tag per line");
      auto tag = intAt(tokens, 0, "a node tag");
      if (!tag)
        return tag.takeError();
      tags.push_back(*tag);
    }
    for (long long i = 0; i < *count; ++i) {
      if (auto err = reader.requireTokens(tokens, "<x> <y> <z>"))
        return err;
      if (tokens.size() != 3)
        return reader.error("expected <x> <y> <z>");
      if (auto err = addNode(tags[i], tokens, 0, mesh))
        return err;
    }
  }
  return expectEnd("Nodes");
}

llvm::Error GmshReader::addElement(long long type, const Tokens &tokens,
                                   size_t first, Mesh &mesh) {
  size_t arity = type == Line ? 2 : type == Triangle ? 3
                                : type == Tetrahedron ? 4
                                                      : 0;
  if (arity == 0)
    return llvm::Error::success(); // points, quads, hexes...: not kept
  if (tokens.size() != first + arity)
    return reader.error("expected " + llvm::Twine(arity) +
                        " node tags for element type " + llvm::Twine(type) +
                        ", found " +
                        llvm::Twine((long long)tokens.size() - (long long)first));
  std::array<int, 4> nodes{};
  for (size_t k = 0; k < arity; ++k) {
    auto tag = reader.parseInt(tokens[first + k], "a node tag");
    if (!tag)
      return tag.takeError();
    auto it = nodeIndex.find(*tag);
    if (it == nodeIndex.end())
      return reader.error("unknown node tag " + llvm::Twine(*tag));
    nodes[k] = it->second;
  }
  if (type == Line)
    mesh.edges.push_back({nodes[0], nodes[1]});
  else if (type == Triangle)
    mesh.triangles.push_back({nodes[0], nodes[1], nodes[2]});
  else
    mesh.tets.push_back(nodes);
  return llvm::Error::success();
}

llvm::Error GmshReader::readElementsV2(Mesh &mesh) {
  Tokens tokens;
  if (auto err = reader.requireTokens(tokens, "the number of elements"))
    return err;
  auto count = intAt(tokens, 0, "the number of elements");
  if (!count)
    return count.takeError();
  for (long long i = 0; i < *count; ++i) {
    if (auto err = reader.requireTokens(tokens, "element " +
                                                    llvm::Twine(i + 1) +
                                                    " of " +
                                                    llvm::Twine(*count)))
      return err;
    auto type = intAt(tokens, 1, "an element type");
    if (!type)
      return type.takeError();
    auto numTags = intAt(tokens, 2, "the number of tags");
    if (!numTags)
      return numTags.takeError();
    if (*numTags < 0 || 3 + *numTags > (long long)tokens.size())
      return reader.error("expected " + llvm::Twine(*numTags) + " tags");
    if (auto err = addElement(*type, tokens, 3 + *numTags, mesh))
      return err;
  }
  return expectEnd("Elements");
}

llvm::Error GmshReader::readElementsV4(Mesh &mesh) {
  Tokens tokens;
  if (auto err = reader.requireTokens(tokens, "the elements header"))
    return err;
  auto blocks = intAt(tokens, 0, "the number of entity blocks");
  if (!blocks)
    return blocks.takeError();
  for (long long b = 0; b < *blocks; ++b) {
    if (auto err = reader.requireTokens(tokens, "an entity block header"))
      return err;
    if (tokens.size() != 4)
      return reader.error("expected an entity block header of 4 integers");
    auto type = intAt(tokens, 2, "an element type");
    if (!type)
      return type.takeError();
    auto count = intAt(tokens, 3, "the number of elements in the block");
    if (!count)
      return count.takeError();
    for (long long i = 0; i < *count; ++i) {
      if (auto err = reader.requireTokens(tokens, "<element-tag> <node-tag>..."))
        return err;
      if (auto err = addElement(*type, tokens, 1, mesh))
        return err;
    }
  }
  return expectEnd("Elements");
}

llvm::Error GmshReader::read(Mesh &mesh) {
  Tokens tokens;
  bool sawFormat = false, sawNodes = false;
  while (reader.nextTokens(tokens)) {
    llvm::StringRef section = tokens[0];
    if (!section.starts_with("$") || section.starts_with("$End"))
      return reader.error("expected a section header such as $Nodes, found '" +
                          section + "'");
    section = section.drop_front();
    if (section == "MeshFormat") {
      if (auto err = readFormat())
        return err;
      sawFormat = true;
      continue;
    }
    if (!sawFormat)
      return reader.error("expected $MeshFormat before $" + section);
    if (section == "Nodes") {
      if (sawNodes)
        return reader.error("expected a single $Nodes section");
      sawNodes = true;
      if (auto err = major == 2 ? readNodesV2(mesh) : readNodesV4(mesh))
        return err;
    } else if (section == "Elements") {
      if (!sawNodes)
        return reader.error("expected $Nodes before $Elements");
      if (auto err = major == 2 ? readElementsV2(mesh) : readElementsV4(mesh))
        return err;
    } else if (auto err = skipSection(section)) {
      return err;
    }
  }
  if (!sawFormat)
    return reader.fileError("expected a $MeshFormat section");
  if (!sawNodes)
    return reader.fileError("expected a $Nodes section");
  return llvm::Error::success();
}

} // namespace

llvm::Expected<Mesh> simit::loadGmsh(llvm::StringRef path) {
  // Gmsh has no comment syntax; `#` may appear in $PhysicalNames strings.
  auto reader = TextReader::open(path, /*hashComments=*/false);
  if (!reader)
    return reader.takeError();
  Mesh mesh;
  if (auto err = GmshReader(*reader).read(mesh))
    return err;
  return mesh;
}
