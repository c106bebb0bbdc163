#include "remesh/geometry.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <utility>

#include "format/area_sampling.h"
#include "format/split_mix64.h"

namespace srcodec {

std::vector<Eigen::Vector3d> unit_vertex_normals(const std::vector<Eigen::Vector3d>& positions,
                                                 const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<Eigen::Vector3d> n(positions.size(), Eigen::Vector3d::Zero());
  for (const auto& t : triangles) {
    const Eigen::Vector3d fn = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
    for (int32_t v : t) n[v] += fn;
  }
  for (Eigen::Vector3d& x : n) {
    const double len = x.norm();
    if (len > 0.0) x /= len;
  }
  return n;
}

std::vector<char> boundary_vertices(size_t n, const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<std::pair<int32_t, int32_t>> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) edges.emplace_back(std::minmax(t[c], t[(c + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  std::vector<char> on(n, 0);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) on[edges[i].first] = on[edges[i].second] = 1;
    i = j;
  }
  return on;
}

namespace {

// closest_on_triangle, and whether the point found is inside the triangle
// (not on an edge or a corner).
Eigen::Vector3d closest_and_region(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c, bool& inside) {
  inside = false;
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return a + ab * (d1 / (d1 - d3));
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0.0)) return a;
  inside = true;
  return a + ab * (vb / denom) + ac * (vc / denom);
}

}  // namespace

Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  bool inside = false;
  return closest_and_region(p, a, b, c, inside);
}

double squared_distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, Eigen::Vector3d& nearest) {
  bool inside = false;
  nearest = closest_and_region(p, a, b, c, inside);
  if (inside) {
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double h = n.dot(p - a), nn = n.squaredNorm();
    if (nn > 0.0) return h * h / nn;
  }
  return (nearest - p).squaredNorm();
}

Eigen::Vector3d barycentric(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area = n.squaredNorm();
  if (!(area > 0.0)) return Eigen::Vector3d::Constant(1.0 / 3.0);
  const double u = (c - b).cross(q - b).dot(n) / area, v = (a - c).cross(q - c).dot(n) / area;
  return Eigen::Vector3d(u, v, 1.0 - u - v);
}

double degrees_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * (180.0 / 3.14159265358979323846);
}

Eigen::Vector3d triangle_normal(const std::vector<Eigen::Vector3d>& p, const std::array<int32_t, 3>& t) {
  return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
}

double triangle_area(const std::vector<Eigen::Vector3d>& p, const std::array<int32_t, 3>& t) {
  return 0.5 * triangle_normal(p, t).norm();
}

double mesh_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += triangle_area(mesh.positions, t);
  return area;
}

double equilateral_edge_length(double area, size_t vertices) {
  if (vertices == 0 || !(area > 0.0)) return 0.0;
  return std::sqrt(4.0 / std::sqrt(3.0) * area / (2.0 * static_cast<double>(vertices)));
}

std::vector<Eigen::Vector3d> surface_samples(const TriangleMesh& mesh, size_t count, uint64_t seed) {
  std::vector<double> cumulative(mesh.triangles.size());
  double total = 0.0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    total += triangle_area(mesh.positions, mesh.triangles[t]);
    cumulative[t] = total;
  }
  std::vector<Eigen::Vector3d> out;
  if (!(total > 0.0)) return out;
  out.reserve(count);
  SplitMix64 rng(seed);  // the same samples on every platform
  for (size_t k = 0; k < count; ++k) {
    const double at = rng.uniform() * total;
    const size_t t = std::min<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin(),
                                      cumulative.size() - 1);
    const auto& tri = mesh.triangles[t];
    out.push_back(point_in_triangle(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], rng));
  }
  return out;
}

}  // namespace srcodec
