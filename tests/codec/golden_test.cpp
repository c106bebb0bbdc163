// Pins .srm versions 1 and 2: a file written by each version's encoder
// (tools/make_golden.sh) must keep decoding to the same meshes.
#include <gtest/gtest.h>

#include "codec/srm_codec.h"
#include "format/mesh_files/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

// `version`'s golden file (`size` bytes) decodes to its pinned meshes.
void expect_golden(int version, uint64_t size, int raw_planes) {
  const std::string name = "tests/data/golden_v" + std::to_string(version);
  StatusOr<SrmFile> file = read_srm(test::source_path(name + ".srm"));
  ASSERT_TRUE(file.ok()) << file.status().message();
  EXPECT_EQ(file->header.version(), version);
  EXPECT_EQ(file->header.raw_planes, raw_planes);
  EXPECT_EQ(file->header.levels, 2);
  EXPECT_EQ(file->header.input_vertices, 2930u);
  EXPECT_EQ(file->file_size, size);
  for (int level = 0; level <= 2; ++level) {
    SrmDecodeOptions options;
    options.level = level;
    StatusOr<DecodedSrm> decoded = decode_srm(file.value(), options);
    ASSERT_TRUE(decoded.ok()) << decoded.status().message();
    StatusOr<TriangleMesh> pinned =
        read_triangle_mesh(test::source_path(name + "_l" + std::to_string(level) + ".obj"));
    ASSERT_TRUE(pinned.ok()) << pinned.status().message();
    ASSERT_EQ(decoded->mesh.positions.size(), pinned->positions.size()) << level;
    ASSERT_EQ(decoded->mesh.triangles, pinned->triangles) << level;
    double worst = 0;
    for (size_t v = 0; v < pinned->positions.size(); ++v)
      worst = std::max(worst, (decoded->mesh.positions[v] - pinned->positions[v]).norm());
    EXPECT_LT(worst, 1e-6) << level;  // the OBJ reader parses single precision
  }
}

TEST(GoldenV1, DecodesToThePinnedMeshesAtEveryLevel) { expect_golden(1, 2500, 0); }

// Version 2 with raw planes 0 and 1, cut inside plane 0.
TEST(GoldenV2, DecodesToThePinnedMeshesAtEveryLevel) { expect_golden(2, 5400, 2); }

}  // namespace
}  // namespace srcodec
