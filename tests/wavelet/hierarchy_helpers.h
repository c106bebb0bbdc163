// Hierarchies and positions for the wavelet tests: uniform and random
// refinement of a base mesh, and noisy copies of its positions.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <random>
#include <utility>
#include <vector>

#include "format/mesh.h"
#include "format/semi_regular/hierarchy.h"
#include "wavelet/lifting.h"

namespace srcodec::test {

inline TriangleHierarchy make_hierarchy(const TriangleMesh& base) {
  auto h = TriangleHierarchy::create(static_cast<int32_t>(base.positions.size()), base.triangles);
  EXPECT_TRUE(h.ok()) << h.status().message();
  return std::move(h).value();
}

inline void refine_uniform(TriangleHierarchy& h, int32_t levels) {
  for (int32_t level = 0; level < levels; ++level) {
    const size_t count = h.nodes().size();
    for (size_t i = 0; i < count; ++i)
      if (h.nodes()[i].level == level && h.nodes()[i].first_child < 0) h.split(static_cast<int32_t>(i));
  }
}

// Random splits of leaves above `max_level`: the balancing and green closure
// make the level meshes irregular.
inline void refine_random(TriangleHierarchy& h, int32_t max_level, int splits, std::mt19937& rng) {
  for (int s = 0; s < splits; ++s) {
    std::vector<int32_t> leaves;
    for (size_t i = 0; i < h.nodes().size(); ++i)
      if (h.nodes()[i].first_child < 0 && h.nodes()[i].level < max_level) leaves.push_back(static_cast<int32_t>(i));
    if (leaves.empty()) return;
    h.split(leaves[rng() % leaves.size()]);
  }
}

inline std::vector<Eigen::Vector3d> noisy_base(const TriangleMesh& m, double noise, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> p = m.positions;
  for (auto& v : p) v += noise * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return p;
}

// Base positions, then every new vertex (ids grow after its parents') at its
// parent edge's midpoint plus noise of size `noise`.
inline std::vector<Eigen::Vector3d> place(const TriangleHierarchy& h, const std::vector<Eigen::Vector3d>& base,
                                          double noise, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> x(base);
  x.resize(h.vertex_count());
  for (int32_t v = h.base_vertex_count(); v < h.vertex_count(); ++v) {
    const auto e = h.parent_edge(v);
    x[v] = 0.5 * (x[e[0]] + x[e[1]]) + noise * Eigen::Vector3d(u(rng), u(rng), u(rng));
  }
  return x;
}

// The mesh `plan`'s prediction makes from `base` (the inverse transform with
// every detail zero), and what the forward transform gives back for it: its
// largest detail and base change, over the mesh's bounding-box diagonal.
struct PredictedMesh {
  std::vector<Eigen::Vector3d> x;
  double diagonal = 0.0;
  double worst_detail = 0.0, worst_base = 0.0;  // relative to the diagonal
};
inline PredictedMesh predicted_mesh(const LiftingPlan& plan, const std::vector<Eigen::Vector3d>& base) {
  PredictedMesh out;
  const std::vector<Eigen::Vector3d> zero(static_cast<size_t>(plan.vertex_count()), Eigen::Vector3d::Zero());
  out.x = inverse_lifting(plan, base, zero, plan.levels());
  out.diagonal = bounding_box_diagonal(out.x);
  const WaveletCoefficients c = forward_lifting(plan, out.x);
  for (const auto& d : c.detail) out.worst_detail = std::max(out.worst_detail, d.norm() / out.diagonal);
  for (size_t i = 0; i < base.size(); ++i)
    out.worst_base = std::max(out.worst_base, (c.base[i] - base[i]).norm() / out.diagonal);
  return out;
}

}  // namespace srcodec::test
