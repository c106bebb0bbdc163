// The paper's refinement (Kammoun, Payan, Antonini §III-B, Fig. 4 and 5,
// Eqs. 4-5): per level, split the triangles Eq. 5 selects 1-to-4, start the
// new vertices (new_vertices.cpp), relax the sites of all levels with Lloyd
// (lloyd_relaxation.cpp), and select the next level's splits from the
// relaxed cells. Then, with Eq. 5 judged on a uniform refinement or with the
// geometric tolerance (ours), the splits that fail are undone bottom up.
#include "remesh/refiner.h"

namespace srcodec {

Refiner::Refiner(const TriangleMesh& input, const BaseMesh& base, const RefineOptions& options,
                 TriangleHierarchy hierarchy)
    : created_(std::chrono::steady_clock::now()),
      input_(input),
      base_(base),
      options_(options),
      h_(std::move(hierarchy)),
      points_(input.positions),
      param_(base.param),
      density_(vertex_density(input)),
      normals_(unit_vertex_normals(input.positions, input.triangles)),
      embedded_(embed()),
      cloud_{embedded_},
      tree_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)),
      input_cloud_{input.positions},
      input_tree_(3, input_cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)),
      base_vertex_faces_(vertex_triangles(base.mesh.positions.size(), base.mesh.triangles)),
      site_of_(input.positions.size(), -1),
      input_on_boundary_(boundary_vertices(input.positions.size(), input.triangles)),
      input_around_(vertex_triangles(input.positions.size(), input.triangles)) {
  tree_.buildIndex();
  input_tree_.buildIndex();
  build_face_points();
  build_loops();
  build_curves();
  anchor_ = base.input_vertex;
  for (size_t v = 0; v < anchor_.size(); ++v) site_of_[anchor_[v]] = static_cast<int32_t>(v);
}

Status Refiner::run(std::vector<RefineLevelReport>* report) {
  // Level 0: the base mesh's own cells, for the first selection.
  int32_t level = 0;
  std::vector<int32_t> cell_of = assign(level);
  RemeshProgress set_up;
  set_up.step = RemeshStep::kRefineSetUp;
  set_up.vertices = points_.size();
  set_up.seconds = seconds_since(created_);
  progress(set_up);
  for (int step = 0; step < options_.levels; ++step) {
    const auto start = std::chrono::steady_clock::now();
    RefineLevelReport lr;
    lr.level = level + 1;
    const std::vector<int32_t> selected = select(level, cell_of);
    lr.selected = selected.size();
    if (options_.threshold_after_uniform && std::none_of(selected.begin(), selected.end(), [&](int32_t n) {
          return g_of_[n] > options_.threshold;
        }))
      lr.selected = 0;  // nothing would be kept above this level
    if (lr.selected == 0) {
      RemeshProgress p;
      p.step = RemeshStep::kThresholdStops;
      p.level = level + 1;
      progress(p);
      break;
    }
    const size_t nodes_before = h_.nodes().size();
    std::vector<int32_t> new_vertices;
    for (int32_t node : selected) h_.split(node, &new_vertices);
    lr.split = (h_.nodes().size() - nodes_before) / 4;
    ++level;
    anchor_.resize(h_.vertex_count(), -1);
    build_level_mesh(level);  // new vertices need to know whether they are on the boundary
    const size_t midpoints_before = midpoint_vertices_, surface_before = surface_vertices_;
    for (int32_t v : new_vertices) SRCODEC_RETURN_IF_ERROR(place_new_vertex(v));
    lr.midpoint_vertices = midpoint_vertices_ - midpoints_before;
    lr.surface_vertices = surface_vertices_ - surface_before;
    cell_of = relax(level, lr);
    lr.vertices = h_.level_vertex_count(level);
    lr.triangles = triangles_.size();
    lr.seconds = seconds_since(start);
    RemeshProgress p;
    p.step = RemeshStep::kLevel;
    p.refine_level = &lr;
    p.seconds = lr.seconds;
    progress(p);
    if (report) report->push_back(lr);
  }
  if ((options_.tolerance > 0.0 || options_.threshold_after_uniform) && level > 0)
    SRCODEC_RETURN_IF_ERROR(coarsen(level, cell_of, report));
  return ok_status();
}

RefineResult Refiner::result() && {
  RefineResult r{std::move(h_), {}, std::move(anchor_)};
  r.positions.reserve(r.anchor.size());
  for (int32_t& a : r.anchor) {
    r.positions.push_back(points_[a]);
    if (a >= static_cast<int32_t>(input_.positions.size())) a = -1;
  }
  return r;
}

