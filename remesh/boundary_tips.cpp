#include "remesh/boundary_tips.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "remesh/geometry.h"

namespace srcodec {
namespace {

// The boundary loops of a consistently oriented mesh, each in the order its
// triangles run along it. A loop through a vertex with two boundary edges
// leaving it is not a simple cycle and is left out.
std::vector<std::vector<int32_t>> boundary_loops(const TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  std::vector<std::pair<int32_t, int32_t>> directed;
  directed.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) directed.emplace_back(t[c], t[(c + 1) % 3]);
  std::sort(directed.begin(), directed.end());
  std::vector<std::vector<int32_t>> out;
  std::vector<int32_t> next(n, -1);
  std::vector<char> irregular(n, 0);
  for (const auto& [a, b] : directed) {
    if (std::binary_search(directed.begin(), directed.end(), std::make_pair(b, a))) continue;
    if (next[static_cast<size_t>(a)] >= 0) irregular[static_cast<size_t>(a)] = 1;
    next[static_cast<size_t>(a)] = b;
  }
  std::vector<char> visited(n, 0);
  for (size_t start = 0; start < n; ++start) {
    if (next[start] < 0 || visited[start]) continue;
    std::vector<int32_t> loop;
    bool simple = true;
    int32_t v = static_cast<int32_t>(start);
    do {
      simple = simple && !irregular[static_cast<size_t>(v)];
      visited[static_cast<size_t>(v)] = 1;
      loop.push_back(v);
      v = next[static_cast<size_t>(v)];
    } while (v >= 0 && !visited[static_cast<size_t>(v)]);
    if (simple && v == static_cast<int32_t>(start)) out.push_back(std::move(loop));
  }
  return out;
}

}  // namespace

double boundary_tip_reach(const TriangleMesh& mesh, size_t sites) {
  double area = 0.0;
  for (const auto& t : mesh.triangles) area += triangle_area(mesh.positions, t);
  if (sites == 0 || !(area > 0.0)) return 0.0;
  return 0.5 * std::sqrt(4.0 / std::sqrt(3.0) * area / (2.0 * static_cast<double>(sites)));
}

size_t add_boundary_tip_sites(const TriangleMesh& mesh, const BoundaryTipOptions& options, VoronoiCells* cells) {
  if (!(options.reach > 0.0) || cells->cell_of.size() != mesh.positions.size()) return 0;
  const std::vector<std::vector<int32_t>> loops = boundary_loops(mesh);
  std::vector<std::vector<int32_t>> neighbours;  // the mesh's edges around each vertex, once a tip is found
  const double max_cosine = std::cos(options.min_turn_degrees * M_PI / 180.0);
  std::vector<char> is_site(mesh.positions.size(), 0);
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
      if (neighbours.empty()) {
        neighbours.resize(mesh.positions.size());
        for (const auto& t : mesh.triangles)
          for (int corner = 0; corner < 3; ++corner) {
            const int32_t from = t[corner], to = t[(corner + 1) % 3];
            neighbours[static_cast<size_t>(from)].push_back(to);
            neighbours[static_cast<size_t>(to)].push_back(from);
          }
        for (auto& around : neighbours) {
          std::sort(around.begin(), around.end());
          around.erase(std::unique(around.begin(), around.end()), around.end());
        }
      }
      is_site[tip] = 1;
      const int32_t old_cell = cells->cell_of[tip], new_cell = static_cast<int32_t>(cells->sites.size());
      const Eigen::Vector3d old_site = mesh.positions[static_cast<size_t>(cells->sites[static_cast<size_t>(old_cell)])];
      const Eigen::Vector3d& here = mesh.positions[tip];
      cells->sites.push_back(static_cast<int32_t>(tip));
      cells->cell_of[tip] = new_cell;
      std::vector<int32_t> reached_from_tip{static_cast<int32_t>(tip)};
      for (size_t q = 0; q < reached_from_tip.size(); ++q)
        for (int32_t u : neighbours[static_cast<size_t>(reached_from_tip[q])]) {
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
