#include "format/mesh_files/mesh_io.h"

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
    for (const char* name : {"m.obj", "m.ply", "m.off"}) {
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

// The OBJ writer's text, to the byte: without normals (what `srcodec decode`
// writes for files without creases), and with a normal per sector.
TEST(MeshIo, ObjTextWithAndWithoutNormals) {
  ScratchDir dir;
  TriangleMesh m = test::tetrahedron();
  m.positions[3].z() = 0.1;  // not a float: written as a double
  ASSERT_TRUE(write_mesh(m, dir.file("plain.obj")).ok());
  EXPECT_EQ(read_file_bytes(dir.file("plain.obj")).value(),
            "# written by srcodec\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0.1\n"
            "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
  SectorNormals n;
  n.normals = {{0, 0, -1}, {0, -1, 0}, {0.6f, 0.8f, 0}};
  n.vertex = {0, 1, 2};
  n.corners = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 1, 2}};
  ASSERT_TRUE(write_mesh(m, dir.file("normals.obj"), &n).ok());
  EXPECT_EQ(read_file_bytes(dir.file("normals.obj")).value(),
            "# written by srcodec\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 0.1\nvn 0 0 -1\nvn 0 -1 0\nvn 0.6 0.8 0\n"
            "f 1//1 3//1 2//1\nf 1//2 2//2 4//2\nf 1//3 4//3 3//3\nf 2//1 3//2 4//3\n");
  // The other formats have no normals per corner: the same bytes without.
  for (const char* name : {"m.ply", "m.off", "m.stl"}) {
    ASSERT_TRUE(write_mesh(m, dir.file(std::string("a_") + name)).ok());
    ASSERT_TRUE(write_mesh(m, dir.file(std::string("b_") + name), &n).ok());
    EXPECT_EQ(read_file_bytes(dir.file(std::string("a_") + name)).value(),
              read_file_bytes(dir.file(std::string("b_") + name)).value()) << name;
  }
}

TEST(MeshIo, StlRoundTripsToFloatPrecision) {
  const TriangleMesh sphere = test::icosphere(2, 0.37);
  ScratchDir dir;
  ASSERT_TRUE(write_mesh(sphere, dir.file("m.stl")).ok());
  auto back = read_triangle_mesh(dir.file("m.stl"));
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_EQ(back->positions.size(), sphere.positions.size());  // corners welded back
  ASSERT_EQ(back->triangles.size(), sphere.triangles.size());
  for (size_t t = 0; t < sphere.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d original = sphere.positions[sphere.triangles[t][k]];
      EXPECT_NEAR((back->positions[back->triangles[t][k]] - original).norm(), 0.0, 1e-7);
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
  // Some exporters write the keywords in capitals.
  std::string upper = stl;
  for (char& ch : upper) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  auto u = read_triangle_mesh(dir.write("u.stl", upper));
  ASSERT_TRUE(u.ok()) << u.status().message();
  EXPECT_EQ(u->triangles.size(), 4u);
}

TEST(MeshIo, ReadsObjStatements) {
  ScratchDir dir;
  // Texture and normal indices, relative indices, a continued line, a
  // quad, comments, CRLF line ends and statements srcodec ignores.
  const std::string obj =
      "# comment\r\nmtllib x.mtl\r\no thing\nv 0 0 0 1.0\nv 1 0 0\nv +1 1 0 0.5 0.5 0.5\nv 0 1e0 0\n"
      "vt 0 0\nvn 0 0 1\ng group\ns 1\nusemtl m\n"
      "f 1/1/1 2/1/1 \\\n 3/1/1\nf -4//1 -2//1 -1//1\nl 1 2\nf 1 2 3 4 # a quad\n";
  auto m = read_polygon_mesh(dir.write("s.obj", obj));
  ASSERT_TRUE(m.ok()) << m.status().message();
  ASSERT_EQ(m->positions.size(), 4u);
  EXPECT_EQ(m->positions[2], Eigen::Vector3d(1, 1, 0));
  ASSERT_EQ(m->num_faces(), 3u);
  EXPECT_EQ(std::vector<int32_t>(m->face(0), m->face(0) + 3), (std::vector<int32_t>{0, 1, 2}));
  EXPECT_EQ(std::vector<int32_t>(m->face(1), m->face(1) + 3), (std::vector<int32_t>{0, 2, 3}));
  EXPECT_EQ(m->face_size(2), 4);
}

TEST(MeshIo, ReadsBinaryStl) {
  const TriangleMesh tet = test::tetrahedron();
  auto binary = [&](const std::string& header80) {
    std::string out = header80;
    out.resize(80, ' ');
    const auto count = static_cast<uint32_t>(tet.triangles.size());
    out.append(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : tet.triangles) {
      const float normal[3] = {0, 0, 0};
      out.append(reinterpret_cast<const char*>(normal), sizeof normal);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3f p = tet.positions[t[k]].cast<float>();
        out.append(reinterpret_cast<const char*>(p.data()), 12);
      }
      out.append(2, '\0');
    }
    return out;
  };
  ScratchDir dir;
  // Some exporters start binary headers with "solid": the length decides.
  for (const char* header : {"binary header", "solid but binary"}) {
    auto m = read_polygon_mesh(dir.write("b.stl", binary(header)));
    ASSERT_TRUE(m.ok()) << header << ": " << m.status().message();
    EXPECT_EQ(m->positions.size(), 4u) << header;  // repeated corners welded
    EXPECT_EQ(m->num_faces(), 4u) << header;
  }
  std::string cut = binary("binary header");
  cut.resize(cut.size() - 7);
  auto bad = read_polygon_mesh(dir.write("cut.stl", cut));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("says 4 triangles"), std::string::npos) << bad.status().message();
}

