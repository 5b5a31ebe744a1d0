//===--- SupernodalAnalysis.cpp - Symbolic LL^T of a block pattern --------===//
//
// Ordering, elimination tree, the structure of L and its supernodes, all on
// the graph of the matrix's blocks: a block's unknowns share their
// structure, so every step runs on blockSize^2 times fewer entries than on
// the scalar graph, and the supernodes are whole blocks wide.
//
//===----------------------------------------------------------------------===//

#include "SupernodalCholesky.h"

#include <algorithm>
#include <numeric>

extern "C" {
#include <suitesparse/amd.h>
}

using namespace simit;
using namespace simit::direct;

namespace {

/// Whether two consecutive supernodes merge into a relaxed one of
/// `columns` scalar columns whose panel holds `zeros` of `entries` as
/// stored zeros (CHOLMOD's default rule): narrow supernodes cost more in
/// loop and call overhead than the zeros they would add.
bool relaxes(int64_t columns, int64_t zeros, int64_t entries) {
  double fraction = static_cast<double>(zeros) / static_cast<double>(entries);
  return columns <= 4 || (columns <= 16 && fraction < 0.8) ||
         (columns <= 48 && fraction < 0.1) || fraction < 0.05;
}

/// The adjacency of A + A^T without the diagonal, each neighbour once (as
/// AMD needs), in lists that are not sorted: nothing below needs them
/// sorted. Vertex v's list is neighbours[start[v] .. start[v] + length[v]),
/// with gaps where a block and its mirror were both stored. It is read in
/// AMD's numbering through `Numbering`, without being renumbered.
struct Graph {
  std::vector<int32_t> start, length, neighbours;

  Graph(int64_t rows, const int32_t *rowptr, const int32_t *colidx) {
    start.assign(static_cast<size_t>(rows) + 1, 0);
    for (int64_t r = 0; r < rows; ++r)
      for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k)
        if (colidx[k] != r) {
          ++start[r + 1];
          ++start[colidx[k] + 1];
        }
    std::partial_sum(start.begin(), start.end(), start.begin());
    neighbours.resize(static_cast<size_t>(start[rows]));
    std::vector<int32_t> fill(start.begin(), start.end() - 1);
    for (int64_t r = 0; r < rows; ++r) {
      // The row's own cursor stays in a register; its mirrors' are stored.
      int32_t own = fill[r];
      for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k) {
        int32_t c = colidx[k];
        if (c == r)
          continue;
        neighbours[own++] = c;
        neighbours[fill[c]++] = static_cast<int32_t>(r);
      }
      fill[r] = own;
    }
    // Each list keeps the first of its duplicates, in place.
    length.resize(static_cast<size_t>(rows));
    std::vector<int32_t> seenBy(static_cast<size_t>(rows), -1);
    for (int64_t v = 0; v < rows; ++v) {
      int32_t kept = start[v];
      for (int32_t p = start[v]; p < start[v + 1]; ++p) {
        int32_t c = neighbours[p];
        if (seenBy[c] != v) {
          seenBy[c] = static_cast<int32_t>(v);
          neighbours[kept++] = c;
        }
      }
      length[v] = kept - start[v];
    }
  }

  int64_t size() const { return static_cast<int64_t>(length.size()); }
  int32_t end(int64_t v) const { return start[v] + length[v]; }
};

/// AMD's fill-reducing order of the graph's vertices (order[k] is the one
/// eliminated k-th), from amd_2 on a copy of the lists: amd_order would
/// check the pattern, build A + A^T and allocate its workspace again,
/// which costs more than the ordering itself on the graphs of small
/// Newton systems (a few hundred blocks).
std::vector<int32_t> minimumDegreeOrder(const Graph &graph) {
  int32_t n = static_cast<int32_t>(graph.size());
  std::vector<int32_t> order(static_cast<size_t>(n));
  if (n == 0)
    return order;
  // The lists, with the elbow room amd_order gives: an fifth of their
  // length and one entry per vertex.
  int32_t used = graph.start[n];
  int32_t room = used + used / 5 + n;
  std::vector<int32_t> iw(static_cast<size_t>(room)),
      pe(graph.start.begin(), graph.start.end() - 1), len(graph.length),
      work(static_cast<size_t>(n) * 6);
  std::copy(graph.neighbours.begin(), graph.neighbours.end(), iw.begin());
  int32_t *nv = work.data(), *next = nv + n, *head = next + n, *elen = head + n,
          *degree = elen + n, *w = degree + n;
  double control[AMD_CONTROL], info[AMD_INFO];
  amd_defaults(control);
  amd_2(n, pe.data(), iw.data(), len.data(), room, used, nv, next, order.data(),
        head, elen, degree, w, control, info);
  return order;
}

/// A numbering of the graph's vertices: vertex[k] is the k-th, index[v]
/// the number of vertex v.
struct Numbering {
  const std::vector<int64_t> &vertex, &index;
};

