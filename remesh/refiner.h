// The refiner's state, shared by the files of the refinement (private to
// remesh/: refine() in remesh/refine.h is the public face). The paper's
// refinement (refine.cpp, lloyd_relaxation.cpp, new_vertices.cpp) and our
// repairs of the folds it leaves (fold_repairs.cpp, patch_reparam.cpp,
// spike_mending.cpp) work on one hierarchy and one set of sites, so they are
// one class; each file defines its part.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <nanoflann.hpp>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "remesh/adjacency.h"
#include "remesh/density.h"
#include "remesh/disk_map.h"
#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "remesh/point_cloud.h"
#include "remesh/refine.h"

namespace srcodec {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A new vertex whose nearest free input vertex is farther from its edge's
// midpoint than this fraction of the edge goes onto the input surface.
constexpr double kSparseFraction = 0.25;

class Refiner {
 public:
  Refiner(const TriangleMesh& input, const BaseMesh& base, const RefineOptions& options, TriangleHierarchy hierarchy);

  Status run(std::vector<RefineLevelReport>* report);

  RefineResult result() &&;

 private:
  void progress(const RemeshProgress& p) const {
    if (options_.progress) options_.progress(p);
  }

  Eigen::Vector3d on_base(const ParamPoint& p) const;

  // Each input vertex's image on the base mesh: distances between these are
  // distances on the base domain (exact inside a face, a chord across edges).
  std::vector<Eigen::Vector3d> embed() const;

  void build_face_points();

  // Base faces that share a corner with `face`: the part of the base domain
  // a new vertex of `face` may take its input vertex from.
  bool near_face(int32_t face, int32_t other) const;

  // The input's vertex neighbours, built on first use (by the repairs'
  // input_disk; most runs need none).
  const Adjacency& input_neighbors();


  // Starts new vertex v on the surface at its parent edge's midpoint
  // (§III-B, Fig. 4b-c): the free input vertex nearest the line through the
  // chord's midpoint along the endpoints' normals, where that line crosses
  // the surface. The paper's dyadic point on the base domain comes second:
  // where the base mesh's parameterization is stretched (around holes, on
  // thin ridges) it lies rings away from the edge, and the nearest point to
  // the chord's midpoint cuts across curved parts.
  Status place_new_vertex(int32_t v);

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
                                  const Eigen::Vector3d& side = Eigen::Vector3d::Zero()) const;

  // The point of the input's boundary nearest to x among the boundary edges
  // at the input vertices nearest x (on the base faces near `face`); vertex
  // -1 when there is none.
  // With `site` (a boundary site), only on the boundary between its
  // boundary neighbours (on_rim_arc).
  SurfacePoint nearest_on_boundary(const Eigen::Vector3d& x, int32_t face, int32_t site = -1) const;

  // nearest_on_surface's point, added as a point off the input's vertices;
  // -1 when there is none.
  int32_t surface_point(const Eigen::Vector3d& x, int32_t face, double bound);

  Status take(int32_t v, int32_t i);

  // Site s leaves its point for point i (free), which it now holds.
  void move_site(int32_t s, int32_t i);

  // Eq. 1 restricted to the sites near each input vertex on the base domain.
  // Each vertex is independent: the result does not depend on threads.
  std::vector<int32_t> assign(int32_t level);

  // The mesh of `level`, its adjacency, and which of its vertices lie on its
  // boundary (an edge used by one triangle).
  void build_level_mesh(int32_t level);

  // Boundary sites stay on the input's boundary and interior sites inside,
  // or the boundary would shrink and fold: a site may only sit on an input
  // vertex of its own kind.
  // And a boundary site keeps to the input's boundary between its two
  // boundary neighbours (on_rim_arc).
  bool allowed(int32_t site, int32_t i) const;

  // The input's boundary loops, each walked the way its triangles run along
  // it: per input vertex its loop (-1: none, or a loop that is not a simple
  // cycle) and its place along it.
  void build_loops();

