// Lloyd relaxation over the sites of all levels (Kammoun, Payan, Antonini
// §III-B, Eqs. 1-2): Voronoi cells of the input vertices, each site moved to
// the input vertex nearest its cell's density-weighted centroid.
//
// Choices the paper leaves open, and why:
//  - Voronoi cells during refinement (Eq. 1) use the Euclidean distance, as
//    in the paper, but an input vertex only considers the sites near it on
//    the base domain: the corners of the semi-regular triangle its
//    parameterization falls in, and their neighbours. A global nearest site
//    would jump across thin parts (two sides of an ear) once the sites are
//    dense; the parameterization knows which side a vertex is on. From the
//    nearest of those, it walks the level's mesh to a neighbour while one is
//    nearer: the parameterization is the base mesh's, and where it is
//    stretched the located triangle lies rings away from the vertex's
//    nearest sites, whose cells then miss it.
//  - A site's new position is the input vertex of its cell nearest the
//    cell's density-weighted centroid (Eq. 2 and §II-C), applied site after
//    site (Gauss-Seidel) so the fold test sees its neighbours' current
//    positions. A move that would flip or flatten a triangle of the current
//    level around the site is refused.
//  - A site's own input vertex always stays in its cell, so f(s) >= 1 and
//    two sites never share an input vertex.
#include "remesh/refiner.h"

namespace srcodec {

std::vector<int32_t> Refiner::assign(int32_t level) {
  build_level_mesh(level);
  return reassign(level);
}

void Refiner::build_level_mesh(int32_t level) {
  triangles_ = h_.level_triangles(level);
  const size_t n = static_cast<size_t>(h_.vertex_count());
  neighbors_ = vertex_neighbors(n, triangles_);
  around_ = vertex_triangles(n, triangles_);
  site_on_boundary_ = boundary_vertices(n, triangles_);
  rim_prev_.assign(n, -1);
  rim_next_.assign(n, -1);
  for_each_boundary_edge(triangles_, around_, [&](int32_t a, int32_t b) {
    rim_next_[a] = rim_next_[a] == -1 ? b : -2;  // -2: a vertex where boundaries touch
    rim_prev_[b] = rim_prev_[b] == -1 ? a : -2;
  });
  build_level_creases(level);
  // The coarser levels' meshes too: sites of every level move, and each
  // level's mesh must stay unfolded, not only the finest.
  coarse_triangles_.resize(level);
  coarse_around_.resize(level);
  for (int32_t k = 0; k < level; ++k) {
    coarse_triangles_[k] = h_.level_triangles(k);
    coarse_around_[k] = vertex_triangles(n, coarse_triangles_[k]);
  }
}

bool Refiner::allowed(int32_t site, int32_t i) const {
  return site_on_boundary_[site] == input_on_boundary_[i] && (!site_on_boundary_[site] || on_rim_arc(site, i)) &&
         (!has_creases_ || crease_allowed(site, i));
}

void Refiner::build_loops() {
  loop_.assign(input_.positions.size(), -1);
  loop_pos_.assign(input_.positions.size(), 0.0);
  loop_walk_ = boundary_loops(input_.positions.size(), input_.triangles, input_around_);
  for (size_t l = 0; l < loop_walk_.size(); ++l)
    for (size_t k = 0; k < loop_walk_[l].size(); ++k) {
      loop_[loop_walk_[l][k]] = static_cast<int32_t>(l);
      loop_pos_[loop_walk_[l][k]] = static_cast<double>(k);
    }
}

double Refiner::along_loop(int32_t from, int32_t to) const {
  const double size = static_cast<double>(loop_walk_[loop_[from]].size());
  return std::fmod(loop_pos_[to] - loop_pos_[from] + size, size);
}

double Refiner::arc_length(int32_t from, int32_t to) const {
  const double d = along_loop(from, to);
  return d == 0.0 ? static_cast<double>(loop_walk_[loop_[from]].size()) : d;
}

bool Refiner::rim_middle(int32_t a, int32_t b, Eigen::Vector3d* x, double* place) const {
  const int32_t pa = anchor_[a], pb = anchor_[b];
  if (pa < 0 || pb < 0 || loop_[pa] < 0 || loop_[pb] != loop_[pa]) return false;
  const std::vector<int32_t>& walk = loop_walk_[loop_[pa]];
  *place = std::fmod(loop_pos_[pa] + 0.5 * arc_length(pa, pb), static_cast<double>(walk.size()));
  const size_t k = static_cast<size_t>(*place);
  const double t = *place - static_cast<double>(k);
  *x = (1.0 - t) * points_[walk[k % walk.size()]] + t * points_[walk[(k + 1) % walk.size()]];
  return true;
}

bool Refiner::on_rim_arc(int32_t s, int32_t i) const {
  const int32_t p = rim_prev_[s], n = rim_next_[s];
  if (p < 0 || n < 0) return true;
  const int32_t ap = anchor_[p], an = anchor_[n];
  if (ap < 0 || an < 0) return true;
  const int32_t loop = loop_[ap];
  if (loop < 0 || loop_[an] != loop) return true;
  const double span = arc_length(ap, an);
  auto inside = [&](int32_t x) {
    if (loop_[x] != loop) return false;
    const double d = along_loop(ap, x);
    return d > 0.0 && d < span;
  };
  const int32_t own = anchor_[s];
  if (own >= 0 && loop_[own] >= 0 && !inside(own)) return true;
  return loop_[i] < 0 || inside(i);
}

std::vector<int32_t> Refiner::locate_points(int32_t level) const {
  std::vector<int32_t> node(input_.positions.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, node.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) node[i] = h_.locate(param_[i], level);
  });
  return node;
}