std::vector<int32_t> Refiner::select(int32_t level, const std::vector<int32_t>& cell_of) {
  std::vector<int32_t> f(static_cast<size_t>(h_.vertex_count()), 0);
  for (int32_t s : cell_of)
    if (s >= 0) ++f[s];
  std::vector<int32_t> out;
  const auto& nodes = h_.nodes();
  if (options_.threshold_after_uniform) g_of_.resize(nodes.size(), -1);
  for (size_t n = 0; n < nodes.size(); ++n) {
    const TriangleHierarchy::Node& node = nodes[n];
    if (node.level != level || node.first_child >= 0) continue;
    const int32_t g = std::min({f[node.v[0]], f[node.v[1]], f[node.v[2]]});
    if (options_.threshold_after_uniform) g_of_[n] = g;
    if (!options_.uniform && !options_.threshold_after_uniform && !(g > options_.threshold)) continue;
    out.push_back(static_cast<int32_t>(n));
  }
  return out;
}

Status Refiner::coarsen(int32_t level, const std::vector<int32_t>& cell_of, std::vector<RefineLevelReport>* report) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<size_t> selected, within_tolerance;
  SRCODEC_RETURN_IF_ERROR(undo_splits(level, cell_of, &selected, &within_tolerance));
  std::vector<size_t> split(static_cast<size_t>(level), 0);  // with the closure's
  for (const TriangleHierarchy::Node& node : h_.nodes())
    if (node.first_child >= 0) ++split[node.level];
  level = h_.max_level();  // every split of the top levels may be undone
  build_level_mesh(level);
  RefineLevelReport lr;  // the repairs' counts on the coarsened mesh
  untangle(level, lr);
  count_tangles(lr);
  if (report) report->resize(static_cast<size_t>(level));
  if (report && level > 0) {
    for (int32_t k = 0; k < level; ++k) {
      RefineLevelReport& r = (*report)[k];
      if (options_.threshold_after_uniform) r.selected = selected[k];
      r.within_tolerance = within_tolerance[k];
      r.split = split[k];
      r.vertices = h_.level_vertex_count(k + 1);
      r.triangles = k + 1 < level ? coarse_triangles_[k + 1].size() : triangles_.size();  // build_level_mesh's
    }
    RefineLevelReport& last = report->back();
    last.untangled += lr.untangled;
    last.off_input_moves += lr.off_input_moves;
    last.smoothed += lr.smoothed;
    last.midpoint_resets += lr.midpoint_resets;
    last.reparameterized += lr.reparameterized;
    last.folded_triangles = lr.folded_triangles;
    last.coarse_folded_triangles = lr.coarse_folded_triangles;
    last.folded_by_nearest_input = lr.folded_by_nearest_input;
    last.pleats = lr.pleats;
    last.seconds += seconds_since(start);
  }
  RemeshProgress p;
  p.step = RemeshStep::kSplitsUndone;
  p.refine_level = &lr;
  p.triangles = triangles_.size();
  p.threshold = options_.threshold_after_uniform;
  p.tolerance = options_.tolerance > 0.0;
  p.seconds = seconds_since(start);
  progress(p);
  return ok_status();
}