  // Creases (crease_sites.cpp; RemeshOptions::creases): the vertices on the
  // base mesh's crease edges and on the edges refining them stay on the
  // input's creases, as boundary vertices stay on its boundary. A site on
  // one crease of its level's mesh relaxes along the input's crease between
  // its two crease neighbours; one where creases meet or end, or on an input
  // corner, stays; the others keep off the creases.
  // The input's creases as curves (per point: crease kind, curve, place).
  void build_curves();
  // The current level's crease edges: each site's crease degree and its
  // crease neighbours.
  void build_level_creases(int32_t level);
  bool crease_allowed(int32_t site, int32_t i) const;
  // Whether site s keeps to a crease (the repairs leave such sites alone).
  bool keeps_to_crease(int32_t s) const;
  // The input curve holding points a and b (a fixed point is on the curves
  // it ends), -1 if none.
  int32_t common_curve(int32_t a, int32_t b) const;
  // Point i's place along curve c, -1 when it is not on it.
  double place_on(int32_t c, int32_t i) const;
  // Whether point i lies strictly between sites' points along their curve:
  // on a closed curve the arc holding `own` (a point), else the shorter.
  bool between_on_curve(int32_t a, int32_t b, int32_t own, int32_t i) const;
  // The point of the input's crease halfway along the curve between site a's
  // point and site b's, with its curve and place; false when they share no
  // curve.
  bool crease_middle(int32_t a, int32_t b, Eigen::Vector3d* x, int32_t* curve, double* place) const;

  // How far along their loop (in its vertices) point `to` comes after point
  // `from`, in [0, length); both on one loop.
  double along_loop(int32_t from, int32_t to) const;
  // ... and to the point after it along the loop, a full turn when it is
  // `from` itself.
  double arc_length(int32_t from, int32_t to) const;

  // The point of the input's boundary halfway along the loop from a's
  // point to b's (sites on one loop, in the loop's order), with its loop
  // place; false when their order is not known.
  bool rim_middle(int32_t a, int32_t b, Eigen::Vector3d* x, double* place) const;

  // Boundary site s (of the current level's mesh) may take boundary point i
  // only between its boundary neighbours along the input's loop, the way the
  // level's boundary edges run: a site taken from across a narrow hole
  // (a slit) makes the remesh's boundary zigzag across it, with
  // triangles over the hole. True wherever that order is not known (a
  // point off the input's vertices, a loop that is not a simple cycle, a
  // site whose own point is already out of order).
  bool on_rim_arc(int32_t s, int32_t i) const;

  // Per input point, the node of `level` its parameterization falls in.
  std::vector<int32_t> locate_points(int32_t level) const;
  // Per node some point is located in (a row per node of the hierarchy):
  // the sites its points consider first, its corners and their neighbours,
  // each once. The level's mesh, not the sites' places: the Lloyd steps of
  // a level share them.
  Adjacency first_sites(const std::vector<int32_t>& located) const;
  // Every input point's cell (-1: none), from the sites around its located
  // node (locate_points, first_sites) and a walk to nearer ones.
  std::vector<int32_t> reassign(const std::vector<int32_t>& located, const Adjacency& first_sites) const;
  std::vector<int32_t> reassign(int32_t level) const {
    const std::vector<int32_t> located = locate_points(level);
    return reassign(located, first_sites(located));
  }

  // Lloyd relaxation over the sites of all levels (§III-B). Returns the
  // final cells, which Eqs. 4-5 use to select the next level's splits.
  std::vector<int32_t> relax(int32_t level, RefineLevelReport& lr);

  // Mean length of site s's edges in the current level's mesh, s placed at
  // `at`.
  double mean_edge(int32_t s, const Eigen::Vector3d& at) const;

  // Spikes, after the repairs: an interior site whose edges are on average
  // more than three times as long as its neighbours' (their median), one
  // that took an input vertex on another sheet while its neighbours stayed
  // on this one: a spike that folds nothing yet can hold most of the error.
  // Such a site moves to the first
  // free input vertex near its neighbours' mean that halves its edges, when
  // no more triangles fold around it and the input its old triangles
  // reached (within its longest edge) stays covered: each such input vertex
  // within a quarter of the neighbours' median edge of the remesh, or of
  // twice its distance now. A site that is a thin part's only cover stays:
  // moving it would leave that part far from the remesh.
  // Returns the sites moved.
  size_t mend_spikes();

  // The folds and pleats left on the current level's mesh and the coarser ones.
  void count_tangles(RefineLevelReport& lr) const;

  // Lloyd cannot undo every fold the initial placement made, nor the pleats:
  // rounds of repairs, then the midpoint resets of this level's new sites
  // where folds remain, then the rounds once more. A reset patch comes back
  // with fewer folds but can leave a sliver that one site's move undoes.
  // Where folds
  // are still left on the last level, the patches around them are redrawn
  // in a map of the input (reparam_patch), then the rounds run again. On
  // the last level only: on a coarser one it moves sites that the levels
  // above then refine from, which costs the adaptive runs.
  void untangle(int32_t level, RefineLevelReport& lr);

  // The three repairs, in rounds while they leave fewer folds and pleats (a
  // repair can free the sites another needs).
  void repair_rounds(RefineLevelReport& lr);

