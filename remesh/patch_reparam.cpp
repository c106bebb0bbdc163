// The last fold repair (ours): the patch of sites around a fold that no
// other repair undid is redrawn in a planar map of the input under it
// (remesh/disk_map.h), where a triangle cannot fold, and put back on the
// input; kept only when it leaves fewer folds without moving away from the
// input.
#include "remesh/refiner.h"

namespace srcodec {

const Adjacency& Refiner::input_neighbors() {
  if (input_neighbors_.size() == 0) input_neighbors_ = vertex_neighbors(input_.positions.size(), input_.triangles);
  return input_neighbors_;
}

size_t Refiner::reparam_patch(const std::vector<int32_t>& patch, int32_t level) {
  constexpr double kMaxRmsGrowth = 1.1;
  // The patch's interior sites and the triangles around them: a disk, on
  // local ids (sites, sorted), whose rim stays put.
  std::vector<int32_t> movable, tri_ids, sites;
  for (int32_t s : patch)
    if (!site_on_boundary_[s] && !keeps_to_crease(s) && neighbors_.begin(s) != neighbors_.end(s))
      movable.push_back(s);
  if (movable.empty()) return 0;
  for (int32_t s : movable) tri_ids.insert(tri_ids.end(), around_.begin(s), around_.end(s));
  std::sort(tri_ids.begin(), tri_ids.end());
  tri_ids.erase(std::unique(tri_ids.begin(), tri_ids.end()), tri_ids.end());
  for (int32_t t : tri_ids) sites.insert(sites.end(), triangles_[t].begin(), triangles_[t].end());
  std::sort(sites.begin(), sites.end());
  sites.erase(std::unique(sites.begin(), sites.end()), sites.end());
  auto local = [&](int32_t s) {
    return static_cast<int32_t>(std::lower_bound(sites.begin(), sites.end(), s) - sites.begin());
  };
  std::vector<std::array<int32_t, 3>> patch_tris;
  double reach = 0.0;  // the patch's longest edge
  for (int32_t t : tri_ids) {
    const auto& tri = triangles_[t];
    const int new_corners = (h_.vertex_level(tri[0]) == level) + (h_.vertex_level(tri[1]) == level) +
                            (h_.vertex_level(tri[2]) == level);
    if (new_corners < 2) return 0;  // a leaf of a coarser level, or the closure's
    patch_tris.push_back({local(tri[0]), local(tri[1]), local(tri[2])});
    for (int c = 0; c < 3; ++c)
      reach = std::max(reach, (points_[anchor_[tri[c]]] - points_[anchor_[tri[(c + 1) % 3]]]).norm());
  }
  if (disk_boundary_loop(sites.size(), patch_tris).empty()) return 0;
  InputDisk disk = input_disk(sites, reach);
  if (disk.vertices.empty()) return 0;
  // The rim's places in the input's map, the inside by convex combinations
  // (Tutte), then unflipped where the rim is not convex.
  std::vector<char> site_fixed(sites.size(), 1);
  std::vector<Eigen::Vector2d> site_uv(sites.size(), Eigen::Vector2d::Zero());
  for (int32_t s : movable) site_fixed[local(s)] = 0;
  for (size_t j = 0; j < sites.size(); ++j)
    if (site_fixed[j]) site_uv[j] = disk.place(*this, anchor_[sites[j]]);
  if (!convex_combination_map(sites.size(), patch_tris, nullptr, site_fixed, site_uv)) {
    disk.release(region_id_);
    return 0;
  }
  constexpr int kUntanglePasses = 64;
  untangle_planar(sites.size(), patch_tris, site_fixed, site_uv, kUntanglePasses);
  // Back onto the input: the point of the input triangle each site's
  // place falls in.
  struct Lifted {
    Eigen::Vector3d x, normal;
    int32_t vertex;
  };
  std::vector<Lifted> lifted;
  const PlanarLocator locator(disk.uv, disk.triangles);
  for (int32_t s : movable) {
    Eigen::Vector3d b;
    const int32_t t = locator.locate(site_uv[local(s)], &b);
    if (t < 0) break;
    const auto& tri = disk.triangles[t];
    const Eigen::Vector3d &p0 = points_[disk.vertices[tri[0]]], &p1 = points_[disk.vertices[tri[1]]],
                          &p2 = points_[disk.vertices[tri[2]]];
    Eigen::Index corner = 0;
    b.maxCoeff(&corner);
    b = b.cwiseMax(0.0);
    b /= b.sum();
    Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0);
    if (!(normal.norm() > 0.0)) break;
    lifted.push_back({b[0] * p0 + b[1] * p1 + b[2] * p2, normal.normalized(), disk.vertices[tri[corner]]});
  }
  disk.release(region_id_);
  if (lifted.size() != movable.size()) return 0;
  const auto tangles = tangles_around(patch);
  const std::pair<size_t, size_t> before = tangles();
  const double rms_before = rms_to_patch(disk.vertices, sites);
  const size_t points_before = points_.size();
  std::vector<int32_t> old;
  for (size_t j = 0; j < movable.size(); ++j) {
    old.push_back(anchor_[movable[j]]);
    move_site(movable[j], add_point(lifted[j].x, param_[lifted[j].vertex], lifted[j].normal, 0));
  }
  if (tangles() < before && rms_to_patch(disk.vertices, sites) <= kMaxRmsGrowth * rms_before) return movable.size();
  for (size_t j = 0; j < movable.size(); ++j) move_site(movable[j], old[j]);
  while (points_.size() > points_before) drop_last_point();
  return 0;
}

