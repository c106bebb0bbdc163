#include "remesh/measured_coarsening.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include "remesh/geometry.h"
#include "remesh/levels_to_move.h"
#include "remesh/nearest_triangle.h"

namespace srcodec {
namespace {

// The mean of f over triangle abc by the centroids of its n x n sub-triangles.
template <class F>
double grid_mean(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int n, F&& f) {
  double sum = 0.0;
  for_each_subtriangle_centroid(a, b, c, n, [&](const Eigen::Vector3d& p) { sum += f(p); });
  return sum / (n * n);
}

// Per triangle: its area times its mean squared distance to the input (0 for
// the triangles `skip` marks), by the centroids of its 2 x 2 sub-triangles
// (4 x 4 for those `larger` marks).
// The error is heavy-tailed (a flap standing off the input can hold most
// of it): the triangles holding the largest 2% of it, whose distance varies
// most across them, are measured again on an 8 x 8 grid, with the exact
// search (a few random samples per triangle put the error off).
std::vector<double> squared_to_input(const std::vector<Eigen::Vector3d>& x,
                                     const std::vector<std::array<int32_t, 3>>& triangles, const std::vector<char>& skip,
                                     const NearestTriangle& input, const std::vector<char>* larger = nullptr) {
  std::vector<double> out(triangles.size(), 0.0);
  auto measure = [&](size_t t, int n, bool exact) {
    const auto& tri = triangles[t];
    out[t] = triangle_area(x, tri) * grid_mean(x[tri[0]], x[tri[1]], x[tri[2]], n, [&](const Eigen::Vector3d& p) {
               return exact ? input.exact(p).squared : input(p).squared;
             });
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t != r.end(); ++t)
      if (!skip[t]) measure(t, larger && (*larger)[t] ? 4 : 2, false);
  });
  std::vector<int32_t> largest(triangles.size());
  std::iota(largest.begin(), largest.end(), 0);
  const size_t count = std::min(largest.size(), largest.size() / 50 + 1);
  std::partial_sort(largest.begin(), largest.begin() + static_cast<std::ptrdiff_t>(count), largest.end(),
                    [&](int32_t a, int32_t b) { return out[a] > out[b] || (out[a] == out[b] && a < b); });
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 64), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t k = r.begin(); k != r.end(); ++k)
      if (!skip[largest[k]]) measure(largest[k], 8, true);
  });
  return out;
}

// Each triangle's part of the mean square both ways, as the metric weighs
// them: its own distance to the input (`to_input`, squared_to_input's, per
// unit of the mesh's `area`) and the input's samples nearest it (found by
// `near`, a search over the same triangles; per sample).
std::vector<double> error_share(const std::vector<double>& to_input, double area, const NearestTriangle& near,
                                const std::vector<Eigen::Vector3d>& samples) {
  std::vector<double> out(to_input.size());
  for (size_t t = 0; t < out.size(); ++t) out[t] = area > 0.0 ? to_input[t] / area : 0.0;
  std::vector<NearestTriangle::Hit> hits(samples.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) hits[i] = near(samples[i]);
  });
  const double per_sample = 1.0 / static_cast<double>(std::max<size_t>(samples.size(), 1));
  for (const NearestTriangle::Hit& hit : hits)  // in order: the sums do not depend on the threads
    if (hit.triangle >= 0) out[hit.triangle] += hit.squared * per_sample;
  return out;
}

