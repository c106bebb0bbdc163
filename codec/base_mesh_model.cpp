#include <algorithm>
#include <cmath>

#include "codec/base_mesh_coder.h"

namespace srcodec {

Eigen::Vector3d QuantizationGrid::dequantize(const Eigen::Vector3i& q) const {
  return origin + step * q.cast<double>();
}

Eigen::Vector3i QuantizationGrid::quantize(const Eigen::Vector3d& p) const {
  const double top = std::ldexp(1.0, std::clamp(bits, 1, 30)) - 1.0;
  Eigen::Vector3i q;
  for (int j = 0; j < 3; ++j) {
    const double x = std::floor((p[j] - origin[j]) / step + 0.5);
    q[j] = std::isnan(x) ? 0 : static_cast<int>(std::clamp(x, 0.0, top));
  }
  return q;
}

}  // namespace srcodec
