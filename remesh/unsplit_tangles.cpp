#include "remesh/unsplit_tangles.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <utility>

namespace srcodec {

StatusOr<SemiRegularMesh> unsplit_tangles(const TriangleMesh& sides, const SemiRegularMesh& mesh,
                                          const UnsplitOptions& options, UnsplitReport* report) {
  if (sides.positions.empty() || sides.triangles.empty()) {
    if (report) *report = UnsplitReport{};
    return mesh;
  }
  return unsplit_tangles(FoldCounter::Sides(sides), mesh, options, report);
}

StatusOr<SemiRegularMesh> unsplit_tangles(const FoldCounter::Sides& sides, const SemiRegularMesh& mesh,
                                          const UnsplitOptions& options, UnsplitReport* report) {
  const auto start = std::chrono::steady_clock::now();
  UnsplitReport rep;
  auto done = [&](SemiRegularMesh out) -> StatusOr<SemiRegularMesh> {
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (report) *report = std::move(rep);
    return out;
  };
  const int32_t top = mesh.levels;
  const TriangleHierarchy& h = mesh.hierarchy;
  if (top < 1 || h.max_level() < top) return done(mesh);
  const std::vector<TriangleHierarchy::Node>& nodes = h.nodes();
  const std::vector<Eigen::Vector3d>& x = mesh.positions;

  // The finest level's tangled triangles, judged as the untangling judges.
  const std::vector<Eigen::Vector3d> side = sides.of(x);
  std::vector<int32_t> node_of;
  const std::vector<std::array<int32_t, 3>> finest = h.level_triangles(top, &node_of);
  std::vector<char> marked;
  rep.before = count_by_sides(x, side, finest, &marked);

  // The splits that may be undone: of level top - 1, whose children are all
  // leaves; and per vertex, those it is a corner of (its star).
  std::vector<char> candidate(nodes.size(), 0);
  std::vector<std::pair<int32_t, int32_t>> star_of;  // (corner, candidate), sorted
  for (size_t n = 0; n < nodes.size(); ++n) {
    const TriangleHierarchy::Node& node = nodes[n];
    if (node.level != top - 1 || node.first_child < 0) continue;  // (its children are leaves: top is the finest)
    candidate[n] = 1;
    for (int32_t v : node.v) star_of.emplace_back(v, static_cast<int32_t>(n));
  }
  std::sort(star_of.begin(), star_of.end());
  auto star = [&](int32_t v) {
    const auto lo = std::lower_bound(star_of.begin(), star_of.end(), std::make_pair(v, int32_t{-1}));
    std::vector<int32_t> out;
    for (auto it = lo; it != star_of.end() && it->first == v; ++it) out.push_back(it->second);
    return out;
  };
  // The most a star's children reach out of it: |m - (a + b) / 2| over
  // their new vertices m of edges (a, b), against |b - a|.
  auto reach_of = [&](const std::vector<int32_t>& s) {
    double most = 0.0;
    for (int32_t n : s)
      for (int32_t m : nodes[static_cast<size_t>(nodes[static_cast<size_t>(n)].first_child + 3)].v) {
        const std::array<int32_t, 2> e = h.parent_edge(m);
        const Eigen::Vector3d& a = x[static_cast<size_t>(e[0])];
        const Eigen::Vector3d& b = x[static_cast<size_t>(e[1])];
        most = std::max(most, (x[static_cast<size_t>(m)] - 0.5 * (a + b)).norm() / std::max((b - a).norm(), 1e-300));
      }
    return most;
  };

  // How many tangled children each candidate has.
  std::vector<int32_t> tangled_under(nodes.size(), 0);
  for (size_t t = 0; t < finest.size(); ++t) {
    const int32_t p = nodes[static_cast<size_t>(node_of[t])].parent;
    if (marked[t] && nodes[static_cast<size_t>(node_of[t])].level == top && candidate[static_cast<size_t>(p)])
      ++tangled_under[static_cast<size_t>(p)];
  }
  // For each tangled triangle, in order: the corner of its parent (of its
  // own node, where that is a leaf of level top - 1: left unsplit before,
  // or bisected by the closure) whose star holds most tangled children (the
  // lowest id on a tie), among those whose star has a split to undo and
  // reaches out by at most options.max_reach.
  std::vector<char> keep(nodes.size(), 1);
  auto take = [&](const std::array<int32_t, 3>& corners) {
    int32_t best = -1, best_score = -1;
    std::vector<int32_t> best_star;
    for (int32_t v : corners) {
      std::vector<int32_t> s = star(v);
      s.erase(std::remove_if(s.begin(), s.end(), [&](int32_t n) { return !keep[static_cast<size_t>(n)]; }), s.end());
      if (s.empty() || reach_of(s) > options.max_reach) continue;
      int32_t score = 0;
      for (int32_t n : s) score += tangled_under[static_cast<size_t>(n)];
      if (score > best_score || (score == best_score && v < best)) {
        best = v;
        best_score = score;
        best_star = std::move(s);
      }
    }
    if (best < 0) return;
    ++rep.stars;
    for (int32_t n : best_star) keep[static_cast<size_t>(n)] = 0;
  };
  for (size_t t = 0; t < finest.size(); ++t) {
    if (!marked[t]) continue;
    const TriangleHierarchy::Node& node = nodes[static_cast<size_t>(node_of[t])];
    int32_t p = -1;
    if (node.level == top && candidate[static_cast<size_t>(node.parent)]) p = node.parent;
    else if (node.level == top - 1 && node.first_child < 0) p = node_of[t];
    if (p < 0 || (p != node_of[t] && !keep[static_cast<size_t>(p)])) continue;
    take(nodes[static_cast<size_t>(p)].v);
  }
  if (options.coarser)
    for (int32_t level = top - 1; level >= 1; --level) {
      const std::vector<std::array<int32_t, 3>> coarse = h.level_triangles(level);
      std::vector<char> coarse_marked;
      count_by_sides(x, side, coarse, &coarse_marked);
      for (size_t t = 0; t < coarse.size(); ++t)
        if (coarse_marked[t]) take(coarse[t]);
    }
  if (rep.stars == 0) return done(mesh);

  // The result: the stars unsplit, with the closure's splits (a star
  // triangle left with two split neighbours is split again).
  std::vector<int32_t> old_vertex, old_node;
  SemiRegularMesh out;
  SRCODEC_ASSIGN_OR_RETURN(out.hierarchy, h.replayed(keep, &old_vertex, &old_node));
  out.base = mesh.base;
  out.levels = mesh.levels;
  out.positions.resize(old_vertex.size());
  for (size_t v = 0; v < old_vertex.size(); ++v) out.positions[v] = x[static_cast<size_t>(old_vertex[v])];
  const std::vector<TriangleHierarchy::Node>& now = out.hierarchy.nodes();
  for (size_t n = 0; n < now.size(); ++n) rep.undone += !keep[static_cast<size_t>(old_node[n])] && now[n].first_child < 0;
  return done(std::move(out));
}

}  // namespace srcodec
