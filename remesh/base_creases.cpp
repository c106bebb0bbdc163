#include "remesh/base_creases.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "remesh/geometry.h"

namespace srcodec {

namespace {

double curve_length(const TriangleMesh& mesh, const FeatureCurve& curve) {
  double length = 0.0;
  for (size_t k = 1; k < curve.vertices.size(); ++k)
    length += (mesh.positions[curve.vertices[k]] - mesh.positions[curve.vertices[k - 1]]).norm();
  return length;
}

// The crease curves (not boundaries) at least `shortest` long.
std::vector<const FeatureCurve*> followable(const TriangleMesh& mesh, const Features& features, double shortest) {
  std::vector<const FeatureCurve*> out;
  for (const FeatureCurve& curve : features.curves) {
    const std::vector<int32_t>& v = curve.vertices;
    if (v.size() < 2 || curve_length(mesh, curve) < shortest) continue;
    const FeatureEdge* first = features.find(v[0], v[1]);
    if (first && first->kind == FeatureKind::kCrease) out.push_back(&curve);
  }
  return out;
}

}  // namespace

double followable_base_edges(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options) {
  if (options.base_vertices == 0) return 0.0;
  const double base_edge = equilateral_edge_length(mesh_area(mesh), options.base_vertices);
  double length = 0.0;
  for (const FeatureCurve* curve : followable(mesh, features, options.min_base_edges * base_edge))
    length += curve_length(mesh, *curve);
  return length / base_edge;
}

BaseMeshCreases base_creases(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options) {
  const double shortest = options.min_base_edges * equilateral_edge_length(mesh_area(mesh), options.base_vertices);
  const size_t n = mesh.positions.size();
  std::vector<int32_t> degree(n, 0);
  std::vector<char> on_boundary(n, 0);
  for (const FeatureEdge& e : features.edges)
    if (e.kind == FeatureKind::kBoundary) on_boundary[e.a] = on_boundary[e.b] = 1;
  BaseMeshCreases out;
  for (const FeatureCurve* curve : followable(mesh, features, shortest)) {
    const std::vector<int32_t>& v = curve->vertices;
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
