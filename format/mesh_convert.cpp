// Between the public srcodec::Mesh and format/mesh.h's TriangleMesh.
#include "format/mesh_convert.h"

#include <cmath>
#include <limits>
#include <string>

namespace srcodec {

Mesh to_public_mesh(const TriangleMesh& mesh) {
  Mesh out;
  out.positions.reserve(3 * mesh.positions.size());
  for (const Eigen::Vector3d& p : mesh.positions) out.positions.insert(out.positions.end(), {p.x(), p.y(), p.z()});
  out.triangles.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int32_t v : t) out.triangles.push_back(static_cast<uint32_t>(v));
  return out;
}

StatusOr<TriangleMesh> from_public_mesh(const Mesh& mesh, const std::string& what) {
  if (mesh.positions.size() % 3 != 0)
    return invalid_argument(what + ": " + std::to_string(mesh.positions.size()) +
                            " position values, not a multiple of 3 (x, y, z per vertex)");
  if (mesh.triangles.size() % 3 != 0)
    return invalid_argument(what + ": " + std::to_string(mesh.triangles.size()) +
                            " triangle indices, not a multiple of 3");
  constexpr size_t kMaxCount = std::numeric_limits<int32_t>::max();
  if (mesh.vertex_count() > kMaxCount || mesh.triangle_count() > kMaxCount)
    return invalid_argument(what + ": " + std::to_string(mesh.vertex_count()) + " vertices and " +
                            std::to_string(mesh.triangle_count()) + " triangles, more than srcodec's limit of " +
                            std::to_string(kMaxCount) + " each");
  TriangleMesh out;
  out.positions.resize(mesh.vertex_count());
  for (size_t v = 0; v < out.positions.size(); ++v) {
    out.positions[v] = {mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]};
    if (!out.positions[v].allFinite())
      return invalid_mesh(what + ": vertex " + std::to_string(v) + " has a coordinate that is not a finite number");
  }
  out.triangles.resize(mesh.triangle_count());
  for (size_t t = 0; t < out.triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const uint32_t v = mesh.triangles[3 * t + c];
      if (v >= out.positions.size())
        return invalid_mesh(what + ": triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) +
                            ", but there are " + std::to_string(out.positions.size()) + " vertices");
      out.triangles[t][c] = static_cast<int32_t>(v);
    }
  return out;
}

}  // namespace srcodec
