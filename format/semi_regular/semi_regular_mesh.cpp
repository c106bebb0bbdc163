#include "format/semi_regular/semi_regular_mesh.h"

#include <cstddef>

namespace srcodec {

TriangleMesh SemiRegularMesh::level_mesh(int32_t level) const {
  return compact_mesh(positions, hierarchy.level_triangles(level));
}

TriangleMesh compact_mesh(const std::vector<Eigen::Vector3d>& positions,
                          const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<int32_t> index(positions.size(), -1);
  for (const auto& t : triangles)
    for (int32_t v : t) index[v] = 0;
  size_t used = 0;
  for (int32_t i : index) used += i == 0;
  TriangleMesh mesh;
  mesh.positions.reserve(used);
  for (size_t v = 0; v < positions.size(); ++v)
    if (index[v] == 0) {
      index[v] = static_cast<int32_t>(mesh.positions.size());
      mesh.positions.push_back(positions[v]);
    }
  mesh.triangles.reserve(triangles.size());
  for (const auto& t : triangles) mesh.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
  return mesh;
}

}  // namespace srcodec