// The mesh with its finest level's triangles that hold the most error
// (`fraction` of them, by `share`, error_share's over the finest level's
// triangles, which come from the nodes `node_of`) split once more, with the
// balance and closure splits they bring. The new vertices start at their
// parent edge's midpoint and are fitted (the others stay where they are);
// without `fit`, they go to the input point nearest it instead. `split`:
// how many were chosen.
SemiRegularMesh deepened(const TriangleMesh& input, const TriangleMesh& sides, const SemiRegularMesh& mesh,
                         const std::vector<int32_t>& node_of, const std::vector<double>& share,
                         const NearestTriangle& near_input, double fraction, const FitOptions* fit, size_t* split) {
  *split = 0;
  const int32_t top = mesh.levels;
  std::vector<int32_t> order(share.size());
  std::iota(order.begin(), order.end(), 0);
  const size_t count = std::min(share.size(), static_cast<size_t>(fraction * static_cast<double>(share.size())));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(),
                    [&](int32_t a, int32_t b) { return share[a] > share[b] || (share[a] == share[b] && a < b); });
  SemiRegularMesh out = mesh;
  const auto& nodes = out.hierarchy.nodes();
  const int32_t old_vertices = out.hierarchy.vertex_count();
  for (size_t k = 0; k < count; ++k) {
    const int32_t n = node_of[order[k]];
    if (nodes[n].level != top || nodes[n].first_child >= 0) continue;  // a green half's node, or split already
    out.hierarchy.split(n);
    ++*split;
  }
  if (*split == 0) return mesh;
  out.levels = out.hierarchy.max_level();
  out.positions.resize(static_cast<size_t>(out.hierarchy.vertex_count()));
  for (int32_t v = old_vertices; v < out.hierarchy.vertex_count(); ++v) {  // parents come first
    const auto [a, b] = out.hierarchy.parent_edge(v);
    const Eigen::Vector3d mid = 0.5 * (out.positions[a] + out.positions[b]);
    out.positions[v] = fit ? mid : near_input.exact(mid).point;
  }
  if (!fit) return out;
  const LevelsToMove moving =
      levels_to_move(out.hierarchy, out.levels, out.base.positions.size(), out.positions.size(), out.crease_edges);
  std::vector<char> fixed = moving.fixed;
  std::fill(fixed.begin(), fixed.begin() + old_vertices, 1);
  fit_to_surface(input, sides, moving.triangles, fixed, &out.positions, *fit, &near_input);
  return out;
}

// The candidates (split nodes whose splits may be undone) of the hierarchy
// `h` whose finest level is `top`, and the coarser and finer meshes they are
// compared on.
struct Candidates {
  std::vector<int32_t> coarse_node, fine_node;
  std::vector<std::array<int32_t, 3>> coarse, fine;
  std::vector<int32_t> candidate_of, candidates;  // per node its candidate (-1: none); per candidate its node
  size_t m = 0;                                    // candidates.size()
  std::vector<int32_t> coarse_candidate, fine_candidate;  // per triangle, the candidate over it (-1: none)
};

Candidates find_candidates(const TriangleHierarchy& h, int32_t top, bool deeper) {
  Candidates out;
  std::vector<int32_t>& coarse_node = out.coarse_node;
  std::vector<int32_t>& fine_node = out.fine_node;
  std::vector<std::array<int32_t, 3>>& coarse = out.coarse;
  std::vector<std::array<int32_t, 3>>& fine = out.fine;
  std::vector<int32_t>& candidate_of = out.candidate_of;
  std::vector<int32_t>& candidates = out.candidates;
  size_t& m = out.m;
  std::vector<int32_t>& coarse_candidate = out.coarse_candidate;
  std::vector<int32_t>& fine_candidate = out.fine_candidate;
  const auto& nodes = h.nodes();
  coarse = h.level_triangles(top - 1, &coarse_node);
  fine = h.level_triangles(top, &fine_node);

  // The candidates: split nodes of level top - 1, whose children are leaves,
  // that are one whole triangle of the coarser mesh (not bisected there);
  // after deepening also those of level top - 2 whose children are leaves.
  std::vector<int32_t> pieces(nodes.size(), 0);
  for (int32_t n : coarse_node) ++pieces[n];
  candidate_of.assign(nodes.size(), -1);
  for (size_t n = 0; n < nodes.size(); ++n) {
    const TriangleHierarchy::Node& node = nodes[n];
    const bool whole = node.level == top - 1 && pieces[n] == 1;
    if (node.first_child < 0 || !(whole || (deeper && node.level == top - 2))) continue;
    bool leaves = true;
    for (int c = 0; c < 4; ++c) leaves &= nodes[node.first_child + c].first_child < 0;
    if (!leaves) continue;
    candidate_of[n] = static_cast<int32_t>(candidates.size());
    candidates.push_back(static_cast<int32_t>(n));
  }
  m = candidates.size();
  if (deeper) {  // the coarser mesh has the candidates of level top - 2 whole
    std::vector<std::array<int32_t, 3>> merged;
    std::vector<int32_t> merged_node;
    std::vector<char> placed(nodes.size(), 0);
    for (size_t t = 0; t < coarse.size(); ++t) {
      const int32_t p = nodes[coarse_node[t]].parent;
      if (p >= 0 && candidate_of[p] >= 0) {
        if (!placed[p]) {
          placed[p] = 1;
          merged.push_back(nodes[p].v);
          merged_node.push_back(p);
        }
        continue;
      }
      merged.push_back(coarse[t]);
      merged_node.push_back(coarse_node[t]);
    }
    coarse.swap(merged);
    coarse_node.swap(merged_node);
  }
  coarse_candidate.resize(coarse.size());
  fine_candidate.resize(fine.size());
  for (size_t t = 0; t < coarse.size(); ++t) coarse_candidate[t] = candidate_of[coarse_node[t]];
  for (size_t t = 0; t < fine.size(); ++t) {
    const int32_t p = nodes[fine_node[t]].parent;
    fine_candidate[t] = p >= 0 ? candidate_of[p] : -1;
  }
  return out;
}

