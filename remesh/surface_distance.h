// Symmetric surface distance in the style of Metro (Cignoni, Rocchini,
// Scopigno 1998) and MESH (Aspert, Santa-Cruz, Ebrahimi 2002): both surfaces
// are sampled area-uniformly, each sample's exact distance to the other
// surface is found by a nearest-point search, and RMS, mean and max are
// reported each way. PSNR = 20 log10(bbox diagonal of the reference / RMS).
// The one definition of the metric: the encoder measures with our own search
// (remesh/triangle_tree.h); the measuring instruments plug in CGAL's
// (tools/measure/surface_distance.h) and share the sampling and formulas.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

struct SurfaceDistanceOptions {
  // Area-uniform samples on each mesh, >= 1. Stratified: each triangle gets
  // floor(e) or floor(e) + 1 samples, e = its share of the area times this,
  // so the count drawn (DirectedDistance::samples) is this on average only.
  size_t samples_per_surface = 200000;
  uint64_t seed = 1;  // same seed, same samples, same figures (whatever the thread count)
};

struct DirectedDistance {
  double rms = 0, mean = 0, max = 0;
  size_t samples = 0;
};

struct SurfaceDistance {
  DirectedDistance ref_to_test;  // samples on the reference, distances to the test mesh
  DirectedDistance test_to_ref;
  double rms = 0;        // the larger RMS of the two directions
  double hausdorff = 0;  // the larger max
  double diag = 0;       // bounding-box diagonal of the reference
  double psnr = 0;       // 20 log10(diag / rms); +inf when rms == 0
};

// 20 log10(peak / rms), +inf when rms is 0: the PSNR of every figure here
// (peak the reference's bounding-box diagonal) and of the estimates and
// measures built on it.
double psnr_db(double peak, double rms);

// A mesh reduced to what has surface: the triangles of positive area, after
// checking that every index is valid and every used vertex finite. Both the
// metric and the visual measure (tools/measure/visual_difference.h) see a
// mesh through this. Holds a pointer to the mesh, which must outlive it.
struct MeasuredSurface {
  const TriangleMesh* mesh = nullptr;
  std::vector<uint32_t> faces;  // indices into mesh->triangles, positive area only
  std::vector<double> areas;    // area of faces[i]
  double total_area = 0;
};
// Fails with kInvalidMesh, naming `role` ("reference", "test") and the
// triangle or vertex, on a bad index, a non-finite vertex or no surface.
StatusOr<MeasuredSurface> measured_surface(const TriangleMesh& mesh, const char* role);

// What the metric asks of a search structure: the exact squared distance
// from a point to the nearest of its triangles. Queried from several
// threads at once, so it must be thread-safe once built.
class NearestSurfacePoint {
 public:
  virtual ~NearestSurfacePoint() = default;
  virtual double squared_distance(const Eigen::Vector3d& p) const = 0;
};

// Builds the search over `faces`: indices into mesh.triangles, already
// checked (valid, finite, of positive area). Called for both meshes at once.
using NearestSurfacePointBuilder =
    std::function<std::unique_ptr<NearestSurfacePoint>(const TriangleMesh& mesh, const std::vector<uint32_t>& faces)>;

// Our own search: an AABB tree over the triangles (remesh/triangle_tree.h).
std::unique_ptr<NearestSurfacePoint> triangle_tree_search(const TriangleMesh& mesh, const std::vector<uint32_t>& faces);

// The reference's half of the metric, built once: its samples and its
// search, for measuring many test meshes against one reference (rate control
// measures each cut of a stream against the input). distance_to(test) gives
// the figures surface_distance(reference, test, options, build_search) gives.
// Holds a reference to the mesh, which must outlive it.
class SurfaceReference {
 public:
  static StatusOr<SurfaceReference> build(const TriangleMesh& reference, const SurfaceDistanceOptions& options,
                                          const NearestSurfacePointBuilder& build_search = triangle_tree_search);
  StatusOr<SurfaceDistance> distance_to(const TriangleMesh& test) const;
  size_t samples_per_surface() const { return samples_per_surface_; }

 private:
  SurfaceReference() = default;
  NearestSurfacePointBuilder build_search_;
  size_t samples_per_surface_ = 0;
  uint64_t test_seed_ = 0;
  double diag_ = 0;
  std::vector<Eigen::Vector3d> samples_;
  std::unique_ptr<NearestSurfacePoint> search_;
};

// Zero-area triangles are ignored: they have no surface to sample or to be
// near. Runs on every core TBB allows (tbb::global_control limits it); the
// figures are bit-identical whatever the thread count.
//
// Fails with kInvalidMesh when either mesh has no triangle of positive area,
// a triangle references a vertex that does not exist or a used vertex is not
// finite; with kInvalidArgument when samples_per_surface is 0.
StatusOr<SurfaceDistance> surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                           const SurfaceDistanceOptions& options = {});
// The same with another search (the same figures when it is exact, up to
// the rounding of each distance).
StatusOr<SurfaceDistance> surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                           const SurfaceDistanceOptions& options,
                                           const NearestSurfacePointBuilder& build_search);

}  // namespace srcodec
