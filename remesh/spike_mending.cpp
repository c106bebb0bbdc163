// Spike mending (ours, after the fold repairs): a site that took an input
// vertex on another sheet of a thin part, while its neighbours stayed on
// this one, makes long edges across the gap without folding anything, so
// the fold repairs do not see it. It moves back near its neighbours where
// that keeps the input it covered covered.
#include "remesh/refiner.h"

namespace srcodec {

double Refiner::mean_edge(int32_t s, const Eigen::Vector3d& at) const {
  double sum = 0.0;
  for (const int32_t* n = neighbors_.begin(s); n != neighbors_.end(s); ++n) sum += (points_[anchor_[*n]] - at).norm();
  return sum / static_cast<double>(neighbors_.end(s) - neighbors_.begin(s));
}

size_t Refiner::mend_spikes() {
  constexpr double kSpikeRatio = 3.0;
  constexpr size_t kCandidates = 48, kCoverChecks = 8, kMaxCovered = 8192;
  const int32_t sites = static_cast<int32_t>(neighbors_.size());
  auto in_mesh = [&](int32_t s) { return neighbors_.begin(s) != neighbors_.end(s); };
  std::vector<double> edge(sites, 0.0);
  for (int32_t s = 0; s < sites; ++s)
    if (in_mesh(s)) edge[s] = mean_edge(s, points_[anchor_[s]]);
  std::vector<std::pair<int32_t, double>> spikes;  // site, its neighbours' median edge
  std::vector<double> around;
  for (int32_t s = 0; s < sites; ++s) {
    if (!in_mesh(s) || site_on_boundary_[s] || keeps_to_crease(s)) continue;
    around.clear();
    for (const int32_t* n = neighbors_.begin(s); n != neighbors_.end(s); ++n) around.push_back(edge[*n]);
    std::nth_element(around.begin(), around.begin() + around.size() / 2, around.end());
    if (edge[s] > kSpikeRatio * around[around.size() / 2]) spikes.emplace_back(s, around[around.size() / 2]);
  }
  if (spikes.empty()) return 0;
  // The sites where they are now, to find the remesh's triangles near an
  // input vertex (a spike moved since keeps its old place in the tree: its
  // triangles are still found, and measured where they are).
  std::vector<Eigen::Vector3d> at;
  std::vector<int32_t> at_site;
  for (int32_t s = 0; s < sites; ++s)
    if (in_mesh(s)) {
      at.push_back(points_[anchor_[s]]);
      at_site.push_back(s);
    }
  PointCloud cloud{at};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  // Squared distance from x to the triangles of the current level's mesh,
  // site s on point `to`: those around the sites nearest x and s's own.
  auto to_remesh = [&](const Eigen::Vector3d& x, int32_t s, int32_t to) {
    auto corner = [&](int32_t v) -> const Eigen::Vector3d& { return points_[v == s ? to : anchor_[v]]; };
    auto nearest = [&](const Adjacency& triangles_at, int32_t v, double best) {
      for (const int32_t* f = triangles_at.begin(v); f != triangles_at.end(v); ++f) {
        const auto& tri = triangles_[*f];
        best = std::min(best, (closest_on_triangle(x, corner(tri[0]), corner(tri[1]), corner(tri[2])) - x).squaredNorm());
      }
      return best;
    };
    constexpr size_t kNear = 8;
    std::array<uint32_t, kNear> idx{};
    std::array<double, kNear> d2{};
    const size_t k = tree.knnSearch(x.data(), kNear, idx.data(), d2.data());
    double best = nearest(around_, s, std::numeric_limits<double>::infinity());
    for (size_t j = 0; j < k; ++j) best = nearest(around_, at_site[idx[j]], best);
    return best;
  };
  std::vector<uint32_t> idx(kCandidates);
  std::vector<double> dist(kCandidates);
  std::vector<std::pair<uint32_t, double>> reached;
  std::vector<double> cover;
  size_t mended = 0;
  for (const auto& [s, median] : spikes) {
    const int32_t from = anchor_[s];
    double reach = 0.0;
    for (const int32_t* n = neighbors_.begin(s); n != neighbors_.end(s); ++n)
      reach = std::max(reach, (points_[anchor_[*n]] - points_[from]).squaredNorm());
    reached.clear();
    input_tree_.radiusSearch(points_[from].data(), reach, reached, nanoflann::SearchParams());
    if (reached.size() > kMaxCovered) {  // a spike across the model: every so many, nearest first
      const size_t stride = (reached.size() + kMaxCovered - 1) / kMaxCovered;
      size_t kept = 0;
      for (size_t j = 0; j < reached.size(); j += stride) reached[kept++] = reached[j];
      reached.resize(kept);
    }
    cover.resize(reached.size());
    for (size_t j = 0; j < reached.size(); ++j)
      cover[j] = std::max(0.0625 * median * median, 4.0 * to_remesh(points_[reached[j].first], s, from));
    const int folds = star_quality(s, from).first;
    const Eigen::Vector3d mean = neighbour_mean(s);
    const size_t k = input_tree_.knnSearch(mean.data(), kCandidates, idx.data(), dist.data());
    size_t checks = 0;
    for (size_t j = 0; j < k && checks < kCoverChecks; ++j) {
      const int32_t i = static_cast<int32_t>(idx[j]);
      if (site_of_[i] >= 0 || !allowed(s, i) || !(mean_edge(s, points_[i]) < 0.5 * edge[s]) ||
          star_quality(s, i).first > folds)
        continue;
      ++checks;
      bool covered = true;
      for (size_t m = 0; m < reached.size() && covered; ++m)
        covered = to_remesh(points_[reached[m].first], s, i) <= cover[m];
      if (!covered) continue;
      move_site(s, i);
      ++mended;
      break;
    }
  }
  return mended;
}

}  // namespace srcodec
