// Semi-regular refinement with Lloyd relaxation (Kammoun, Payan, Antonini
// §III-B) and the adaptive criterion of Eqs. 4-5.
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
//    nearest sites, whose cells then miss it (nefertiti with 521 base
//    vertices: 71.8 dB at 4 levels without the walk, 76.1 with it; armadillo
//    with 608: 70.5 and 74.6).
//  - A site's new position is the input vertex of its cell nearest the
//    cell's density-weighted centroid (Eq. 2 and §II-C), applied site after
//    site (Gauss-Seidel) so the fold test sees its neighbours' current
//    positions. A move that would flip or flatten a triangle of the current
//    level around the site is refused.
//  - A site's own input vertex always stays in its cell, so f(s) >= 1 and
//    two sites never share an input vertex.
#include "remesh/refine.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <queue>

#include "remesh/adjacency.h"
#include "remesh/density.h"
#include "remesh/disk_map.h"
#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "remesh/point_cloud.h"

namespace srcodec {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A new vertex whose nearest free input vertex is farther from its edge's
// midpoint than this fraction of the edge goes onto the input surface.
constexpr double kSparseFraction = 0.25;

class Refiner {
 public:
  Refiner(const TriangleMesh& input, const BaseMesh& base, const RefineOptions& options, TriangleHierarchy hierarchy)
      : input_(input),
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
    anchor_ = base.input_vertex;
    for (size_t v = 0; v < anchor_.size(); ++v) site_of_[anchor_[v]] = static_cast<int32_t>(v);
  }

