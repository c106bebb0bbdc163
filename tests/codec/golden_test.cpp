// Pins .srm version 1: a file written by the version-1 encoder
// (tools/make_golden.sh) must keep decoding to the same meshes.
#include <gtest/gtest.h>

#include "codec/srm_codec.h"
#include "format/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

TEST(GoldenV1, DecodesToThePinnedMeshesAtEveryLevel) {
  const std::string path = test::source_path("tests/data/golden_v1.srm");
  StatusOr<SrmFile> file = read_srm(path);
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_EQ(file->header.levels, 2);
  EXPECT_EQ(file->header.input_vertices, 2930u);
  EXPECT_EQ(file->file_size, 2500u);
  for (int level = 0; level <= 2; ++level) {
    DecodeOptions options;
    options.level = level;
    StatusOr<DecodedSrm> decoded = decode_srm(file.value(), options);
    ASSERT_TRUE(decoded.ok()) << decoded.status().message();
    StatusOr<TriangleMesh> pinned =
        read_triangle_mesh(test::source_path("tests/data/golden_v1_l" + std::to_string(level) + ".obj"));
    ASSERT_TRUE(pinned.ok()) << pinned.status().message();
    ASSERT_EQ(decoded->mesh.positions.size(), pinned->positions.size()) << level;
    ASSERT_EQ(decoded->mesh.triangles, pinned->triangles) << level;
    double worst = 0;
    for (size_t v = 0; v < pinned->positions.size(); ++v)
      worst = std::max(worst, (decoded->mesh.positions[v] - pinned->positions[v]).norm());
    EXPECT_LT(worst, 1e-6) << level;  // the OBJ reader parses single precision
  }
}

}  // namespace
}  // namespace srcodec
