// The public mesh and mesh files (<srcodec/mesh.h>).
#include <srcodec/mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

TEST(MeshApi, ReadsCleanedAsTheStagesDo) {
  const std::string path = test::source_path("data/spot.obj");
  StatusOr<Mesh> mesh = read_mesh(path);
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  StatusOr<TriangleMesh> internal = read_triangle_mesh(path);
  ASSERT_TRUE(internal.ok());
  ASSERT_EQ(mesh->vertex_count(), internal->positions.size());
  ASSERT_EQ(mesh->triangle_count(), internal->triangles.size());
  EXPECT_EQ(mesh->vertex_count(), 2930u);
  for (size_t v = 0; v < mesh->vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(mesh->positions[3 * v + k], internal->positions[v][k]);
  for (size_t t = 0; t < mesh->triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(mesh->triangles[3 * t + k], static_cast<uint32_t>(internal->triangles[t][k]));
}

TEST(MeshApi, WritesEveryFormatAndReadsItBack) {
  test::ScratchDir dir;
  Mesh square;
  square.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0.1};
  square.triangles = {0, 1, 2, 0, 2, 3};
  for (const char* ext : {".obj", ".ply", ".off", ".stl"}) {
    const std::string path = dir.file(std::string("square") + ext);
    ASSERT_TRUE(write_mesh(path, square).ok()) << ext;
    StatusOr<Mesh> back = read_mesh(path);
    ASSERT_TRUE(back.ok()) << ext << ": " << back.status().message();
    EXPECT_EQ(back->vertex_count(), 4u) << ext;
    EXPECT_EQ(back->triangle_count(), 2u) << ext;
  }
  // OBJ keeps every bit.
  square.positions[0] = 0.1;
  ASSERT_TRUE(write_mesh(dir.file("exact.obj"), square).ok());
  EXPECT_EQ(read_mesh(dir.file("exact.obj"))->positions, square.positions);
}

TEST(MeshApi, BadMeshesAreRefusedAndNothingIsWritten) {
  test::ScratchDir dir;
  const std::string path = dir.file("bad.obj");
  Mesh ragged;
  ragged.positions = {0, 0, 0, 1, 0};
  ragged.triangles = {0, 0, 0};
  Status s = write_mesh(path, ragged);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("multiple of 3"), std::string::npos) << s.message();

  Mesh dangling;
  dangling.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  dangling.triangles = {0, 1, 7};
  s = write_mesh(path, dangling);
  EXPECT_EQ(s.code(), StatusCode::kInvalidMesh);
  EXPECT_NE(s.message().find("vertex 7"), std::string::npos) << s.message();

  dangling.triangles = {0, 1, 2};
  dangling.positions[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(write_mesh(path, dangling).code(), StatusCode::kInvalidMesh);
  EXPECT_FALSE(read_file_bytes(path).ok());

  EXPECT_EQ(write_mesh(dir.file("x.fbx"), Mesh{}).code(), StatusCode::kUnsupported);
  StatusOr<Mesh> missing = read_mesh(dir.file("missing.obj"));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("missing.obj"), std::string::npos);
}

// The unit cube (two triangles a face) as the public mesh, and its 12 edges
// (vertex ids that differ in one bit) as crease edges.
Mesh public_cube(std::vector<uint32_t>* edges) {
  Mesh cube;
  const TriangleMesh m = test::unit_cube();
  for (const auto& p : m.positions) cube.positions.insert(cube.positions.end(), {p.x(), p.y(), p.z()});
  for (const auto& t : m.triangles) cube.triangles.insert(cube.triangles.end(), t.begin(), t.end());
  for (uint32_t a = 0; a < 8; ++a)
    for (uint32_t bit : {1u, 2u, 4u})
      if ((a & bit) == 0) edges->insert(edges->end(), {a, a | bit});
  return cube;
}

