#include "remesh/relax_slivers.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "remesh/adjacency.h"
#include "remesh/folds.h"
#include "remesh/geometry.h"

namespace srcodec {

double triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double squares = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
  if (!(squares > 0.0)) return 0.0;
  return 2.0 * std::sqrt(3.0) * (b - a).cross(c - a).norm() / squares;  // 4 sqrt(3) * area
}

SliverRelaxReport relax_slivers(const FoldCounter::Sides& sides, const std::vector<std::array<int32_t, 3>>& finest,
                                const std::vector<std::array<int32_t, 3>>& coarser, const std::vector<char>& fixed,
                                std::vector<Eigen::Vector3d>* positions, const SliverRelaxOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector3d>& p = *positions;
  const size_t n = p.size();
  SliverRelaxReport report;
  auto quality = [&](const std::array<int32_t, 3>& t) { return triangle_quality(p[t[0]], p[t[1]], p[t[2]]); };
  for (const auto& t : finest) report.poor_before += quality(t) < options.poor_quality;

  std::vector<char> movable(n, 0);
  for (const auto& t : finest)
    for (int32_t v : t) movable[v] = fixed[v] == 0;
  for (const auto& t : coarser)
    for (int32_t v : t) movable[v] = 0;
  const Adjacency star = vertex_triangles(n, finest);
  const Adjacency ring = vertex_neighbors(n, finest);
  const std::vector<std::array<int32_t, 3>> across = triangles_across(finest);
  std::vector<Eigen::Vector3d> side = sides.of(p);  // each vertex's side of the input, as the fold count judges
  auto sound = [&](int32_t t) {  // faces out, and no pleat with a neighbour
    if (folded(p, side, finest[t])) return false;
    const Eigen::Vector3d normal = triangle_normal(p, finest[t]);
    for (int e = 0; e < 3; ++e)
      if (across[t][e] >= 0 && pleat(normal, triangle_normal(p, finest[across[t][e]]))) return false;
    return true;
  };

  for (int round = 0; round < options.rounds; ++round) {
    size_t moved = 0;
    for (size_t v = 0; v < n; ++v) {
      const int32_t row = static_cast<int32_t>(v);
      if (!movable[v]) continue;
      double worst = 1.0;
      bool tangled = false;  // left to the untangling, whose counts then stay the output's
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      for (const int32_t* t = star.begin(row); t != star.end(row); ++t) {
        worst = std::min(worst, quality(finest[*t]));
        normal += triangle_normal(p, finest[*t]);
        tangled = tangled || !sound(*t);
      }
      if (tangled || !(worst < options.poor_quality) || !(normal.norm() > 0.0)) continue;
      bool flat = true;
      for (const int32_t* u = ring.begin(row); flat && u != ring.end(row); ++u)
        flat = side[*u].dot(side[v]) > options.flat_cosine;
      if (!flat) continue;
      normal.normalize();
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const int32_t* u = ring.begin(row); u != ring.end(row); ++u) mean += p[*u];
      mean /= static_cast<double>(ring.end(row) - ring.begin(row));
      const Eigen::Vector3d old = p[v], old_side = side[v];
      p[v] += (mean - old) - (mean - old).dot(normal) * normal;
      side[v] = sides(p[v]);
      double after = 1.0;
      bool kept = true;
      for (const int32_t* t = star.begin(row); kept && t != star.end(row); ++t) {
        after = std::min(after, quality(finest[*t]));
        kept = sound(*t);
      }
      if (kept && after > worst) {
        ++moved;
      } else {
        p[v] = old;
        side[v] = old_side;
      }
    }
    report.moved += moved;
    if (moved == 0) break;
  }
  for (const auto& t : finest) report.poor_after += quality(t) < options.poor_quality;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace srcodec
