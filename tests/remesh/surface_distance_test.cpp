#include "remesh/surface_distance.h"

#include "tests/test_util.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace srcodec {
namespace {

constexpr size_t kSamples = 20000;

SurfaceDistanceOptions options_with(size_t samples, uint64_t seed = 1) {
  SurfaceDistanceOptions o;
  o.samples_per_surface = samples;
  o.seed = seed;
  return o;
}

// The unit square z = 0, [0,1]^2, as two triangles.
TriangleMesh unit_square() {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

using test::icosphere;

TriangleMesh scaled(TriangleMesh m, double factor) {
  for (auto& v : m.positions) v *= factor;
  return m;
}

TriangleMesh translated(TriangleMesh m, const Eigen::Vector3d& t) {
  for (auto& v : m.positions) v += t;
  return m;
}

// Area-weighted RMS over the faces of f(face normal, distance of the face's
// plane from the origin).
template <typename F>
double area_weighted_rms(const TriangleMesh& m, F f) {
  double sum = 0, area = 0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d& a = m.positions[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = m.positions[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = m.positions[static_cast<size_t>(t[2])];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const Eigen::Vector3d n = cross.normalized();
    const double value = f(n, n.dot(a));
    sum += 0.5 * cross.norm() * value * value;
    area += 0.5 * cross.norm();
  }
  return std::sqrt(sum / area);
}

void expect_identical(const SurfaceDistance& a, const SurfaceDistance& b) {
  for (const auto& [x, y] : {std::make_pair(a.ref_to_test, b.ref_to_test),
                             std::make_pair(a.test_to_ref, b.test_to_ref)}) {
    EXPECT_EQ(x.rms, y.rms);
    EXPECT_EQ(x.mean, y.mean);
    EXPECT_EQ(x.max, y.max);
    EXPECT_EQ(x.samples, y.samples);
  }
  EXPECT_EQ(a.rms, b.rms);
  EXPECT_EQ(a.hausdorff, b.hausdorff);
  EXPECT_EQ(a.diag, b.diag);
  EXPECT_EQ(a.psnr, b.psnr);
}

TEST(SurfaceDistanceTest, MeshAgainstItselfIsZero) {
  const TriangleMesh sphere = icosphere(3, 2.0);
  auto result = surface_distance(sphere, sphere, options_with(kSamples));
  ASSERT_TRUE(result.ok()) << result.status().message();
  const double diag = bounding_box_diagonal(sphere.positions);
  EXPECT_DOUBLE_EQ(result->diag, diag);
  EXPECT_LT(result->rms, 1e-12 * diag);
  EXPECT_LT(result->hausdorff, 1e-12 * diag);
  EXPECT_GT(result->psnr, 200.0);  // +inf when every distance rounds to exactly 0
}

TEST(SurfaceDistanceTest, ExactlyZeroGivesInfinitePsnr) {
  // Samples on the axis-aligned square project onto it exactly.
  const TriangleMesh square = unit_square();
  auto result = surface_distance(square, square, options_with(1000));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_EQ(result->rms, 0.0);
  EXPECT_EQ(result->psnr, std::numeric_limits<double>::infinity());
}

TEST(SurfaceDistanceTest, SampleCountIsAreaUniformAndNearTheRequest) {
  // Two triangles of areas 1/2 and 1/2 * 3: expected counts N/4 and 3N/4,
  // each floor(e) or floor(e)+1, so the total is within 2 of N.
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {3, 0, 1}, {0, 1, 1}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  auto result = surface_distance(m, m, options_with(1001));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_GE(result->ref_to_test.samples, 999u);
  EXPECT_LE(result->ref_to_test.samples, 1003u);
  EXPECT_GE(result->test_to_ref.samples, 999u);
  EXPECT_LE(result->test_to_ref.samples, 1003u);
}

// Two icospheres with identical connectivity, the second scaled radially by
// s = 1 + delta/r. Every face plane of the inner sphere A is at distance h_f
// from the centre and its scaled copy at s h_f; the faces are acute, so the
// foot of the centre lies inside each face and a sample on face f of A
// projects inside face f of B: its distance is (s - 1) h_f = delta h_f / r
// (ignoring a band ~delta wide along the edges, whose neighbouring plane can
// be nearer). The analytic RMS is then delta * area-weighted RMS of h_f / r:
// exact for the polyhedra, no chordal error, and within ~0.1% of delta
// itself at 4 levels (h_f / r = cos of the face's angular circumradius).
TEST(SurfaceDistanceTest, ConcentricIcospheresGiveTheRadialOffset) {
  const double r = 3.0, delta = 1e-3 * r;
  const TriangleMesh inner = icosphere(4, r);
  const TriangleMesh outer = scaled(inner, 1.0 + delta / r);
  const double expected = delta / r * area_weighted_rms(inner, [](const Eigen::Vector3d&, double h) { return h; });
  ASSERT_NEAR(expected, delta, 2e-3 * delta);

  auto result = surface_distance(inner, outer, options_with(kSamples));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_NEAR(result->ref_to_test.rms, expected, 2e-4 * expected);
  EXPECT_NEAR(result->test_to_ref.rms, expected, 2e-4 * expected);
  EXPECT_NEAR(result->rms, delta, 1e-2 * delta);  // the 1% against the sphere
  EXPECT_NEAR(result->ref_to_test.mean, expected, 5e-4 * expected);
  // Every distance is at most delta: the largest is between a vertex of B and
  // the matching vertex of A, exactly delta apart.
  EXPECT_LE(result->hausdorff, delta * (1 + 1e-9));
  EXPECT_GT(result->hausdorff, 0.99 * delta);
  EXPECT_DOUBLE_EQ(result->diag, bounding_box_diagonal(inner.positions));
  EXPECT_NEAR(result->psnr, 20 * std::log10(result->diag / result->rms), 1e-9);
}

TEST(SurfaceDistanceTest, SquareTranslatedPerpendicularIsExactlyTheOffset) {
  const double offset = 0.0125;
  const TriangleMesh square = unit_square();
  auto result = surface_distance(square, translated(square, {0, 0, offset}), options_with(kSamples));
  ASSERT_TRUE(result.ok()) << result.status().message();
  // Every sample projects inside the other square at exactly `offset`.
  // (Up to rounding in the closest-point construction: 1e-12 relative.)
  EXPECT_NEAR(result->ref_to_test.rms, offset, 1e-12 * offset);
  EXPECT_NEAR(result->test_to_ref.rms, offset, 1e-12 * offset);
  EXPECT_NEAR(result->ref_to_test.mean, offset, 1e-12 * offset);
  EXPECT_NEAR(result->rms, offset, 1e-12 * offset);
  EXPECT_NEAR(result->hausdorff, offset, 1e-12 * offset);
  EXPECT_DOUBLE_EQ(result->diag, std::sqrt(2.0));
  EXPECT_NEAR(result->psnr, 20 * std::log10(std::sqrt(2.0) / offset), 1e-9);
}

TEST(SurfaceDistanceTest, SquareTranslatedInItsPlane) {
  // Shifted by t along x: samples on the reference with x < t are t - x from
  // the copy, the rest are on it. RMS = sqrt(int_0^t (t-x)^2 dx) = sqrt(t^3/3)
  // each way, Hausdorff = t (the edge x = 0). Only ~t of the samples see a
  // distance, so this one takes 10x the samples: the estimate's standard
  // deviation is then ~0.5%, the tolerance 5 of them.
  const double t = 0.1;
  const TriangleMesh square = unit_square();
  auto result = surface_distance(square, translated(square, {t, 0, 0}), options_with(10 * kSamples));
  ASSERT_TRUE(result.ok()) << result.status().message();
  const double expected_rms = std::sqrt(t * t * t / 3);
  EXPECT_NEAR(result->ref_to_test.rms, expected_rms, 0.025 * expected_rms);
  EXPECT_NEAR(result->test_to_ref.rms, expected_rms, 0.025 * expected_rms);
  EXPECT_NEAR(result->ref_to_test.mean, t * t / 2, 0.025 * t * t / 2);
  EXPECT_LE(result->hausdorff, t);
  EXPECT_GT(result->hausdorff, 0.99 * t);
}

// A closed, curved mesh translated along an axis by t, small against the
// faces: a sample on face f is |t . n_f| from the copy (away from a thin band
// along the edges), so RMS = |t| * area-weighted RMS of |n_f . e_z|, which is
// 1/sqrt(3) for a sphere (and exactly so for the icosphere: a quadratic form
// averaged over a shape with icosahedral symmetry is isotropic); Hausdorff is
// |t|, at the poles. The band along the edges lowers the RMS by ~0.1% here.
TEST(SurfaceDistanceTest, IcosphereTranslatedAlongAnAxis) {
  const double r = 1.0, t = 1e-3;
  const TriangleMesh sphere = icosphere(4, r);
  const double expected =
      t * area_weighted_rms(sphere, [](const Eigen::Vector3d& n, double) { return n.z(); });
  ASSERT_NEAR(expected, t / std::sqrt(3.0), 1e-9 * t);

  auto result = surface_distance(sphere, translated(sphere, {0, 0, t}), options_with(kSamples));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_NEAR(result->ref_to_test.rms, expected, 5e-3 * expected);
  EXPECT_NEAR(result->test_to_ref.rms, expected, 5e-3 * expected);
  EXPECT_NEAR(result->rms, expected, 5e-3 * expected);
  EXPECT_LE(result->hausdorff, t * (1 + 1e-9));
  EXPECT_GT(result->hausdorff, 0.98 * t);
}

TEST(SurfaceDistanceTest, SameSeedSameFiguresWhateverTheThreadCount) {
  const TriangleMesh a = icosphere(3, 1.0);
  const TriangleMesh b = translated(scaled(a, 1.01), {0.003, -0.002, 0.001});
  // Fewer samples here: four runs, and bit-identity needs no statistics.
  const size_t samples = kSamples / 4;
  auto first = surface_distance(a, b, options_with(samples, 7));
  auto second = surface_distance(a, b, options_with(samples, 7));
  ASSERT_TRUE(first.ok() && second.ok());
  expect_identical(first.value(), second.value());

  {
    tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
    auto sequential = surface_distance(a, b, options_with(samples, 7));
    ASSERT_TRUE(sequential.ok());
    expect_identical(first.value(), sequential.value());
  }

  // A different seed draws different samples: close figures, not the same.
  auto other = surface_distance(a, b, options_with(samples, 8));
  ASSERT_TRUE(other.ok());
  EXPECT_NE(other->ref_to_test.rms, first->ref_to_test.rms);
  EXPECT_NEAR(other->rms, first->rms, 0.02 * first->rms);
}

TEST(SurfaceDistanceTest, AReferenceBuiltOnceGivesTheSameFiguresForEveryTest) {
  const TriangleMesh a = icosphere(3, 1.0);
  const std::vector<TriangleMesh> tests = {translated(scaled(a, 1.01), {0.003, -0.002, 0.001}), icosphere(2, 0.98), a};
  const SurfaceDistanceOptions options = options_with(kSamples / 4, 3);
  auto reference = SurfaceReference::build(a, options);
  ASSERT_TRUE(reference.ok()) << reference.status().message();
  for (const TriangleMesh& test : tests) {
    auto once = surface_distance(a, test, options);
    auto kept = reference->distance_to(test);
    ASSERT_TRUE(once.ok() && kept.ok());
    expect_identical(once.value(), kept.value());
  }
  TriangleMesh no_surface = unit_square();
  for (auto& t : no_surface.triangles) t = {t[0], t[0], t[1]};
  EXPECT_EQ(reference->distance_to(no_surface).status().code(), StatusCode::kInvalidMesh);
  EXPECT_EQ(SurfaceReference::build(no_surface, options).status().code(), StatusCode::kInvalidMesh);
  EXPECT_EQ(SurfaceReference::build(a, options_with(0)).status().code(), StatusCode::kInvalidArgument);
}

TEST(SurfaceDistanceTest, ZeroAreaTrianglesAreIgnored) {
  // The square plus a degenerate sliver far away: the sliver has no surface,
  // so it neither draws samples nor attracts distances.
  TriangleMesh with_sliver = unit_square();
  with_sliver.positions.push_back({5, 5, 5});
  with_sliver.positions.push_back({6, 6, 6});
  with_sliver.positions.push_back({7, 7, 7});
  with_sliver.triangles.push_back({4, 5, 6});
  with_sliver.triangles.push_back({0, 0, 1});
  const TriangleMesh lifted = translated(unit_square(), {0, 0, 0.25});
  auto result = surface_distance(with_sliver, lifted, options_with(kSamples));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_NEAR(result->hausdorff, 0.25, 1e-12);
  EXPECT_NEAR(result->rms, 0.25, 1e-12);
}

TEST(SurfaceDistanceTest, SingleTriangles) {
  // One primitive: CGAL's tree has no node at all, only the primitive.
  TriangleMesh a;
  a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  a.triangles = {{0, 1, 2}};
  auto result = surface_distance(a, translated(a, {0, 0, -0.5}), options_with(1000));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_NEAR(result->rms, 0.5, 1e-12);
  EXPECT_NEAR(result->hausdorff, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(result->diag, std::sqrt(2.0));
}

TEST(SurfaceDistanceTest, MeshWithoutSurfaceIsInvalid) {
  const TriangleMesh square = unit_square();
  TriangleMesh degenerate;
  degenerate.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  degenerate.triangles = {{0, 1, 2}, {1, 1, 2}};

  auto as_test = surface_distance(square, degenerate);
  ASSERT_FALSE(as_test.ok());
  EXPECT_EQ(as_test.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(as_test.status().message().find("test mesh has no triangle of positive area"), std::string::npos)
      << as_test.status().message();

  auto as_reference = surface_distance(degenerate, square);
  ASSERT_FALSE(as_reference.ok());
  EXPECT_EQ(as_reference.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(as_reference.status().message().find("reference mesh"), std::string::npos);

  auto empty = surface_distance(TriangleMesh{}, square);
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.status().code(), StatusCode::kInvalidMesh);
}

TEST(SurfaceDistanceTest, BadIndicesAndNonFinitePositionsAreInvalid) {
  const TriangleMesh square = unit_square();
  TriangleMesh out_of_range = unit_square();
  out_of_range.triangles.push_back({0, 2, 4});
  auto result = surface_distance(square, out_of_range);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(result.status().message().find("vertex 4"), std::string::npos) << result.status().message();

  TriangleMesh not_finite = unit_square();
  not_finite.positions[2].x() = std::numeric_limits<double>::quiet_NaN();
  result = surface_distance(not_finite, square);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidMesh);
}

TEST(SurfaceDistanceTest, ZeroSamplesIsAnInvalidArgument) {
  const TriangleMesh square = unit_square();
  auto result = surface_distance(square, square, options_with(0));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.status().code(), StatusCode::kInvalidArgument);
}

TEST(SurfaceDistanceTest, OneSampleRequestedGivesAtLeastOne) {
  const TriangleMesh sphere = icosphere(2, 1.0);
  auto result = surface_distance(sphere, scaled(sphere, 1.5), options_with(1));
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_GE(result->ref_to_test.samples, 1u);
  EXPECT_GE(result->test_to_ref.samples, 1u);
  EXPECT_GT(result->rms, 0.0);
}

}  // namespace
}  // namespace srcodec
