// The public mesh and mesh files (<srcodec/mesh.h>).
#include <srcodec/mesh.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

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

}  // namespace
}  // namespace srcodec
