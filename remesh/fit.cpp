#include "remesh/fit.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <limits>
#include <nanoflann.hpp>

#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "remesh/nearest_triangle.h"
#include "remesh/parallel_flags.h"
#include "remesh/point_cloud.h"

namespace srcodec {
namespace {

// The order in which to search the samples' nearest triangles: along a
// Z-order curve of a 1024^3 grid over their bounding box, so that
// consecutive searches visit the same part of the tree (faster on large
// meshes). Each sample's result is its own: the order changes no output.
// 32-bit indices: 4 samples per vertex reach 2^32 only past a billion vertices.
std::vector<uint32_t> spatial_order(const std::vector<Eigen::Vector3d>& points) {
  std::vector<uint32_t> order(points.size());
  if (points.empty()) return order;
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Eigen::Vector3d scale = (1023.0 / (hi - lo).array().max(1e-300)).matrix();
  auto spread = [](uint64_t v) {  // 10 bits to every third bit
    v = (v | (v << 16)) & 0x030000FFull;
    v = (v | (v << 8)) & 0x0300F00Full;
    v = (v | (v << 4)) & 0x030C30C3ull;
    v = (v | (v << 2)) & 0x09249249ull;
    return v;
  };
  std::vector<std::pair<uint64_t, uint32_t>> keyed(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d g = (points[i] - lo).cwiseProduct(scale);
    uint64_t key = 0;
    for (int a = 0; a < 3; ++a) key |= spread(static_cast<uint64_t>(std::clamp(g[a], 0.0, 1023.0))) << a;
    keyed[i] = {key, static_cast<uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  for (size_t i = 0; i < keyed.size(); ++i) order[i] = keyed[i].second;
  return order;
}

// Each input sample's signed distance to its nearest triangle of `fine`,
// shared among that triangle's corners by the barycentric coordinates of its
// nearest point there: added to `sum` (weighted) and `mass` (the weights).
// `nearest` searches `fine`.
void add_sample_offsets(const std::vector<Eigen::Vector3d>& x, const std::vector<std::array<int32_t, 3>>& fine,
                        const NearestTriangle& nearest, const std::vector<Eigen::Vector3d>& samples,
                        const std::vector<uint32_t>& search_order, std::vector<double>* sum,
                        std::vector<double>* mass) {
  std::vector<int32_t> owner(samples.size());
  std::vector<Eigen::Vector3d> weight(samples.size());
  std::vector<double> offset_of(samples.size());
  // Each sample's nearest triangle, where on it, and its signed distance
  // from it.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, samples.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t o = r.begin(); o != r.end(); ++o) {
      const size_t i = search_order[o];
      const Eigen::Vector3d& q = samples[i];
      const NearestTriangle::Hit hit = nearest(q);
      const int32_t best_t = hit.triangle;
      const Eigen::Vector3d& best_c = hit.point;
      owner[i] = best_t;
      if (best_t < 0) continue;
      const auto& tri = fine[best_t];
      const Eigen::Vector3d normal = triangle_normal(x, tri);
      const double len = normal.norm();
      if (!(len > 0.0)) {
        owner[i] = -1;
        continue;
      }
      weight[i] = barycentric(best_c, x[tri[0]], x[tri[1]], x[tri[2]]).cwiseMax(0.0);
      offset_of[i] = (q - best_c).dot(normal) / len;
    }
  });
  for (size_t i = 0; i < samples.size(); ++i) {
    if (owner[i] < 0) continue;
    for (int c = 0; c < 3; ++c) {
      const int32_t v = fine[owner[i]][c];
      (*sum)[v] += weight[i][c] * offset_of[i];
      (*mass)[v] += weight[i][c];
    }
  }
}

// The four points of a remesh triangle measured to the input: its centroid
// and the points halfway between it and each corner (barycentric).
constexpr double kAt[4][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                              {2.0 / 3, 1.0 / 6, 1.0 / 6},
                              {1.0 / 6, 2.0 / 3, 1.0 / 6},
                              {1.0 / 6, 1.0 / 6, 2.0 / 3}};

// Each point's signed distance to the input along its triangle's normal (0
// for a triangle without area, or no input triangle found). `input_triangle`:
// each point's nearest input triangle, where the next search starts.
void offsets_to_input(const std::vector<Eigen::Vector3d>& x, const std::vector<std::array<int32_t, 3>>& fine,
                      const NearestTriangle& to_input, std::vector<std::array<double, 4>>* offsets,
                      std::vector<std::array<int32_t, 4>>* input_triangles) {
  std::vector<std::array<double, 4>>& offset_to_input = *offsets;
  std::vector<std::array<int32_t, 4>>& input_triangle = *input_triangles;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, fine.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t t = r.begin(); t != r.end(); ++t) {
      const auto& tri = fine[t];
      const Eigen::Vector3d normal = triangle_normal(x, tri);
      const double len = normal.norm();
      for (int k = 0; k < 4; ++k) {
        offset_to_input[t][k] = 0.0;
        if (!(len > 0.0)) continue;
        const Eigen::Vector3d q = kAt[k][0] * x[tri[0]] + kAt[k][1] * x[tri[1]] + kAt[k][2] * x[tri[2]];
        // Last iteration's, or in the first this triangle's previous point's.
        const int32_t from = input_triangle[t][k] >= 0 || k == 0 ? input_triangle[t][k] : input_triangle[t][k - 1];
        const NearestTriangle::Hit hit = to_input.exact(q, from);
        input_triangle[t][k] = hit.triangle;
        if (hit.triangle >= 0) offset_to_input[t][k] = (hit.point - q).dot(normal) / len;
      }
    }
  });
}