Adjacency Refiner::first_sites(const std::vector<int32_t>& located) const {
  const auto& nodes = h_.nodes();
  std::vector<char> used(nodes.size(), 0);
  for (int32_t node : located) used[node] = 1;
  // Node by node (the same list twice: to count, then to fill).
  const auto sites_of = [&](size_t node, std::vector<int32_t>* sites) {
    sites->clear();
    for (int32_t c : nodes[node].v) {
      sites->push_back(c);
      sites->insert(sites->end(), neighbors_.begin(c), neighbors_.end(c));
    }
    std::sort(sites->begin(), sites->end());
    sites->erase(std::unique(sites->begin(), sites->end()), sites->end());
  };
  Adjacency out;
  out.offsets.assign(nodes.size() + 1, 0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<int32_t> sites;
    for (size_t node = r.begin(); node != r.end(); ++node)
      if (used[node]) {
        sites_of(node, &sites);
        out.offsets[node + 1] = static_cast<int32_t>(sites.size());
      }
  });
  for (size_t node = 0; node < nodes.size(); ++node) out.offsets[node + 1] += out.offsets[node];
  out.items.resize(static_cast<size_t>(out.offsets.back()));
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<int32_t> sites;
    for (size_t node = r.begin(); node != r.end(); ++node)
      if (used[node]) {
        sites_of(node, &sites);
        std::copy(sites.begin(), sites.end(), out.items.begin() + out.offsets[node]);
      }
  });
  return out;
}

std::vector<int32_t> Refiner::reassign(const std::vector<int32_t>& located, const Adjacency& first_sites) const {
  constexpr int kMaxWalk = 64;
  // The sites' places side by side: the searches read little else.
  std::vector<Eigen::Vector3d> site_x(anchor_.size(), Eigen::Vector3d::Zero());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, site_x.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t s = r.begin(); s != r.end(); ++s)
      if (anchor_[s] >= 0) site_x[s] = points_[anchor_[s]];
  });
  std::vector<int32_t> cell_of(points_.size(), -1);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cell_of.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      if (site_of_[i] >= 0 && anchor_[site_of_[i]] == static_cast<int32_t>(i)) {
        cell_of[i] = site_of_[i];
        continue;
      }
      if (i >= input_.positions.size()) continue;  // a point off the input no site holds: in no cell (-1)
      const int32_t node = located[i];
      const Eigen::Vector3d& x = points_[i];
      int32_t best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      // The nearest, ties to the lower site: the same whatever the order.
      auto consider = [&](int32_t s) {
        const double d = (site_x[s] - x).squaredNorm();
        if (d < best_d || (d == best_d && s < best)) {
          best_d = d;
          best = s;
        }
      };
      for (const int32_t* s = first_sites.begin(node); s != first_sites.end(node); ++s) consider(*s);
      // Then down the level's mesh, neighbour by neighbour, while a site
      // is nearer: the base domain locates the vertex on the right sheet,
      // but its stretch goes stale as sites move. A corner's neighbours
      // were all considered: the walk would stop at once.
      const auto& corners = h_.nodes()[node].v;
      const bool walk = std::find(corners.begin(), corners.end(), best) == corners.end();
      for (int step = 0; walk && step < kMaxWalk && best >= 0; ++step) {
        const int32_t from = best;
        for (const int32_t* s = neighbors_.begin(from); s != neighbors_.end(from); ++s) consider(*s);
        if (best == from) break;
      }
      cell_of[i] = best;
    }
  });
  return cell_of;
}

