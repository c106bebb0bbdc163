// The metric (remesh/surface_distance.h) with our tree, as the encoder
// measures, and with CGAL's search (tools/measure/surface_distance.h), as
// `compare` and `rd` do: the same samples and exact distances, so the same
// figures up to the rounding of each distance.
#include "tools/measure/surface_distance.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "format/mesh_files/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

// Every vertex moved by up to `amount` of the bounding-box diagonal.
TriangleMesh jittered(TriangleMesh m, double amount, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double step = amount * bounding_box_diagonal(m.positions);
  for (auto& p : m.positions) p += step * Eigen::Vector3d(unit(random), unit(random), unit(random));
  return m;
}

void expect_same_figures(const TriangleMesh& reference, const TriangleMesh& test, const std::string& what) {
  SurfaceDistanceOptions o;
  o.samples_per_surface = 30000;
  const StatusOr<SurfaceDistance> ours = surface_distance(reference, test, o);
  const StatusOr<SurfaceDistance> cgal = cgal_surface_distance(reference, test, o);
  ASSERT_TRUE(ours.ok()) << ours.status().message();
  ASSERT_TRUE(cgal.ok()) << cgal.status().message();
  const auto near = [&](double a, double b, const char* name) {
    EXPECT_NEAR(a, b, 1e-9 * std::abs(b)) << what << ": " << name;
  };
  for (const auto& [a, b] : {std::pair{ours->ref_to_test, cgal->ref_to_test}, {ours->test_to_ref, cgal->test_to_ref}}) {
    EXPECT_EQ(a.samples, b.samples) << what;
    near(a.rms, b.rms, "rms");
    near(a.mean, b.mean, "mean");
    near(a.max, b.max, "max");
  }
  near(ours->hausdorff, cgal->hausdorff, "hausdorff");
  near(ours->psnr, cgal->psnr, "psnr");
  EXPECT_GT(ours->rms, 0.0) << what;
}

TEST(SurfaceDistanceBackends, AgreeOnSpheresAndCubes) {
  const TriangleMesh sphere = test::icosphere(4, 2.0);
  expect_same_figures(sphere, jittered(sphere, 1e-3, 1), "jittered icosphere");
  expect_same_figures(sphere, test::icosphere(2, 2.0), "icospheres of two resolutions");
  const TriangleMesh cube = test::unit_cube();
  expect_same_figures(cube, jittered(cube, 1e-2, 2), "jittered cube");
}

TEST(SurfaceDistanceBackends, AgreeOnTheSamples) {
  for (const char* name : {"data/spot.obj", "data/bunny_npm.obj"}) {
    const StatusOr<TriangleMesh> mesh = read_triangle_mesh(test::source_path(name));
    ASSERT_TRUE(mesh.ok()) << mesh.status().message();
    expect_same_figures(*mesh, jittered(*mesh, 2e-4, 3), name);
  }
}

TEST(SurfaceDistanceBackends, FailAlike) {
  TriangleMesh flat;
  flat.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.triangles = {{0, 1, 2}};
  const TriangleMesh sphere = test::icosphere(1, 1.0);
  const auto ours = surface_distance(sphere, flat), cgal = cgal_surface_distance(sphere, flat);
  ASSERT_FALSE(ours.ok());
  ASSERT_FALSE(cgal.ok());
  EXPECT_EQ(ours.status().message(), cgal.status().message());
}

}  // namespace
}  // namespace srcodec