  // A site whose cell sits on the wrong side of a neighbour moves within
  // that cell. For each site on a folded triangle, try the free input
  // vertices nearest (in space) to the mean of its neighbours, a Laplacian
  // step, and take the first that leaves fewer folded triangles around it,
  // or as many with a better worst triangle.
  void untangle_on_input(RefineLevelReport& lr);

  // For the few folds no input vertex undoes (a site squeezed between
  // neighbours that are themselves stuck): the site leaves the input and
  // goes to the mean of its neighbours, when that is better. Repeated while
  // it helps: a site moved off the input can free its neighbours for the
  // next pass.
  void untangle_off_input(RefineLevelReport& lr);

  // The triangle of the current level's mesh across edge (c, c + 1) of
  // triangle t, or -1 on the boundary.
  int32_t across(int32_t t, int c) const;

  // Triangles t and u of the current level's mesh (neighbours) meet at more
  // than 150 degrees, folded onto each other: a pleat, which the facing test
  // misses when both lean the same way. Not on a smooth surface sampled as
  // finely as the finest level.
  bool pleated(int32_t t, int32_t u) const;

  // The pleated pairs of neighbouring triangles (t < u) of the current
  // level's mesh.
  std::vector<std::pair<int32_t, int32_t>> pleats() const;

  // The folded triangles of the current level's mesh and of the coarser ones.
  std::vector<std::array<int32_t, 3>> folded_triangles() const;
  // Per triangle of `triangles` (of some level's mesh), 1 when folded.
  std::vector<char> folded_flags(const std::vector<std::array<int32_t, 3>>& triangles) const;

  // The resort for folds that no single site's move undoes (a site whose
  // neighbours are themselves out of place, often beside a jagged hole),
  // and for pleats: Laplacian smoothing of the patch around each, every
  // interior site of the patch at once, each step's positions put back on
  // the input surface. A patch's new positions are kept only when its
  // triangles have fewer folds (on every level), or as many and fewer
  // pleats; the patches grow ring by ring while any remain. Boundary sites
  // move along the input's boundary.
  void smooth_tangles(RefineLevelReport& lr);

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
  std::function<std::pair<size_t, size_t>()> tangles_around(const std::vector<int32_t>& patch) const;

  // The last resort, when smoothing leaves folds: this level's new sites in
  // a patch go back to their parent edges' midpoints, off the input. A
  // triangle split at its edges' midpoints faces the way it did, so where
  // the coarser level is unfolded, a patch grown far enough unfolds this
  // one, at the price of its detail. Kept only when the patch has fewer
  // folds, or as many and fewer pleats. Returns the sites moved.
  size_t midpoint_patch(const std::vector<int32_t>& patch, int32_t level);

  // The last resort, for folds the repairs and the midpoint resets leave:
  // a patch's interior sites go to a convex-combination map of its
  // triangles drawn in a planar map of the input surface under it, then
  // back onto the input. Two walls of a cleft, near in space, are apart in
  // that map, so the patch cannot bridge them as the Laplacian in space
  // does. Kept only when the patch has fewer folds (every level), or as
  // many and fewer pleats, and the input under it is no farther from the
  // patch (RMS) than 1.1 times what it was: without that bound a patch on
  // thin flaps untangles its count at the price of its shape. Returns the
  // sites moved; 0 when the patch or the input under it is not a disk, or
  // when the patch holds a triangle not split on this level (a coarser leaf
  // or the closure's, which redrawn with the rest cost adaptive runs dearly).
  size_t reparam_patch(const std::vector<int32_t>& patch, int32_t level);

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
  InputDisk input_disk(const std::vector<int32_t>& sites, double reach);

  // The RMS distance from input vertices to the triangles around the sites
  // nearest each (of `sites`, at their current points).
  double rms_to_patch(const std::vector<int32_t>& vertices, const std::vector<int32_t>& sites) const;

  // The input vertex a point stands for: itself, or for a point off the
  // input the input vertex nearest it.
  int32_t nearest_input_vertex(int32_t a) const;

  // smooth_tangles for one patch (sorted sites); returns the sites moved.
  // Smoothing far enough untangles the patch but can fold triangles at its
  // rim, where the sites that stay put are denser or sparser than the mean:
  // the patch keeps the step count, out of a few, that leaves fewest folds,
  // then fewest pleats.
  size_t smooth_patch(const std::vector<int32_t>& patch);