// Mean squares per candidate, of its triangle and of its four children,
// both ways: samples of the input to the coarser and the finer mesh, and
// points of each mesh to the input; `rest`, where both meshes are the same.
struct SplitErrors {
  std::vector<double> in_coarse, in_fine, remesh_coarse, remesh_fine;
  double in_rest = 0.0, remesh_rest = 0.0;
  double fresh_in_full = 0.0;  // with fresh_mean_square: the fresh samples' to the finer mesh
  double fine_area = 0.0;
};

SplitErrors measure_splits(const std::vector<Eigen::Vector3d>& x, const Candidates& cand,
                           const std::vector<Eigen::Vector3d>& samples, const NearestTriangle& near_input,
                           const std::function<double(const NearestTriangle&)>* fresh_mean_square) {
  SplitErrors out;
  std::vector<double>& in_coarse = out.in_coarse;
  std::vector<double>& in_fine = out.in_fine;
  std::vector<double>& remesh_coarse = out.remesh_coarse;
  std::vector<double>& remesh_fine = out.remesh_fine;
  double& in_rest = out.in_rest;
  double& remesh_rest = out.remesh_rest;
  double& fresh_in_full = out.fresh_in_full;
  double& fine_area = out.fine_area;
  const size_t m = cand.m;
  const auto& coarse = cand.coarse;
  const auto& fine = cand.fine;
  const auto& coarse_candidate = cand.coarse_candidate;
  const auto& fine_candidate = cand.fine_candidate;
  // Samples of the input to the coarser and the finer mesh: each sample's
  // squared distances go to the candidate under its nearest coarser
  // triangle (elsewhere both meshes are the same there).
  in_coarse.assign(m, 0.0);
  in_fine.assign(m, 0.0);
  remesh_coarse.assign(m, 0.0);
  remesh_fine.assign(m, 0.0);
  {
    const NearestTriangle near_coarse(x, coarse), near_fine(x, fine);
    if (fresh_mean_square) fresh_in_full = (*fresh_mean_square)(near_fine);
    std::vector<int32_t> under(samples.size(), -1);
    std::vector<double> d_coarse(samples.size(), 0.0), d_fine(samples.size(), 0.0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        const NearestTriangle::Hit c = near_coarse(samples[i]);
        under[i] = c.triangle >= 0 ? coarse_candidate[c.triangle] : -1;
        d_coarse[i] = c.squared;
        d_fine[i] = near_fine(samples[i]).squared;
      }
    });
    for (size_t i = 0; i < samples.size(); ++i) {  // in order: the sums do not depend on the threads
      if (under[i] < 0) {
        in_rest += d_fine[i];
        continue;
      }
      in_coarse[under[i]] += d_coarse[i];
      in_fine[under[i]] += d_fine[i];
    }
  }
  // Samples of the remesh to the input: over each candidate's triangle and
  // over its four children, weighted by area.
  std::vector<char> skip(coarse.size());
  for (size_t t = 0; t < coarse.size(); ++t) skip[t] = coarse_candidate[t] < 0;
  const std::vector<double> coarse_sq = squared_to_input(x, coarse, skip, near_input);
  const std::vector<double> fine_sq = squared_to_input(x, fine, std::vector<char>(fine.size(), 0), near_input);
  for (size_t t = 0; t < coarse.size(); ++t)
    if (coarse_candidate[t] >= 0) remesh_coarse[coarse_candidate[t]] += coarse_sq[t];
  for (size_t t = 0; t < fine.size(); ++t) {
    fine_area += triangle_area(x, fine[t]);
    if (fine_candidate[t] >= 0) remesh_fine[fine_candidate[t]] += fine_sq[t];
    else remesh_rest += fine_sq[t];
  }
  return out;
}

