// Repairs of the folds and pleats the refinement leaves (ours, not in the
// paper): where the base mesh's parameterization is stretched, a new vertex
// starts on the wrong side of its neighbours and Lloyd, which only refuses
// moves that fold more, cannot bring it back. In rounds, while they leave
// fewer: single sites moved to other input vertices, off the input to their
// neighbours' mean, patches smoothed, patches put back at their edges'
// midpoints, and on the last level patches redrawn (patch_reparam.cpp).
// Folds and pleats are judged as remesh/folds.h defines them.
#include "remesh/refiner.h"
#include "remesh/parallel_flags.h"

namespace srcodec {

void Refiner::count_tangles(RefineLevelReport& lr) const {
  const std::vector<char> fine = folded_flags(triangles_);
  lr.folded_triangles = static_cast<size_t>(std::count(fine.begin(), fine.end(), 1));
  lr.folded_by_nearest_input = folded_by_nearest_input();
  lr.pleats = pleats().size();
  lr.coarse_folded_triangles = 0;
  for (const auto& level_tris : coarse_triangles_) {
    const std::vector<char> coarse = folded_flags(level_tris);
    lr.coarse_folded_triangles += static_cast<size_t>(std::count(coarse.begin(), coarse.end(), 1));
  }
}

std::vector<char> Refiner::folded_flags(const std::vector<std::array<int32_t, 3>>& triangles) const {
  return parallel_flags(triangles.size(), [&](size_t t) { return folded(triangles[t], -1, -1); });
}

void Refiner::untangle(int32_t level, RefineLevelReport& lr) {
  repair_rounds(lr);
  if (level == 0 || folded_triangles().empty()) return;
  for (int rings : {0, 1, 2, 4, 8, 16})
    if (!for_each_tangle_patch(rings, [&](const std::vector<int32_t>& patch) {
          lr.midpoint_resets += midpoint_patch(patch, level);
        }))
      return;
  repair_rounds(lr);
  if (level != options_.levels || folded_triangles().empty()) return;
  for (int rings : {0, 1, 2, 4, 8, 16})
    if (!for_each_tangle_patch(
            rings, [&](const std::vector<int32_t>& patch) { lr.reparameterized += reparam_patch(patch, level); }, false))
      return;
  repair_rounds(lr);
}

void Refiner::repair_rounds(RefineLevelReport& lr) {
  constexpr int kRounds = 4;
  size_t before = folded_triangles().size() + pleats().size();
  for (int round = 0; round < kRounds && before > 0; ++round) {
    untangle_on_input(lr);
    smooth_tangles(lr);  // before leaving the surface: a site off the input is what the smoothing cannot undo
    untangle_off_input(lr);
    const size_t after = folded_triangles().size() + pleats().size();
    if (after >= before) return;
    before = after;
  }
}

void Refiner::untangle_on_input(RefineLevelReport& lr) {
  constexpr int kPasses = 8;
  constexpr size_t kCandidates = 48;
  std::vector<uint32_t> idx(kCandidates);
  std::vector<double> dist(kCandidates);
  for (int pass = 0; pass < kPasses; ++pass) {
    std::vector<int32_t> tangled;
    for (const auto& tri : folded_triangles()) tangled.insert(tangled.end(), tri.begin(), tri.end());
    if (tangled.empty()) break;
    std::sort(tangled.begin(), tangled.end());
    tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());
    size_t fixed = 0;
    for (int32_t s : tangled) {
      if (neighbors_.begin(s) == neighbors_.end(s)) continue;
      const Eigen::Vector3d mean = neighbour_mean(s);
      const int32_t face = param_[anchor_[s]].face;
      const std::pair<int, double> before = star_quality(s, anchor_[s]);
      const size_t k = input_tree_.knnSearch(mean.data(), kCandidates, idx.data(), dist.data());
      for (size_t j = 0; j < k; ++j) {
        const int32_t i = static_cast<int32_t>(idx[j]);
        if (site_of_[i] >= 0 || !allowed(s, i) || !near_face(face, param_[i].face)) continue;
        if (better_star(star_quality(s, i), before)) {
          move_site(s, i);
          ++fixed;
          break;
        }
      }
    }
    lr.untangled += fixed;
    if (fixed == 0) break;
  }
}

void Refiner::untangle_off_input(RefineLevelReport& lr) {
  constexpr int kPasses = 8;
  for (int pass = 0; pass < kPasses; ++pass) {
    size_t moved = 0;
    for (const auto& tri : folded_triangles()) {
      if (!folded(tri, -1, -1)) continue;
      for (int32_t s : tri) {
        if (neighbors_.begin(s) == neighbors_.end(s) || keeps_to_crease(s)) continue;
        const int32_t from = anchor_[s];
        const int32_t i = add_point(neighbour_mean(s), param_[from], normals_[from], site_on_boundary_[s]);
        if (better_star(star_quality(s, i), star_quality(s, from))) {
          move_site(s, i);
          ++lr.off_input_moves;
          ++moved;
          break;
        }
        drop_last_point();
      }
    }
    if (moved == 0) break;
  }
}

