#include "remesh/surface_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "format/area_sampling.h"
#include "format/split_mix64.h"
#include "remesh/geometry.h"
#include "remesh/triangle_tree.h"

namespace srcodec {

double psnr_db(double peak, double rms) {
  return rms > 0 ? 20.0 * std::log10(peak / rms) : std::numeric_limits<double>::infinity();
}

StatusOr<MeasuredSurface> measured_surface(const TriangleMesh& mesh, const char* role) {
  const size_t num_vertices = mesh.positions.size();
  if (mesh.triangles.size() > std::numeric_limits<uint32_t>::max()) {
    return invalid_mesh(std::string(role) + " mesh has too many triangles (" +
                        std::to_string(mesh.triangles.size()) + ")");
  }
  MeasuredSurface s;
  s.mesh = &mesh;
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int32_t v : t) {
      if (v < 0 || static_cast<size_t>(v) >= num_vertices) {
        return invalid_mesh(std::string(role) + " mesh: triangle " + std::to_string(f) +
                            " references vertex " + std::to_string(v) + " but there are " +
                            std::to_string(num_vertices) + " vertices");
      }
      if (!mesh.positions[static_cast<size_t>(v)].allFinite()) {
        return invalid_mesh(std::string(role) + " mesh: vertex " + std::to_string(v) +
                            " (used by triangle " + std::to_string(f) +
                            ") has a non-finite coordinate");
      }
    }
    const double area = triangle_area(mesh.positions, t);
    if (area > 0) {  // zero-area triangles have no surface to sample or to be near
      s.faces.push_back(static_cast<uint32_t>(f));
      s.areas.push_back(area);
      s.total_area += area;
    }
  }
  if (s.faces.empty() || !(s.total_area > 0) || !std::isfinite(s.total_area)) {
    return invalid_mesh(std::string(role) + " mesh has no triangle of positive area (" +
                        std::to_string(mesh.triangles.size()) + " triangles, " +
                        std::to_string(num_vertices) + " vertices): it has no surface to measure");
  }
  return s;
}

namespace {

// ---------------------------------------------------------------------------
// Area-uniform, stratified sampling: triangle i gets floor(e_i) samples plus
// one more with probability frac(e_i), where e_i = area_i / total * n, so the
// expected count is exactly n and every triangle is represented in proportion.
// Within a triangle, point_in_triangle (format/area_sampling.h).

std::vector<Eigen::Vector3d> sample_surface(const MeasuredSurface& s, size_t n, uint64_t seed) {
  SplitMix64 rng(seed);
  std::vector<Eigen::Vector3d> samples;
  samples.reserve(n + n / 16 + 16);
  const double per_area = static_cast<double>(n) / s.total_area;
  for (size_t i = 0; i < s.faces.size(); ++i) {
    const double expected = s.areas[i] * per_area;
    double whole = std::floor(expected);
    if (rng.uniform() < expected - whole) whole += 1;
    const auto count = static_cast<size_t>(whole);
    if (count == 0) continue;
    const auto& t = s.mesh->triangles[s.faces[i]];
    const Eigen::Vector3d& a = s.mesh->positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = s.mesh->positions[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = s.mesh->positions[static_cast<size_t>(t[2])];
    for (size_t k = 0; k < count; ++k) {
      samples.push_back(point_in_triangle(a, b, c, rng));
    }
  }
  if (samples.empty()) {
    // Only possible when n is far below the number of triangles and every
    // Bernoulli draw failed: take one sample, the face chosen by area.
    const double target = rng.uniform() * s.total_area;
    double cumulative = 0;
    size_t i = 0;
    while (i + 1 < s.faces.size() && (cumulative += s.areas[i]) <= target) ++i;
    const auto& t = s.mesh->triangles[s.faces[i]];
    samples.push_back(point_in_triangle(s.mesh->positions[static_cast<size_t>(t[0])],
                                        s.mesh->positions[static_cast<size_t>(t[1])],
                                        s.mesh->positions[static_cast<size_t>(t[2])], rng));
  }
  return samples;
}

class TriangleTreeSearch final : public NearestSurfacePoint {
 public:
  TriangleTreeSearch(const TriangleMesh& mesh, const std::vector<uint32_t>& faces)
      : tree_(mesh.positions, mesh.triangles, faces) {}
  double squared_distance(const Eigen::Vector3d& p) const override { return tree_.closest(p).squared; }

 private:
  TriangleTree tree_;
};

// Compensated summation (Neumaier 1974): the sum of a million squared
// distances is accurate to the last bit or two instead of ~n ulps.
class NeumaierSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    compensation_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0, compensation_ = 0;
};

DirectedDistance directed_distance(const std::vector<Eigen::Vector3d>& samples, const NearestSurfacePoint& search) {
  std::vector<double> squared(samples.size());
  // Each sample writes its own slot: any split of the range, any thread
  // count gives the same values.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 256),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i != range.end(); ++i) {
                        squared[i] = search.squared_distance(samples[i]);
                      }
                    });
  // Sequential reduction in sample order: the same figures whatever the
  // number of threads or how TBB split the range.
  DirectedDistance d;
  d.samples = samples.size();
  NeumaierSum sum_squared, sum;
  double max_squared = 0;
  for (double q : squared) {
    sum_squared.add(q);
    sum.add(std::sqrt(q));
    if (q > max_squared) max_squared = q;
  }
  if (d.samples > 0) {
    const auto n = static_cast<double>(d.samples);
    d.rms = std::sqrt(sum_squared.value() / n);
    d.mean = sum.value() / n;
    d.max = std::sqrt(max_squared);
  }
  return d;
}

