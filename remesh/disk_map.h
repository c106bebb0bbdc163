// Planar maps of triangulated disks by convex combinations (Tutte's
// embedding, in Floater's form): each free vertex is a positive weighted
// mean of its neighbours, the boundary is fixed. With the boundary on a
// convex polygon the map is one-to-one (no triangle flips). The remesher
// uses it to untangle a patch of the remesh in a parameterization of the
// input surface under it, where two walls of a cleft are far apart even
// when they are near in space.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace srcodec {

// The boundary loop of a triangulated disk over vertices [0, n), in the
// triangles' orientation (the disk lies to the left when walking it), or
// empty when the triangles are not one disk: every edge in one or two
// triangles, one boundary loop that passes each of its vertices once, and
// Euler characteristic 1 over the vertices the triangles use.
std::vector<int32_t> disk_boundary_loop(size_t n, const std::vector<std::array<int32_t, 3>>& triangles);

// Solves for the positions of the vertices with fixed[v] == 0 as convex
// combinations of their neighbours: weights 1 / edge length in `positions`
// when given (the edge's 3D length), 1 otherwise. uv holds the fixed
// vertices' positions on entry and every vertex's on return. False when a
// free vertex has no path to a fixed one (the system is singular).
// Triangle indices must be in [0, n), as for untangle_planar.
bool convex_combination_map(size_t n, const std::vector<std::array<int32_t, 3>>& triangles,
                            const std::vector<Eigen::Vector3d>* positions, const std::vector<char>& fixed,
                            std::vector<Eigen::Vector2d>& uv);

// Moves the free vertices (fixed[v] == 0) of a planar triangulation until no
// triangle is flipped, or `passes` passes over the vertices of flipped
// triangles have run: each goes to the point of its star's kernel (where
// it sees every opposite edge on its left) farthest from those edges, or the
// point that violates them least when the kernel is empty. Tutte's map
// flips triangles where the fixed boundary is not convex; this undoes it
// when the boundary polygon is simple. Returns the flipped triangles left.
size_t untangle_planar(size_t n, const std::vector<std::array<int32_t, 3>>& triangles, const std::vector<char>& fixed,
                       std::vector<Eigen::Vector2d>& uv, int passes);

// Finds the triangle of a planar triangulation (positive ones only) that
// holds a point, through a uniform grid over the triangles' bounding boxes.
class PlanarLocator {
 public:
  PlanarLocator(const std::vector<Eigen::Vector2d>& uv, const std::vector<std::array<int32_t, 3>>& triangles);
  // The triangle holding p and p's barycentric coordinates in it; when no
  // triangle holds it (outside, or in a gap), the one p is least outside of
  // among those near it, and -1 when there is none.
  int32_t locate(const Eigen::Vector2d& p, Eigen::Vector3d* bary) const;

 private:
  int32_t cell(double x, double lo, double size) const;
  const std::vector<Eigen::Vector2d>& uv_;
  const std::vector<std::array<int32_t, 3>>& triangles_;
  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  double cell_size_ = 1.0;
  int32_t side_ = 1;
  std::vector<int32_t> offsets_, items_;  // per grid cell, the triangles overlapping it
};

// Twice the signed area of triangle (a, b, c) in the plane.
inline double signed_area2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

}  // namespace srcodec
