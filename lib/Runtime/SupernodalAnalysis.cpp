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
#include <utility>

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
/// with gaps where a block and its mirror were both stored.
struct Graph {
  std::vector<int32_t> start, length, neighbours;

  Graph() = default;
  Graph(int32_t rows, const int32_t *rowptr, const int32_t *colidx) {
    start.assign(static_cast<size_t>(rows) + 1, 0);
    for (int32_t r = 0; r < rows; ++r)
      for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k)
        if (colidx[k] != r) {
          ++start[r + 1];
          ++start[colidx[k] + 1];
        }
    std::partial_sum(start.begin(), start.end(), start.begin());
    neighbours.resize(static_cast<size_t>(start[rows]));
    std::vector<int32_t> fill(start.begin(), start.end() - 1);
    for (int32_t r = 0; r < rows; ++r) {
      // The row's own cursor stays in a register; its mirrors' are stored.
      int32_t own = fill[r];
      for (int32_t k = rowptr[r]; k < rowptr[r + 1]; ++k) {
        int32_t c = colidx[k];
        if (c == r)
          continue;
        neighbours[own++] = c;
        neighbours[fill[c]++] = r;
      }
      fill[r] = own;
    }
    // Each list keeps the first of its duplicates, in place.
    length.resize(static_cast<size_t>(rows));
    std::vector<int32_t> seenBy(static_cast<size_t>(rows), -1);
    for (int32_t v = 0; v < rows; ++v) {
      int32_t kept = start[v];
      for (int32_t p = start[v]; p < start[v + 1]; ++p) {
        int32_t c = neighbours[p];
        if (seenBy[c] != v) {
          seenBy[c] = v;
          neighbours[kept++] = c;
        }
      }
      length[v] = kept - start[v];
    }
  }

  int32_t size() const { return static_cast<int32_t>(length.size()); }
  int32_t end(int32_t v) const { return start[v] + length[v]; }

  /// The graph with vertex order[k] numbered k (index its inverse), its
  /// lists packed: the elimination tree and the row subtrees then walk
  /// their lists in order, without a lookup per neighbour.
  Graph renumbered(const std::vector<int32_t> &order,
                   const std::vector<int32_t> &index) const {
    int32_t n = size();
    Graph out;
    out.start.resize(static_cast<size_t>(n) + 1);
    out.length.resize(static_cast<size_t>(n));
    out.neighbours.resize(neighbours.size());
    int32_t used = 0;
    for (int32_t k = 0; k < n; ++k) {
      int32_t v = order[k];
      out.start[k] = used;
      out.length[k] = length[v];
      for (int32_t p = start[v]; p < end(v); ++p)
        out.neighbours[used++] = index[neighbours[p]];
    }
    out.start[n] = used;
    return out;
  }
};

/// AMD's fill-reducing order of a graph's vertices (order[k] is the one
/// eliminated k-th) and its count of L's entries below the diagonal.
struct Ordering {
  std::vector<int32_t> order;
  int64_t entriesBelow = 0;
};

/// AMD by amd_2 on a copy of the lists: amd_order would check the
/// pattern, build A + A^T and allocate its workspace again, which costs
/// more than the ordering itself on the graphs of small Newton systems (a
/// few hundred blocks).
Ordering minimumDegreeOrder(const Graph &graph) {
  int32_t n = graph.size();
  Ordering ordering;
  ordering.order.resize(static_cast<size_t>(n));
  if (n == 0)
    return ordering;
  // The lists, with the elbow room amd_order gives: a fifth of their
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
  amd_2(n, pe.data(), iw.data(), len.data(), room, used, nv, next,
        ordering.order.data(), head, elen, degree, w, control, info);
  // AMD's count is an upper bound (mass elimination), used as a capacity.
  ordering.entriesBelow = static_cast<int64_t>(info[AMD_LNZ]);
  return ordering;
}

/// The elimination tree of a graph numbered in elimination order (Liu's
/// algorithm with path compression); -1 for roots.
std::vector<int32_t> eliminationTree(const Graph &graph) {
  int32_t n = graph.size();
  std::vector<int32_t> parent(static_cast<size_t>(n), -1),
      ancestor(static_cast<size_t>(n), -1);
  for (int32_t k = 0; k < n; ++k)
    for (int32_t p = graph.start[k]; p < graph.end(k); ++p)
      for (int32_t i = graph.neighbours[p]; i != -1 && i < k;) {
        int32_t next = ancestor[i];
        ancestor[i] = k;
        if (next == -1)
          parent[i] = k;
        i = next;
      }
  return parent;
}

