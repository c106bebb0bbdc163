// Small geometric helpers the refinement and the fit share.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "format/mesh.h"

namespace srcodec {

// Per vertex: the unit area-weighted normal of the triangles around it (zero
// where they have no area).
std::vector<Eigen::Vector3d> unit_vertex_normals(const std::vector<Eigen::Vector3d>& positions,
                                                 const std::vector<std::array<int32_t, 3>>& triangles);

// Per vertex (of n): 1 when it is on an edge that only one triangle uses.
std::vector<char> boundary_vertices(size_t n, const std::vector<std::array<int32_t, 3>>& triangles);

// The point of a set of triangles nearest a query, as the searches over
// them (NearestTriangle, TriangleTree) answer it.
struct TriangleHit {
  int32_t triangle = -1;                                     // -1: the set has no triangle
  Eigen::Vector3d point = Eigen::Vector3d::Zero();           // the nearest point on it
  double squared = std::numeric_limits<double>::infinity();  // squared distance to it
};

// The point of triangle abc nearest to p (by the triangle's Voronoi regions:
// a vertex, an edge or the inside).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c);

// The squared distance from p to triangle abc, and its nearest point. Inside
// the triangle, the distance to its plane: a point on that plane is at
// distance exactly 0, as with CGAL's squared_distance, which the metric's
// two searches must agree with.
double squared_distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c, Eigen::Vector3d& nearest);

// The barycentric coordinates of q, a point of triangle abc, in it (a
// third each for a triangle with no area).
Eigen::Vector3d barycentric(const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c);

// The angle between two vectors (any length), in degrees; exact near 0 and
// 180, where an arccosine of their dot product loses its digits.
double degrees_between(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// The normal of triangle t of `p`, twice its area long; its area.
Eigen::Vector3d triangle_normal(const std::vector<Eigen::Vector3d>& p, const std::array<int32_t, 3>& t);
double triangle_area(const std::vector<Eigen::Vector3d>& p, const std::array<int32_t, 3>& t);
// The sum of the areas of the mesh's triangles.
double mesh_area(const TriangleMesh& mesh);
// The edge length of equilateral triangles, two per vertex as on a closed
// mesh, that cover `area` with `vertices` vertices: the mean edge of a mesh
// of that many vertices over that area (a base mesh's, from its sites). 0
// without vertices or area.
double equilateral_edge_length(double area, size_t vertices);

// Calls f with the centroid of each of the n x n sub-triangles of triangle
// abc (those of a regular split of each edge into n), row by row.
template <class F>
void for_each_subtriangle_centroid(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int n,
                                   F&& f) {
  const Eigen::Vector3d u = (b - a) / n, v = (c - a) / n;
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      const Eigen::Vector3d corner = a + i * u + j * v;
      f(Eigen::Vector3d(corner + (u + v) / 3.0));                               // upright sub-triangle
      if (i + j + 1 < n) f(Eigen::Vector3d(corner + (2.0 * u + 2.0 * v) / 3.0));  // the inverted one beside it
    }
}

// `count` points spread over the mesh's surface by area (none when it has
// no area), the same for the same seed on every platform.
std::vector<Eigen::Vector3d> surface_samples(const TriangleMesh& mesh, size_t count, uint64_t seed);

}  // namespace srcodec
