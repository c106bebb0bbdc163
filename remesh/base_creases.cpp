#include "remesh/base_creases.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "remesh/geometry.h"

namespace srcodec {

double base_edge_length(double area, size_t vertices) {
  if (vertices == 0 || !(area > 0.0)) return 0.0;
  return std::sqrt(2.0 * area / (std::sqrt(3.0) * static_cast<double>(vertices)));
}

namespace {

double surface_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += triangle_area(mesh.positions, t);
  return area;
}

double curve_length(const TriangleMesh& mesh, const FeatureCurve& curve) {
  double length = 0.0;
  for (size_t k = 1; k < curve.vertices.size(); ++k)
    length += (mesh.positions[curve.vertices[k]] - mesh.positions[curve.vertices[k - 1]]).norm();
  return length;
}

// The kind of feature edge a-b (features.edges is sorted by (a, b)).
FeatureKind kind_of(const Features& features, int32_t a, int32_t b) {
  const FeatureEdge key{std::min(a, b), std::max(a, b), FeatureKind::kCrease};
  const auto it = std::lower_bound(features.edges.begin(), features.edges.end(), key, [](const auto& x, const auto& y) {
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  return it != features.edges.end() && it->a == key.a && it->b == key.b ? it->kind : FeatureKind::kBoundary;
}

}  // namespace

BaseMeshCreases base_creases(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options) {
  const double shortest = options.min_base_edges * base_edge_length(surface_area(mesh), options.base_vertices);
  const size_t n = mesh.positions.size();
  std::vector<int32_t> degree(n, 0);
  std::vector<char> on_boundary(n, 0);
  for (const FeatureEdge& e : features.edges)
    if (e.kind == FeatureKind::kBoundary) on_boundary[e.a] = on_boundary[e.b] = 1;
  BaseMeshCreases out;
  for (const FeatureCurve& curve : features.curves) {
    const std::vector<int32_t>& v = curve.vertices;
    if (v.size() < 2 || curve_length(mesh, curve) < shortest) continue;
    if (kind_of(features, v[0], v[1]) != FeatureKind::kCrease) continue;
    for (size_t k = 1; k < v.size(); ++k) {
      out.edges.push_back({std::min(v[k - 1], v[k]), std::max(v[k - 1], v[k])});
      ++degree[v[k - 1]];
      ++degree[v[k]];
    }
  }
  std::sort(out.edges.begin(), out.edges.end());
  for (const std::vector<int32_t>* list : {&features.corners, &features.ends})
    for (int32_t v : *list)
      if (degree[v] > 0) out.fixed.push_back(v);
  for (size_t v = 0; v < n; ++v)
    if (degree[v] > 0 && (degree[v] != 2 || on_boundary[v])) out.fixed.push_back(static_cast<int32_t>(v));
  std::sort(out.fixed.begin(), out.fixed.end());
  out.fixed.erase(std::unique(out.fixed.begin(), out.fixed.end()), out.fixed.end());
  return out;
}

}  // namespace srcodec