int32_t Refiner::across(int32_t t, int c) const {
  const int32_t a = triangles_[t][c], b = triangles_[t][(c + 1) % 3];
  for (const int32_t* u = around_.begin(a); u != around_.end(a); ++u)
    if (*u != t && std::find(triangles_[*u].begin(), triangles_[*u].end(), b) != triangles_[*u].end()) return *u;
  return -1;
}

bool Refiner::pleated(int32_t t, int32_t u) const {
  auto normal = [&](int32_t k) {
    const auto& tri = triangles_[k];
    const Eigen::Vector3d &p0 = points_[anchor_[tri[0]]], &p1 = points_[anchor_[tri[1]]], &p2 = points_[anchor_[tri[2]]];
    return Eigen::Vector3d((p1 - p0).cross(p2 - p0));
  };
  return pleat(normal(t), normal(u));
}

std::vector<std::pair<int32_t, int32_t>> Refiner::pleats() const {
  // Each triangle's pleated later neighbours found in parallel, then listed
  // in the order of a serial scan.
  std::vector<std::array<int32_t, 3>> with(triangles_.size(), {-1, -1, -1});
  tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const auto t = static_cast<int32_t>(i);
      for (int c = 0; c < 3; ++c) {
        const int32_t u = across(t, c);
        if (u > t && pleated(t, u)) with[i][c] = u;
      }
    }
  });
  std::vector<std::pair<int32_t, int32_t>> out;
  for (size_t t = 0; t < with.size(); ++t)
    for (int32_t u : with[t])
      if (u >= 0) out.emplace_back(static_cast<int32_t>(t), u);
  return out;
}

std::vector<std::array<int32_t, 3>> Refiner::folded_triangles() const {
  std::vector<std::array<int32_t, 3>> out;
  const auto add = [&](const std::vector<std::array<int32_t, 3>>& triangles) {
    const std::vector<char> flags = folded_flags(triangles);
    for (size_t t = 0; t < triangles.size(); ++t)
      if (flags[t]) out.push_back(triangles[t]);
  };
  add(triangles_);
  for (const auto& level_tris : coarse_triangles_) add(level_tris);
  return out;
}

void Refiner::smooth_tangles(RefineLevelReport& lr) {
  for (int rings : {1, 2, 4, 8})
    if (!for_each_tangle_patch(rings, [&](const std::vector<int32_t>& patch) { lr.smoothed += smooth_patch(patch); }))
      return;
}

std::function<std::pair<size_t, size_t>()> Refiner::tangles_around(const std::vector<int32_t>& patch) const {
  // The triangles around the patch, per level (this level's mesh last).
  std::vector<std::vector<int32_t>> around(coarse_triangles_.size() + 1);
  auto gather = [&](const Adjacency& adjacency, std::vector<int32_t>& ids) {
    for (int32_t s : patch) ids.insert(ids.end(), adjacency.begin(s), adjacency.end(s));
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  };
  for (size_t k = 0; k < coarse_triangles_.size(); ++k) gather(coarse_around_[k], around[k]);
  gather(around_, around.back());
  return [this, around = std::move(around)] {
    std::pair<size_t, size_t> count{0, 0};
    for (size_t k = 0; k < around.size(); ++k) {
      const auto& tris = k < coarse_triangles_.size() ? coarse_triangles_[k] : triangles_;
      for (int32_t t : around[k]) count.first += folded(tris[t], -1, -1);
    }
    const std::vector<int32_t>& fine = around.back();
    for (int32_t t : fine)
      for (int c = 0; c < 3; ++c) {
        const int32_t u = across(t, c);
        if (u >= 0 && (u > t || !std::binary_search(fine.begin(), fine.end(), u))) count.second += pleated(t, u);
      }
    return count;
  };
}

size_t Refiner::midpoint_patch(const std::vector<int32_t>& patch, int32_t level) {
  const auto tangles = tangles_around(patch);
  const std::pair<size_t, size_t> before = tangles();
  const size_t points_before = points_.size();
  std::vector<int32_t> moved, old;
  for (int32_t s : patch) {
    if (h_.vertex_level(s) != level || keeps_to_crease(s)) continue;
    const auto edge = h_.parent_edge(s);
    const int32_t a = anchor_[edge[0]], b = anchor_[edge[1]];
    Eigen::Vector3d normal = normals_[a] + normals_[b];
    if (normal.norm() > 0.0) normal.normalize();
    moved.push_back(s);
    old.push_back(anchor_[s]);
    move_site(s, add_point(0.5 * (points_[a] + points_[b]), h_.nominal_param(s), normal, site_on_boundary_[s]));
  }
  if (moved.empty()) return 0;
  if (tangles() < before) return moved.size();
  for (size_t j = 0; j < moved.size(); ++j) move_site(moved[j], old[j]);
  while (points_.size() > points_before) drop_last_point();
  return 0;
}

