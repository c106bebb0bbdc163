#include "codec/cut_estimate.h"

#include <cmath>
#include <string>

#include "remesh/geometry.h"

namespace srcodec {

CutEstimate::CutEstimate(const TriangleMesh& whole, const SurfaceDistance& measured)
    : positions_(whole.positions),
      triangles_(whole.triangles),
      unit_normals_(whole.triangles.size(), Eigen::Vector3d::Zero()),
      area_share_(whole.triangles.size(), 0.0),
      whole_squared_(measured.rms * measured.rms),
      whole_psnr_(measured.psnr),
      diag_(measured.diag) {
  double total = 0.0;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    const Eigen::Vector3d n = triangle_normal(positions_, triangles_[t]);
    const double twice_area = n.norm();
    if (!(twice_area > 0.0)) continue;
    unit_normals_[t] = n / twice_area;
    area_share_[t] = twice_area;
    total += twice_area;
  }
  if (total > 0.0)
    for (double& a : area_share_) a /= total;
}

StatusOr<double> CutEstimate::psnr(const TriangleMesh& cut) const {
  if (cut.positions.size() != positions_.size() || cut.triangles.size() != triangles_.size())
    return invalid_argument("cut estimate: the cut decodes to " + std::to_string(cut.positions.size()) +
                            " vertices and " + std::to_string(cut.triangles.size()) +
                            " triangles, not the whole stream's " + std::to_string(positions_.size()) + " and " +
                            std::to_string(triangles_.size()));
  // The mean square of a function linear over a triangle, with corner values
  // a, b, c, is (a² + b² + c² + ab + bc + ca) / 6.
  double displaced = 0.0;
  for (size_t t = 0; t < triangles_.size(); ++t) {
    if (area_share_[t] == 0.0) continue;
    const auto& tri = triangles_[t];
    const Eigen::Vector3d& n = unit_normals_[t];
    const double a = n.dot(cut.positions[tri[0]] - positions_[tri[0]]);
    const double b = n.dot(cut.positions[tri[1]] - positions_[tri[1]]);
    const double c = n.dot(cut.positions[tri[2]] - positions_[tri[2]]);
    displaced += area_share_[t] * (a * a + b * b + c * c + a * b + b * c + c * a) / 6.0;
  }
  return psnr_db(diag_, std::sqrt(whole_squared_ + displaced));
}

}  // namespace srcodec
