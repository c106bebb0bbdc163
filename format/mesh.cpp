#include "format/mesh.h"

namespace srcodec {

PolygonMesh to_polygon_mesh(const TriangleMesh& mesh) {
  PolygonMesh out;
  out.positions = mesh.positions;
  out.corners.reserve(mesh.triangles.size() * 3);
  out.face_offsets.reserve(mesh.triangles.size() + 1);
  for (const auto& t : mesh.triangles) out.add_face(t.data(), 3);
  return out;
}

double bounding_box_diagonal(const std::vector<Eigen::Vector3d>& positions) {
  if (positions.empty()) return 0.0;
  Eigen::Vector3d lo = positions[0], hi = positions[0];
  for (const auto& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

void append_mesh(TriangleMesh& to, const TriangleMesh& from) {
  const int32_t offset = static_cast<int32_t>(to.positions.size());
  to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
  to.triangles.reserve(to.triangles.size() + from.triangles.size());
  for (const auto& t : from.triangles) to.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace srcodec