// The first k in that order kept split (and those `forced`), with the
// splits their balance and closure need: the hierarchy, its nodes' and
// vertices' old ids, and the loss.
// Per candidate: kForced, kept split whatever its place in the order (the
// rounds below), or kBarred, never kept (a deeper split whose children fold).
// Per candidate: kForced, kept split whatever its place in the order (the
// rounds of coarsened()), or kBarred, never kept (a deeper split whose
// children fold).
constexpr char kForced = 1, kBarred = 2;
struct Choice {
  TriangleHierarchy hierarchy;
  std::vector<int32_t> old_vertex, old_node;
  double loss_db = 0.0;
  size_t split = 0;
  size_t kept_for_folds = 0;
};

// The choices of splits to keep, over the candidates in order of gain.
struct SplitChooser {
  const TriangleHierarchy& h;
  int32_t top;
  bool deeper;
  const Candidates& cand;
  const std::vector<int32_t>& order;  // the candidates, most gain first
  size_t useful;                      // the first `useful` of them may be kept for the budget
  std::function<double(const std::vector<char>&)> loss_db_of;  // of the candidates kept split
  const FoldCounter& folds;
  const std::vector<Eigen::Vector3d>& x;
  std::vector<char> forced = std::vector<char>(cand.m, 0);

  StatusOr<Choice> choose(size_t k) const;
  StatusOr<Choice> fewest(double budget_db) const;
  StatusOr<Choice> coarsened(double budget_db);
};

StatusOr<Choice> SplitChooser::choose(size_t k) const {
  const auto& nodes = h.nodes();
  const size_t m = cand.m;
  const auto& candidates = cand.candidates;
  const auto& candidate_of = cand.candidate_of;
  std::vector<char> keep(nodes.size(), 1);
  for (size_t j = 0; j < m; ++j)
    if (j < k ? forced[order[j]] == kBarred : forced[order[j]] != kForced) keep[candidates[order[j]]] = 0;
  Choice c;
  SRCODEC_ASSIGN_OR_RETURN(c.hierarchy, h.replayed(keep, &c.old_vertex, &c.old_node));
  std::vector<char> split(m, 0);
  for (size_t n = 0; n < c.old_node.size(); ++n) {
    const int32_t at = candidate_of[c.old_node[n]];
    if (at >= 0 && c.hierarchy.nodes()[n].first_child >= 0) split[at] = 1;
  }
  c.loss_db = loss_db_of(split);
  c.split = static_cast<size_t>(std::count(split.begin(), split.end(), 1));
  return c;
}

// The fewest splits in that order whose loss is within the limit (all of
// them are).
// After deepening, the splits that gain nothing (a deeper split can lose,
// where it lies across a cleft) are never kept for the budget, even when
// it cannot be met without them.
StatusOr<Choice> SplitChooser::fewest(double budget_db) const {
  size_t lo = 0, hi = useful;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    SRCODEC_ASSIGN_OR_RETURN(Choice c, choose(mid));
    if (c.loss_db <= budget_db) hi = mid;
    else lo = mid + 1;
  }
  return choose(lo);
}

