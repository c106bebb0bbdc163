#include "format/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::ScratchDir;

TEST(MeshIo, ReadsBundledSample) {
  auto mesh = read_polygon_mesh(test::source_path("data/spot.obj"));
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  EXPECT_EQ(mesh->positions.size(), 2930u);
  EXPECT_EQ(mesh->num_faces(), 5856u);
}

TEST(MeshIo, ObjAndPlyRoundTripExactly) {
  const TriangleMesh cube = test::unit_cube();
  const TriangleMesh sphere = test::icosphere(2, 0.37);  // non-float-exact doubles
  ScratchDir dir;
  for (const TriangleMesh* mesh : {&cube, &sphere}) {
    for (const char* name : {"m.obj", "m.ply"}) {
      ASSERT_TRUE(write_mesh(*mesh, dir.file(name)).ok());
      auto back = read_triangle_mesh(dir.file(name));
      ASSERT_TRUE(back.ok()) << back.status().message();
      ASSERT_EQ(back->positions.size(), mesh->positions.size()) << name;
      EXPECT_EQ(back->triangles, mesh->triangles) << name;
      for (size_t i = 0; i < mesh->positions.size(); ++i) {
        // Float-exact positions come back exactly; OpenMesh's readers parse
        // coordinates as float, so others come back to float precision.
        const double tolerance = mesh == &cube ? 0.0 : 1e-7;
        EXPECT_NEAR((back->positions[i] - mesh->positions[i]).norm(), 0.0, tolerance) << name << " vertex " << i;
      }
    }
  }
}

TEST(MeshIo, ReadsOffAndAsciiStl) {
  ScratchDir dir;
  const std::string off = dir.write("t.off", "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  auto m = read_triangle_mesh(off);
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_EQ(m->positions.size(), 4u);
  EXPECT_EQ(m->triangles.size(), 4u);

  std::string stl = "solid t\n";
  const TriangleMesh tet = test::tetrahedron();
  for (const auto& t : tet.triangles) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (int k = 0; k < 3; ++k) {
      const auto& p = tet.positions[t[k]];
      stl += "vertex " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
    }
    stl += "endloop\nendfacet\n";
  }
  stl += "endsolid t\n";
  auto s = read_triangle_mesh(dir.write("t.stl", stl));
  ASSERT_TRUE(s.ok()) << s.status().message();
  EXPECT_EQ(s->positions.size(), 4u);  // STL repeats corners; they are welded
  EXPECT_EQ(s->triangles.size(), 4u);
}

TEST(MeshIo, ReadsPlyTriangleStrips) {
  ScratchDir dir;
  // A strip over a 2x1 quad row: 0 1 2 3 4 5 gives 4 triangles, then a restart.
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
      "element tristrips 1\nproperty list int int vertex_indices\nend_header\n"
      "0 0 0\n0 1 0\n1 0 0\n1 1 0\n2 0 0\n2 1 0\n"
      "7 0 1 2 3 4 5 -1\n";
  auto m = read_triangle_mesh(dir.write("s.ply", ply));
  ASSERT_TRUE(m.ok()) << m.status().message();
  ASSERT_EQ(m->triangles.size(), 4u);
  // Alternate triangles are flipped so all normals agree (all -z here).
  for (const auto& t : m->triangles) {
    const Eigen::Vector3d n = (m->positions[t[1]] - m->positions[t[0]]).cross(m->positions[t[2]] - m->positions[t[0]]);
    EXPECT_LT(n.z(), 0.0);
  }
}

TEST(MeshIo, CorpusTristripPlyMatchesItsObj) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not present";
  auto ply = read_triangle_mesh(test::corpus_path("igea.ply"));
  ASSERT_TRUE(ply.ok()) << ply.status().message();
  EXPECT_EQ(ply->positions.size(), 134345u);
  EXPECT_EQ(ply->triangles.size(), 268686u);
}

struct BadInput {
  const char* name;
  const char* contents;  // nullptr: the file is not created
  const char* expected;  // part of the error message
};

class MeshIoBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(MeshIoBadInput, ClearErrorNamingTheFile) {
  ScratchDir dir;
  const BadInput& b = GetParam();
  const std::string path = b.contents ? dir.write(b.name, b.contents) : dir.file(b.name);
  auto m = read_triangle_mesh(path);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find(path), std::string::npos) << m.status().message();
  EXPECT_NE(m.status().message().find(b.expected), std::string::npos) << m.status().message();
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MeshIoBadInput,
    ::testing::Values(BadInput{"missing.obj", nullptr, "no such file"},
                      BadInput{"mesh.xyz", "v 0 0 0\n", "unknown mesh extension"},
                      BadInput{"empty.obj", "", "empty"},
                      BadInput{"garbage.ply", "\x01\x02\xff\xfe garbage\n\x7f", "not a PLY file"},
                      BadInput{"garbage.off", "this is not an off file\n", "not an OFF file"},
                      BadInput{"range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "vertex index 9"},
                      BadInput{"nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "not a finite number"},
                      BadInput{"inf.off", "OFF\n3 1 0\n0 0 0\ninf 0 0\n0 1 0\n3 0 1 2\n", "not a finite number"},
                      BadInput{"short.obj", "v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2"},
                      BadInput{"inf.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 -inf 0\n3 0 1 2\n", "line 12"},
                      BadInput{"huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4294967295 0 1 2\n", "line 6"},
                      BadInput{"counts.off", "OFF\n49999999999999999 1 0\n0 0 0\n", "only 1 lines follow"},
                      BadInput{"nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces"},
                      BadInput{"flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "degenerate"}),
    [](const auto& test_param) {
      std::string n = test_param.param.name;
      for (auto& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return n;
    });

TEST(MeshIo, FailedWriteLeavesExistingFileAlone) {
  ScratchDir dir;
  const std::string path = dir.write("keep.obj", "original");
  EXPECT_FALSE(write_mesh(test::unit_cube(), dir.file("no/such/folder/x.obj")).ok());
  EXPECT_FALSE(write_mesh(test::unit_cube(), dir.file("x.stl")).ok());  // unsupported output
  auto bytes = read_file_bytes(path);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(bytes.value(), "original");
  // No temporary files left behind.
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.file(""))) ++files;
  EXPECT_EQ(files, 1u);
}

}  // namespace
}  // namespace srcodec
