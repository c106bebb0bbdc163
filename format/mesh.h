// The mesh values passed between srcodec's stages.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products everywhere meshes are

#include <array>
#include <cstdint>
#include <vector>

namespace srcodec {

// Faces as read from a file: any polygon size, indices not yet validated
// against manifoldness, vertices possibly duplicated or unreferenced.
struct PolygonMesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<int32_t> face_offsets{0};  // face f has corners [face_offsets[f], face_offsets[f+1])
  std::vector<int32_t> corners;          // vertex index of every face corner

  size_t num_faces() const { return face_offsets.size() - 1; }
  int32_t face_size(size_t f) const { return face_offsets[f + 1] - face_offsets[f]; }
  const int32_t* face(size_t f) const { return corners.data() + face_offsets[f]; }
  void add_face(const int32_t* indices, int32_t count) {
    corners.insert(corners.end(), indices, indices + count);
    face_offsets.push_back(static_cast<int32_t>(corners.size()));
  }
};

// An indexed triangle mesh: what every stage after reading works on.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int32_t, 3>> triangles;
};

PolygonMesh to_polygon_mesh(const TriangleMesh& mesh);

// Axis-aligned bounding-box diagonal over all positions (0 for none).
double bounding_box_diagonal(const std::vector<Eigen::Vector3d>& positions);

// Appends `from`'s vertices and triangles to `to` (indices shifted): joins
// disjoint pieces into one mesh.
void append_mesh(TriangleMesh& to, const TriangleMesh& from);

}  // namespace srcodec
