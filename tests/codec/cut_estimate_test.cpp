// CutEstimate (codec/cut_estimate.h): the PSNR of a cut from its
// displacement against the whole stream's mesh, on displacements whose mean
// square over the surface is known.
#include "codec/cut_estimate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace srcodec {
namespace {

// The unit square in the plane z = 0, n x n cells of two triangles each.
TriangleMesh square(int n) {
  TriangleMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.positions.emplace_back(double(i) / n, double(j) / n, 0.0);
  const auto at = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

SurfaceDistance measured(double rms, double diag) {
  SurfaceDistance s;
  s.rms = rms;
  s.diag = diag;
  s.psnr = rms > 0 ? 20.0 * std::log10(diag / rms) : INFINITY;
  return s;
}

double psnr_of(double rms, double diag) { return 20.0 * std::log10(diag / rms); }

TEST(CutEstimate, TheWholeStreamIsItsMeasure) {
  const TriangleMesh whole = square(4);
  const CutEstimate e(whole, measured(0.01, 2.0));
  EXPECT_DOUBLE_EQ(e.whole_psnr(), psnr_of(0.01, 2.0));
  EXPECT_NEAR(e.psnr(whole).value(), psnr_of(0.01, 2.0), 1e-9);
}

TEST(CutEstimate, ADisplacementAcrossTheSurfaceAddsItsMeanSquare) {
  const TriangleMesh whole = square(8);
  TriangleMesh cut = whole;
  // A constant offset of 0.003 across: its mean square is 0.003².
  for (auto& p : cut.positions) p.z() += 0.003;
  const CutEstimate exact(whole, measured(0.0, 1.0));
  EXPECT_NEAR(exact.psnr(cut).value(), psnr_of(0.003, 1.0), 1e-9);
  // Added to a remesh error of 0.004: sqrt(0.003² + 0.004²) = 0.005.
  const CutEstimate remeshed(whole, measured(0.004, 1.0));
  EXPECT_NEAR(remeshed.psnr(cut).value(), psnr_of(0.005, 1.0), 1e-9);
  // A ramp z = 0.01 x, linear on every triangle: its mean square over the
  // unit square is 0.01² / 3, exactly.
  for (size_t v = 0; v < cut.positions.size(); ++v) cut.positions[v].z() = 0.01 * whole.positions[v].x();
  EXPECT_NEAR(exact.psnr(cut).value(), psnr_of(0.01 / std::sqrt(3.0), 1.0), 1e-9);
}

TEST(CutEstimate, ADisplacementAlongTheSurfaceCostsNothing) {
  const TriangleMesh whole = square(8);
  TriangleMesh cut = whole;
  for (auto& p : cut.positions) p.x() += 0.002 * p.y();
  const CutEstimate e(whole, measured(0.001, 1.0));
  EXPECT_NEAR(e.psnr(cut).value(), psnr_of(0.001, 1.0), 1e-9);
  const CutEstimate exact(whole, measured(0.0, 1.0));
  EXPECT_TRUE(std::isinf(exact.psnr(cut).value()));
}

TEST(CutEstimate, AnotherMeshIsRefused) {
  const CutEstimate e(square(4), measured(0.01, 1.0));
  const StatusOr<double> other = e.psnr(square(5));
  ASSERT_FALSE(other.ok());
  EXPECT_EQ(other.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(other.status().message().find("not the whole stream's"), std::string::npos) << other.status().message();
}

}  // namespace
}  // namespace srcodec