// The fewest splits within `budget_db`, then those put back where undoing
// them folded or pleated a triangle: a candidate left unsplit, or bisected
// by the closure, under a marked triangle of the finest level (the fit kept
// the full refinement's levels from folding, not a mix of them). Then the
// fewest splits again: those put back may gain nothing (their children
// fold or pleat instead). After deepening, a deeper split kept whose
// children fold or pleat is barred instead.
StatusOr<Choice> SplitChooser::coarsened(double budget_db) {
  const auto& nodes = h.nodes();
  const auto& candidate_of = cand.candidate_of;
  std::fill(forced.begin(), forced.end(), 0);
  size_t kept = 0;
  SRCODEC_ASSIGN_OR_RETURN(Choice best, fewest(budget_db));
  for (int round = 0; round < 8; ++round) {
    std::vector<int32_t> node_of;
    std::vector<Eigen::Vector3d> at(best.old_vertex.size());
    for (size_t v = 0; v < at.size(); ++v) at[v] = x[best.old_vertex[v]];
    const std::vector<std::array<int32_t, 3>> finest = best.hierarchy.level_triangles(top, &node_of);
    std::vector<char> marked;
    folds(at, finest, &marked);
    size_t more = 0;
    for (size_t t = 0; t < finest.size(); ++t) {
      if (!marked[t]) continue;
      const int32_t was = best.old_node[node_of[t]];
      const int32_t c = candidate_of[was];
      if (c >= 0 && !forced[c]) {
        forced[c] = kForced;
        ++more;
      }
      // After deepening: a deeper split kept whose child folds or pleats.
      const int32_t p = nodes[was].parent;
      const int32_t d = deeper && c < 0 && p >= 0 && nodes[p].level == top - 1 ? candidate_of[p] : -1;
      if (d >= 0 && !forced[d]) {
        forced[d] = kBarred;
        ++more;
      }
    }
    if (more == 0) break;
    kept += more;
    SRCODEC_ASSIGN_OR_RETURN(best, fewest(budget_db));
  }
  best.kept_for_folds = kept;
  return best;
}

// A choice made a mesh; with options.refit, its vertices at the corners of
// the finest level's unsplit triangles fitted again (they were fitted to
// the children around them), and its loss measured again.
struct Result {
  SemiRegularMesh mesh;
  Choice choice;
  double loss_db = 0.0;
  size_t refit = 0;
};

struct Refit {
  const SemiRegularMesh& mesh;
  const std::vector<Eigen::Vector3d>& x;  // the positions of the mesh the choices replay
  const std::vector<int32_t>& candidate_of;
  const CoarseningOptions& options;
  const TriangleMesh& input;
  const TriangleMesh& sides;
  const NearestTriangle& near_input;
  // A mesh's loss by fresh samples (positions, finest triangles, which of
  // them are unsplit).
  std::function<double(const std::vector<Eigen::Vector3d>&, const std::vector<std::array<int32_t, 3>>&,
                       const std::vector<char>&)>
      loss_of;

  Result operator()(Choice choice, double* loss_before_refit) const;
};

