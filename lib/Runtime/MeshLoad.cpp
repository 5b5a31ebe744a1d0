//===--- MeshLoad.cpp - Mesh loader dispatch and refinement ---------------===//

#include "simit/Runtime/Mesh.h"

#include "llvm/Support/Path.h"

#include <unordered_map>

using namespace simit;

llvm::Expected<Mesh> simit::loadMesh(llvm::StringRef path) {
  llvm::StringRef extension = llvm::sys::path::extension(path);
  std::string lower = extension.lower();
  if (lower == ".msh")
    return loadGmsh(path);
  if (lower == ".obj")
    return loadObj(path);
  if (lower == ".node" || lower == ".ele" || lower == ".edge" ||
      lower == ".face")
    return loadTetGen(path.drop_back(extension.size()));
  if (extension.empty())
    return loadTetGen(path);
  return llvm::createStringError(
      std::errc::invalid_argument,
      "%s: unknown mesh format '%s' (expected .node, .ele, .edge, .face, .msh "
      "or .obj)",
      path.str().c_str(), extension.str().c_str());
}

double simit::signedTetVolume(const Mesh &m, const std::array<int, 4> &t) {
  const auto &p0 = m.points[t[0]];
  double a[3], b[3], c[3];
  for (int d = 0; d < 3; ++d) {
    a[d] = m.points[t[1]][d] - p0[d];
    b[d] = m.points[t[2]][d] - p0[d];
    c[d] = m.points[t[3]][d] - p0[d];
  }
  double det = a[0] * (b[1] * c[2] - b[2] * c[1]) -
               a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
  return det / 6.0;
}

namespace {
double squaredDistance(const std::array<double, 3> &a,
                       const std::array<double, 3> &b) {
  double sum = 0;
  for (int d = 0; d < 3; ++d)
    sum += (a[d] - b[d]) * (a[d] - b[d]);
  return sum;
}
} // namespace

Mesh simit::refineTets(const Mesh &m) {
  Mesh out;
  out.points = m.points;
  out.tets.reserve(m.tets.size() * 8);
  std::unordered_map<uint64_t, int> midpoints;
  midpoints.reserve(m.tets.size() * 2);
  auto midpoint = [&](int a, int b) {
    uint64_t lo = std::min(a, b), hi = std::max(a, b);
    auto [it, inserted] =
        midpoints.try_emplace((hi << 32) | lo, (int)out.points.size());
    if (inserted) {
      std::array<double, 3> p;
      for (int d = 0; d < 3; ++d)
        p[d] = 0.5 * (out.points[a][d] + out.points[b][d]);
      out.points.push_back(p);
    }
    return it->second;
  };

  for (const std::array<int, 4> &t : m.tets) {
    int v0 = t[0], v1 = t[1], v2 = t[2], v3 = t[3];
    // First-encounter order: 01, 02, 03, 12, 13, 23.
    int m01 = midpoint(v0, v1), m02 = midpoint(v0, v2),
        m03 = midpoint(v0, v3), m12 = midpoint(v1, v2),
        m13 = midpoint(v1, v3), m23 = midpoint(v2, v3);
    std::array<std::array<int, 4>, 8> children;
    children[0] = {v0, m01, m02, m03};
    children[1] = {m01, v1, m12, m13};
    children[2] = {m02, m12, v2, m23};
    children[3] = {m03, m13, m23, v3};

    // The inner octahedron's three diagonals, in tie-break order; each comes
    // with the cycle of the four other midpoints around it.
    struct Diagonal {
      int a, b;
      std::array<int, 4> ring;
    };
    Diagonal diagonals[3] = {{m01, m23, {m02, m03, m13, m12}},
                             {m02, m13, {m01, m03, m23, m12}},
                             {m03, m12, {m01, m02, m23, m13}}};
    const Diagonal *shortest = &diagonals[0];
    double best = squaredDistance(out.points[m01], out.points[m23]);
    for (const Diagonal &d : llvm::ArrayRef(diagonals).drop_front()) {
      double length = squaredDistance(out.points[d.a], out.points[d.b]);
      if (length < best) {
        best = length;
        shortest = &d;
      }
    }
    for (int k = 0; k < 4; ++k)
      children[4 + k] = {shortest->a, shortest->b, shortest->ring[k],
                         shortest->ring[(k + 1) % 4]};

    bool parentPositive = signedTetVolume(m, t) > 0;
    for (std::array<int, 4> &child : children) {
      if ((signedTetVolume(out, child) > 0) != parentPositive)
        std::swap(child[2], child[3]);
      out.tets.push_back(child);
    }
  }
  return out;
}
