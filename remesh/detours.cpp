// Detours (ours, RefineOptions::follow_detours, off by default): where the
// input between an edge's ends runs far off the chord (a pocket, a crease,
// a gap narrower than an edge), the new vertex goes to the middle of the
// input's path and Lloyd may not make such edges, instead of bridging.
#include "remesh/refiner.h"

namespace srcodec {

double Refiner::path_length(int32_t from, int32_t to, double limit) {
  const Adjacency& neighbors = input_neighbors();
  if (path_dist_.empty()) {
    path_dist_.assign(input_.positions.size(), std::numeric_limits<double>::infinity());
    path_prev_.assign(input_.positions.size(), -1);
  }
  clear_path();
  const Eigen::Vector3d& goal = points_[to];
  using Entry = std::pair<double, int32_t>;  // estimated total length, vertex
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  path_touched_.push_back(from);
  path_dist_[from] = 0.0;
  open.push({(points_[from] - goal).norm(), from});
  while (!open.empty()) {
    const auto [f, i] = open.top();
    open.pop();
    if (f > limit) break;
    if (i == to) return path_dist_[to];
    if (f > path_dist_[i] + (points_[i] - goal).norm()) continue;  // an older entry
    for (const int32_t* jt = neighbors.begin(i); jt != neighbors.end(i); ++jt) {
      const int32_t j = *jt;
      const double d = path_dist_[i] + (points_[i] - points_[j]).norm();
      if (d < path_dist_[j]) {
        if (std::isinf(path_dist_[j])) path_touched_.push_back(j);
        path_dist_[j] = d;
        path_prev_[j] = i;
        open.push({d + (points_[j] - goal).norm(), j});
      }
    }
  }
  return std::numeric_limits<double>::infinity();
}

void Refiner::clear_path() {
  for (int32_t i : path_touched_) {
    path_dist_[i] = std::numeric_limits<double>::infinity();
    path_prev_[i] = -1;
  }
  path_touched_.clear();
}

bool Refiner::detour(int32_t a, int32_t b) {
  const int32_t n = static_cast<int32_t>(input_.positions.size());
  if (a >= n || b >= n || a == b) return false;
  return std::isinf(path_length(a, b, kDetour * (points_[a] - points_[b]).norm()));
}

int32_t Refiner::middle_of_detour(int32_t v, int32_t from, int32_t to) {
  constexpr double kMaxDetour = 16.0;
  const int32_t n = static_cast<int32_t>(input_.positions.size());
  if (!options_.follow_detours || from >= n || to >= n || from == to || site_on_boundary_[v]) return -1;
  const double chord = (points_[from] - points_[to]).norm();
  const double length = path_length(from, to, kMaxDetour * chord);
  int32_t best = -1;
  if (std::isfinite(length) && length > kDetour * chord) {
    double best_off = std::numeric_limits<double>::infinity();
    for (int32_t i = path_prev_[to]; i >= 0 && i != from; i = path_prev_[i]) {
      const double off = std::abs(path_dist_[i] - 0.5 * length);
      if (site_of_[i] < 0 && allowed(v, i) && off < best_off) {
        best_off = off;
        best = i;
      }
    }
  }
  clear_path();
  return best;
}

bool Refiner::keeps_off_detours(int32_t s, int32_t i) {
  if (!options_.follow_detours) return true;
  for (const int32_t* nb = neighbors_.begin(s); nb != neighbors_.end(s); ++nb) {
    const int32_t other = anchor_[*nb];
    if (other >= 0 && detour(i, other) && !detour(anchor_[s], other)) return false;
  }
  return true;
}

}  // namespace srcodec
