// Barycentric dual-cell areas (Kammoun, Payan, Antonini, Fig. 2).
#include "remesh/density.h"

#include <cassert>

namespace srcodec {

std::vector<double> vertex_density(const TriangleMesh& mesh) {
  std::vector<double> rho(mesh.positions.size(), 0.0);
  for (const auto& t : mesh.triangles) {
    assert(t[0] >= 0 && t[1] >= 0 && t[2] >= 0);
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    const double third_area = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm() / 6.0;
    for (int32_t v : t) rho[v] += third_area;
  }
  return rho;
}

}  // namespace srcodec