/// The vertices in a postorder of the forest in which each vertex's
/// children come by increasing weight (then index), roots by index: the
/// child with the most rows comes last, next to its parent, where it can
/// share its supernode (CHOLMOD's weighted postorder). Weights lie in
/// [0, n).
std::vector<int32_t> postorder(const std::vector<int32_t> &parent,
                               const std::vector<int32_t> &weight) {
  int32_t n = static_cast<int32_t>(parent.size());
  // The vertices by (weight, index), a counting sort; appended in that
  // order, each vertex's children come sorted.
  std::vector<int32_t> byWeightStart(static_cast<size_t>(n) + 1, 0);
  for (int32_t v = 0; v < n; ++v)
    ++byWeightStart[weight[v] + 1];
  std::partial_sum(byWeightStart.begin(), byWeightStart.end(),
                   byWeightStart.begin());
  std::vector<int32_t> byWeight(static_cast<size_t>(n));
  for (int32_t v = 0; v < n; ++v)
    byWeight[byWeightStart[weight[v]]++] = v;
  std::vector<int32_t> childStart(static_cast<size_t>(n) + 1, 0);
  for (int32_t v = 0; v < n; ++v)
    if (parent[v] != -1)
      ++childStart[parent[v] + 1];
  std::partial_sum(childStart.begin(), childStart.end(), childStart.begin());
  std::vector<int32_t> children(static_cast<size_t>(childStart[n]));
  std::vector<int32_t> fill(childStart.begin(), childStart.end() - 1);
  for (int32_t v : byWeight)
    if (parent[v] != -1)
      children[fill[parent[v]]++] = v;
  std::vector<int32_t> order, stack,
      nextChild(childStart.begin(), childStart.end() - 1);
  order.reserve(static_cast<size_t>(n));
  for (int32_t root = 0; root < n; ++root) {
    if (parent[root] != -1)
      continue;
    stack.push_back(root);
    while (!stack.empty()) {
      int32_t v = stack.back();
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
/// subtree). The graph is numbered in elimination order, `parent` its
/// tree.
template <typename Visit>
void rowSubtrees(const Graph &graph, const std::vector<int32_t> &parent,
                 Visit visit) {
  int32_t n = graph.size();
  std::vector<int32_t> mark(static_cast<size_t>(n), -1);
  for (int32_t i = 0; i < n; ++i) {
    mark[i] = i;
    for (int32_t p = graph.start[i]; p < graph.end(i); ++p)
      for (int32_t j = graph.neighbours[p]; j < i && mark[j] != i;
           j = parent[j]) {
        mark[j] = i;
        visit(j, i);
      }
  }
}

} // namespace

std::vector<int32_t> direct::minimumDegreeOrder(int64_t rows,
                                                const int32_t *rowptr,
                                                const int32_t *colidx) {
  return ::minimumDegreeOrder(Graph(static_cast<int32_t>(rows), rowptr, colidx))
      .order;
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
  int32_t n = static_cast<int32_t>(blockRows);
  SupernodalSymbolic symbolic;
  if (n == 0) {
    symbolic.first = symbolic.rowStart = symbolic.valueStart = {0};
    return symbolic;
  }
  // Fill-reducing order, then the elimination tree's postorder, which
  // keeps the fill and makes every supernode's columns consecutive.
  Graph graph(n, rowptr, colidx);
  Ordering amd = ::minimumDegreeOrder(graph);
  std::vector<int32_t> amdIndex(static_cast<size_t>(n));
  for (int32_t k = 0; k < n; ++k)
    amdIndex[amd.order[k]] = k;
  Graph eliminated = graph.renumbered(amd.order, amdIndex);
  std::vector<int32_t> tree = eliminationTree(eliminated);
  // L's entries below the diagonal in AMD's numbering, row by row, and
  // their count per column.
  std::vector<std::pair<int32_t, int32_t>> entriesBelow; // (column, row)
  entriesBelow.reserve(static_cast<size_t>(
      std::clamp<int64_t>(amd.entriesBelow, 0, int64_t(n) * (n - 1) / 2)));
  std::vector<int32_t> amdCount(static_cast<size_t>(n), 0);
  rowSubtrees(eliminated, tree, [&](int32_t j, int32_t i) {
    entriesBelow.emplace_back(j, i);
    ++amdCount[j];
  });
  std::vector<int32_t> post = postorder(tree, amdCount);
  std::vector<int32_t> blockOrder(static_cast<size_t>(n)),
      positionInPost(static_cast<size_t>(n)), count(static_cast<size_t>(n));
  for (int32_t k = 0; k < n; ++k) {
    blockOrder[k] = amd.order[post[k]];
    positionInPost[post[k]] = k;
    count[k] = amdCount[post[k]];
  }
  std::vector<int32_t> parent(static_cast<size_t>(n), -1);
  for (int32_t k = 0; k < n; ++k)
    if (tree[post[k]] != -1)
      parent[k] = positionInPost[tree[post[k]]];

  // The rows below the diagonal of each column in the postorder, sorted:
  // a column's rows are its ancestors in the tree, which come in the same
  // order in both numberings, and were visited in AMD's.
  std::vector<int64_t> columnStart(static_cast<size_t>(n) + 1, 0);
  for (int32_t k = 0; k < n; ++k)
    columnStart[k + 1] = columnStart[k] + count[k];
  std::vector<int32_t> belowRows(static_cast<size_t>(columnStart[n]));
  std::vector<int64_t> filled(columnStart.begin(), columnStart.end() - 1);
  for (auto [j, i] : entriesBelow)
    belowRows[filled[positionInPost[j]]++] = positionInPost[i];

  // Fundamental supernodes: a column joins the previous one's supernode
  // when it is that column's parent, its only child, and has one row less.
  std::vector<int32_t> children(static_cast<size_t>(n), 0);
  for (int32_t k = 0; k < n; ++k)
    if (parent[k] != -1)
      ++children[parent[k]];
  std::vector<int32_t> firstColumn; // of each supernode, in block columns
  for (int32_t k = 0; k < n; ++k)
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
  auto storedIn = [&](int32_t f, int32_t l) { // columns [f, l)
    int64_t entries = 0;
    for (int32_t c = f; c < l; ++c)
      entries += count[c] + 1;
    return entries;
  };
  std::vector<int32_t> merged{0};
  int64_t stored = storedIn(0, firstColumn[1]);
  for (size_t s = 1; s + 1 < firstColumn.size(); ++s) {
    int32_t f = merged.back(), l = firstColumn[s], next = firstColumn[s + 1];
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
  int64_t bs = blockSize, supernodes = static_cast<int64_t>(merged.size()) - 1;
  symbolic.permutation.resize(static_cast<size_t>(n * bs));
  for (int64_t k = 0; k < n; ++k)
    for (int64_t c = 0; c < bs; ++c)
      symbolic.permutation[k * bs + c] = blockOrder[k] * bs + c;
  symbolic.first.resize(static_cast<size_t>(supernodes) + 1);
  symbolic.rowStart.resize(static_cast<size_t>(supernodes) + 1);
  symbolic.valueStart.resize(static_cast<size_t>(supernodes) + 1);
  symbolic.first[0] = symbolic.rowStart[0] = symbolic.valueStart[0] = 0;
  for (int64_t s = 0; s < supernodes; ++s) {
    int64_t f = merged[s], l = merged[s + 1];
    int64_t height = (l - f + count[l - 1]) * bs;
    symbolic.first[s + 1] = l * bs;
    symbolic.rowStart[s + 1] = symbolic.rowStart[s] + height;
    symbolic.valueStart[s + 1] = symbolic.valueStart[s] + height * (l - f) * bs;
  }
  symbolic.rows.resize(static_cast<size_t>(symbolic.rowStart[supernodes]));
  int64_t *row = symbolic.rows.data();
  for (int64_t s = 0; s < supernodes; ++s) {
    int64_t f = merged[s], l = merged[s + 1];
    for (int64_t b = f * bs; b < l * bs; ++b)
      *row++ = b;
    for (int64_t p = columnStart[l - 1]; p < columnStart[l]; ++p)
      for (int64_t c = 0; c < bs; ++c)
        *row++ = belowRows[p] * bs + c;
  }
  return symbolic;
}