// Found by fuzz/mesh_read_fuzzer: float-typed list counts and indices that
// no integer holds (converting them was undefined behaviour).
TEST(MeshIo, PlyFloatListsOutOfRangeAreErrors) {
  auto ply = [](float count, float index) {
    std::string out =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list float float vertex_indices\nend_header\n";
    const float body[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, count, 0, 1, index};
    out.append(reinterpret_cast<const char*>(body), sizeof body);
    return out;
  };
  ScratchDir dir;
  auto good = read_polygon_mesh(dir.write("good.ply", ply(3, 2)));
  ASSERT_TRUE(good.ok()) << good.status().message();
  EXPECT_EQ(good->num_faces(), 1u);
  for (const float index : {2.9274e29f, -5.0f, std::nanf("")}) {
    auto m = read_polygon_mesh(dir.write("index.ply", ply(3, index)));
    ASSERT_FALSE(m.ok()) << index;
    EXPECT_NE(m.status().message().find("uses vertex index"), std::string::npos) << m.status().message();
  }
  for (const float count : {std::nanf(""), 1e30f, -1.0f}) {
    auto m = read_polygon_mesh(dir.write("count.ply", ply(count, 2)));
    ASSERT_FALSE(m.ok()) << count;
    EXPECT_NE(m.status().message().find("impossible list length"), std::string::npos) << m.status().message();
  }
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
                      BadInput{"flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", "degenerate"},
                      // An `f` line without corners aborted OpenMesh's OBJ reader (fuzz/).
                      BadInput{"nocorners.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf \nf 1 2 3\n", "line 4: face has 0 corners"},
                      BadInput{"zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "vertex index 0"},
                      BadInput{"relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", "line 3"},
                      BadInput{"minrelative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n",
                               "line 4: face uses relative vertex index"},
                      BadInput{"letters.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x/3\n", "'x/3'"},
                      BadInput{"bigindex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "line 4"},
                      BadInput{"range2.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n#\n", "line 3: face uses vertex index 3"},
                      BadInput{"garbage.stl", "not an stl", "not an STL file"},
                      BadInput{"short.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
                               "line 6: facet has 2 vertices"},
                      BadInput{"open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", "ends inside a facet"},
                      BadInput{"nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 nan 0\n", "line 4"}),
    [](const auto& test_param) {
      std::string n = test_param.param.name;
      for (auto& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return n;
    });

TEST(MeshIo, FailedWriteLeavesExistingFileAlone) {
  ScratchDir dir;
  const std::string path = dir.write("keep.obj", "original");
  EXPECT_FALSE(write_mesh(test::unit_cube(), dir.file("no/such/folder/x.obj")).ok());
  EXPECT_FALSE(write_mesh(test::unit_cube(), dir.file("x.xyz")).ok());  // unsupported output
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
