// Folded triangles and pleats: the one definition of a tangle that every
// remesh stage judges and counts by (the refinement's repairs, the fit, the
// untangling, the unsplitting, the sliver relaxation, the measured
// coarsening and the reports). Ours, not the paper's: the paper's remesh sits
// on input vertices and never asks whether a triangle turned over.
//
// A triangle is folded when it does not face the way of the input surface at
// its corners (facing() <= kFoldedFacing); two neighbouring triangles are a
// pleat when they meet at more than 150 degrees, folded onto each other
// whichever way they face (the facing test cannot see that).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "format/mesh.h"
#include "remesh/point_cloud.h"

namespace srcodec {

// How triangle p0 p1 p2 faces along `reference` (a sum of unit normals at
// its corners): its normal's dot product with it, over |reference| and the
// triangle's squared edge lengths; 0 with no reference or no edges.
double facing(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
              const Eigen::Vector3d& reference);
// facing() of triangle t of `p` along the sum of `side` (a unit normal per
// vertex) at its corners.
double facing(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& side,
              const std::array<int32_t, 3>& t);

// A triangle is folded when facing() is not above this: a sliver with no
// area counts as folded, as it points nowhere.
constexpr double kFoldedFacing = 1e-9;
inline bool folded(double facing_value) { return !(facing_value > kFoldedFacing); }
inline bool folded(const std::vector<Eigen::Vector3d>& p, const std::vector<Eigen::Vector3d>& side,
                   const std::array<int32_t, 3>& t) {
  return folded(facing(p, side, t));
}
// How far past folded a facing() value is (0 when not folded): what a
// repair that cannot unfold a triangle yet may still reduce.
inline double fold_depth(double facing_value) { return folded(facing_value) ? kFoldedFacing - facing_value : 0.0; }

// Two neighbouring triangles, of these normals (any length), meet at more
// than 150 degrees: a pleat.
bool pleat(const Eigen::Vector3d& normal_t, const Eigen::Vector3d& normal_u);
// How far past 150 degrees a pleat is, as the cosine of the angle between
// the normals below -cos(30 degrees) (to seven digits); 0 when not a pleat.
double pleat_depth(const Eigen::Vector3d& normal_t, const Eigen::Vector3d& normal_u);

// The pairs of triangles that share an edge, each pair once.
std::vector<std::pair<int32_t, int32_t>> neighbour_pairs(const std::vector<std::array<int32_t, 3>>& triangles);

// The folded triangles and the pleats of one set of triangles.
struct FoldCount {
  size_t folded_by_nearest_input = 0;
  size_t pleats = 0;
};
// Counts them with each vertex's side (the unit normal judging it) given.
// With `marked`, also per triangle: 1 when it is folded or in a pleat.
FoldCount count_by_sides(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& side,
                         const std::vector<std::array<int32_t, 3>>& triangles, std::vector<char>* marked = nullptr);
// The same with the pairs of neighbouring triangles given (each pair once),
// for a caller that counts one set of triangles many times.
FoldCount count_by_sides(const std::vector<Eigen::Vector3d>& positions, const std::vector<Eigen::Vector3d>& side,
                         const std::vector<std::array<int32_t, 3>>& triangles,
                         const std::vector<std::pair<int32_t, int32_t>>& neighbours, std::vector<char>* marked);

// count_by_sides with each corner judged by the normal of the vertex of
// `sides` (the oversampled input the remesher ran on) nearest it: a corner
// off the input takes the side of the input surface it is near.
class FoldCounter {
 public:
  explicit FoldCounter(const TriangleMesh& sides);  // keeps a reference to it
  ~FoldCounter();
  FoldCount operator()(const std::vector<Eigen::Vector3d>& positions,
                       const std::vector<std::array<int32_t, 3>>& triangles, std::vector<char>* marked = nullptr) const;

  // Per point, the unit normal of the nearest vertex of a mesh: the side of
  // the input surface a corner off it is on.
  class Sides {
   public:
    explicit Sides(const TriangleMesh& mesh);  // keeps a reference to mesh.positions
    Eigen::Vector3d operator()(const Eigen::Vector3d& p) const;
    // operator() of each point (in parallel).
    std::vector<Eigen::Vector3d> of(const std::vector<Eigen::Vector3d>& points) const;
    // The (up to) k vertices of the mesh nearest p, nearest first.
    std::vector<uint32_t> nearest(const Eigen::Vector3d& p, size_t k) const;
    const Eigen::Vector3d& normal(uint32_t vertex) const { return normals_[vertex]; }

   private:
    std::vector<Eigen::Vector3d> normals_;
    PointCloud cloud_;
    PointTree tree_;
  };

 private:
  std::unique_ptr<Sides> sides_;
};

}  // namespace srcodec