// Undoes the moves around any triangle (of any level) that would turn by
// 60 degrees or more, or come to face against the input, and around two
// neighbours that would pleat, until none does. Returns the moves undone.
size_t undo_tangling_moves(const std::vector<std::vector<std::array<int32_t, 3>>>& levels,
                           const std::vector<std::array<int32_t, 3>>& fine,
                           const std::vector<std::pair<int32_t, int32_t>>& neighbours,
                           const std::vector<Eigen::Vector3d>& before, const std::vector<Eigen::Vector3d>& side_before,
                           std::vector<Eigen::Vector3d>* positions, std::vector<Eigen::Vector3d>* sides,
                           std::vector<char>* moved_out) {
  std::vector<Eigen::Vector3d>& x = *positions;
  std::vector<Eigen::Vector3d>& side = *sides;
  std::vector<char>& moved = *moved_out;
  size_t refused = 0;
  auto pleated = [&](const std::vector<Eigen::Vector3d>& p, int32_t t, int32_t u) {
    return pleat(triangle_normal(p, fine[t]), triangle_normal(p, fine[u]));
  };
  // Whether the pair / the triangle asks for its moves undone.
  auto pair_refuses = [&](const std::pair<int32_t, int32_t>& pair) {
    const auto &a = fine[pair.first], &b = fine[pair.second];
    if (!moved[a[0]] && !moved[a[1]] && !moved[a[2]] && !moved[b[0]] && !moved[b[1]] && !moved[b[2]]) return false;
    return pleated(x, pair.first, pair.second) && !pleated(before, pair.first, pair.second);
  };
  auto triangle_refuses = [&](const std::array<int32_t, 3>& tri) {
    if (!moved[tri[0]] && !moved[tri[1]] && !moved[tri[2]]) return false;
    const Eigen::Vector3d was = triangle_normal(before, tri), now = triangle_normal(x, tri);
    return !(now.dot(was) > 0.5 * now.norm() * was.norm() &&
             (!folded(x, side, tri) || folded(before, side_before, tri)));
  };
  std::vector<char> undone(x.size(), 0);  // this pass
  auto undo = [&](const std::array<int32_t, 3>& tri) {
    bool any = false;
    for (int32_t v : tri)
      if (moved[v]) {
        x[v] = before[v];
        side[v] = side_before[v];
        moved[v] = 0;
        undone[v] = 1;
        ++refused;
        any = true;
      }
    return any;
  };
  auto touched = [&](const std::array<int32_t, 3>& tri) { return undone[tri[0]] || undone[tri[1]] || undone[tri[2]]; };
  // Each pass judges every pair and triangle in parallel on the positions
  // it starts from, then undoes in order as a serial pass would: one with
  // a corner undone earlier in the pass is judged again.
  for (bool changed = true; changed;) {
    changed = false;
    std::fill(undone.begin(), undone.end(), 0);
    const std::vector<char> pairs =
        parallel_flags(neighbours.size(), [&](size_t i) { return pair_refuses(neighbours[i]); });
    std::vector<std::vector<char>> triangles(levels.size());
    for (size_t k = 0; k < levels.size(); ++k)
      triangles[k] = parallel_flags(levels[k].size(), [&](size_t i) { return triangle_refuses(levels[k][i]); });
    for (size_t i = 0; i < neighbours.size(); ++i) {
      const auto &a = fine[neighbours[i].first], &b = fine[neighbours[i].second];
      if (touched(a) || touched(b) ? pair_refuses(neighbours[i]) : pairs[i]) changed |= undo(a) | undo(b);
    }
    for (size_t k = 0; k < levels.size(); ++k)
      for (size_t i = 0; i < levels[k].size(); ++i) {
        const auto& tri = levels[k][i];
        if (touched(tri) ? triangle_refuses(tri) : triangles[k][i]) changed |= undo(tri);
      }
  }
  return refused;
}

}  // namespace

