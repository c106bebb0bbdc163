// The refinement along the input's creases (RemeshOptions::creases): the
// base mesh follows each crease with a chain of edges (remesh/base_mesh.h),
// and the vertices that refine those edges are kept on the crease the way
// boundary vertices are kept on the boundary (lloyd_relaxation.cpp): Lloyd
// moves a crease site only along its curve, between its two neighbours on
// it, so the curve's 1D Voronoi cells relax and the chain stays in order
// (MAPS keeps feature vertices on their curves in the same way: Lee et al.
// 1998, §3.4).
#include "format/semi_regular/creases.h"
#include "format/union_find.h"
#include "remesh/features.h"
#include "remesh/refiner.h"

namespace srcodec {

void Refiner::build_curves() {
  const BaseMeshCreases& creases = base_.input_creases;
  has_creases_ = !creases.edges.empty();
  if (!has_creases_) return;
  const size_t n = points_.size();
  point_crease_.assign(n, 0);
  curve_.assign(n, -1);
  curve_pos_.assign(n, 0.0);
  std::vector<FeatureEdge> edges;
  edges.reserve(creases.edges.size());
  for (const auto& [a, b] : creases.edges) {
    edges.push_back({a, b, FeatureKind::kCrease});
    point_crease_[a] = point_crease_[b] = 1;
  }
  std::vector<char> stops(n, 0);
  for (int32_t v : creases.fixed) stops[v] = point_crease_[v] = 2;
  for (const FeatureCurve& curve : chain_feature_curves(n, edges, stops)) {
    const int32_t c = static_cast<int32_t>(curve_walk_.size());
    const std::vector<int32_t>& walk = curve.vertices;
    // A closed curve's last point is its first, at place 0.
    for (size_t k = 0; k + (curve.closed() ? 1 : 0) < walk.size(); ++k) {
      if (point_crease_[walk[k]] != 1) continue;
      curve_[walk[k]] = c;
      curve_pos_[walk[k]] = static_cast<double>(k);
    }
    for (int32_t end : {walk.front(), walk.back()})
      if (point_crease_[end] == 2) curves_at_fixed_.push_back({end, c});
    curve_walk_.push_back(walk);
  }
  std::sort(curves_at_fixed_.begin(), curves_at_fixed_.end());
  curves_at_fixed_.erase(std::unique(curves_at_fixed_.begin(), curves_at_fixed_.end()), curves_at_fixed_.end());

  // The base faces' patches: faces joined across every base edge but the creases.
  const auto& faces = base_.mesh.triangles;
  const std::vector<std::array<int32_t, 3>> across = triangles_across(faces);
  UnionFind patches(faces.size());
  for (size_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const auto [a, b] = std::minmax(faces[f][c], faces[f][(c + 1) % 3]);
      const bool crease = std::binary_search(base_.crease_edges.begin(), base_.crease_edges.end(), std::array{a, b});
      if (across[f][c] >= 0 && !crease) patches.unite(f, static_cast<size_t>(across[f][c]));
    }
  face_patch_.resize(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) face_patch_[f] = static_cast<int32_t>(patches.find(f));
}

void Refiner::build_level_creases(int32_t level) {
  if (!has_creases_) return;
  const size_t n = static_cast<size_t>(h_.vertex_count());
  site_crease_degree_.assign(n, 0);
  site_crease_ends_.assign(n, {-1, -1});
  site_patch_.assign(n, -1);
  for (size_t s = 0; s < n; ++s) {
    const int32_t face = h_.nominal_param(static_cast<int32_t>(s)).face;
    if (face >= 0) site_patch_[s] = face_patch_[face];
  }
  for (const auto& [a, b] : crease_edges_up_to(h_, base_.crease_edges, level))
    for (const auto& [v, other] : {std::pair{a, b}, std::pair{b, a}}) {
      if (site_crease_degree_[v] < 2) site_crease_ends_[v][site_crease_degree_[v]] = other;
      if (site_crease_degree_[v] < 255) ++site_crease_degree_[v];
    }
}

double Refiner::place_on(int32_t c, int32_t i) const {
  if (i < 0 || c < 0) return -1.0;
  if (point_crease_[i] == 1) return curve_[i] == c ? curve_pos_[i] : -1.0;
  if (point_crease_[i] != 2) return -1.0;
  const std::vector<int32_t>& walk = curve_walk_[c];
  if (walk.front() == i) return 0.0;
  return walk.back() == i ? static_cast<double>(walk.size() - 1) : -1.0;
}

int32_t Refiner::common_curve(int32_t a, int32_t b) const {
  if (a < 0 || b < 0) return -1;
  for (int32_t p : {a, b})
    if (point_crease_[p] == 1) return place_on(curve_[p], a) >= 0.0 && place_on(curve_[p], b) >= 0.0 ? curve_[p] : -1;
  if (point_crease_[a] != 2) return -1;
  const auto first = std::lower_bound(curves_at_fixed_.begin(), curves_at_fixed_.end(), std::pair{a, -1});
  for (auto it = first; it != curves_at_fixed_.end() && it->first == a; ++it)
    if (place_on(it->second, b) >= 0.0) return it->second;
  return -1;
}

bool Refiner::between_on_curve(int32_t a, int32_t b, int32_t own, int32_t i) const {
  const int32_t c = common_curve(anchor_[a], anchor_[b]);
  const double pi = place_on(c, i);
  if (c < 0 || pi < 0.0 || point_crease_[i] != 1) return false;
  const double pa = place_on(c, anchor_[a]), pb = place_on(c, anchor_[b]);
  const std::vector<int32_t>& walk = curve_walk_[c];
  if (walk.front() != walk.back()) return std::min(pa, pb) < pi && pi < std::max(pa, pb);
  // A closed curve: the arc from a forwards to b, or the other one.
  const double size = static_cast<double>(walk.size() - 1);
  auto forward = [&](double from, double to) { return std::fmod(to - from + 2.0 * size, size); };
  const double span = forward(pa, pb);
  const double po = place_on(c, own);
  const bool forwards = po >= 0.0 && point_crease_[own] == 1 ? forward(pa, po) < span : span <= 0.5 * size;
  const double d = forward(pa, pi);
  return forwards ? d > 0.0 && d < span : d > span;
}

bool Refiner::crease_allowed(int32_t site, int32_t i) const {
  const int32_t own = anchor_[site];
  if (own >= 0 && point_crease_[own] == 2) return i == own;
  const uint8_t degree = site_crease_degree_[site];
  if (degree == 0) return point_crease_[i] == 0 && face_patch_[param_[i].face] == site_patch_[site];
  if (degree != 2) return i == own;
  const auto [a, b] = site_crease_ends_[site];
  return between_on_curve(a, b, own, i);
}

bool Refiner::keeps_to_crease(int32_t s) const {
  if (!has_creases_) return false;
  const int32_t own = anchor_[s];
  return site_crease_degree_[s] > 0 || (own >= 0 && point_crease_[own] == 2);
}

bool Refiner::crease_middle(int32_t a, int32_t b, Eigen::Vector3d* x, int32_t* curve, double* place) const {
  const int32_t c = common_curve(anchor_[a], anchor_[b]);
  if (c < 0) return false;
  const std::vector<int32_t>& walk = curve_walk_[c];
  const double pa = place_on(c, anchor_[a]), pb = place_on(c, anchor_[b]);
  double middle = 0.5 * (pa + pb);
  if (walk.front() == walk.back()) {  // closed: halfway along the shorter arc
    const double size = static_cast<double>(walk.size() - 1);
    const double span = std::fmod(pb - pa + 2.0 * size, size);
    middle = std::fmod(pa + (span <= 0.5 * size ? 0.5 * span : 0.5 * (span - size)) + size, size);
  }
  const size_t k = std::min(static_cast<size_t>(middle), walk.size() - 2);
  const double t = middle - static_cast<double>(k);
  *x = (1.0 - t) * points_[walk[k]] + t * points_[walk[k + 1]];
  *curve = c;
  *place = middle;
  return true;
}

}  // namespace srcodec