Result Refit::operator()(Choice choice, double* loss_before_refit) const {
  Result r;
  r.mesh.base = mesh.base;
  r.mesh.positions.resize(choice.old_vertex.size());
  for (size_t v = 0; v < choice.old_vertex.size(); ++v) r.mesh.positions[v] = x[choice.old_vertex[v]];
  r.mesh.levels = choice.hierarchy.max_level();
  r.mesh.hierarchy = std::move(choice.hierarchy);
  r.loss_db = choice.loss_db;
  r.choice = std::move(choice);
  if (loss_before_refit) *loss_before_refit = r.loss_db;
  if (!options.refit || r.mesh.levels < 1) return r;
  const LevelsToMove moving =
      levels_to_move(r.mesh.hierarchy, r.mesh.levels, r.mesh.base.positions.size(), r.mesh.positions.size(),
                     r.mesh.crease_edges);
  const auto& finest = moving.triangles.back();
  // The finest level's triangles left unsplit: candidates now whole
  // (their corners are coarser than the children around them; after
  // deepening, those of the deeper splits undone were fitted to the levels
  // asked, and fitting them again to the mesh around them gains: fewer
  // triangles at the same loss).
  std::vector<int32_t> node_of;
  r.mesh.hierarchy.level_triangles(r.mesh.levels, &node_of);
  const auto& now = r.mesh.hierarchy.nodes();
  std::vector<char> unsplit(finest.size());
  for (size_t t = 0; t < finest.size(); ++t) {
    const int32_t n = node_of[t];
    const int32_t was = r.choice.old_node[n];
    unsplit[t] = candidate_of[was] >= 0 &&
                 std::all_of(finest[t].begin(), finest[t].end(),
                             [&](int32_t v) { return r.mesh.hierarchy.vertex_level(v) <= now[n].level; });
  }
  std::vector<char> fixed(r.mesh.positions.size(), 1);
  for (size_t t = 0; t < finest.size(); ++t)
    if (unsplit[t])
      for (int32_t v : finest[t]) fixed[v] = moving.fixed[v];
  r.refit = static_cast<size_t>(std::count(fixed.begin(), fixed.end(), 0));
  if (r.refit == 0) return r;
  if (loss_before_refit) *loss_before_refit = loss_of(r.mesh.positions, finest, unsplit);
  fit_to_surface(input, sides, moving.triangles, fixed, &r.mesh.positions, options.fit, &near_input);
  r.loss_db = loss_of(r.mesh.positions, finest, unsplit);
  return r;
}

// The mean of the squared distances of `fresh` (samples of the input) to
// the mesh `near` searches (0 with no samples).
double mean_square_from(const std::vector<Eigen::Vector3d>& fresh, const NearestTriangle& near) {
  std::vector<double> d(fresh.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, fresh.size(), 4096), [&](const tbb::blocked_range<size_t>& b) {
    for (size_t i = b.begin(); i != b.end(); ++i) d[i] = near(fresh[i]).squared;
  });
  return std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(std::max<size_t>(fresh.size(), 1));
}

// `mesh` with the triangles of its finest level (`asked`, from nodes
// `asked_node`) that hold the most error split once more (deepened()); with
// `fresh`, also the full refinement's mean square by those samples, in
// `fresh_reference`.
SemiRegularMesh deepen_worst(const TriangleMesh& input, const TriangleMesh& sides, const SemiRegularMesh& mesh,
                             const std::vector<std::array<int32_t, 3>>& asked, const std::vector<int32_t>& asked_node,
                             const std::vector<Eigen::Vector3d>& samples, const NearestTriangle& near_input,
                             const CoarseningOptions& options, const std::vector<Eigen::Vector3d>* fresh,
                             size_t* deepened_count, double* fresh_reference) {
  // The levels asked measured once, for the choice of triangles and the whole.
  const NearestTriangle near_asked(mesh.positions, asked);
  const std::vector<double> to_input =
      squared_to_input(mesh.positions, asked, std::vector<char>(asked.size(), 0), near_input);
  double area = 0.0;
  for (const auto& t : asked) area += triangle_area(mesh.positions, t);
  SemiRegularMesh deep =
      deepened(input, sides, mesh, asked_node, error_share(to_input, area, near_asked, samples), near_input,
               options.deepen_fraction, options.refit ? &options.fit : nullptr, deepened_count);
  if (*deepened_count > 0 && fresh)
    *fresh_reference =
        std::max(mean_square_from(*fresh, near_asked), std::accumulate(to_input.begin(), to_input.end(), 0.0) / area);
  return deep;
}

}  // namespace