  // A point that is not an input vertex (an edge midpoint, or an untangled
  // site): it joins the points with no density, so Lloyd's centroids ignore
  // it, and no site on it yet.
  // `loop`, `place`: on the input's boundary, where along it (loop_).
  int32_t add_point(const Eigen::Vector3d& x, const ParamPoint& p, const Eigen::Vector3d& normal, char boundary,
                    int32_t loop = -1, double place = 0.0);
  void drop_last_point();

  static Adjacency cells(const std::vector<int32_t>& cell_of, size_t sites);

  // How well a triangle of the remesh faces along the input surface: its
  // normal against the sum of the input normals at its corners' vertices,
  // scaled by its squared edge lengths (1/sqrt(3)-ish for a well-shaped,
  // well-facing triangle; <= 0 when it faces against the surface or has no
  // area). Site `moved` is taken to sit on input vertex `to`.
  double facing(const std::array<int32_t, 3>& tri, int32_t moved, int32_t to) const;

  // RefineLevelReport::folded_by_nearest_input for the current level's mesh.
  size_t folded_by_nearest_input() const;

  // Folded: facing the wrong way, or so thin it has no usable area.
  bool folded(const std::array<int32_t, 3>& tri, int32_t moved, int32_t to) const;

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
  std::pair<int, double> star_quality(int32_t s, int32_t to) const;

  // Moving site s onto input vertex `to` is refused when it would leave more
  // folded triangles around s than there are now: a move never folds a
  // triangle it does not also unfold elsewhere, and moves that unfold are
  // welcome (the initial placement of new vertices can fold triangles where
  // the parameterization is stretched).
  bool keeps_orientation(int32_t s, int32_t to) const;

  // Eqs. 4-5: f(s) = vertices in the cell of s, g(t) = min over t's corners;
  // the leaves of `level` with g(t) > threshold (all of them when uniform).
  // With threshold_after_uniform, all of them, and g(t) kept for undo_splits.
  std::vector<int32_t> select(int32_t level, const std::vector<int32_t>& cell_of);

  // The tolerance, or the threshold after a uniform refinement, once the
  // last level is relaxed: undo_splits, then the repairs on the new finest
  // mesh, and the level reports brought up to date (fewer levels when every
  // split of the top ones was undone).
  Status coarsen(int32_t level, const std::vector<int32_t>& cell_of, std::vector<RefineLevelReport>* report);

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
  // the input's boundary between its corners (a flat square loses its
  // corners where the plane sees no error). The kept splits are
  // replayed into a new hierarchy, which adds the balance and closure splits
  // they need, and its sites keep the places the full refinement gave them.
  // Deciding level by level before each relaxation instead, each adaptive
  // run relaxes into its own tangles at thin parts and stays below the
  // uniform refinement however many triangles it keeps.
  //
  // With threshold_after_uniform, Eq. 5 first: a split node whose g(t) at
  // its level was within the threshold becomes a leaf, and all below it
  // goes. Per level k, `selected` counts the split nodes of level k that
  // Eq. 5 kept and `within_tolerance` those the tolerance then undid (the
  // closure can put some back).
  Status undo_splits(int32_t level, const std::vector<int32_t>& cell_of, std::vector<size_t>* selected,
                     std::vector<size_t>* within_tolerance);

  // When the set-up began: its progress line gives its seconds.
  std::chrono::steady_clock::time_point created_;
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
  size_t surface_vertices_ = 0;   // new vertices put on the input surface between its vertices
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
  // build_curves' (empty without creases): per point, 0 off the creases, 1
  // on one, 2 a fixed point (a corner or end, BaseMeshCreases::fixed); its
  // curve (-1 for 0 and 2) and place along it; each curve's points in order
  // (back() == front() on a closed one); (fixed point, curve) pairs, sorted,
  // for each curve a fixed point ends.
  bool has_creases_ = false;
  std::vector<char> point_crease_;
  std::vector<int32_t> curve_;
  std::vector<double> curve_pos_;
  std::vector<std::vector<int32_t>> curve_walk_;
  std::vector<std::pair<int32_t, int32_t>> curves_at_fixed_;
  // Per base face: its patch, the faces reached without crossing a base
  // crease edge. A site off the creases keeps to its own patch: across a
  // crease its triangles would straddle the fold.
  std::vector<int32_t> face_patch_;
  std::vector<int32_t> site_patch_;  // per site of the current level: its patch (by its dyadic point)
  // Per site, in the current level's mesh: its crease edges, saturated at
  // 255, and the other ends of its first two.
  std::vector<uint8_t> site_crease_degree_;
  std::vector<std::array<int32_t, 2>> site_crease_ends_;
};

}  // namespace srcodec
