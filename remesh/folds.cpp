#include "remesh/folds.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <nanoflann.hpp>

#include "remesh/geometry.h"
#include "remesh/parallel_flags.h"

namespace srcodec {

double facing(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
              const Eigen::Vector3d& reference) {
  const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
  const double r = reference.norm();
  const double scale = (p1 - p0).squaredNorm() + (p2 - p1).squaredNorm() + (p0 - p2).squaredNorm();
  if (!(r > 0.0) || !(scale > 0.0)) return 0.0;
  return n.dot(reference) / (r * scale);
}

double facing(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& side,
              const std::array<int32_t, 3>& t) {
  return facing(p[t[0]], p[t[1]], p[t[2]], side[t[0]] + side[t[1]] + side[t[2]]);
}

bool pleat(const Eigen::Vector3d& normal_t, const Eigen::Vector3d& normal_u) {
  constexpr double kCos150 = -0.86602540378443865;
  return normal_t.dot(normal_u) < kCos150 * normal_t.norm() * normal_u.norm();
}

double pleat_depth(const Eigen::Vector3d& normal_t, const Eigen::Vector3d& normal_u) {
  if (!pleat(normal_t, normal_u)) return 0.0;
  return -normal_t.dot(normal_u) / std::max(normal_t.norm() * normal_u.norm(), 1e-300) - 0.8660254;
}

// The pairs of triangles that share an edge.
std::vector<std::pair<int32_t, int32_t>> neighbour_pairs(const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<std::array<int32_t, 3>> edges;  // lower vertex, higher vertex, triangle
  edges.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const auto [a, b] = std::minmax(triangles[t][c], triangles[t][(c + 1) % 3]);
      edges.push_back({a, b, static_cast<int32_t>(t)});
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<int32_t, int32_t>> out;
  for (size_t i = 0; i + 1 < edges.size(); ++i)
    if (edges[i][0] == edges[i + 1][0] && edges[i][1] == edges[i + 1][1]) out.emplace_back(edges[i][2], edges[i + 1][2]);
  return out;
}

FoldCounter::Sides::Sides(const TriangleMesh& mesh)
    : normals_(unit_vertex_normals(mesh.positions, mesh.triangles)),
      cloud_{mesh.positions},
      tree_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
  tree_.buildIndex();
}

Eigen::Vector3d FoldCounter::Sides::operator()(const Eigen::Vector3d& p) const {
  uint32_t i = 0;
  double d2 = 0.0;
  return tree_.knnSearch(p.data(), 1, &i, &d2) == 1 ? normals_[i] : Eigen::Vector3d::Zero().eval();
}

std::vector<Eigen::Vector3d> FoldCounter::Sides::of(const std::vector<Eigen::Vector3d>& points) const {
  std::vector<Eigen::Vector3d> out(points.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v != r.end(); ++v) out[v] = (*this)(points[v]);
  });
  return out;
}

std::vector<uint32_t> FoldCounter::Sides::nearest(const Eigen::Vector3d& p, size_t k) const {
  std::vector<uint32_t> out(k);
  std::vector<double> d2(k);
  out.resize(tree_.knnSearch(p.data(), k, out.data(), d2.data()));
  return out;
}

FoldCount count_by_sides(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& side,
                         const std::vector<std::array<int32_t, 3>>& triangles, std::vector<char>* marked) {
  return count_by_sides(positions, side, triangles, neighbour_pairs(triangles), marked);
}

FoldCount count_by_sides(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& side,
                         const std::vector<std::array<int32_t, 3>>& triangles,
                         const std::vector<std::pair<int32_t, int32_t>>& neighbours, std::vector<char>* marked) {
  // Each triangle and pair judged in parallel; counted and marked after.
  const std::vector<char> fold =
      parallel_flags(triangles.size(), [&](size_t t) { return folded(positions, side, triangles[t]); });
  const std::vector<char> pleated = parallel_flags(neighbours.size(), [&](size_t k) {
    const auto [t, u] = neighbours[k];
    return pleat(triangle_normal(positions, triangles[t]), triangle_normal(positions, triangles[u]));
  });
  FoldCount count;
  if (marked) marked->assign(triangles.size(), 0);
  for (size_t t = 0; t < triangles.size(); ++t)
    if (fold[t]) {
      ++count.folded_by_nearest_input;
      if (marked) (*marked)[t] = 1;
    }
  for (size_t k = 0; k < neighbours.size(); ++k)
    if (pleated[k]) {
      ++count.pleats;
      if (marked) (*marked)[neighbours[k].first] = (*marked)[neighbours[k].second] = 1;
    }
  return count;
}

FoldCounter::FoldCounter(const TriangleMesh& sides)
    : sides_(sides.positions.empty() ? nullptr : std::make_unique<Sides>(sides)) {}
FoldCounter::~FoldCounter() = default;

FoldCount FoldCounter::operator()(const std::vector<Eigen::Vector3d>& positions,
                                  const std::vector<std::array<int32_t, 3>>& triangles, std::vector<char>* marked) const {
  if (!sides_) {
    if (marked) marked->assign(triangles.size(), 0);
    return FoldCount{};
  }
  return count_by_sides(positions, sides_->of(positions), triangles, marked);
}

}  // namespace srcodec