// corner_normals on the cube creased at its 12 edges: three normals a
// vertex, each a face's; at every corner its triangle's normal.
TEST(MeshApi, CornerNormalsOfACubeAreItsFaceNormals) {
  std::vector<uint32_t> edges;
  const Mesh cube = public_cube(&edges);
  ASSERT_EQ(edges.size(), 24u);
  StatusOr<CornerNormals> n = corner_normals(cube, edges);
  ASSERT_TRUE(n.ok()) << n.status().message();
  ASSERT_EQ(n->normals.size(), 3u * 24);
  ASSERT_EQ(n->vertices.size(), 24u);
  ASSERT_EQ(n->corners.size(), cube.triangles.size());
  for (size_t c = 0; c < n->corners.size(); ++c) {
    const uint32_t i = n->corners[c];
    ASSERT_LT(i, 24u);
    EXPECT_EQ(n->vertices[i], cube.triangles[c]);
    const uint32_t* t = &cube.triangles[c - c % 3];
    // The face's axis is the coordinate its three corners share.
    for (int k = 0; k < 3; ++k) {
      const double a = cube.positions[3 * t[0] + k];
      const bool shared = a == cube.positions[3 * t[1] + k] && a == cube.positions[3 * t[2] + k];
      EXPECT_EQ(n->normals[3 * i + k], shared ? (a == 1 ? 1.0f : -1.0f) : 0.0f) << c << " " << k;
    }
  }
  // No crease edges: one normal a vertex, in vertex order, the corners the triangles.
  StatusOr<CornerNormals> smooth = corner_normals(cube, {});
  ASSERT_TRUE(smooth.ok());
  EXPECT_EQ(smooth->vertices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(smooth->corners, cube.triangles);

  EXPECT_EQ(corner_normals(cube, {0, 1, 2}).status().code(), StatusCode::kInvalidArgument);
  const Status out_of_range = corner_normals(cube, {0, 8}).status();
  EXPECT_EQ(out_of_range.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(out_of_range.message().find("vertex 8"), std::string::npos) << out_of_range.message();
  Mesh ragged = cube;
  ragged.triangles.pop_back();
  EXPECT_EQ(corner_normals(ragged, edges).status().code(), StatusCode::kInvalidArgument);
}

// write_mesh with crease edges: an OBJ with a `vn` line per normal and
// corners `v//vn`, which reads back to the same mesh; without crease edges,
// and in the other formats, the bytes write_mesh writes.
TEST(MeshApi, WritesCreaseNormalsToObjOnly) {
  test::ScratchDir dir;
  std::vector<uint32_t> edges;
  const Mesh cube = public_cube(&edges);
  ASSERT_TRUE(write_mesh(dir.file("sharp.obj"), cube, edges).ok());
  const std::string sharp = read_file_bytes(dir.file("sharp.obj")).value();
  EXPECT_NE(sharp.find("\nvn 0 0 -1\n"), std::string::npos) << sharp;
  EXPECT_NE(sharp.find("\nf 1//1 3//"), std::string::npos) << sharp;
  size_t normals = 0;
  for (size_t at = sharp.find("\nvn "); at != std::string::npos; at = sharp.find("\nvn ", at + 1)) ++normals;
  EXPECT_EQ(normals, 24u);
  StatusOr<Mesh> back = read_mesh(dir.file("sharp.obj"));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->positions, cube.positions);
  EXPECT_EQ(back->triangles, cube.triangles);
  for (const char* ext : {".obj", ".ply", ".off", ".stl"}) {
    const std::string plain = dir.file(std::string("plain") + ext), creased = dir.file(std::string("creased") + ext);
    ASSERT_TRUE(write_mesh(plain, cube).ok());
    ASSERT_TRUE(write_mesh(creased, cube, std::string(ext) == ".obj" ? std::vector<uint32_t>{} : edges).ok());
    EXPECT_EQ(read_file_bytes(creased).value(), read_file_bytes(plain).value()) << ext;
  }
  EXPECT_EQ(write_mesh(dir.file("odd.obj"), cube, {1}).code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(read_file_bytes(dir.file("odd.obj")).ok());
}

}  // namespace
}  // namespace srcodec