// One independent sample stream per surface, both derived from the seed.
struct SampleSeeds {
  uint64_t reference = 0, test = 0;
};

SampleSeeds sample_seeds(uint64_t seed) {
  SplitMix64 seeds(seed);
  SampleSeeds out;
  out.reference = seeds.next();
  out.test = seeds.next();
  return out;
}

Status check_samples(const SurfaceDistanceOptions& options) {
  if (options.samples_per_surface == 0) {
    return invalid_argument("surface distance: samples_per_surface must be at least 1");
  }
  return ok_status();
}

// Both directions, the larger RMS and max, and the PSNR over the reference's diagonal.
SurfaceDistance both_ways(const std::vector<Eigen::Vector3d>& ref_samples, const NearestSurfacePoint& test_search,
                          const std::vector<Eigen::Vector3d>& test_samples, const NearestSurfacePoint& ref_search,
                          double diag) {
  SurfaceDistance out;
  out.ref_to_test = directed_distance(ref_samples, test_search);
  out.test_to_ref = directed_distance(test_samples, ref_search);
  out.rms = std::max(out.ref_to_test.rms, out.test_to_ref.rms);
  out.hausdorff = std::max(out.ref_to_test.max, out.test_to_ref.max);
  out.diag = diag;
  out.psnr = psnr_db(out.diag, out.rms);
  return out;
}

}  // namespace

StatusOr<SurfaceReference> SurfaceReference::build(const TriangleMesh& reference,
                                                   const SurfaceDistanceOptions& options,
                                                   const NearestSurfacePointBuilder& build_search) {
  SRCODEC_RETURN_IF_ERROR(check_samples(options));
  SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface surface, measured_surface(reference, "reference"));
  const SampleSeeds seeds = sample_seeds(options.seed);
  SurfaceReference out;
  out.build_search_ = build_search;
  out.samples_per_surface_ = options.samples_per_surface;
  out.test_seed_ = seeds.test;
  out.diag_ = bounding_box_diagonal(reference.positions);
  out.samples_ = sample_surface(surface, options.samples_per_surface, seeds.reference);
  out.search_ = build_search(reference, surface.faces);
  return out;
}

StatusOr<SurfaceDistance> SurfaceReference::distance_to(const TriangleMesh& test) const {
  SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface surface, measured_surface(test, "test"));
  // Both serial (or mostly), so at once.
  std::vector<Eigen::Vector3d> test_samples;
  std::unique_ptr<NearestSurfacePoint> test_search;
  tbb::parallel_invoke([&] { test_samples = sample_surface(surface, samples_per_surface_, test_seed_); },
                       [&] { test_search = build_search_(test, surface.faces); });
  return both_ways(samples_, *test_search, test_samples, *search_, diag_);
}

std::unique_ptr<NearestSurfacePoint> triangle_tree_search(const TriangleMesh& mesh, const std::vector<uint32_t>& faces) {
  return std::make_unique<TriangleTreeSearch>(mesh, faces);
}

StatusOr<SurfaceDistance> surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                           const SurfaceDistanceOptions& options) {
  return surface_distance(reference, test, options, triangle_tree_search);
}

StatusOr<SurfaceDistance> surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                           const SurfaceDistanceOptions& options,
                                           const NearestSurfacePointBuilder& build_search) {
  SRCODEC_RETURN_IF_ERROR(check_samples(options));
  SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface ref_surface, measured_surface(reference, "reference"));
  SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface test_surface, measured_surface(test, "test"));
  const SampleSeeds seeds = sample_seeds(options.seed);
  const size_t n = options.samples_per_surface;
  const std::vector<Eigen::Vector3d> ref_samples = sample_surface(ref_surface, n, seeds.reference);
  const std::vector<Eigen::Vector3d> test_samples = sample_surface(test_surface, n, seeds.test);

  // Building a search is sequential, so the two are built at once, one per
  // core; the queries then use every core, one direction after the other.
  std::unique_ptr<NearestSurfacePoint> ref_search, test_search;
  tbb::parallel_invoke([&] { test_search = build_search(test, test_surface.faces); },
                       [&] { ref_search = build_search(reference, ref_surface.faces); });
  return both_ways(ref_samples, *test_search, test_samples, *ref_search, bounding_box_diagonal(reference.positions));
}

}  // namespace srcodec