size_t Refiner::smooth_patch(const std::vector<int32_t>& patch) {
  constexpr std::array<int, 7> kCheckpoints{1, 2, 3, 5, 8, 13, 20};
  const auto folds = tangles_around(patch);
  // Interior sites move to their neighbours' mean, boundary sites to the
  // mean of their two neighbours along the boundary, put back on the
  // input's boundary (rim: those two neighbours).
  std::vector<int32_t> movable, old;
  std::vector<std::array<int32_t, 2>> rim;
  for (int32_t s : patch) {
    std::array<int32_t, 2> along{-1, -1};
    if (keeps_to_crease(s)) continue;
    if (site_on_boundary_[s]) {
      if (rim_prev_[s] < 0 || rim_next_[s] < 0) continue;  // a corner where boundary loops touch: stays
      along = {rim_prev_[s], rim_next_[s]};
    } else if (neighbors_.begin(s) == neighbors_.end(s)) {
      continue;
    }
    movable.push_back(s);
    rim.push_back(along);
  }
  if (movable.empty()) return 0;
  // Positions during the smoothing: the movable sites' own, the others'
  // from their points.
  std::vector<Eigen::Vector3d> x(movable.size()), stepped(movable.size());
  std::vector<SurfacePoint> on(movable.size()), best_on;
  for (size_t j = 0; j < movable.size(); ++j) {
    old.push_back(anchor_[movable[j]]);
    x[j] = points_[old[j]];
  }
  auto position = [&](int32_t s) -> const Eigen::Vector3d& {
    const auto it = std::lower_bound(movable.begin(), movable.end(), s);
    return it != movable.end() && *it == s ? x[it - movable.begin()] : points_[anchor_[s]];
  };
  // Puts the movable sites on points at x (on the input surface where
  // `on` found it); undo() takes them back to their old points.
  const size_t points_before = points_.size();
  auto apply = [&] {
    for (size_t j = 0; j < movable.size(); ++j) {
      const bool on_loop = rim[j][0] >= 0 && x[j] == on[j].x;
      move_site(movable[j], add_point(x[j], param_[on[j].vertex], on[j].normal, rim[j][0] >= 0,
                                      on_loop ? on[j].loop : -1, on[j].loop_pos));
    }
  };
  auto undo = [&] {
    for (size_t j = 0; j < movable.size(); ++j) move_site(movable[j], old[j]);
    while (points_.size() > points_before) drop_last_point();
  };
  std::pair<size_t, size_t> best = folds();
  std::vector<Eigen::Vector3d> best_x;
  for (int step = 1; step <= kCheckpoints.back(); ++step) {
    for (size_t j = 0; j < movable.size(); ++j) {
      const int32_t s = movable[j];
      if (rim[j][0] >= 0) {
        on[j] = nearest_on_boundary(0.5 * (position(rim[j][0]) + position(rim[j][1])), param_[old[j]].face, s);
        stepped[j] = on[j].x;
        continue;
      }
      const Eigen::Vector3d mean = neighbour_mean(s, position);
      on[j] = nearest_on_surface(mean, param_[old[j]].face, std::numeric_limits<double>::infinity(), normals_[old[j]]);
      stepped[j] = on[j].x;
    }
    x.swap(stepped);
    // A site the input surface was not found under has left it: stop.
    if (std::any_of(on.begin(), on.end(), [](const SurfacePoint& q) { return q.vertex < 0; })) break;
    if (std::find(kCheckpoints.begin(), kCheckpoints.end(), step) == kCheckpoints.end()) continue;
    apply();
    const std::pair<size_t, size_t> now = folds();
    undo();
    if (now < best) {
      best = now;
      best_x = x;
      best_on = on;
    }
  }
  if (best_x.empty()) return 0;
  x.swap(best_x);
  on.swap(best_on);
  apply();
  return movable.size();
}

size_t Refiner::folded_by_nearest_input() const {
  std::vector<Eigen::Vector3d> corner_normal(anchor_.size(), Eigen::Vector3d::Zero());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, anchor_.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t s = r.begin(); s != r.end(); ++s)
      if (anchor_[s] >= 0) corner_normal[s] = normals_[nearest_input_vertex(anchor_[s])];
  });
  const std::vector<char> flags = parallel_flags(triangles_.size(), [&](size_t i) {
    const auto& t = triangles_[i];
    return srcodec::folded(srcodec::facing(points_[anchor_[t[0]]], points_[anchor_[t[1]]], points_[anchor_[t[2]]],
                                           corner_normal[t[0]] + corner_normal[t[1]] + corner_normal[t[2]]));
  });
  return static_cast<size_t>(std::count(flags.begin(), flags.end(), 1));
}

}  // namespace srcodec