Refiner::InputDisk Refiner::input_disk(const std::vector<int32_t>& sites, double reach) {
  const Adjacency& neighbors = input_neighbors();
  if (region_id_.empty()) region_id_.assign(input_.positions.size(), -1);  // most runs leave no fold for this repair
  InputDisk disk;
  std::vector<double> dist;
  std::vector<std::pair<double, int32_t>> heap;
  auto visit = [&](int32_t i, double d) {
    if (region_id_[i] < 0) {
      region_id_[i] = static_cast<int32_t>(disk.vertices.size());
      disk.vertices.push_back(i);
      dist.push_back(d);
    } else if (d < dist[region_id_[i]]) {
      dist[region_id_[i]] = d;
    } else {
      return;
    }
    heap.emplace_back(d, i);
    std::push_heap(heap.begin(), heap.end(), std::greater<>());
  };
  for (int32_t s : sites) visit(nearest_input_vertex(anchor_[s]), 0.0);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), std::greater<>());
    const auto [d, i] = heap.back();
    heap.pop_back();
    if (d > dist[region_id_[i]]) continue;
    for (const int32_t* n = neighbors.begin(i); n != neighbors.end(i); ++n) {
      const double dn = d + (points_[*n] - points_[i]).norm();
      if (dn <= reach) visit(*n, dn);
    }
  }
  for (int32_t i : disk.vertices)
    for (const int32_t* t = input_around_.begin(i); t != input_around_.end(i); ++t) {
      const auto& tri = input_.triangles[*t];
      if (i == std::min({tri[0], tri[1], tri[2]}) &&
          std::all_of(tri.begin(), tri.end(), [&](int32_t v) { return region_id_[v] >= 0; }))
        disk.triangles.push_back({region_id_[tri[0]], region_id_[tri[1]], region_id_[tri[2]]});
    }
  const std::vector<int32_t> loop = disk_boundary_loop(disk.vertices.size(), disk.triangles);
  std::vector<Eigen::Vector3d> x(disk.vertices.size());
  for (size_t j = 0; j < x.size(); ++j) x[j] = points_[disk.vertices[j]];
  std::vector<double> arc(loop.size() + 1, 0.0);
  for (size_t j = 0; j < loop.size(); ++j) arc[j + 1] = arc[j] + (x[loop[(j + 1) % loop.size()]] - x[loop[j]]).norm();
  std::vector<char> fixed(x.size(), 0);
  disk.uv.assign(x.size(), Eigen::Vector2d::Zero());
  constexpr double kTwoPi = 6.283185307179586;
  for (size_t j = 0; j < loop.size(); ++j) {
    const double angle = arc.back() > 0.0 ? kTwoPi * arc[j] / arc.back() : kTwoPi * j / loop.size();
    disk.uv[loop[j]] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    fixed[loop[j]] = 1;
  }
  if (loop.empty() || !convex_combination_map(x.size(), disk.triangles, &x, fixed, disk.uv)) {
    disk.release(region_id_);
    return {};
  }
  return disk;
}

double Refiner::rms_to_patch(const std::vector<int32_t>& vertices, const std::vector<int32_t>& sites) const {
  std::vector<Eigen::Vector3d> at(sites.size());
  for (size_t j = 0; j < sites.size(); ++j) at[j] = points_[anchor_[sites[j]]];
  const PointCloud cloud{at};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  constexpr size_t kNear = 4;
  std::array<uint32_t, kNear> idx{};
  std::array<double, kNear> d2{};
  double sum = 0.0;
  for (int32_t i : vertices) {
    const size_t k = tree.knnSearch(points_[i].data(), kNear, idx.data(), d2.data());
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < k; ++j)
      for (const int32_t* t = around_.begin(sites[idx[j]]); t != around_.end(sites[idx[j]]); ++t) {
        const auto& tri = triangles_[*t];
        best = std::min(best, (closest_on_triangle(points_[i], points_[anchor_[tri[0]]], points_[anchor_[tri[1]]],
                                                   points_[anchor_[tri[2]]]) - points_[i]).squaredNorm());
      }
    sum += best;
  }
  return vertices.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(vertices.size()));
}

}  // namespace srcodec
