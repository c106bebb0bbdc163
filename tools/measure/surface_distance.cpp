#include "tools/measure/surface_distance.h"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "format/area_sampling.h"
#include "format/split_mix64.h"

namespace srcodec {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;

// ---------------------------------------------------------------------------
// A mesh reduced to what has surface: the triangles of positive area.

struct Surface {
  const TriangleMesh* mesh = nullptr;
  std::vector<uint32_t> faces;  // indices into mesh->triangles, positive area only
  std::vector<double> areas;    // area of faces[i]
  double total_area = 0;
};

double triangle_area(const TriangleMesh& mesh, const std::array<int32_t, 3>& t) {
  const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(t[0])];
  const Eigen::Vector3d& b = mesh.positions[static_cast<size_t>(t[1])];
  const Eigen::Vector3d& c = mesh.positions[static_cast<size_t>(t[2])];
  return 0.5 * (b - a).cross(c - a).norm();
}

StatusOr<Surface> make_surface(const TriangleMesh& mesh, const char* role) {
  const size_t num_vertices = mesh.positions.size();
  if (mesh.triangles.size() > std::numeric_limits<uint32_t>::max()) {
    return invalid_mesh(std::string(role) + " mesh has too many triangles (" +
                        std::to_string(mesh.triangles.size()) + ")");
  }
  Surface s;
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
    const double area = triangle_area(mesh, t);
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

// ---------------------------------------------------------------------------
// Area-uniform, stratified sampling: triangle i gets floor(e_i) samples plus
// one more with probability frac(e_i), where e_i = area_i / total * n, so the
// expected count is exactly n and every triangle is represented in proportion.
// Within a triangle, point_in_triangle (format/area_sampling.h).

std::vector<Eigen::Vector3d> sample_surface(const Surface& s, size_t n, uint64_t seed) {
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

// ---------------------------------------------------------------------------
// The AABB tree over a surface. Primitives hold only a 32-bit face index; the
// triangle is built on the fly from the mesh (CGAL's "shared data" primitive,
// which measured faster to build than caching the triangle and uses 72 bytes
// a face less). Per face the tree costs 4 bytes of id and ~64 bytes of node.
//
// Distance queries start from a hint, the nearest of a set of points on the
// surface found in a KD tree. CGAL's default puts one point per face in it,
// which takes nearly as long to build as the AABB tree itself and more memory
// (~100 MB per million faces); the centroid of every kHintStride-th face
// builds 4x faster in a quarter of the memory, for ~10% more query time
// (measured on 1M faces with 2 x 200k samples). The hints only speed the
// search up: the distance found is the same (bit-identical in that test).

constexpr size_t kHintStride = 4;

inline Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

struct FaceTriangleMap {
  using key_type = uint32_t;
  using value_type = Triangle;
  using reference = Triangle;
  using category = boost::readable_property_map_tag;

  const TriangleMesh* mesh = nullptr;

  friend Triangle get(const FaceTriangleMap& map, uint32_t face) {
    const auto& t = map.mesh->triangles[face];
    return Triangle(to_point(map.mesh->positions[static_cast<size_t>(t[0])]),
                    to_point(map.mesh->positions[static_cast<size_t>(t[1])]),
                    to_point(map.mesh->positions[static_cast<size_t>(t[2])]));
  }
};

// The reference point, along which CGAL splits the primitives when building
// the tree, is the face's first corner (the centroid measured no better).
struct FaceCornerMap {
  using key_type = uint32_t;
  using value_type = Point;
  using reference = Point;
  using category = boost::readable_property_map_tag;

  const TriangleMesh* mesh = nullptr;

  friend Point get(const FaceCornerMap& map, uint32_t face) {
    return to_point(map.mesh->positions[static_cast<size_t>(map.mesh->triangles[face][0])]);
  }
};

using Primitive = CGAL::AABB_primitive<uint32_t, FaceTriangleMap, FaceCornerMap,
                                       CGAL::Tag_true /*maps in the tree*/,
                                       CGAL::Tag_false /*no cached datum*/>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

// Builds the tree and its KD tree of hints eagerly: CGAL builds both lazily
// on the first query otherwise, which must not happen inside the parallel
// loop. After this the tree is only read, and queries may run concurrently.
void build_tree(const Surface& s, Tree& tree) {
  FaceTriangleMap triangles{s.mesh};
  FaceCornerMap corners{s.mesh};
  tree.insert(s.faces.begin(), s.faces.end(), triangles, corners);
  tree.build();

  std::vector<Tree::Point_and_primitive_id> hints;
  hints.reserve(s.faces.size() / kHintStride + 1);
  for (size_t i = 0; i < s.faces.size(); i += kHintStride) {
    const auto& t = s.mesh->triangles[s.faces[i]];
    const Eigen::Vector3d centroid = (s.mesh->positions[static_cast<size_t>(t[0])] +
                                      s.mesh->positions[static_cast<size_t>(t[1])] +
                                      s.mesh->positions[static_cast<size_t>(t[2])]) /
                                     3.0;
    hints.emplace_back(to_point(centroid), s.faces[i]);
  }
  tree.accelerate_distance_queries(hints.begin(), hints.end());
}

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

DirectedDistance directed_distance(const std::vector<Eigen::Vector3d>& samples, const Tree& tree) {
  std::vector<double> squared(samples.size());
  // Each sample writes its own slot: any split of the range, any thread
  // count gives the same values.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 256),
                    [&](const tbb::blocked_range<size_t>& range) {
                      for (size_t i = range.begin(); i != range.end(); ++i) {
                        squared[i] = tree.squared_distance(to_point(samples[i]));  // hint from the KD tree
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

}  // namespace

StatusOr<SurfaceDistance> surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                           const SurfaceDistanceOptions& options) {
  if (options.samples_per_surface == 0) {
    return invalid_argument("surface distance: samples_per_surface must be at least 1");
  }
  SRCODEC_ASSIGN_OR_RETURN(const Surface ref_surface, make_surface(reference, "reference"));
  SRCODEC_ASSIGN_OR_RETURN(const Surface test_surface, make_surface(test, "test"));

  // One independent sample stream per surface, both derived from the seed.
  SplitMix64 seeds(options.seed);
  const uint64_t ref_seed = seeds.next();
  const uint64_t test_seed = seeds.next();

  const std::vector<Eigen::Vector3d> ref_samples =
      sample_surface(ref_surface, options.samples_per_surface, ref_seed);
  const std::vector<Eigen::Vector3d> test_samples =
      sample_surface(test_surface, options.samples_per_surface, test_seed);

  // Building a tree is sequential, so the two are built at once, one per
  // core; the queries then use every core, one direction after the other.
  Tree ref_tree, test_tree;
  tbb::parallel_invoke([&] { build_tree(test_surface, test_tree); },
                       [&] { build_tree(ref_surface, ref_tree); });

  SurfaceDistance out;
  out.ref_to_test = directed_distance(ref_samples, test_tree);
  out.test_to_ref = directed_distance(test_samples, ref_tree);
  out.rms = std::max(out.ref_to_test.rms, out.test_to_ref.rms);
  out.hausdorff = std::max(out.ref_to_test.max, out.test_to_ref.max);
  out.diag = bounding_box_diagonal(reference.positions);
  out.psnr = out.rms > 0 ? 20.0 * std::log10(out.diag / out.rms)
                         : std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace srcodec
