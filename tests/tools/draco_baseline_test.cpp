#include "tools/measure/draco_baseline.h"

#include <gtest/gtest.h>

#include "format/mesh_files/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

TEST(DracoBaseline, RoundTripKeepsTopologyAndQuantizationBound) {
  auto mesh = read_triangle_mesh(test::source_path("data/bunny_npm.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  const double diag = bounding_box_diagonal(mesh->positions);
  size_t previous_bytes = 0;
  for (int qp : {8, 11, 14}) {
    auto r = draco_round_trip(mesh.value(), {qp, 10});
    ASSERT_TRUE(r.ok()) << r.status().message();
    EXPECT_EQ(r->decoded.triangles.size(), mesh->triangles.size());
    EXPECT_EQ(r->decoded.positions.size(), mesh->positions.size());
    EXPECT_GT(r->encoded.size(), previous_bytes) << "more bits, more bytes";
    previous_bytes = r->encoded.size();
    // Every decoded vertex lies within half a quantization cell of an input
    // vertex: Draco quantizes over the largest bounding-box side.
    const double cell = diag / double((1 << qp) - 1);
    double worst = 0;
    std::vector<Eigen::Vector3d> sorted = mesh->positions;
    for (const auto& p : r->decoded.positions) {
      double best = 1e300;
      for (const auto& q : sorted) best = std::min(best, (p - q).squaredNorm());
      worst = std::max(worst, std::sqrt(best));
    }
    EXPECT_LE(worst, cell) << "qp " << qp;
    EXPECT_GT(r->encode_ms, 0.0);
    EXPECT_GT(r->decode_ms, 0.0);
  }
}

TEST(DracoBaseline, DecodeRejectsGarbage) {
  auto r = draco_decode("definitely not a draco stream");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("Draco"), std::string::npos);
}

TEST(DracoBaseline, RejectsBadOptions) {
  EXPECT_FALSE(draco_round_trip(test::unit_cube(), {0, 10}).ok());
  EXPECT_FALSE(draco_round_trip(test::unit_cube(), {11, 11}).ok());
  EXPECT_FALSE(draco_round_trip(TriangleMesh{}, {11, 10}).ok());
}

}  // namespace
}  // namespace srcodec