  Status run(std::vector<RefineLevelReport>* report) {
    // Level 0: the base mesh's own cells, for the first selection.
    int32_t level = 0;
    std::vector<int32_t> cell_of = assign(level);
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
        progress("level " + std::to_string(level + 1) + ": no triangle passes the threshold; refinement stops");
        break;
      }
      const size_t nodes_before = h_.nodes().size();
      std::vector<int32_t> new_vertices;
      for (int32_t node : selected) h_.split(node, &new_vertices);
      lr.split = (h_.nodes().size() - nodes_before) / 4;
      ++level;
      anchor_.resize(h_.vertex_count(), -1);
      build_level_mesh(level);  // new vertices need to know whether they are on the boundary
      const size_t midpoints_before = midpoint_vertices_, surface_before = surface_vertices_,
                   detours_before = detour_vertices_;
      for (int32_t v : new_vertices) SRCODEC_RETURN_IF_ERROR(place_new_vertex(v));
      lr.midpoint_vertices = midpoint_vertices_ - midpoints_before;
      lr.surface_vertices = surface_vertices_ - surface_before;
      lr.detour_vertices = detour_vertices_ - detours_before;
      cell_of = relax(level, lr);
      lr.vertices = h_.level_vertex_count(level);
      lr.triangles = triangles_.size();
      lr.seconds = seconds_since(start);
      std::string tangles;  // the goal is none; say so when some are left
      if (lr.folded_triangles + lr.coarse_folded_triangles > 0)
        tangles += ", " + std::to_string(lr.folded_triangles) + " folded (" +
                   std::to_string(lr.coarse_folded_triangles) + " on coarser levels)";
      if (lr.pleats > 0) tangles += ", " + std::to_string(lr.pleats) + " pleats";
      if (lr.spikes_mended > 0) tangles += ", " + std::to_string(lr.spikes_mended) + " spikes mended";
      progress("level " + std::to_string(level) + ": " + std::to_string(lr.vertices) + " vertices, " +
               std::to_string(lr.triangles) + " triangles, " + std::to_string(lr.lloyd_iterations) +
               " Lloyd steps" + tangles + ", " + std::to_string(lr.seconds) + " s");
      if (report) report->push_back(lr);
    }
    if ((options_.tolerance > 0.0 || options_.threshold_after_uniform) && level > 0)
      SRCODEC_RETURN_IF_ERROR(coarsen(level, cell_of, report));
    return ok_status();
  }

  RefineResult result() && {
    RefineResult r{std::move(h_), {}, std::move(anchor_)};
    r.positions.reserve(r.anchor.size());
    for (int32_t& a : r.anchor) {
      r.positions.push_back(points_[a]);
      if (a >= static_cast<int32_t>(input_.positions.size())) a = -1;
    }
    return r;
  }

 private:
  void progress(const std::string& line) const {
    if (options_.progress) options_.progress(line);
  }

  Eigen::Vector3d on_base(const ParamPoint& p) const {
    const auto& t = base_.mesh.triangles[p.face];
    return p.bary[0] * base_.mesh.positions[t[0]] + p.bary[1] * base_.mesh.positions[t[1]] +
           p.bary[2] * base_.mesh.positions[t[2]];
  }

  // Each input vertex's image on the base mesh: distances between these are
  // distances on the base domain (exact inside a face, a chord across edges).
  std::vector<Eigen::Vector3d> embed() const {
    std::vector<Eigen::Vector3d> out(input_.positions.size());
    for (size_t i = 0; i < out.size(); ++i) out[i] = on_base(param_[i]);
    return out;
  }

  void build_face_points() {
    const size_t faces = base_.mesh.triangles.size();
    face_points_.offsets.assign(faces + 1, 0);
    for (const ParamPoint& p : base_.param) ++face_points_.offsets[p.face + 1];
    for (size_t f = 0; f < faces; ++f) face_points_.offsets[f + 1] += face_points_.offsets[f];
    std::vector<int32_t> fill(face_points_.offsets.begin(), face_points_.offsets.end() - 1);
    face_points_.items.resize(base_.param.size());
    for (size_t i = 0; i < base_.param.size(); ++i)
      face_points_.items[fill[param_[i].face]++] = static_cast<int32_t>(i);
  }

  // Base faces that share a corner with `face`: the part of the base domain
  // a new vertex of `face` may take its input vertex from.
  bool near_face(int32_t face, int32_t other) const {
    if (face == other) return true;
    for (int32_t c : base_.mesh.triangles[face])
      for (const int32_t* f = base_vertex_faces_.begin(c); f != base_vertex_faces_.end(c); ++f)
        if (*f == other) return true;
    return false;
  }

  // The input's vertex neighbours, built on first use (by the repairs'
  // input_disk and path_length; most runs need neither).
  const Adjacency& input_neighbors() {
    if (input_neighbors_.size() == 0) input_neighbors_ = vertex_neighbors(input_.positions.size(), input_.triangles);
    return input_neighbors_;
  }

  // The shortest path along the input's edges from input vertex `from` to
  // `to`, when it is no longer than `limit`: its length, with path_prev_
  // leading back from `to` until clear_path(); infinity otherwise. A* with
  // the straight distance to `to` as the estimate.
  double path_length(int32_t from, int32_t to, double limit) {
    const Adjacency& neighbors = input_neighbors();
    if (path_dist_.empty()) {
      path_dist_.assign(input_.positions.size(), std::numeric_limits<double>::infinity());
      path_prev_.assign(input_.positions.size(), -1);
    }
    clear_path();
    const Eigen::Vector3d& goal = points_[to];
    using Entry = std::pair<double, int32_t>;  // estimated total length, vertex
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
    path_touched_.push_back(from);
    path_dist_[from] = 0.0;
    open.push({(points_[from] - goal).norm(), from});
    while (!open.empty()) {
      const auto [f, i] = open.top();
      open.pop();
      if (f > limit) break;
      if (i == to) return path_dist_[to];
      if (f > path_dist_[i] + (points_[i] - goal).norm()) continue;  // an older entry
      for (const int32_t* jt = neighbors.begin(i); jt != neighbors.end(i); ++jt) {
        const int32_t j = *jt;
        const double d = path_dist_[i] + (points_[i] - points_[j]).norm();
        if (d < path_dist_[j]) {
          if (std::isinf(path_dist_[j])) path_touched_.push_back(j);
          path_dist_[j] = d;
          path_prev_[j] = i;
          open.push({d + (points_[j] - goal).norm(), j});
        }
      }
    }
    return std::numeric_limits<double>::infinity();
  }
  void clear_path() {
    for (int32_t i : path_touched_) {
      path_dist_[i] = std::numeric_limits<double>::infinity();
      path_prev_[i] = -1;
    }
    path_touched_.clear();
  }

  // An edge of input vertices a and b spans a detour of the input when the
  // shortest path between them along the input's edges is more than
  // kDetour times the chord: a pocket, a crease, the gap between two walls
  // or the rim of a thin flap, which a triangle on the edge cuts across.
  // The bunny at 5 levels with 170 base vertices (78.8 dB) lost 92.8% of its
  // squared error to such a bridge between its ears, 5.5 level-3 edges deep
  // along the input.
  static constexpr double kDetour = 1.6;
  bool detour(int32_t a, int32_t b) {
    const int32_t n = static_cast<int32_t>(input_.positions.size());
    if (a >= n || b >= n || a == b) return false;
    return std::isinf(path_length(a, b, kDetour * (points_[a] - points_[b]).norm()));
  }

  // Where new vertex v's parent edge (input vertices from, to) spans a
  // detour, v goes to the free input vertex of the path nearest the path's
  // middle, so that the finer levels follow the surface into it: the
  // chord's midpoint lies across the gap, and every finer level would keep
  // spanning it. -1 where the edge spans no detour, the path is longer than
  // kMaxDetour times the chord, or no vertex of it is free for v.
  int32_t middle_of_detour(int32_t v, int32_t from, int32_t to) {
    constexpr double kMaxDetour = 16.0;
    const int32_t n = static_cast<int32_t>(input_.positions.size());
    if (!options_.follow_detours || from >= n || to >= n || from == to || site_on_boundary_[v]) return -1;
    const double chord = (points_[from] - points_[to]).norm();
    const double length = path_length(from, to, kMaxDetour * chord);
    int32_t best = -1;
    if (std::isfinite(length) && length > kDetour * chord) {
      double best_off = std::numeric_limits<double>::infinity();
      for (int32_t i = path_prev_[to]; i >= 0 && i != from; i = path_prev_[i]) {
        const double off = std::abs(path_dist_[i] - 0.5 * length);
        if (site_of_[i] < 0 && allowed(v, i) && off < best_off) {
          best_off = off;
          best = i;
        }
      }
    }
    clear_path();
    return best;
  }

  // Site s may move to point i (in Lloyd's steps) without an edge of the
  // current level's mesh coming to span a detour that did not: a site moved
  // to the far wall of a pocket would bridge it again.
  bool keeps_off_detours(int32_t s, int32_t i) {
    if (!options_.follow_detours) return true;
    for (const int32_t* nb = neighbors_.begin(s); nb != neighbors_.end(s); ++nb) {
      const int32_t other = anchor_[*nb];
      if (other >= 0 && detour(i, other) && !detour(anchor_[s], other)) return false;
    }
    return true;
  }

  // Starts new vertex v on the surface at its parent edge's midpoint
  // (§III-B, Fig. 4b-c): the free input vertex nearest the line through the
  // chord's midpoint along the endpoints' normals, where that line crosses
  // the surface. The paper's dyadic point on the base domain comes second:
  // where the base mesh's parameterization is stretched (around holes, on
  // thin ridges) it lies rings away from the edge, and the nearest point to
  // the chord's midpoint cuts across curved parts. Measured at 4 levels with
  // the defaults, against the domain first: igea 86.07 -> 87.74 dB, the
  // bunny 79.97 -> 80.92 dB with 13 folded triangles -> 6, armadillo 74.23 ->
  // 75.02, nefertiti 76.80 -> 77.24. Before both, where the edge spans a
  // detour of the input: the middle of its path (middle_of_detour).
  Status place_new_vertex(int32_t v) {
    const ParamPoint p = h_.nominal_param(v);
    const auto edge = h_.parent_edge(v);
    const Eigen::Vector3d a = points_[anchor_[edge[0]]], b = points_[anchor_[edge[1]]];  // copies: add_point may grow points_
    const Eigen::Vector3d midpoint = 0.5 * (a + b);
    const double edge_length = (a - b).norm();
    if (const int32_t across = middle_of_detour(v, anchor_[edge[0]], anchor_[edge[1]]); across >= 0) {
      ++detour_vertices_;
      return take(v, across);
    }
    const Eigen::Vector3d side = normals_[anchor_[edge[0]]] + normals_[anchor_[edge[1]]];
    if (side.norm() > 0.0) {
      const Eigen::Vector3d axis = side.normalized();
      constexpr size_t kNear = 64;
      std::array<uint32_t, kNear> idx{};
      std::array<double, kNear> dist{};
      const size_t k = input_tree_.knnSearch(midpoint.data(), kNear, idx.data(), dist.data());
      int32_t best = -1;
      double best_d = kSparseFraction * edge_length;
      for (size_t j = 0; j < k; ++j) {
        const int32_t i = static_cast<int32_t>(idx[j]);
        // Free, of the site's kind, on the same part of the base domain and
        // on the same sheet (facing along the edge).
        if (site_of_[i] >= 0 || !allowed(v, i) || !near_face(p.face, param_[i].face) || !(normals_[i].dot(side) > 0.0))
          continue;
        const Eigen::Vector3d off = points_[i] - midpoint;
        const double along = off.dot(axis);
        const double across = (off - along * axis).norm();
        if (std::abs(along) < edge_length && across <= best_d && (across < best_d || i < best)) {
          best_d = across;
          best = i;
        }
      }
      if (best >= 0) return take(v, best);
    }
    // Else among the kInit free vertices nearest v's dyadic point on the base
    // domain, the one nearest in space to the edge's midpoint. The domain
    // picks the right sheet of the surface; space corrects the
    // parameterization's stretch.
    constexpr size_t kInit = 8;
    const Eigen::Vector3d target = on_base(p);
    for (size_t k : {64, 512, 4096}) {
      k = std::min(k, embedded_.size());
      std::vector<uint32_t> idx(k);
      std::vector<double> dist(k);
      k = tree_.knnSearch(target.data(), k, idx.data(), dist.data());
      int32_t best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      size_t seen = 0;
      for (size_t j = 0; j < k && seen < kInit; ++j) {
        const int32_t i = static_cast<int32_t>(idx[j]);
        if (site_of_[i] >= 0 || !allowed(v, i) || !near_face(p.face, param_[i].face)) continue;
        ++seen;
        const double d = (points_[i] - midpoint).squaredNorm();
        if (d < best_d) {
          best_d = d;
          best = i;
        }
      }
      if (best >= 0) {
        // Where the input is sparse, its nearest free vertex is far from the
        // edge: the new vertex goes to the input surface point nearest the
        // edge's midpoint instead (a forced split would otherwise stack
        // vertices and fold the mesh).
        if (!site_on_boundary_[v] && std::sqrt(best_d) > kSparseFraction * edge_length) {
          const int32_t on_surface = surface_point(midpoint, p.face, best_d);
          if (on_surface >= 0) {
            ++surface_vertices_;
            return take(v, on_surface);
          }
        }
        return take(v, best);
      }
      if (k == embedded_.size()) break;
    }
    // The nearest points are all taken (the parameterization crowds them
    // elsewhere): widen ring by ring over the base faces around `face`.
    std::vector<int32_t> ring{p.face}, next;
    std::vector<char> seen(base_.mesh.triangles.size(), 0);
    seen[p.face] = 1;
    // Three rings out, a point is no longer near the edge: stop there rather
    // than scan the whole component for every vertex.
    for (int rings = 0; rings < 3 && !ring.empty(); ++rings) {
      int32_t best = -1;
      double best_d = std::numeric_limits<double>::infinity();
      for (int32_t f : ring)
        for (const int32_t* i = face_points_.begin(f); i != face_points_.end(f); ++i) {
          const double d = (embedded_[*i] - target).squaredNorm();
          if (site_of_[*i] < 0 && allowed(v, *i) && (d < best_d || (d == best_d && *i < best))) {
            best_d = d;
            best = *i;
          }
        }
      if (best >= 0) return take(v, best);
      next.clear();
      for (int32_t f : ring)
        for (int32_t c : base_.mesh.triangles[f])
          for (const int32_t* g = base_vertex_faces_.begin(c); g != base_vertex_faces_.end(c); ++g)
            if (!seen[*g]) {
              seen[*g] = 1;
              next.push_back(*g);
            }
      ring.swap(next);
    }
    // No input vertex is left near the edge: the input is locally too coarse
    // for this level. The new vertex goes to its parent edge's midpoint, a
    // point that is not an input vertex (counted in the level report).
    Eigen::Vector3d normal = normals_[anchor_[edge[0]]] + normals_[anchor_[edge[1]]];
    if (normal.norm() > 0.0) normal.normalize();
    // On the boundary: halfway along the input's boundary between the
    // edge's ends (the chord's midpoint when they are neighbours on it).
    Eigen::Vector3d x = midpoint;
    double place = 0.0;
    const bool on_rim = site_on_boundary_[v] && rim_prev_[v] >= 0 && rim_next_[v] >= 0 &&
                        rim_middle(rim_prev_[v], rim_next_[v], &x, &place);
    const int32_t i =
        add_point(x, p, normal, site_on_boundary_[v], on_rim ? loop_[anchor_[rim_prev_[v]]] : -1, place);
    ++midpoint_vertices_;
    return take(v, i);
  }

  struct SurfacePoint {
    Eigen::Vector3d x;
    Eigen::Vector3d normal;  // unit, of the input triangle it lies on
    int32_t vertex = -1;     // the input vertex whose triangle it lies on (-1: none found)
    int32_t loop = -1;       // nearest_on_boundary's: the boundary loop it lies on, and where (loop_)
    double loop_pos = 0.0;
  };

  // The point of the input surface nearest to x among the triangles around
  // the input vertices nearest x (on the base faces near `face`, not on the
  // input's boundary, and facing along `side` unless it is zero: the sheet a
  // site is on, where two sheets of a thin part are near); vertex -1 when
  // none is nearer than sqrt(bound).
  SurfacePoint nearest_on_surface(const Eigen::Vector3d& x, int32_t face, double bound,
                                  const Eigen::Vector3d& side = Eigen::Vector3d::Zero()) const {
    constexpr size_t kNear = 8;
    std::array<uint32_t, kNear> idx{};
    std::array<double, kNear> dist{};
    const size_t k = input_tree_.knnSearch(x.data(), kNear, idx.data(), dist.data());
    SurfacePoint out;
    int32_t best_triangle = -1;
    for (size_t j = 0; j < k; ++j) {
      const int32_t i = static_cast<int32_t>(idx[j]);
      if (input_on_boundary_[i] || !near_face(face, param_[i].face)) continue;
      for (const int32_t* t = input_around_.begin(i); t != input_around_.end(i); ++t) {
        const auto& tri = input_.triangles[*t];
        if (!(side.dot((points_[tri[1]] - points_[tri[0]]).cross(points_[tri[2]] - points_[tri[0]])) >= 0.0)) continue;
        const Eigen::Vector3d q = closest_on_triangle(x, points_[tri[0]], points_[tri[1]], points_[tri[2]]);
        const double d = (q - x).squaredNorm();
        if (d < bound) {
          bound = d;
          out.x = q;
          best_triangle = *t;
          out.vertex = i;
        }
      }
    }
    if (best_triangle < 0) return out;
    const auto& tri = input_.triangles[best_triangle];
    out.normal = (points_[tri[1]] - points_[tri[0]]).cross(points_[tri[2]] - points_[tri[0]]);
    if (out.normal.norm() > 0.0) out.normal.normalize();
    return out;
  }

  // The point of the input's boundary nearest to x among the boundary edges
  // at the input vertices nearest x (on the base faces near `face`); vertex
  // -1 when there is none.
  // With `site` (a boundary site), only on the boundary between its
  // boundary neighbours (on_rim_arc).
  SurfacePoint nearest_on_boundary(const Eigen::Vector3d& x, int32_t face, int32_t site = -1) const {
    auto on_arc = [&](int32_t i) {
      return site < 0 || on_rim_arc(site, i) || (rim_prev_[site] >= 0 && i == anchor_[rim_prev_[site]]) ||
             (rim_next_[site] >= 0 && i == anchor_[rim_next_[site]]);
    };
    constexpr size_t kNear = 16;
    std::array<uint32_t, kNear> idx{};
    std::array<double, kNear> dist{};
    const size_t k = input_tree_.knnSearch(x.data(), kNear, idx.data(), dist.data());
    SurfacePoint out;
    double bound = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < k; ++j) {
      const int32_t i = static_cast<int32_t>(idx[j]);
      if (!input_on_boundary_[i] || !near_face(face, param_[i].face)) continue;
      for (const int32_t* t = input_around_.begin(i); t != input_around_.end(i); ++t)
        for (int32_t other : input_.triangles[*t]) {
          if (other == i || !input_on_boundary_[other] ||
              triangles_on_edge(input_around_, input_.triangles, i, other) != 1 || !on_arc(i) || !on_arc(other))
            continue;
          const Eigen::Vector3d &a = points_[i], &b = points_[other];
          const double len2 = (b - a).squaredNorm();
          const double along = len2 > 0.0 ? std::clamp((x - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
          const Eigen::Vector3d q = a + along * (b - a);
          const double d = (q - x).squaredNorm();
          if (d < bound) {
            bound = d;
            out.x = q;
            out.vertex = along < 0.5 ? i : other;
            out.normal = normals_[out.vertex];
            out.loop = -1;
            const int32_t loop = loop_[i];
            if (loop >= 0 && loop_[other] == loop) {  // neighbours along the loop, one way or the other
              const double size = static_cast<double>(loop_walk_[loop].size());
              const bool forward = along_loop(i, other) == 1.0;
              out.loop = loop;
              out.loop_pos = forward ? loop_pos_[i] + along : std::fmod(loop_pos_[other] + 1.0 - along, size);
              if (out.loop_pos >= size) out.loop_pos -= size;
            }
          }
        }
    }
    return out;
  }

  // nearest_on_surface's point, added as a point off the input's vertices;
  // -1 when there is none.
  int32_t surface_point(const Eigen::Vector3d& x, int32_t face, double bound) {
    const SurfacePoint q = nearest_on_surface(x, face, bound);
    if (q.vertex < 0) return -1;
    return add_point(q.x, param_[q.vertex], q.normal, 0);
  }

  Status take(int32_t v, int32_t i) {
    anchor_[v] = i;
    site_of_[i] = v;
    return ok_status();
  }

  // Site s leaves its point for point i (free), which it now holds.
  void move_site(int32_t s, int32_t i) {
    site_of_[anchor_[s]] = -1;
    anchor_[s] = i;
    site_of_[i] = s;
  }

  // Eq. 1 restricted to the sites near each input vertex on the base domain.
  // Each vertex is independent: the result does not depend on threads.
  std::vector<int32_t> assign(int32_t level) {
    build_level_mesh(level);
    return reassign(level);
  }

  // The mesh of `level`, its adjacency, and which of its vertices lie on its
  // boundary (an edge used by one triangle).
  void build_level_mesh(int32_t level) {
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
    // The coarser levels' meshes too: sites of every level move, and each
    // level's mesh must stay unfolded, not only the finest.
    coarse_triangles_.resize(level);
    coarse_around_.resize(level);
    for (int32_t k = 0; k < level; ++k) {
      coarse_triangles_[k] = h_.level_triangles(k);
      coarse_around_[k] = vertex_triangles(n, coarse_triangles_[k]);
    }
  }

  // Boundary sites stay on the input's boundary and interior sites inside,
  // or the boundary would shrink and fold: a site may only sit on an input
  // vertex of its own kind.
  // And a boundary site keeps to the input's boundary between its two
  // boundary neighbours (on_rim_arc).
  bool allowed(int32_t site, int32_t i) const {
    return site_on_boundary_[site] == input_on_boundary_[i] && (!site_on_boundary_[site] || on_rim_arc(site, i));
  }

  // The input's boundary loops, each walked the way its triangles run along
  // it: per input vertex its loop (-1: none, or a loop that is not a simple
  // cycle) and its place along it.
  void build_loops() {
    loop_.assign(input_.positions.size(), -1);
    loop_pos_.assign(input_.positions.size(), 0.0);
    loop_walk_ = boundary_loops(input_.positions.size(), input_.triangles, input_around_);
    for (size_t l = 0; l < loop_walk_.size(); ++l)
      for (size_t k = 0; k < loop_walk_[l].size(); ++k) {
        loop_[loop_walk_[l][k]] = static_cast<int32_t>(l);
        loop_pos_[loop_walk_[l][k]] = static_cast<double>(k);
      }
  }

  // How far along their loop (in its vertices) point `to` comes after point
  // `from`, in [0, length); both on one loop.
  double along_loop(int32_t from, int32_t to) const {
    const double size = static_cast<double>(loop_walk_[loop_[from]].size());
    return std::fmod(loop_pos_[to] - loop_pos_[from] + size, size);
  }
  // ... and to the point after it along the loop, a full turn when it is
  // `from` itself.
  double arc_length(int32_t from, int32_t to) const {
    const double d = along_loop(from, to);
    return d == 0.0 ? static_cast<double>(loop_walk_[loop_[from]].size()) : d;
  }

  // The point of the input's boundary halfway along the loop from a's
  // point to b's (sites on one loop, in the loop's order), with its loop
  // place; false when their order is not known.
  bool rim_middle(int32_t a, int32_t b, Eigen::Vector3d* x, double* place) const {
    const int32_t pa = anchor_[a], pb = anchor_[b];
    if (pa < 0 || pb < 0 || loop_[pa] < 0 || loop_[pb] != loop_[pa]) return false;
    const std::vector<int32_t>& walk = loop_walk_[loop_[pa]];
    *place = std::fmod(loop_pos_[pa] + 0.5 * arc_length(pa, pb), static_cast<double>(walk.size()));
    const size_t k = static_cast<size_t>(*place);
    const double t = *place - static_cast<double>(k);
    *x = (1.0 - t) * points_[walk[k % walk.size()]] + t * points_[walk[(k + 1) % walk.size()]];
    return true;
  }

  // Boundary site s (of the current level's mesh) may take boundary point i
  // only between its boundary neighbours along the input's loop, the way the
  // level's boundary edges run: a site taken from across a narrow hole
  // (the bunny's slits) makes the remesh's boundary zigzag across it, with
  // triangles over the hole. True wherever that order is not known (a
  // point off the input's vertices, a loop that is not a simple cycle, a
  // site whose own point is already out of order).
  bool on_rim_arc(int32_t s, int32_t i) const {
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

  std::vector<int32_t> reassign(int32_t level) const {
    constexpr int kMaxWalk = 64;
    std::vector<int32_t> cell_of(points_.size(), -1);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, cell_of.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        if (site_of_[i] >= 0 && anchor_[site_of_[i]] == static_cast<int32_t>(i)) {
          cell_of[i] = site_of_[i];
          continue;
        }
        if (i >= input_.positions.size()) continue;  // a point off the input no site holds: in no cell (-1)
        const int32_t node = h_.locate(param_[i], level);
        const Eigen::Vector3d& x = points_[i];
        int32_t best = -1;
        double best_d = std::numeric_limits<double>::infinity();
        auto consider = [&](int32_t s) {
          const double d = (points_[anchor_[s]] - x).squaredNorm();
          if (d < best_d || (d == best_d && s < best)) {
            best_d = d;
            best = s;
          }
        };
        for (int32_t c : h_.nodes()[node].v) {
          consider(c);
          for (const int32_t* s = neighbors_.begin(c); s != neighbors_.end(c); ++s) consider(*s);
        }
        // Then down the level's mesh, neighbour by neighbour, while a site
        // is nearer: the base domain locates the vertex on the right sheet,
        // but its stretch goes stale as sites move.
        for (int step = 0; step < kMaxWalk && best >= 0; ++step) {
          const int32_t from = best;
          for (const int32_t* s = neighbors_.begin(from); s != neighbors_.end(from); ++s) consider(*s);
          if (best == from) break;
        }
        cell_of[i] = best;
      }
    });
    return cell_of;
  }

  // Lloyd relaxation over the sites of all levels (§III-B). Returns the
  // final cells, which Eqs. 4-5 use to select the next level's splits.
  std::vector<int32_t> relax(int32_t level, RefineLevelReport& lr) {
    std::vector<int32_t> cell_of = reassign(level);  // run() built this level's mesh before placing vertices
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
        if (!keeps_off_detours(row, best)) {
          ++lr.refused_detours;
          continue;
        }
        move_site(row, best);
        ++moved;
      }
      lr.moves += moved;
      lr.lloyd_iterations = it + 1;
      cell_of = reassign(level);
      if (static_cast<double>(moved) < options_.min_moved_fraction * static_cast<double>(sites)) break;
    }
    const Adjacency members = cells(cell_of, sites);
    for (size_t s = 0; s < sites; ++s)
      if (members.offsets[s + 1] - members.offsets[s] == 1) ++lr.empty_cells;
    untangle(level, lr);
    lr.spikes_mended = mend_spikes();
    count_tangles(lr);
    return reassign(level);
  }

  // Mean length of site s's edges in the current level's mesh, s placed at
  // `at`.
  double mean_edge(int32_t s, const Eigen::Vector3d& at) const {
    double sum = 0.0;
    for (const int32_t* n = neighbors_.begin(s); n != neighbors_.end(s); ++n) sum += (points_[anchor_[*n]] - at).norm();
    return sum / static_cast<double>(neighbors_.end(s) - neighbors_.begin(s));
  }

  // Spikes, after the repairs: an interior site whose edges are on average
  // more than three times as long as its neighbours' (their median), one
  // that took an input vertex on another sheet while its neighbours stayed
  // on this one (the bunny at 5 levels: three sites between its ears held
  // 61% of the error, none of them folded). Such a site moves to the first
  // free input vertex near its neighbours' mean that halves its edges, when
  // no more triangles fold around it and the input its old triangles
  // reached (within its longest edge) stays covered: each such input vertex
  // within a quarter of the neighbours' median edge of the remesh, or of
  // twice its distance now. A site that is a thin part's only cover stays
  // (moved before the repairs and without that check, the spikes' moves
  // left a part of armadillo's hand 1.5% of the diagonal from the remesh).
  // Returns the sites moved.
  size_t mend_spikes() {
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
      if (!in_mesh(s) || site_on_boundary_[s]) continue;
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

  // The folds and pleats left on the current level's mesh and the coarser ones.
  void count_tangles(RefineLevelReport& lr) const {
    lr.folded_triangles = 0;
    for (const auto& tri : triangles_) lr.folded_triangles += folded(tri, -1, -1);
    lr.folded_by_nearest_input = folded_by_nearest_input();
    lr.pleats = pleats().size();
    lr.coarse_folded_triangles = 0;
    for (const auto& level_tris : coarse_triangles_)
      for (const auto& tri : level_tris) lr.coarse_folded_triangles += folded(tri, -1, -1);
  }

  // Lloyd cannot undo every fold the initial placement made, nor the pleats:
  // rounds of repairs, then the midpoint resets of this level's new sites
  // where folds remain, then the rounds once more. A reset patch comes back
  // with fewer folds but can leave a sliver that one site's move undoes
  // (4 levels, defaults: ogre 143 + 38 folded -> 103 + 28, recount 1355 ->
  // 1336; beast 147 + 30 -> 140 + 29, 625 -> 624; the bunny's recount 3 ->
  // 2 and pleats 2 -> 0; the other corpus meshes unchanged). Where folds
  // are still left on the last level, the patches around them are redrawn
  // in a map of the input (reparam_patch), then the rounds run again. On
  // the last level only: on a coarser one it moved sites that the levels
  // above then refined from, and nefertiti's adaptive 5-level runs lost
  // 0.5-1.2 dB that way (uniform 5 levels gained 0.4).
  void untangle(int32_t level, RefineLevelReport& lr) {
    repair_rounds(lr);
    if (level == 0 || folded_triangles().empty()) return;
    for (int rings : {0, 1, 2, 4, 8, 16})
      if (!for_each_tangle_patch(rings, [&](const std::vector<int32_t>& patch) {
            lr.midpoint_resets += midpoint_patch(patch, level);
          }))
        return;
    repair_rounds(lr);
    if (level != options_.levels || folded_triangles().empty()) return;
    for (int rings : {0, 1, 2, 4, 8, 16})
      if (!for_each_tangle_patch(
              rings, [&](const std::vector<int32_t>& patch) { lr.reparameterized += reparam_patch(patch, level); }, false))
        return;
    repair_rounds(lr);
  }

  // The three repairs, in rounds while they leave fewer folds and pleats (a
  // repair can free the sites another needs).
  void repair_rounds(RefineLevelReport& lr) {
    constexpr int kRounds = 4;
    size_t before = folded_triangles().size() + pleats().size();
    for (int round = 0; round < kRounds && before > 0; ++round) {
      untangle_on_input(lr);
      smooth_tangles(lr);  // before leaving the surface: bunny at 7a08122 79.67 dB and 9 folds, against 79.49 and 12
      untangle_off_input(lr);
      const size_t after = folded_triangles().size() + pleats().size();
      if (after >= before) return;
      before = after;
    }
  }

  // A site whose cell sits on the wrong side of a neighbour moves within
  // that cell. For each site on a folded triangle, try the free input
  // vertices nearest (in space) to the mean of its neighbours, a Laplacian
  // step, and take the first that leaves fewer folded triangles around it,
  // or as many with a better worst triangle.
  void untangle_on_input(RefineLevelReport& lr) {
    constexpr int kPasses = 8;
    constexpr size_t kCandidates = 48;
    std::vector<uint32_t> idx(kCandidates);
    std::vector<double> dist(kCandidates);
    for (int pass = 0; pass < kPasses; ++pass) {
      std::vector<int32_t> tangled;
      for (const auto& tri : folded_triangles()) tangled.insert(tangled.end(), tri.begin(), tri.end());
      if (tangled.empty()) break;
      std::sort(tangled.begin(), tangled.end());
      tangled.erase(std::unique(tangled.begin(), tangled.end()), tangled.end());
      size_t fixed = 0;
      for (int32_t s : tangled) {
        if (neighbors_.begin(s) == neighbors_.end(s)) continue;
        const Eigen::Vector3d mean = neighbour_mean(s);
        const int32_t face = param_[anchor_[s]].face;
        const std::pair<int, double> before = star_quality(s, anchor_[s]);
        const size_t k = input_tree_.knnSearch(mean.data(), kCandidates, idx.data(), dist.data());
        for (size_t j = 0; j < k; ++j) {
          const int32_t i = static_cast<int32_t>(idx[j]);
          if (site_of_[i] >= 0 || !allowed(s, i) || !near_face(face, param_[i].face)) continue;
          if (better_star(star_quality(s, i), before)) {
            move_site(s, i);
            ++fixed;
            break;
          }
        }
      }
      lr.untangled += fixed;
      if (fixed == 0) break;
    }
  }

  // For the few folds no input vertex undoes (a site squeezed between
  // neighbours that are themselves stuck): the site leaves the input and
  // goes to the mean of its neighbours, when that is better. Repeated while
  // it helps: a site moved off the input can free its neighbours for the
  // next pass.
  void untangle_off_input(RefineLevelReport& lr) {
    constexpr int kPasses = 8;
    for (int pass = 0; pass < kPasses; ++pass) {
      size_t moved = 0;
      for (const auto& tri : folded_triangles()) {
        if (!folded(tri, -1, -1)) continue;
        for (int32_t s : tri) {
          if (neighbors_.begin(s) == neighbors_.end(s)) continue;
          const int32_t from = anchor_[s];
          const int32_t i = add_point(neighbour_mean(s), param_[from], normals_[from], site_on_boundary_[s]);
          if (better_star(star_quality(s, i), star_quality(s, from))) {
            move_site(s, i);
            ++lr.off_input_moves;
            ++moved;
            break;
          }
          drop_last_point();
        }
      }
      if (moved == 0) break;
    }
  }

  // The triangle of the current level's mesh across edge (c, c + 1) of
  // triangle t, or -1 on the boundary.
  int32_t across(int32_t t, int c) const {
    const int32_t a = triangles_[t][c], b = triangles_[t][(c + 1) % 3];
    for (const int32_t* u = around_.begin(a); u != around_.end(a); ++u)
      if (*u != t && std::find(triangles_[*u].begin(), triangles_[*u].end(), b) != triangles_[*u].end()) return *u;
    return -1;
  }

  // Triangles t and u of the current level's mesh (neighbours) meet at more
  // than 150 degrees, folded onto each other: a pleat, which the facing test
  // misses when both lean the same way. Not on a smooth surface sampled as
  // finely as the finest level.
  bool pleated(int32_t t, int32_t u) const {
    auto normal = [&](int32_t k) {
      const auto& tri = triangles_[k];
      const Eigen::Vector3d &p0 = points_[anchor_[tri[0]]], &p1 = points_[anchor_[tri[1]]], &p2 = points_[anchor_[tri[2]]];
      return Eigen::Vector3d((p1 - p0).cross(p2 - p0));
    };
    return pleat(normal(t), normal(u));
  }

  // The pleated pairs of neighbouring triangles (t < u) of the current
  // level's mesh.
  std::vector<std::pair<int32_t, int32_t>> pleats() const {
    std::vector<std::pair<int32_t, int32_t>> out;
    for (int32_t t = 0; t < static_cast<int32_t>(triangles_.size()); ++t)
      for (int c = 0; c < 3; ++c) {
        const int32_t u = across(t, c);
        if (u > t && pleated(t, u)) out.emplace_back(t, u);
      }
    return out;
  }

  // The folded triangles of the current level's mesh and of the coarser ones.
  std::vector<std::array<int32_t, 3>> folded_triangles() const {
    std::vector<std::array<int32_t, 3>> out;
    for (const auto& tri : triangles_)
      if (folded(tri, -1, -1)) out.push_back(tri);
    for (const auto& level_tris : coarse_triangles_)
      for (const auto& tri : level_tris)
        if (folded(tri, -1, -1)) out.push_back(tri);
    return out;
  }

  // The resort for folds that no single site's move undoes (a site whose
  // neighbours are themselves out of place, often beside a jagged hole),
  // and for pleats: Laplacian smoothing of the patch around each, every
  // interior site of the patch at once, each step's positions put back on
  // the input surface. A patch's new positions are kept only when its
  // triangles have fewer folds (on every level), or as many and fewer
  // pleats; the patches grow ring by ring while any remain. Boundary sites
  // move along the input's boundary.
  void smooth_tangles(RefineLevelReport& lr) {
    for (int rings : {1, 2, 4, 8})
      if (!for_each_tangle_patch(rings, [&](const std::vector<int32_t>& patch) { lr.smoothed += smooth_patch(patch); }))
        return;
  }

  // Hands `repair` the patches around the current folds (on every level)
  // and pleats: the sites within `rings` rings of one, each connected part
  // of them a patch (sorted sites). False when there is nothing to repair.
  template <class Repair>
  bool for_each_tangle_patch(int rings, Repair&& repair, bool with_pleats = true) {
    const size_t sites = neighbors_.size();
    std::vector<std::array<int32_t, 3>> folds = folded_triangles();
    if (with_pleats)
      for (const auto& [t, u] : pleats()) {
        folds.push_back(triangles_[t]);
        folds.push_back(triangles_[u]);
      }
    if (folds.empty()) return false;
    std::vector<char> in(sites, 0);
    std::vector<int32_t> frontier, next, patch;
    for (const auto& tri : folds)
      for (int32_t s : tri)
        if (!in[s]) {
          in[s] = 1;
          frontier.push_back(s);
        }
    for (int r = 0; r < rings; ++r) {
      next.clear();
      for (int32_t s : frontier)
        for (const int32_t* n = neighbors_.begin(s); n != neighbors_.end(s); ++n)
          if (!in[*n]) {
            in[*n] = 1;
            next.push_back(*n);
          }
      frontier.swap(next);
    }
    // Each connected part of the marked sites is a patch (2: taken).
    for (size_t start = 0; start < sites; ++start) {
      if (in[start] != 1) continue;
      patch.assign(1, static_cast<int32_t>(start));
      in[start] = 2;
      for (size_t j = 0; j < patch.size(); ++j)
        for (const int32_t* n = neighbors_.begin(patch[j]); n != neighbors_.end(patch[j]); ++n)
          if (in[*n] == 1) {
            in[*n] = 2;
            patch.push_back(*n);
          }
      std::sort(patch.begin(), patch.end());
      repair(patch);
    }
    return true;
  }

  // Counts, for a patch (sorted sites), the folded triangles around it on
  // every level and the pleats in this level's mesh around it: returns a
  // callable that counts them for the sites' current positions.
  auto tangles_around(const std::vector<int32_t>& patch) const {
    // The triangles around the patch, per level (this level's mesh last).
    std::vector<std::vector<int32_t>> around(coarse_triangles_.size() + 1);
    auto gather = [&](const Adjacency& adjacency, std::vector<int32_t>& ids) {
      for (int32_t s : patch) ids.insert(ids.end(), adjacency.begin(s), adjacency.end(s));
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    };
    for (size_t k = 0; k < coarse_triangles_.size(); ++k) gather(coarse_around_[k], around[k]);
    gather(around_, around.back());
    return [this, around = std::move(around)] {
      std::pair<size_t, size_t> count{0, 0};
      for (size_t k = 0; k < around.size(); ++k) {
        const auto& tris = k < coarse_triangles_.size() ? coarse_triangles_[k] : triangles_;
        for (int32_t t : around[k]) count.first += folded(tris[t], -1, -1);
      }
      const std::vector<int32_t>& fine = around.back();
      for (int32_t t : fine)
        for (int c = 0; c < 3; ++c) {
          const int32_t u = across(t, c);
          if (u >= 0 && (u > t || !std::binary_search(fine.begin(), fine.end(), u))) count.second += pleated(t, u);
        }
      return count;
    };
  }

  // The last resort, when smoothing leaves folds: this level's new sites in
  // a patch go back to their parent edges' midpoints, off the input. A
  // triangle split at its edges' midpoints faces the way it did, so where
  // the coarser level is unfolded, a patch grown far enough unfolds this
  // one, at the price of its detail. Kept only when the patch has fewer
  // folds, or as many and fewer pleats. Returns the sites moved.
  size_t midpoint_patch(const std::vector<int32_t>& patch, int32_t level) {
    const auto tangles = tangles_around(patch);
    const std::pair<size_t, size_t> before = tangles();
    const size_t points_before = points_.size();
    std::vector<int32_t> moved, old;
    for (int32_t s : patch) {
      if (h_.vertex_level(s) != level) continue;
      const auto edge = h_.parent_edge(s);
      const int32_t a = anchor_[edge[0]], b = anchor_[edge[1]];
      Eigen::Vector3d normal = normals_[a] + normals_[b];
      if (normal.norm() > 0.0) normal.normalize();
      moved.push_back(s);
      old.push_back(anchor_[s]);
      move_site(s, add_point(0.5 * (points_[a] + points_[b]), h_.nominal_param(s), normal, site_on_boundary_[s]));
    }
    if (moved.empty()) return 0;
    if (tangles() < before) return moved.size();
    for (size_t j = 0; j < moved.size(); ++j) move_site(moved[j], old[j]);
    while (points_.size() > points_before) drop_last_point();
    return 0;
  }

  // The last resort, for folds the repairs and the midpoint resets leave:
  // a patch's interior sites go to a convex-combination map of its
  // triangles drawn in a planar map of the input surface under it, then
  // back onto the input. Two walls of a cleft, near in space, are apart in
  // that map, so the patch cannot bridge them as the Laplacian in space
  // does. Kept only when the patch has fewer folds (every level), or as
  // many and fewer pleats, and the input under it is no farther from the
  // patch (RMS) than 1.1 times what it was: without that bound a patch on
  // beast's thin flaps untangled its count at the price of its shape (74.62
  // -> 51.54 dB). Returns the sites moved; 0 when the patch or the input
  // under it is not a disk, or when the patch holds a triangle not split on
  // this level (a coarser leaf or the closure's: in adaptive runs, redrawn
  // with the rest, they cost armadillo 6.5 dB at --threshold 16).
  size_t reparam_patch(const std::vector<int32_t>& patch, int32_t level) {
    constexpr double kMaxRmsGrowth = 1.1;
    // The patch's interior sites and the triangles around them: a disk, on
    // local ids (sites, sorted), whose rim stays put.
    std::vector<int32_t> movable, tri_ids, sites;
    for (int32_t s : patch)
      if (!site_on_boundary_[s] && neighbors_.begin(s) != neighbors_.end(s)) movable.push_back(s);
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

  // The input surface under a patch, mapped onto the unit disk: input
  // vertices (and region_id_ marking them until release()), the input
  // triangles among them on local ids, and each vertex's place.
  struct InputDisk {
    std::vector<int32_t> vertices;
    std::vector<std::array<int32_t, 3>> triangles;
    std::vector<Eigen::Vector2d> uv;
    void release(std::vector<int32_t>& region_id) const {
      for (int32_t i : vertices) region_id[i] = -1;
    }
    // The place of point a (an input vertex of the disk, or a point off the
    // input near one): NaN when it is not on the disk.
    Eigen::Vector2d place(const Refiner& r, int32_t a) const {
      const int32_t i = r.nearest_input_vertex(a);
      if (r.region_id_[i] < 0) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
      if (i == a) return uv[r.region_id_[i]];
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector2d out = uv[r.region_id_[i]];
      for (const int32_t* t = r.input_around_.begin(i); t != r.input_around_.end(i); ++t) {
        const auto& tri = r.input_.triangles[*t];
        if (std::any_of(tri.begin(), tri.end(), [&](int32_t v) { return r.region_id_[v] < 0; })) continue;
        const auto& x = r.points_;
        const Eigen::Vector3d q = closest_on_triangle(x[a], x[tri[0]], x[tri[1]], x[tri[2]]);
        const double d = (q - x[a]).squaredNorm();
        if (d < best) {
          best = d;
          const Eigen::Vector3d b = barycentric(q, x[tri[0]], x[tri[1]], x[tri[2]]);
          out = b[0] * uv[r.region_id_[tri[0]]] + b[1] * uv[r.region_id_[tri[1]]] + b[2] * uv[r.region_id_[tri[2]]];
        }
      }
      return out;
    }
  };

  // The input vertices within `reach` of the sites' points along the
  // input's edges, and the input triangles among them, mapped onto the unit
  // disk (the boundary on the circle by arc length, the inside by convex
  // combinations); no vertices when they do not form a disk.
  InputDisk input_disk(const std::vector<int32_t>& sites, double reach) {
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

  // The RMS distance from input vertices to the triangles around the sites
  // nearest each (of `sites`, at their current points).
  double rms_to_patch(const std::vector<int32_t>& vertices, const std::vector<int32_t>& sites) const {
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

  // The input vertex a point stands for: itself, or for a point off the
  // input the input vertex nearest it.
  int32_t nearest_input_vertex(int32_t a) const {
    if (a < static_cast<int32_t>(input_.positions.size())) return a;
    uint32_t nearest = 0;
    double d2 = 0.0;
    input_tree_.knnSearch(points_[a].data(), 1, &nearest, &d2);
    return static_cast<int32_t>(nearest);
  }

  // smooth_tangles for one patch (sorted sites); returns the sites moved.
  // Smoothing far enough untangles the patch but can fold triangles at its
  // rim, where the sites that stay put are denser or sparser than the mean:
  // the patch keeps the step count, out of a few, that leaves fewest folds,
  // then fewest pleats.
  size_t smooth_patch(const std::vector<int32_t>& patch) {
    constexpr std::array<int, 7> kCheckpoints{1, 2, 3, 5, 8, 13, 20};
    const auto folds = tangles_around(patch);
    // Interior sites move to their neighbours' mean, boundary sites to the
    // mean of their two neighbours along the boundary, put back on the
    // input's boundary (rim: those two neighbours).
    std::vector<int32_t> movable, old;
    std::vector<std::array<int32_t, 2>> rim;
    for (int32_t s : patch) {
      std::array<int32_t, 2> along{-1, -1};
      if (site_on_boundary_[s]) {
        if (rim_prev_[s] < 0 || rim_next_[s] < 0) continue;  // a corner where boundary loops touch: stays
        along = {rim_prev_[s], rim_next_[s]};
      } else if (neighbors_.begin(s) == neighbors_.end(s)) {
        continue;
      }
      movable.push_back(s);
      rim.push_back(along);
    }
    if (movable.empty()) return 0;
    // Positions during the smoothing: the movable sites' own, the others'
    // from their points.
    std::vector<Eigen::Vector3d> x(movable.size()), stepped(movable.size());
    std::vector<SurfacePoint> on(movable.size()), best_on;
    for (size_t j = 0; j < movable.size(); ++j) {
      old.push_back(anchor_[movable[j]]);
      x[j] = points_[old[j]];
    }
    auto position = [&](int32_t s) -> const Eigen::Vector3d& {
      const auto it = std::lower_bound(movable.begin(), movable.end(), s);
      return it != movable.end() && *it == s ? x[it - movable.begin()] : points_[anchor_[s]];
    };
    // Puts the movable sites on points at x (on the input surface where
    // `on` found it); undo() takes them back to their old points.
    const size_t points_before = points_.size();
    auto apply = [&] {
      for (size_t j = 0; j < movable.size(); ++j) {
        const bool on_loop = rim[j][0] >= 0 && x[j] == on[j].x;
        move_site(movable[j], add_point(x[j], param_[on[j].vertex], on[j].normal, rim[j][0] >= 0,
                                        on_loop ? on[j].loop : -1, on[j].loop_pos));
      }
    };
    auto undo = [&] {
      for (size_t j = 0; j < movable.size(); ++j) move_site(movable[j], old[j]);
      while (points_.size() > points_before) drop_last_point();
    };
    std::pair<size_t, size_t> best = folds();
    std::vector<Eigen::Vector3d> best_x;
    for (int step = 1; step <= kCheckpoints.back(); ++step) {
      for (size_t j = 0; j < movable.size(); ++j) {
        const int32_t s = movable[j];
        if (rim[j][0] >= 0) {
          on[j] = nearest_on_boundary(0.5 * (position(rim[j][0]) + position(rim[j][1])), param_[old[j]].face, s);
          stepped[j] = on[j].x;
          continue;
        }
        const Eigen::Vector3d mean = neighbour_mean(s, position);
        on[j] = nearest_on_surface(mean, param_[old[j]].face, std::numeric_limits<double>::infinity(), normals_[old[j]]);
        stepped[j] = on[j].x;
      }
      x.swap(stepped);
      // A site the input surface was not found under has left it: stop.
      if (std::any_of(on.begin(), on.end(), [](const SurfacePoint& q) { return q.vertex < 0; })) break;
      if (std::find(kCheckpoints.begin(), kCheckpoints.end(), step) == kCheckpoints.end()) continue;
      apply();
      const std::pair<size_t, size_t> now = folds();
      undo();
      if (now < best) {
        best = now;
        best_x = x;
        best_on = on;
      }
    }
    if (best_x.empty()) return 0;
    x.swap(best_x);
    on.swap(best_on);
    apply();
    return movable.size();
  }

  // A point that is not an input vertex (an edge midpoint, or an untangled
  // site): it joins the points with no density, so Lloyd's centroids ignore
  // it, and no site on it yet.
  // `loop`, `place`: on the input's boundary, where along it (loop_).
  int32_t add_point(const Eigen::Vector3d& x, const ParamPoint& p, const Eigen::Vector3d& normal, char boundary,
                    int32_t loop = -1, double place = 0.0) {
    points_.push_back(x);
    param_.push_back(p);
    density_.push_back(0.0);
    normals_.push_back(normal);
    site_of_.push_back(-1);
    input_on_boundary_.push_back(boundary);
    loop_.push_back(loop);
    loop_pos_.push_back(place);
    return static_cast<int32_t>(points_.size() - 1);
  }
  void drop_last_point() {
    points_.pop_back();
    param_.pop_back();
    density_.pop_back();
    normals_.pop_back();
    site_of_.pop_back();
    input_on_boundary_.pop_back();
    loop_.pop_back();
    loop_pos_.pop_back();
  }

  static Adjacency cells(const std::vector<int32_t>& cell_of, size_t sites) {
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

  // How well a triangle of the remesh faces along the input surface: its
  // normal against the sum of the input normals at its corners' vertices,
  // scaled by its squared edge lengths (1/sqrt(3)-ish for a well-shaped,
  // well-facing triangle; <= 0 when it faces against the surface or has no
  // area). Site `moved` is taken to sit on input vertex `to`.
  double facing(const std::array<int32_t, 3>& tri, int32_t moved, int32_t to) const {
    std::array<int32_t, 3> at{};
    for (int c = 0; c < 3; ++c) at[c] = tri[c] == moved ? to : anchor_[tri[c]];
    return srcodec::facing(points_[at[0]], points_[at[1]], points_[at[2]],
                     normals_[at[0]] + normals_[at[1]] + normals_[at[2]]);
  }

  // RefineLevelReport::folded_by_nearest_input for the current level's mesh.
  size_t folded_by_nearest_input() const {
    std::vector<Eigen::Vector3d> corner_normal(anchor_.size(), Eigen::Vector3d::Zero());
    for (size_t s = 0; s < anchor_.size(); ++s) {
      if (anchor_[s] >= 0) corner_normal[s] = normals_[nearest_input_vertex(anchor_[s])];
    }
    size_t count = 0;
    for (const auto& t : triangles_)
      count += srcodec::folded(srcodec::facing(points_[anchor_[t[0]]], points_[anchor_[t[1]]], points_[anchor_[t[2]]],
                                               corner_normal[t[0]] + corner_normal[t[1]] + corner_normal[t[2]]));
    return count;
  }

  // Folded: facing the wrong way, or so thin it has no usable area.
  bool folded(const std::array<int32_t, 3>& tri, int32_t moved, int32_t to) const {
    return srcodec::folded(facing(tri, moved, to));
  }

  // The mean position of site s's neighbours in the current level's mesh
  // (s has at least one): the Laplacian target of the untangling.
  // `position(n)` gives a neighbour's position (default: where it sits).
  template <class Position>
  Eigen::Vector3d neighbour_mean(int32_t s, const Position& position) const {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const int32_t* n = neighbors_.begin(s); n != neighbors_.end(s); ++n) mean += position(*n);
    return mean / static_cast<double>(neighbors_.end(s) - neighbors_.begin(s));
  }
  Eigen::Vector3d neighbour_mean(int32_t s) const {
    return neighbour_mean(s, [&](int32_t n) -> const Eigen::Vector3d& { return points_[anchor_[n]]; });
  }

  // star_quality() `after` beats `before`: fewer folds, or as many but the
  // worst triangle less bad (a fold two vertices share is undone by moving
  // them in turn).
  static bool better_star(const std::pair<int, double>& after, const std::pair<int, double>& before) {
    return after.first < before.first || (after.first == before.first && after.second > before.second + 1e-12);
  }

  // Around site s on input vertex `to`: the folded triangles, and the worst
  // facing() of the others, for comparing positions.
  std::pair<int, double> star_quality(int32_t s, int32_t to) const {
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

  // Moving site s onto input vertex `to` is refused when it would leave more
  // folded triangles around s than there are now: a move never folds a
  // triangle it does not also unfold elsewhere, and moves that unfold are
  // welcome (the initial placement of new vertices can fold triangles where
  // the parameterization is stretched).
  bool keeps_orientation(int32_t s, int32_t to) const {
    return star_quality(s, to).first <= star_quality(s, anchor_[s]).first;
  }

  // Eqs. 4-5: f(s) = vertices in the cell of s, g(t) = min over t's corners;
  // the leaves of `level` with g(t) > threshold (all of them when uniform).
  // With threshold_after_uniform, all of them, and g(t) kept for undo_splits.
  std::vector<int32_t> select(int32_t level, const std::vector<int32_t>& cell_of) {
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

  // The tolerance, or the threshold after a uniform refinement, once the
  // last level is relaxed: undo_splits, then the repairs on the new finest
  // mesh, and the level reports brought up to date (fewer levels when every
  // split of the top ones was undone).
  Status coarsen(int32_t level, const std::vector<int32_t>& cell_of, std::vector<RefineLevelReport>* report) {
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
    const std::string criteria = options_.threshold_after_uniform && options_.tolerance > 0.0 ? "threshold and tolerance"
                                 : options_.threshold_after_uniform                             ? "threshold"
                                                                                                : "tolerance";
    progress(criteria + ": " + std::to_string(triangles_.size()) + " triangles left, " +
             std::to_string(lr.folded_triangles) + " folded (" + std::to_string(lr.coarse_folded_triangles) +
             " on coarser levels), " + std::to_string(lr.pleats) + " pleats, " +
             std::to_string(seconds_since(start)) + " s");
    return ok_status();
  }

  // The geometric criterion (ours; the paper's Eq. 5 only counts vertices,
  // which on an evenly sampled scan selects nearly everything or an arbitrary
  // part), applied once the last level is relaxed: splits are undone bottom
  // up where the input under a split node, whose children are leaves, lies
  // within the tolerance of the node's plane (RMS distance of the input
  // vertices whose nearest triangle of the finest mesh is under the node; 0
  // when there are none). The plane, not the triangle: the children of a
  // relaxed triangle do not tile its footprint, and a flat part's input lies
  // outside its parent triangle by up to an edge. But the triangle for the
  // input's boundary vertices: a merged triangle's boundary edge cuts across
  // the input's boundary between its corners (a flat square lost its
  // corners, 72.1 -> 45.8 dB, where the plane saw no error). The kept splits are
  // replayed into a new hierarchy, which adds the balance and closure splits
  // they need, and its sites keep the places the full refinement gave them.
  // Deciding level by level before each relaxation instead (sessions 2-11),
  // each adaptive run relaxed into its own tangles at thin parts, and the
  // adaptive runs stayed 0.6-2.7 dB below uniform 5 levels on armadillo and
  // nefertiti however many triangles they kept.
  //
  // With threshold_after_uniform, Eq. 5 first: a split node whose g(t) at
  // its level was within the threshold becomes a leaf, and all below it
  // goes. Per level k, `selected` counts the split nodes of level k that
  // Eq. 5 kept and `within_tolerance` those the tolerance then undid (the
  // closure can put some back).
  Status undo_splits(int32_t level, const std::vector<int32_t>& cell_of, std::vector<size_t>* selected,
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

  const TriangleMesh& input_;
  const BaseMesh& base_;
  const RefineOptions& options_;
  TriangleHierarchy h_;
  // The input's vertices and their places on the base domain, plus any
  // edge-midpoint vertices added where the input ran out (see
  // place_new_vertex); density_, normals_ and site_of_ follow them.
  std::vector<Eigen::Vector3d> points_;
  std::vector<ParamPoint> param_;
  std::vector<double> density_;
  std::vector<Eigen::Vector3d> normals_;  // per input vertex, unit (area-weighted)
  std::vector<Eigen::Vector3d> embedded_;
  PointCloud cloud_;
  PointTree tree_;  // over embedded_: nearest on the base domain
  PointCloud input_cloud_;
  PointTree input_tree_;  // over the input positions: nearest in space
  Adjacency base_vertex_faces_;
  Adjacency face_points_;
  std::vector<int32_t> anchor_;   // per site (hierarchy vertex): its input vertex
  std::vector<int32_t> site_of_;  // per input vertex: the site on it, or -1
  size_t midpoint_vertices_ = 0;  // vertices placed off the input so far
  size_t detour_vertices_ = 0;    // new vertices put in the middle of a detour (middle_of_detour)
  size_t surface_vertices_ = 0;   // new vertices put on the input surface between its vertices
  std::vector<double> path_dist_;  // path_length's, all infinite and -1 after clear_path()
  std::vector<int32_t> path_prev_, path_touched_;
  std::vector<std::array<int32_t, 3>> triangles_;  // the current level's mesh
  Adjacency neighbors_, around_;
  std::vector<std::vector<std::array<int32_t, 3>>> coarse_triangles_;  // levels below the current one
  std::vector<Adjacency> coarse_around_;
  std::vector<char> site_on_boundary_;   // per hierarchy vertex, in the current level's mesh
  std::vector<char> input_on_boundary_;  // per input vertex (points_)
  Adjacency input_around_;               // per input vertex of the input: its triangles
  // reparam_patch's, built on its first use: per input vertex of the input,
  // its neighbours, and its place in the current region (-1: none).
  Adjacency input_neighbors_;
  std::vector<int32_t> region_id_;
  std::vector<int32_t> g_of_;  // per node, with threshold_after_uniform: Eq. 5's g(t) when it was a leaf
  // build_loops': per point, its boundary loop (-1: none or not known) and
  // place along it (a point added on the boundary: between its vertices'
  // places); each loop's input vertices in order.
  std::vector<int32_t> loop_;
  std::vector<double> loop_pos_;
  std::vector<std::vector<int32_t>> loop_walk_;
  // Per site, in the current level's mesh: the boundary neighbours before
  // and after it along the way its boundary edges run (-1: none, -2: more).
  std::vector<int32_t> rim_prev_, rim_next_;
};

}  // namespace

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
