// The measuring instruments' search for the surface-distance metric
// (remesh/surface_distance.h, where the sampling and the formulas are
// defined once): CGAL's AABB tree (Alliez, Tayeb, Wormser, CGAL manual,
// "3D Fast Intersection and Distance Computation"), so that `compare` and
// `rd` measure with a library independent of the encoder's own tree.
#pragma once

#include <memory>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/surface_distance.h"

namespace srcodec {

// CGAL's exact point-to-triangle search over `faces` of `mesh` (valid,
// finite, of positive area: MeasuredSurface::faces), which also tells which
// face is nearest. Memory: ~70 bytes per triangle while it exists. Holds a
// pointer to the mesh, which must outlive it.
class CgalFaceSearch final : public NearestSurfacePoint {
 public:
  CgalFaceSearch(const TriangleMesh& mesh, const std::vector<uint32_t>& faces);
  ~CgalFaceSearch() override;
  double squared_distance(const Eigen::Vector3d& p) const override;
  uint32_t nearest_face(const Eigen::Vector3d& p) const;  // an index into mesh.triangles

 private:
  struct Search;
  std::unique_ptr<Search> search_;
};

// A CgalFaceSearch, as the metric's builder wants it.
std::unique_ptr<NearestSurfacePoint> cgal_search(const TriangleMesh& mesh, const std::vector<uint32_t>& faces);

// surface_distance() measured with cgal_search: the figures of `compare`
// and `rd`. Fails as surface_distance() does.
StatusOr<SurfaceDistance> cgal_surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                                const SurfaceDistanceOptions& options = {});

}  // namespace srcodec