/// The elimination tree of a graph in a numbering (Liu's algorithm with
/// path compression), in that numbering; -1 for roots.
std::vector<int64_t> eliminationTree(const Graph &graph,
                                     const Numbering &numbering) {
  int64_t n = static_cast<int64_t>(numbering.vertex.size());
  std::vector<int64_t> parent(n, -1), ancestor(n, -1);
  for (int64_t k = 0; k < n; ++k) {
    int64_t v = numbering.vertex[k];
    for (int32_t p = graph.start[v]; p < graph.end(v); ++p) {
      int64_t i = numbering.index[graph.neighbours[p]];
      while (i < k && i != -1) {
        int64_t next = ancestor[i];
        ancestor[i] = k;
        if (next == -1)
          parent[i] = k;
        i = next;
      }
    }
  }
  return parent;
}

/// The vertices in a postorder of the forest in which each vertex's
/// children come by increasing weight (then index), roots by index: the
/// child with the most rows comes last, next to its parent, where it can
/// share its supernode (CHOLMOD's weighted postorder). Weights lie in
/// [0, n).
std::vector<int64_t> postorder(const std::vector<int64_t> &parent,
                               const std::vector<int64_t> &weight) {
  int64_t n = static_cast<int64_t>(parent.size());
  // The vertices by (weight, index), a counting sort; appended in that
  // order, each vertex's children come sorted.
  std::vector<int64_t> byWeightStart(n + 1, 0);
  for (int64_t v = 0; v < n; ++v)
    ++byWeightStart[weight[v] + 1];
  std::partial_sum(byWeightStart.begin(), byWeightStart.end(),
                   byWeightStart.begin());
  std::vector<int64_t> byWeight(static_cast<size_t>(n));
  for (int64_t v = 0; v < n; ++v)
    byWeight[byWeightStart[weight[v]]++] = v;
  std::vector<int64_t> childStart(n + 1, 0);
  for (int64_t v = 0; v < n; ++v)
    if (parent[v] != -1)
      ++childStart[parent[v] + 1];
  std::partial_sum(childStart.begin(), childStart.end(), childStart.begin());
  std::vector<int64_t> children(static_cast<size_t>(childStart[n]));
  std::vector<int64_t> fill(childStart.begin(), childStart.end() - 1);
  for (int64_t v : byWeight)
    if (parent[v] != -1)
      children[fill[parent[v]]++] = v;
  std::vector<int64_t> order, stack,
      nextChild(childStart.begin(), childStart.end() - 1);
  order.reserve(n);
  for (int64_t root = 0; root < n; ++root) {
    if (parent[root] != -1)
      continue;
    stack.push_back(root);
    while (!stack.empty()) {
      int64_t v = stack.back();
      if (nextChild[v] < childStart[v + 1]) {
        stack.push_back(children[nextChild[v]++]);
      } else {
        order.push_back(v);
        stack.pop_back();
      }
    }
  }
  return order;
}

/// visit(j, i) for every entry (i, j), i > j, of L's block pattern, by
/// increasing i: row i's entries are the columns up the tree from each of
/// its neighbours below it, until one already visited for i (its row
/// subtree). `parent` is the tree in the numbering's.
template <typename Visit>
void rowSubtrees(const Graph &graph, const Numbering &numbering,
                 const std::vector<int64_t> &parent, Visit visit) {
  int64_t n = static_cast<int64_t>(parent.size());
  std::vector<int64_t> mark(n, -1);
  for (int64_t i = 0; i < n; ++i) {
    mark[i] = i;
    int64_t v = numbering.vertex[i];
    for (int32_t p = graph.start[v]; p < graph.end(v); ++p)
      for (int64_t j = numbering.index[graph.neighbours[p]];
           j < i && mark[j] != i; j = parent[j]) {
        mark[j] = i;
        visit(j, i);
      }
  }
}

} // namespace

std::vector<int32_t> direct::minimumDegreeOrder(int64_t rows,
                                                const int32_t *rowptr,
                                                const int32_t *colidx) {
  return ::minimumDegreeOrder(Graph(rows, rowptr, colidx));
}

SupernodeLayout SupernodalSymbolic::layout() const {
  SupernodeLayout layout;
  layout.supernodes = static_cast<int64_t>(first.size()) - 1;
  layout.first = first.data();
  layout.rowStart = rowStart.data();
  layout.valueStart = valueStart.data();
  layout.rows = rows.data();
  return layout;
}