Status Refiner::undo_splits(int32_t level, const std::vector<int32_t>& cell_of, std::vector<size_t>* selected,
                            std::vector<size_t>* within_tolerance) {
  // Each input vertex's nearest triangle of the finest mesh (among those
  // around its cell's site), and that triangle's node; for the tolerance.
  std::vector<int32_t> node_of;
  h_.level_triangles(level, &node_of);
  const size_t inputs = options_.tolerance > 0.0 ? std::min(cell_of.size(), input_.positions.size()) : 0;
  std::vector<int32_t> under(inputs, -1);
  auto corner = [&](const std::array<int32_t, 3>& v, int c) -> const Eigen::Vector3d& { return points_[anchor_[v[c]]]; };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, inputs, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const int32_t s = cell_of[i];
      if (s < 0) continue;
      double best = std::numeric_limits<double>::infinity();
      for (const int32_t* t = around_.begin(s); t != around_.end(s); ++t) {
        const auto& tri = triangles_[*t];
        const double d =
            (closest_on_triangle(points_[i], corner(tri, 0), corner(tri, 1), corner(tri, 2)) - points_[i]).squaredNorm();
        if (d < best) {
          best = d;
          under[i] = node_of[*t];
        }
      }
    }
  });
  // Bottom up: a split node whose children are all leaves becomes a leaf
  // when its input is within the tolerance of its plane (boundary
  // vertices: of its triangle).
  const auto& nodes = h_.nodes();
  std::vector<char> leaf(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) leaf[n] = nodes[n].first_child < 0;
  if (options_.threshold_after_uniform)
    for (size_t n = 0; n < nodes.size(); ++n)  // a parent comes before its children
      if (!leaf[n] && ((nodes[n].parent >= 0 && leaf[nodes[n].parent]) || !(g_of_[n] > options_.threshold)))
        leaf[n] = 1;
  auto kept_splits = [&] {
    std::vector<size_t> kept(static_cast<size_t>(level), 0);
    for (size_t n = 0; n < nodes.size(); ++n)
      if (!leaf[n]) ++kept[nodes[n].level];
    return kept;
  };
  *selected = kept_splits();
  std::vector<double> squared(inputs, 0.0), sum(nodes.size(), 0.0);
  std::vector<int64_t> count(nodes.size(), 0);
  for (int32_t k = options_.tolerance > 0.0 ? level - 1 : -1; k >= 0; --k) {
    auto candidate = [&](int32_t n) {
      if (nodes[n].level != k || leaf[n]) return false;
      const int32_t first = nodes[n].first_child;
      return std::all_of(&leaf[first], &leaf[first] + 4, [](char c) { return c != 0; });
    };
    // Each input vertex's squared distance to the candidate it is under
    // (negative: under none).
    tbb::parallel_for(tbb::blocked_range<size_t>(0, inputs, 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        squared[i] = -1.0;
        if (under[i] < 0) continue;
        while (nodes[under[i]].level > k) under[i] = nodes[under[i]].parent;
        const TriangleHierarchy::Node& node = nodes[under[i]];
        if (!candidate(under[i])) continue;
        const Eigen::Vector3d normal = (corner(node.v, 1) - corner(node.v, 0)).cross(corner(node.v, 2) - corner(node.v, 0));
        const double length = normal.norm();
        if (input_on_boundary_[i] || !(length > 0.0))
          squared[i] = (closest_on_triangle(points_[i], corner(node.v, 0), corner(node.v, 1), corner(node.v, 2)) -
                        points_[i]).squaredNorm();
        else
          squared[i] = std::pow(normal.dot(points_[i] - corner(node.v, 0)) / length, 2);
      }
    });
    for (size_t i = 0; i < inputs; ++i)
      if (squared[i] >= 0.0) {
        sum[under[i]] += squared[i];
        ++count[under[i]];
      }
    for (size_t n = 0; n < nodes.size(); ++n)
      if (candidate(static_cast<int32_t>(n)) &&
          (count[n] == 0 || std::sqrt(sum[n] / static_cast<double>(count[n])) <= options_.tolerance))
        leaf[n] = 1;
  }
  *within_tolerance = kept_splits();
  for (int32_t k = 0; k < level; ++k) (*within_tolerance)[k] = (*selected)[k] - (*within_tolerance)[k];
  // The kept splits, replayed; the sites: each kept vertex keeps its old
  // vertex's input vertex.
  std::vector<char> keep(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) keep[n] = !leaf[n];
  std::vector<int32_t> old_vertex;
  SRCODEC_ASSIGN_OR_RETURN(TriangleHierarchy kept, h_.replayed(keep, &old_vertex));
  std::vector<int32_t> anchor(old_vertex.size());
  for (int32_t a : anchor_) site_of_[a] = -1;
  for (size_t v = 0; v < old_vertex.size(); ++v) {
    anchor[v] = anchor_[old_vertex[v]];
    site_of_[anchor[v]] = static_cast<int32_t>(v);
  }
  h_ = std::move(kept);
  anchor_ = std::move(anchor);
  return ok_status();
}

StatusOr<RefineResult> refine(const TriangleMesh& input, const BaseMesh& base, const RefineOptions& options,
                              std::vector<RefineLevelReport>* report) {
  if (options.levels < 0 || options.levels > 12)
    return invalid_argument("remesh: " + std::to_string(options.levels) + " levels asked; use 0 to 12");
  if (base.param.size() != input.positions.size())
    return invalid_argument("remesh: the parameterization covers " + std::to_string(base.param.size()) +
                            " vertices but the input has " + std::to_string(input.positions.size()));
  SRCODEC_ASSIGN_OR_RETURN(TriangleHierarchy hierarchy,
                           TriangleHierarchy::create(static_cast<int32_t>(base.mesh.positions.size()),
                                                     base.mesh.triangles));
  Refiner refiner(input, base, options, std::move(hierarchy));
  SRCODEC_RETURN_IF_ERROR(refiner.run(report));
  return std::move(refiner).result();
}

}  // namespace srcodec
