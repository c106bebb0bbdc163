#include "remesh/boundary_tips.h"

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "remesh/adjacency.h"
#include "remesh/geometry.h"

namespace srcodec {

double boundary_tip_reach(const TriangleMesh& mesh, size_t sites) {
  return 0.5 * equilateral_edge_length(mesh_area(mesh), sites);
}

size_t add_boundary_tip_sites(const TriangleMesh& mesh, const BoundaryTipOptions& options, VoronoiCells* cells) {
  if (!(options.reach > 0.0) || cells->cell_of.size() != mesh.positions.size()) return 0;
  const size_t n = mesh.positions.size();
  const std::vector<std::vector<int32_t>> loops =
      boundary_loops(n, mesh.triangles, vertex_triangles(n, mesh.triangles));
  Adjacency neighbours;  // built once a tip is found
  const double max_cosine = std::cos(options.min_turn_degrees * M_PI / 180.0);
  std::vector<char> is_site(n, 0);
  for (int32_t s : cells->sites) is_site[static_cast<size_t>(s)] = 1;
  size_t added = 0;
  for (const std::vector<int32_t>& loop : loops) {
    const int64_t m = static_cast<int64_t>(loop.size());
    if (m < 6) continue;
    auto at = [&](int64_t k) -> const Eigen::Vector3d& {
      return mesh.positions[static_cast<size_t>(loop[static_cast<size_t>(((k % m) + m) % m)])];
    };
    // The loop point `reach` behind k (step -1) or ahead of it (step +1),
    // by length along the loop; at most half the loop away.
    auto reached = [&](int64_t k, int64_t step) {
      double length = 0.0;
      int64_t j = k;
      for (int64_t walked = 0; walked < m / 2 && length < options.reach; ++walked, j += step)
        length += (at(j + step) - at(j)).norm();
      return j;
    };
    std::vector<double> cosine(static_cast<size_t>(m), 1.0);
    for (int64_t k = 0; k < m; ++k) {
      const Eigen::Vector3d in = at(k) - at(reached(k, -1)), out = at(reached(k, +1)) - at(k);
      const double norms = in.norm() * out.norm();
      if (norms > 0.0) cosine[static_cast<size_t>(k)] = in.dot(out) / norms;
    }
    auto cosine_at = [&](int64_t k) { return cosine[static_cast<size_t>(((k % m) + m) % m)]; };
    for (int64_t k = 0; k < m; ++k) {
      const double c = cosine[static_cast<size_t>(k)];
      if (!(c < max_cosine)) continue;
      // The sharpest turn within reach either way (ties: the first on the loop).
      bool sharpest = true;
      for (int64_t step : {-1, 1}) {
        const int64_t last = reached(k, step);
        for (int64_t j = k + step; sharpest && j != last + step; j += step) {
          const int64_t i = ((j % m) + m) % m;
          sharpest = cosine_at(j) > c || (cosine_at(j) == c && i > k);
        }
      }
      const size_t tip = static_cast<size_t>(loop[static_cast<size_t>(k)]);
      if (!sharpest || is_site[tip]) continue;
      if (neighbours.size() == 0) neighbours = vertex_neighbors(n, mesh.triangles);
      is_site[tip] = 1;
      const int32_t old_cell = cells->cell_of[tip], new_cell = static_cast<int32_t>(cells->sites.size());
      const Eigen::Vector3d old_site = mesh.positions[static_cast<size_t>(cells->sites[static_cast<size_t>(old_cell)])];
      const Eigen::Vector3d& here = mesh.positions[tip];
      cells->sites.push_back(static_cast<int32_t>(tip));
      cells->cell_of[tip] = new_cell;
      std::vector<int32_t> reached_from_tip{static_cast<int32_t>(tip)};
      for (size_t q = 0; q < reached_from_tip.size(); ++q)
        for (const int32_t* it = neighbours.begin(reached_from_tip[q]); it != neighbours.end(reached_from_tip[q]);
             ++it) {
          const int32_t u = *it;
          const size_t ui = static_cast<size_t>(u);
          const Eigen::Vector3d& p = mesh.positions[ui];
          if (cells->cell_of[ui] != old_cell || !((p - here).norm() < (p - old_site).norm())) continue;
          cells->cell_of[ui] = new_cell;
          reached_from_tip.push_back(u);
        }
      ++added;
    }
  }
  return added;
}

}  // namespace srcodec