StatusOr<SemiRegularMesh> coarsen_by_measured_error(const TriangleMesh& input, const TriangleMesh& sides,
                                                    const SemiRegularMesh& mesh, const CoarseningOptions& options,
                                                    CoarseningReport* report) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.max_loss_db > 0.0 && options.max_loss_db <= 60.0))
    return invalid_argument("coarsening: the loss allowed is " + std::to_string(options.max_loss_db) +
                            " dB; use more than 0 and at most 60");
  CoarseningReport rep;
  SemiRegularMesh out = mesh;
  const FoldCounter folds(sides);  // for the rounds that put splits back, and the result's count
  auto finish = [&]() -> StatusOr<SemiRegularMesh> {
    const std::vector<std::array<int32_t, 3>> finest = out.hierarchy.level_triangles(out.levels);
    rep.triangles_after = finest.size();
    rep.folds = folds(out.positions, finest);
    rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (report) *report = rep;
    return out;
  };
  std::vector<int32_t> asked_node;  // the levels asked: their finest triangles, and the nodes they come from
  const std::vector<std::array<int32_t, 3>> asked = mesh.hierarchy.level_triangles(mesh.levels, &asked_node);
  rep.triangles_before = asked.size();
  if (mesh.levels < 1 || input.triangles.empty() || mesh.hierarchy.max_level() != mesh.levels) return finish();
  const NearestTriangle near_input(input.positions, input.triangles, /*exact_search=*/true);
  const std::vector<Eigen::Vector3d> samples =
      surface_samples(input, options.input_samples_per_vertex * mesh.positions.size(), options.seed);
  // Fresh samples of the input, for the refit's whole measure (below).
  std::vector<Eigen::Vector3d> fresh;
  if (options.refit) fresh = surface_samples(input, samples.size(), options.seed + 1);
  auto mean_square_to = [&](const NearestTriangle& near) { return mean_square_from(fresh, near); };
  // Deeper where it pays: the loss is then judged against `mesh`, measured
  // whole here (as `full` and `fresh_full` below measure the full refinement).
  SemiRegularMesh deep;
  double fresh_reference = 0.0;
  if (options.deepen_fraction > 0.0)
    deep = deepen_worst(input, sides, mesh, asked, asked_node, samples, near_input, options,
                        options.refit ? &fresh : nullptr, &rep.deepened, &fresh_reference);
  const bool deeper = rep.deepened > 0;
  const SemiRegularMesh& src = deeper ? deep : mesh;
  if (deeper) out = src;
  const int32_t top = src.levels;
  const TriangleHierarchy& h = src.hierarchy;
  const std::vector<Eigen::Vector3d>& x = src.positions;
  const Candidates cand = find_candidates(h, top, deeper);
  const auto& nodes = h.nodes();
  const std::vector<std::array<int32_t, 3>>& fine = cand.fine;
  const std::vector<int32_t>& candidates = cand.candidates;
  const size_t& m = cand.m;
  const std::vector<int32_t>& fine_candidate = cand.fine_candidate;
  rep.candidates = m;
  if (m == 0) return finish();

  const std::function<double(const NearestTriangle&)> fresh_mean_square = mean_square_to;
  const SplitErrors errors =
      measure_splits(x, cand, samples, near_input, options.refit ? &fresh_mean_square : nullptr);
  const std::vector<double>& in_coarse = errors.in_coarse;
  const std::vector<double>& in_fine = errors.in_fine;
  const std::vector<double>& remesh_coarse = errors.remesh_coarse;
  const std::vector<double>& remesh_fine = errors.remesh_fine;
  const double in_rest = errors.in_rest, remesh_rest = errors.remesh_rest;
  const double fresh_in_full = errors.fresh_in_full, fine_area = errors.fine_area;
  if (samples.empty() || !(fine_area > 0.0)) return finish();

  // Mean squares both ways for a choice of splits, and the loss against all.
  const double per_sample = 1.0 / static_cast<double>(samples.size()), per_area = 1.0 / fine_area;
  auto mean_square = [&](const std::vector<char>& split) {
    double in = in_rest, rm = remesh_rest;
    for (size_t c = 0; c < m; ++c) {
      in += split[c] ? in_fine[c] : in_coarse[c];
      rm += split[c] ? remesh_fine[c] : remesh_coarse[c];
    }
    return std::max(in * per_sample, rm * per_area);
  };
  // The full refinement's: after deepening, without the deeper splits.
  std::vector<char> reference(m, 1);
  if (deeper)
    for (size_t c = 0; c < m; ++c) reference[c] = nodes[candidates[c]].level != top - 1;
  const double full = mean_square(reference);
  if (!(full > 0.0)) return finish();
  std::vector<double> gain(m);
  for (size_t c = 0; c < m; ++c)
    gain[c] = (in_coarse[c] - in_fine[c]) * per_sample + (remesh_coarse[c] - remesh_fine[c]) * per_area;
  // After deepening, the deeper splits whose children fold or pleat (judged
  // as the fit judges them) count as gaining nothing.
  if (deeper) {
    std::vector<char> marked;
    folds(x, fine, &marked);
    for (size_t t = 0; t < fine.size(); ++t) {
      const int32_t c = fine_candidate[t];
      if (marked[t] && c >= 0 && nodes[candidates[c]].level == top - 1) gain[c] = std::min(gain[c], 0.0);
    }
  }
  std::vector<int32_t> order(m);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return gain[a] > gain[b]; });

  const size_t useful =
      deeper ? static_cast<size_t>(std::count_if(gain.begin(), gain.end(), [](double g) { return g > 0.0; })) : m;
  auto loss_db_of = [&](const std::vector<char>& split) { return 10.0 * std::log10(mean_square(split) / full); };
  SplitChooser chooser{h, top, deeper, cand, order, useful, loss_db_of, folds, x};
  auto coarsened = [&](double budget_db) { return chooser.coarsened(budget_db); };
  // The full refinement's mean square by the fresh samples.
  double remesh_full = remesh_rest;
  for (size_t c = 0; c < m; ++c) remesh_full += remesh_fine[c];
  const double fresh_full =
      !options.refit ? full : deeper ? fresh_reference : std::max(fresh_in_full, remesh_full * per_area);
  // A mesh's loss: mean squares both ways, as `full`'s, but by fresh samples of
  // the input (those that chose the splits to undo favour their own
  // choice; on the smooth scans the remesh's side decides, and nothing
  // changed), and the unsplit triangles measured on a grid as fine as
  // their children's (a coarser grid puts the loss below the metric's).
  auto loss_of = [&](const std::vector<Eigen::Vector3d>& p, const std::vector<std::array<int32_t, 3>>& finest,
                     const std::vector<char>& unsplit) {
    const std::vector<double> sq = squared_to_input(p, finest, std::vector<char>(finest.size(), 0), near_input, &unsplit);
    const double rm = std::accumulate(sq.begin(), sq.end(), 0.0) * per_area;
    return 10.0 * std::log10(std::max(mean_square_to(NearestTriangle(p, finest)), rm) / fresh_full);
  };
  const Refit made{mesh, x, cand.candidate_of, options, input, sides, near_input, loss_of};
  SRCODEC_ASSIGN_OR_RETURN(Choice first, coarsened(options.max_loss_db));
  Result best = made(std::move(first), &rep.estimated_loss_before_refit_db);
  // The refitted mesh, measured whole, is further from the limit than the
  // choice's estimate (by the pieces of each candidate, which is cautious,
  // and the refit gains more):
  // undo more splits, budgeting as much more as the gap to whole_margin x
  // the limit (half as much after a try that went past it), while the
  // refitted result stays within that.
  const double limit = options.whole_margin * options.max_loss_db;
  double budget = options.max_loss_db, step = limit - best.loss_db;
  for (int pass = 1; pass < options.refit_passes && best.refit > 0 && step > 0.0; ++pass) {
    SRCODEC_ASSIGN_OR_RETURN(Choice more, coarsened(budget + step));
    if (more.split >= best.choice.split) break;
    Result r = made(std::move(more), nullptr);
    if (!(r.loss_db <= limit)) {
      step *= 0.5;
      continue;
    }
    budget += step;
    best = std::move(r);
    step = limit - best.loss_db;
    ++rep.passes;
  }
  rep.undone = m - best.choice.split;
  rep.kept_for_folds = best.choice.kept_for_folds;
  rep.estimated_loss_db = best.loss_db;
  rep.refit = best.refit;
  out = std::move(best.mesh);
  return finish();
}

}  // namespace srcodec
