// The sharp features of a triangle mesh: the edges where the surface folds
// sharply (creases) and its boundaries, chained into curves, the corners
// where three or more curves meet or a curve turns sharply, and the ends of
// creases that fade out. What the remesher must keep as base vertices and
// base edges so that creases stay sharp (the curve rules of Loop's and the
// modified Butterfly's crease and boundary subdivision need them on edges of
// the coarse mesh: Hoppe et al., "Piecewise smooth surface reconstruction",
// SIGGRAPH 1994; Zorin, Schröder, Sweldens, SIGGRAPH 1996).
//
// A crease is judged at a scale, not edge by edge: on a scan, noise bends
// single edges as much as a crease does. An edge is a crease when
//  (a) its two triangles meet at more than the crease angle, and at more
//      than three times the median of the edges around it (the local
//      noise);
//  (b) with the other such edges near it, it cuts the surface within a
//      radius of a few edge lengths into two sides (a spike of noise is
//      walked round), whose mean normals meet at more than the crease angle;
//  (c) its connected set of creases spans more than that radius (a knot of
//      noise or a scratch does not).
#pragma once

#include <cstdint>
#include <vector>

#include "format/mesh.h"

namespace srcodec {

struct FeatureOptions {
  // Two triangles, and the two sides of a crease, meeting at more than this
  // (the angle between their normals; 0 is flat) make a crease. 30 degrees:
  // the normal jump the visual measure counts as a visible defect
  // (tools/measure/visual_difference.h), so a crease is what a viewer sees
  // as an edge.
  double crease_degrees = 30.0;
  // The radius of (b) and (c), in median edge lengths (at most a tenth of
  // the bounding-box diagonal).
  double scale = 4.0;
  // Boundary edges are features (and so are edges where more than two
  // triangles meet).
  bool boundaries = true;
};

enum class FeatureKind : uint8_t { kCrease, kBoundary };

struct FeatureEdge {
  int32_t a = 0, b = 0;  // a < b
  FeatureKind kind = FeatureKind::kCrease;
};

struct FeatureCurve {
  // Consecutive vertices along feature edges, from a corner or end to a
  // corner or end; for a closed loop without either, back() == front().
  std::vector<int32_t> vertices;
  bool closed() const { return vertices.size() > 2 && vertices.front() == vertices.back(); }
};

struct Features {
  std::vector<FeatureEdge> edges;  // sorted by (a, b)
  // Where three or more feature edges meet, or two meet at a turn sharper
  // than the crease angle; ascending.
  std::vector<int32_t> corners;
  // Where a crease stops inside the surface (one feature edge); ascending.
  std::vector<int32_t> ends;
  std::vector<FeatureCurve> curves;  // every feature edge on exactly one
  // The feature edge a-b (either order), or null.
  const FeatureEdge* find(int32_t a, int32_t b) const;
  bool is_feature(int32_t a, int32_t b) const { return find(a, b) != nullptr; }
};

// Feature edges (indices below vertex_count) walked into curves: from every
// vertex `stops` marks (a corner or an end) along each of its edges to the
// next stop, then the closed loops left (back() == front()).
std::vector<FeatureCurve> chain_feature_curves(size_t vertex_count, const std::vector<FeatureEdge>& edges,
                                               const std::vector<char>& stops);

// Indices must be valid (TriangleMesh as read and cleaned); triangles of no
// area have no normal and never make a crease.
Features detect_features(const TriangleMesh& mesh, const FeatureOptions& options = {});

}  // namespace srcodec