SupernodalSymbolic direct::analyse(int64_t blockRows, int64_t blockSize,
                                   const int32_t *rowptr,
                                   const int32_t *colidx) {
  int64_t n = blockRows;
  SupernodalSymbolic symbolic;
  if (n == 0) {
    symbolic.first = symbolic.rowStart = symbolic.valueStart = {0};
    return symbolic;
  }
  // Fill-reducing order, then the elimination tree's postorder, which
  // keeps the fill and makes every supernode's columns consecutive.
  Graph graph(n, rowptr, colidx);
  std::vector<int32_t> amd = ::minimumDegreeOrder(graph);
  std::vector<int64_t> amdVertex(amd.begin(), amd.end()), amdIndex(n);
  for (int64_t k = 0; k < n; ++k)
    amdIndex[amd[k]] = k;
  Numbering amdNumbering{amdVertex, amdIndex};
  std::vector<int64_t> tree = eliminationTree(graph, amdNumbering);
  // L's entries below the diagonal in AMD's numbering, row by row, and
  // their count per column.
  std::vector<std::pair<int32_t, int32_t>> entriesBelow; // (column, row)
  std::vector<int64_t> amdCount(n, 0);
  rowSubtrees(graph, amdNumbering, tree, [&](int64_t j, int64_t i) {
    entriesBelow.emplace_back(j, i);
    ++amdCount[j];
  });
  std::vector<int64_t> post = postorder(tree, amdCount);
  std::vector<int64_t> blockOrder(n), positionInPost(n), count(n);
  for (int64_t k = 0; k < n; ++k) {
    blockOrder[k] = amd[post[k]];
    positionInPost[post[k]] = k;
    count[k] = amdCount[post[k]];
  }
  std::vector<int64_t> parent(n, -1);
  for (int64_t k = 0; k < n; ++k)
    if (tree[post[k]] != -1)
      parent[k] = positionInPost[tree[post[k]]];

  // The rows below the diagonal of each column in the postorder, sorted:
  // a column's rows are its ancestors in the tree, which come in the same
  // order in both numberings, and were visited in AMD's.
  std::vector<int64_t> columnStart(n + 1, 0);
  std::partial_sum(count.begin(), count.end(), columnStart.begin() + 1);
  std::vector<int64_t> belowRows(static_cast<size_t>(columnStart[n]));
  std::vector<int64_t> filled(columnStart.begin(), columnStart.end() - 1);
  for (auto [j, i] : entriesBelow)
    belowRows[filled[positionInPost[j]]++] = positionInPost[i];

  // Fundamental supernodes: a column joins the previous one's supernode
  // when it is that column's parent, its only child, and has one row less.
  std::vector<int64_t> children(n, 0);
  for (int64_t k = 0; k < n; ++k)
    if (parent[k] != -1)
      ++children[parent[k]];
  std::vector<int64_t> firstColumn; // of each supernode, in block columns
  for (int64_t k = 0; k < n; ++k)
    if (k == 0 || parent[k - 1] != k || children[k] != 1 ||
        count[k - 1] != count[k] + 1)
      firstColumn.push_back(k);
  firstColumn.push_back(n);

  // Relaxed: merge a supernode into the next when that is its parent and
  // the merge is narrow and adds few zeros. Rows of the merged panel: the
  // columns, then the later one's rows below it, a superset of the
  // earlier's (its rows below lie on its path to the root, which passes
  // through the later supernode).
  // `stored` counts the entries of L's pattern (not zeros) in the
  // supernode being grown, which starts at merged.back().
  auto storedIn = [&](int64_t f, int64_t l) { // columns [f, l)
    int64_t entries = 0;
    for (int64_t c = f; c < l; ++c)
      entries += count[c] + 1;
    return entries;
  };
  std::vector<int64_t> merged{0};
  int64_t stored = storedIn(0, firstColumn[1]);
  for (size_t s = 1; s + 1 < firstColumn.size(); ++s) {
    int64_t f = merged.back(), l = firstColumn[s], next = firstColumn[s + 1];
    int64_t storedNext = storedIn(l, next);
    if (parent[l - 1] == l) {
      int64_t columns = next - f, height = columns + count[next - 1];
      int64_t panel = columns * height - columns * (columns - 1) / 2;
      if (relaxes(columns * blockSize, panel - stored - storedNext, panel)) {
        stored += storedNext; // l joins the supernode starting at f
        continue;
      }
    }
    merged.push_back(l);
    stored = storedNext;
  }
  merged.push_back(n);

  // Scalar arrays: each block column and row stands for blockSize.
  int64_t bs = blockSize;
  symbolic.permutation.resize(static_cast<size_t>(n * bs));
  for (int64_t k = 0; k < n; ++k)
    for (int64_t c = 0; c < bs; ++c)
      symbolic.permutation[k * bs + c] = blockOrder[k] * bs + c;
  symbolic.first.push_back(0);
  symbolic.rowStart.push_back(0);
  symbolic.valueStart.push_back(0);
  for (size_t s = 0; s + 1 < merged.size(); ++s) {
    int64_t f = merged[s], l = merged[s + 1];
    for (int64_t b = f; b < l; ++b)
      for (int64_t c = 0; c < bs; ++c)
        symbolic.rows.push_back(b * bs + c);
    for (int64_t p = columnStart[l - 1]; p < columnStart[l]; ++p)
      for (int64_t c = 0; c < bs; ++c)
        symbolic.rows.push_back(belowRows[p] * bs + c);
    int64_t height =
        static_cast<int64_t>(symbolic.rows.size()) - symbolic.rowStart.back();
    symbolic.first.push_back(l * bs);
    symbolic.rowStart.push_back(static_cast<int64_t>(symbolic.rows.size()));
    symbolic.valueStart.push_back(symbolic.valueStart.back() +
                                  height * (l - f) * bs);
  }
  return symbolic;
}