std::vector<int32_t> Refiner::relax(int32_t level, RefineLevelReport& lr) {
  // Sites move, the parameterization and the level's triangles do not: each
  // point's triangle is found once for all the steps.
  const std::vector<int32_t> located = locate_points(level);
  const Adjacency first = first_sites(located);        // run() built this level's mesh before placing vertices
  std::vector<int32_t> cell_of = reassign(located, first);
  const size_t sites = static_cast<size_t>(h_.vertex_count());
  for (int it = 0; it < options_.max_lloyd_iterations; ++it) {
    const Adjacency members = cells(cell_of, sites);
    size_t moved = 0;
    for (size_t s = 0; s < sites; ++s) {
      const int32_t row = static_cast<int32_t>(s);
      if (members.begin(row) == members.end(row)) continue;  // not in this level's mesh
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      double mass = 0.0;
      for (const int32_t* i = members.begin(row); i != members.end(row); ++i) {
        if (!allowed(row, *i)) continue;  // a boundary site relaxes along the boundary
        sum += density_[*i] * points_[*i];
        mass += density_[*i];
      }
      if (!(mass > 0.0)) continue;
      const Eigen::Vector3d centroid = sum / mass;
      int32_t best = anchor_[s];
      double best_d = (points_[best] - centroid).squaredNorm();
      for (const int32_t* i = members.begin(row); i != members.end(row); ++i) {
        const double d = (points_[*i] - centroid).squaredNorm();
        if (allowed(row, *i) && (d < best_d || (d == best_d && *i < best))) {
          best_d = d;
          best = *i;
        }
      }
      if (best == anchor_[s]) continue;
      if (!keeps_orientation(row, best)) {
        ++lr.refused_folds;
        continue;
      }
      move_site(row, best);
      ++moved;
    }
    lr.moves += moved;
    lr.lloyd_iterations = it + 1;
    cell_of = reassign(located, first);
    if (static_cast<double>(moved) < options_.min_moved_fraction * static_cast<double>(sites)) break;
  }
  const Adjacency members = cells(cell_of, sites);
  for (size_t s = 0; s < sites; ++s)
    if (members.offsets[s + 1] - members.offsets[s] == 1) ++lr.empty_cells;
  untangle(level, lr);
  lr.spikes_mended = mend_spikes();
  count_tangles(lr);
  // The repairs move sites, not the parameterization or the level's mesh:
  // the points' nodes and their first sites still hold.
  return reassign(located, first);
}

Adjacency Refiner::cells(const std::vector<int32_t>& cell_of, size_t sites) {
  Adjacency members;
  members.offsets.assign(sites + 1, 0);
  for (int32_t s : cell_of)
    if (s >= 0) ++members.offsets[s + 1];
  for (size_t s = 0; s < sites; ++s) members.offsets[s + 1] += members.offsets[s];
  std::vector<int32_t> fill(members.offsets.begin(), members.offsets.end() - 1);
  members.items.resize(members.offsets[sites]);
  for (size_t i = 0; i < cell_of.size(); ++i)
    if (cell_of[i] >= 0) members.items[fill[cell_of[i]]++] = static_cast<int32_t>(i);
  return members;
}

double Refiner::facing(const std::array<int32_t, 3>& tri, int32_t moved, int32_t to) const {
  std::array<int32_t, 3> at{};
  for (int c = 0; c < 3; ++c) at[c] = tri[c] == moved ? to : anchor_[tri[c]];
  return srcodec::facing(points_[at[0]], points_[at[1]], points_[at[2]],
                   normals_[at[0]] + normals_[at[1]] + normals_[at[2]]);
}

bool Refiner::folded(const std::array<int32_t, 3>& tri, int32_t moved, int32_t to) const {
  return srcodec::folded(facing(tri, moved, to));
}

std::pair<int, double> Refiner::star_quality(int32_t s, int32_t to) const {
  int folds = 0;
  double worst = std::numeric_limits<double>::infinity();
  auto add = [&](const std::vector<std::array<int32_t, 3>>& tris, const Adjacency& around) {
    for (const int32_t* t = around.begin(s); t != around.end(s); ++t) {
      const double f = facing(tris[*t], s, to);
      folds += srcodec::folded(f);
      worst = std::min(worst, f);
    }
  };
  add(triangles_, around_);
  for (size_t k = 0; k < coarse_triangles_.size(); ++k) add(coarse_triangles_[k], coarse_around_[k]);
  return {folds, worst};
}

bool Refiner::keeps_orientation(int32_t s, int32_t to) const {
  return star_quality(s, to).first <= star_quality(s, anchor_[s]).first;
}

}  // namespace srcodec