FitReport fit_to_surface(const TriangleMesh& input, const TriangleMesh& sides,
                         const std::vector<std::vector<std::array<int32_t, 3>>>& levels, const std::vector<char>& fixed,
                         std::vector<Eigen::Vector3d>* positions, const FitOptions& options,
                         const NearestTriangle* input_search) {
  const auto start = std::chrono::steady_clock::now();
  FitReport report;
  if (levels.empty() || levels.back().empty() || sides.positions.empty()) return report;
  const auto& fine = levels.back();
  std::vector<Eigen::Vector3d>& x = *positions;
  const size_t n = x.size();
  // Three mostly serial preparations, independent of each other, at once:
  // the input's samples and their search order; a corner's side of the
  // surface, the normal of the vertex of `sides` nearest it (as the fold
  // recount judges corners off the input); the neighbouring triangles of
  // the finest level, for the pleats.
  std::vector<Eigen::Vector3d> samples, side;
  std::vector<uint32_t> search_order;
  std::unique_ptr<const FoldCounter::Sides> sides_search;
  std::vector<std::pair<int32_t, int32_t>> neighbours;
  tbb::parallel_invoke(
      [&] {
        samples = surface_samples(input, options.samples_per_vertex * n, options.seed);
        search_order = spatial_order(samples);
      },
      [&] {
        sides_search = std::make_unique<const FoldCounter::Sides>(sides);
        side = sides_search->of(x);
      },
      [&] { neighbours = neighbour_pairs(fine); });
  const FoldCounter::Sides& side_at = *sides_search;
  // The other way: four points of each triangle of the remesh (its centroid
  // and the points halfway between it and each corner), each measured to the
  // nearest point of the input exactly (the input's slivers can lie nearer
  // than the triangles with the nearest centroids), weighted by a quarter of
  // the triangle's area times the input samples' density.
  const bool both_ways = options.remesh_weight > 0.0;
  std::unique_ptr<NearestTriangle> own_search;
  const NearestTriangle* to_input = input_search;
  double density = 0.0;
  if (both_ways) {
    if (!to_input) {
      own_search = std::make_unique<NearestTriangle>(input.positions, input.triangles, /*exact_search=*/true);
      to_input = own_search.get();
    }
    const double area = mesh_area(input);
    density = area > 0.0 ? static_cast<double>(samples.size()) / area : 0.0;
  }
  std::vector<std::array<double, 4>> offset_to_input(both_ways ? fine.size() : 0);
  // Each point's nearest input triangle, where the next search starts.
  std::vector<std::array<int32_t, 4>> input_triangle(both_ways ? fine.size() : 0, {-1, -1, -1, -1});
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    std::vector<double> sum(n, 0.0), mass(n, 0.0);
    // The search over the remesh is built (serially) while the remesh's
    // points are measured to the input on the other core.
    std::unique_ptr<const NearestTriangle> nearest;
    tbb::parallel_invoke([&] { nearest = std::make_unique<const NearestTriangle>(x, fine); },
                         [&] {
                           if (both_ways) offsets_to_input(x, fine, *to_input, &offset_to_input, &input_triangle);
                         });
    add_sample_offsets(x, fine, *nearest, samples, search_order, &sum, &mass);
    if (both_ways) {
      for (size_t t = 0; t < fine.size(); ++t) {
        const auto& tri = fine[t];
        const double w = options.remesh_weight * density * triangle_area(x, tri) / 4.0;
        for (int k = 0; k < 4; ++k)
          for (int c = 0; c < 3; ++c) {
            sum[tri[c]] += w * kAt[k][c] * offset_to_input[t][k];
            mass[tri[c]] += w * kAt[k][c];
          }
      }
    }
    const std::vector<Eigen::Vector3d> normals = unit_vertex_normals(x, fine);
    const std::vector<Eigen::Vector3d> before = x, side_before = side;
    std::vector<char> moved(n, 0);
    // A move is at most a quarter of the vertex's mean edge: a chord's sag
    // is an eighth of its length where the surface turns by a radian along
    // it; farther input is a part the remesh does not cover, not a sag.
    std::vector<double> edge_sum(n, 0.0), edge_count(n, 0.0);
    for (const auto& t : fine)
      for (int c = 0; c < 3; ++c) {
        const double len = (x[t[c]] - x[t[(c + 1) % 3]]).norm();
        edge_sum[t[c]] += len;
        edge_count[t[c]] += 1.0;
      }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t v = r.begin(); v != r.end(); ++v) {
        if ((v < fixed.size() && fixed[v]) || !(mass[v] > 0.0) || normals[v].isZero()) continue;
        const double reach = 0.25 * edge_sum[v] / edge_count[v];
        x[v] += std::clamp(options.step * sum[v] / mass[v], -reach, reach) * normals[v];
        side[v] = side_at(x[v]);
        moved[v] = 1;
      }
    });
    report.refused += undo_tangling_moves(levels, fine, neighbours, before, side_before, &x, &side, &moved);
    report.moved = 0;
    double total = 0.0;
    for (size_t v = 0; v < n; ++v)
      if (moved[v]) {
        ++report.moved;
        total += (x[v] - before[v]).norm();
      }
    report.mean_offset = report.moved ? total / static_cast<double>(report.moved) : 0.0;
  }
  const FoldCount left = count_by_sides(x, side, fine, neighbours, nullptr);
  report.folded_by_nearest_input = left.folded_by_nearest_input;
  report.pleats = left.pleats;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace srcodec
