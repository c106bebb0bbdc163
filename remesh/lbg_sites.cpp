// LBG + Lloyd site selection (Kammoun, Payan, Antonini, §II-B, §II-C, §III-A):
// nearest-generator assignment (Eq. 1, Euclidean), generators moved to their
// cells' mass centroids (Eq. 2), sites = the vertices nearest the centroids,
// energy (Eq. 3) to stop Lloyd and to rank cells for splitting. LBG is Linde,
// Buzo, Gray 1980; Lloyd is Lloyd 1982.
//
// Why the centroids and not the sites drive the Lloyd steps: a site snapped to
// a vertex every step stalls as soon as its centroid moves less than half a
// vertex spacing, long before the tessellation is centroidal (higher final
// energy, cells of more uneven areas).
#include "remesh/lbg_sites.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <limits>
#include <nanoflann.hpp>
#include <string>

#include "remesh/adjacency.h"
#include "remesh/density.h"
#include "remesh/point_cloud.h"

namespace srcodec {
namespace {

Status check_input(const TriangleMesh& mesh, const LbgOptions& options) {
  const size_t n = mesh.positions.size();
  if (n == 0 || mesh.triangles.empty()) return invalid_mesh("lbg_sites: the mesh has no triangles");
  if (options.target_sites == 0)
    return invalid_argument("lbg_sites: target_sites is 0; ask for at least 1 site (4 or more for the base mesh of a "
                            "closed component)");
  if (options.target_sites > n)
    return invalid_argument("lbg_sites: target_sites " + std::to_string(options.target_sites) + " exceeds the " +
                            std::to_string(n) + " vertices of the mesh; ask for at most " + std::to_string(n) +
                            " or oversample the mesh first");
  if (!(options.min_relative_decrease >= 0.0 && options.min_relative_decrease < 1.0))
    return invalid_argument("lbg_sites: min_relative_decrease is " + std::to_string(options.min_relative_decrease) +
                            "; use a fraction in [0, 1)");
  if (options.max_lloyd_iterations < 0)
    return invalid_argument("lbg_sites: max_lloyd_iterations is " + std::to_string(options.max_lloyd_iterations) +
                            "; use 0 or more");
  if (n > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    return invalid_mesh("lbg_sites: " + std::to_string(n) + " vertices exceed the 32-bit index range");
  for (size_t v = 0; v < n; ++v)
    if (!mesh.positions[v].allFinite())
      return invalid_mesh("lbg_sites: vertex " + std::to_string(v) + " has a non-finite coordinate");
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int32_t v : mesh.triangles[f])
      if (v < 0 || static_cast<size_t>(v) >= n)
        return invalid_mesh("lbg_sites: triangle " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                            ", outside 0.." + std::to_string(n - 1));
  return ok_status();
}

// Cells are grown on the surface, so the mesh must be one edge-connected piece.
Status check_connected(const Adjacency& adj) {
  const size_t n = adj.offsets.size() - 1;
  std::vector<char> seen(n, 0);
  std::vector<int32_t> queue{0};
  seen[0] = 1;
  for (size_t head = 0; head < queue.size(); ++head)
    for (int32_t i = adj.offsets[queue[head]]; i < adj.offsets[queue[head] + 1]; ++i)
      if (!seen[adj.items[i]]) {
        seen[adj.items[i]] = 1;
        queue.push_back(adj.items[i]);
      }
  if (queue.size() == n) return ok_status();
  const size_t lost = std::find(seen.begin(), seen.end(), 0) - seen.begin();
  const bool unused = adj.offsets[lost] == adj.offsets[lost + 1];
  return invalid_mesh("lbg_sites: the mesh is not one connected component (vertex " + std::to_string(lost) +
                      (unused ? " is used by no triangle" : " is not connected to vertex 0") +
                      "); split it into connected components and remesh each one");
}

// Rounds of splitting curled cells (LbgOptions::min_flatness) at most.
constexpr int kCurledPasses = 4;

struct Context {
  const std::vector<Eigen::Vector3d>& positions;
  std::vector<double> density;
  Adjacency adjacency;
};

// ---- Eq. 1: nearest-site assignment -------------------------------------

// A nanoflann result set for the nearest generator, seeded with the vertex's
// current one: its distance bounds the search (most of the tree is pruned
// after a Lloyd step) and on ties the vertex stays where it is. With
// `keep_second`, it also keeps the distance to the nearest other generator:
// the search then prunes by that one, and still finds the same nearest.
class NearestSeeded {
 public:
  using DistanceType = double;
  using IndexType = uint32_t;
  NearestSeeded(double dist, uint32_t index, bool keep_second)
      : dist_(dist), index_(index), keep_second_(keep_second) {}
  double worstDist() const { return keep_second_ ? second_ : dist_; }
  bool full() const { return true; }
  bool addPoint(double dist, uint32_t index) {
    if (index == index_) {  // the nearest so far, met in the tree
      dist_ = std::min(dist_, dist);
    } else if (dist < dist_) {  // a leaf compares against its starting bound only
      second_ = std::min(second_, dist_);
      dist_ = dist;
      index_ = index;
    } else {
      second_ = std::min(second_, dist);
    }
    return true;
  }
  uint32_t index() const { return index_; }
  double second() const { return second_; }

 private:
  double dist_;
  uint32_t index_;
  bool keep_second_;
  double second_ = std::numeric_limits<double>::infinity();
};

// What one assignment leaves for the next (Hamerly, "Making k-means even
// faster", 2010): per vertex a lower bound on its distance to every generator
// but its own, and the generators it was measured against. A vertex nearer
// its own generator than that bound, less how far any generator moved since,
// keeps its cell without a search. Vertices whose label the assignment does
// not give by distance (anchors, the connectivity repair) lose their bound.
struct AssignBounds {
  std::vector<double> lower;  // empty: no bounds yet
  std::vector<Eigen::Vector3d> generators;
  void forget(size_t v) { lower[v] = 0.0; }
};

// Labels each vertex with its nearest generator (Eq. 1). cell_of holds a
// valid label per vertex on entry (the previous assignment) and the new one on
// exit. Anchor k (a vertex) always stays in cell k, so no cell is empty. Each
// vertex is independent, so the parallel loop gives the same result on any
// number of threads. With `bounds` (from the assignment that left cell_of,
// or empty), vertices the bounds settle are not searched; the labels are
// the same either way.
void assign_nearest(const Context& ctx, const std::vector<Eigen::Vector3d>& generators,
                    const std::vector<int32_t>& anchors, std::vector<int32_t>& cell_of, AssignBounds* bounds = nullptr) {
  const PointCloud cloud{generators};
  const PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(8));
  double drift = std::numeric_limits<double>::infinity();  // how far any generator moved
  if (bounds && bounds->generators.size() == generators.size() && !bounds->lower.empty()) {
    drift = 0.0;
    for (size_t k = 0; k < generators.size(); ++k)
      drift = std::max(drift, (generators[k] - bounds->generators[k]).norm());
  }
  if (bounds && bounds->lower.empty()) bounds->lower.assign(cell_of.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cell_of.size(), 2048), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t v = r.begin(); v != r.end(); ++v) {
      const Eigen::Vector3d& p = ctx.positions[v];
      const int32_t current = cell_of[v];
      const double own = (p - generators[current]).squaredNorm();
      if (!bounds) {
        NearestSeeded nearest(own, static_cast<uint32_t>(current), false);
        if (nearest.worstDist() > 0) tree.findNeighbors(nearest, p.data(), nanoflann::SearchParams());
        cell_of[v] = static_cast<int32_t>(nearest.index());
        continue;
      }
      // Strictly inside the bound, with room for rounding: no other
      // generator is as near, so the search would keep `current`.
      const double lower = bounds->lower[v] - drift;
      if (lower > 0.0 && std::sqrt(own) < lower * (1.0 - 1e-9)) {
        bounds->lower[v] = lower;
        continue;
      }
      NearestSeeded nearest(own, static_cast<uint32_t>(current), true);
      tree.findNeighbors(nearest, p.data(), nanoflann::SearchParams());
      cell_of[v] = static_cast<int32_t>(nearest.index());
      bounds->lower[v] = std::sqrt(nearest.second());
    }
  });
  for (size_t k = 0; k < anchors.size(); ++k) {
    cell_of[anchors[k]] = static_cast<int32_t>(k);
    if (bounds) bounds->forget(anchors[k]);
  }
  if (bounds) bounds->generators = generators;
}

// ---- Surface connectivity of the cells ----------------------------------

// Per cell, the vertices it lost and gained between two labelings: cell k
// lost lost[lost_at[k] .. lost_at[k + 1]) and gained likewise.
struct CellChanges {
  std::vector<int32_t> lost_at, lost, gained_at, gained;
};

CellChanges cell_changes(size_t num_cells, const std::vector<int32_t>& before, const std::vector<int32_t>& after) {
  CellChanges c;
  c.lost_at.assign(num_cells + 1, 0);
  c.gained_at.assign(num_cells + 1, 0);
  for (size_t v = 0; v < after.size(); ++v)
    if (before[v] != after[v]) ++c.lost_at[before[v] + 1], ++c.gained_at[after[v] + 1];
  for (size_t k = 0; k < num_cells; ++k) c.lost_at[k + 1] += c.lost_at[k], c.gained_at[k + 1] += c.gained_at[k];
  c.lost.resize(c.lost_at[num_cells]);
  c.gained.resize(c.gained_at[num_cells]);
  std::vector<int32_t> lost_fill(c.lost_at.begin(), c.lost_at.end() - 1);
  std::vector<int32_t> gained_fill(c.gained_at.begin(), c.gained_at.end() - 1);
  for (size_t v = 0; v < after.size(); ++v)
    if (before[v] != after[v]) {
      c.lost[lost_fill[before[v]]++] = static_cast<int32_t>(v);
      c.gained[gained_fill[after[v]]++] = static_cast<int32_t>(v);
    }
  return c;
}

// Whether the members of v's ring (`member`) are edge-connected among
// themselves: then any path through v goes around it, and removing v keeps
// the members' set connected. An empty ring proves nothing.
template <class Member>
bool ring_connected(const Adjacency& adj, int32_t v, Member member, std::vector<int32_t>& ring) {
  ring.clear();
  for (const int32_t* w = adj.begin(v); w != adj.end(v); ++w)
    if (member(*w)) ring.push_back(*w);
  if (ring.empty()) return false;
  // Grow from ring[0]: ring[0 .. reached) are reached, the rest not yet.
  size_t reached = 1;
  for (size_t head = 0; head < reached; ++head)
    for (size_t i = reached; i < ring.size(); ++i)
      if (std::binary_search(adj.begin(ring[head]), adj.end(ring[head]), ring[i])) std::swap(ring[i], ring[reached++]);
  return reached == ring.size();
}

// Whether cell k, connected under `before`, keeps what it did not lose
// connected: its lost vertices are taken out one at a time, each only when
// its ring in what is left stays connected (ring_connected). They are peeled
// from the outside in (first those next to other cells, then the neighbours
// of those taken out): taken in any other order, holes opened inside the
// lost band split the rings of the vertices between them. False means "not
// proven". `state` is all 0 on entry and on exit; task k touches it only at
// vertices of cell k under `before`, so cells can be proven in parallel.
bool kept_connected(const Adjacency& adj, const std::vector<int32_t>& before, const CellChanges& changes, int32_t k,
                    std::vector<char>& state, std::vector<int32_t>& scratch, std::vector<int32_t>& queue) {
  enum : char { kLeft = 0, kQueued = 1, kGone = 2 };
  const int32_t* lost = changes.lost.data() + changes.lost_at[k];
  const size_t count = changes.lost_at[k + 1] - changes.lost_at[k];
  const auto left = [&](int32_t w) { return before[w] == k && state[w] != kGone; };
  queue.clear();
  for (size_t i = 0; i < count; ++i)
    if (std::any_of(adj.begin(lost[i]), adj.end(lost[i]), [&](int32_t w) { return before[w] != k; })) {
      state[lost[i]] = kQueued;
      queue.push_back(lost[i]);
    }
  // Vertices refused wait at the back while others are taken out, until a
  // whole turn of the queue takes none.
  size_t gone = 0;
  for (size_t head = 0, turn_end = queue.size(), gone_at_turn = 0; head < queue.size(); ++head) {
    if (head == turn_end) {
      if (gone == gone_at_turn) break;
      turn_end = queue.size();
      gone_at_turn = gone;
    }
    const int32_t v = queue[head];
    if (!ring_connected(adj, v, left, scratch)) {
      queue.push_back(v);
      continue;
    }
    state[v] = kGone;
    ++gone;
    for (const int32_t* w = adj.begin(v); w != adj.end(v); ++w)
      if (before[*w] == k && state[*w] == kLeft && std::binary_search(lost, lost + count, *w)) {
        state[*w] = kQueued;
        queue.push_back(*w);
      }
  }
  for (size_t i = 0; i < count; ++i) state[lost[i]] = kLeft;
  return gone == count;
}

// Marks in `orphan` the vertices cell k gained that are not edge-connected,
// through other gained vertices, to what it kept (connected, with its site).
void mark_unjoined_gains(const Adjacency& adj, const std::vector<int32_t>& before, const std::vector<int32_t>& after,
                         const CellChanges& changes, int32_t k, std::vector<char>& orphan,
                         std::vector<int32_t>& queue) {
  const int32_t* gained = changes.gained.data() + changes.gained_at[k];
  const size_t count = changes.gained_at[k + 1] - changes.gained_at[k];
  // orphan[] starts at 1 on the gains and is cleared as they join: task k
  // touches only vertices of cell k under `after`.
  for (size_t i = 0; i < count; ++i) orphan[gained[i]] = 1;
  queue.clear();
  for (size_t i = 0; i < count; ++i) {
    const int32_t g = gained[i];
    if (std::any_of(adj.begin(g), adj.end(g), [&](int32_t w) { return before[w] == k && after[w] == k; })) {
      orphan[g] = 0;
      queue.push_back(g);
    }
  }
  for (size_t head = 0; head < queue.size(); ++head)
    for (const int32_t* w = adj.begin(queue[head]); w != adj.end(queue[head]); ++w)
      if (after[*w] == k && orphan[*w]) {  // another cell's task may be writing its own vertices' flags
        orphan[*w] = 0;
        queue.push_back(*w);
      }
}

// Marks (in `reached`) the vertices of cell k edge-connected to its site;
// returns how many there are.
size_t grow_from_site(const Adjacency& adj, const std::vector<int32_t>& cell_of, int32_t k, int32_t site,
                      std::vector<char>& reached, std::vector<int32_t>& queue) {
  queue.assign(1, site);
  reached[site] = 1;
  for (size_t head = 0; head < queue.size(); ++head) {
    const int32_t v = queue[head];
    for (int32_t i = adj.offsets[v]; i < adj.offsets[v + 1]; ++i) {
      const int32_t w = adj.items[i];
      if (cell_of[w] == k && !reached[w]) {  // only this cell's task touches reached[] of its vertices
        reached[w] = 1;
        queue.push_back(w);
      }
    }
  }
  return queue.size();
}

// Orphans (vertices cut off from their site) grouped into edge-connected
// pieces of equal label: piece_of is -1 for settled vertices, and piece p
// holds vertices[offsets[p] .. offsets[p + 1]).
struct OrphanPieces {
  std::vector<int32_t> piece_of;
  std::vector<int32_t> offsets{0};
  std::vector<int32_t> vertices;
};

OrphanPieces orphan_pieces(const Adjacency& adj, const std::vector<int32_t>& cell_of,
                           const std::vector<char>& orphan) {
  const size_t n = cell_of.size();
  OrphanPieces pieces;
  pieces.piece_of.assign(n, -1);
  for (size_t seed = 0; seed < n; ++seed) {
    if (!orphan[seed] || pieces.piece_of[seed] >= 0) continue;
    const auto p = static_cast<int32_t>(pieces.offsets.size() - 1);
    pieces.piece_of[seed] = p;
    pieces.vertices.push_back(static_cast<int32_t>(seed));
    for (size_t head = pieces.offsets.back(); head < pieces.vertices.size(); ++head) {
      const int32_t v = pieces.vertices[head];
      for (int32_t i = adj.offsets[v]; i < adj.offsets[v + 1]; ++i) {
        const int32_t w = adj.items[i];
        if (orphan[w] && pieces.piece_of[w] < 0 && cell_of[w] == cell_of[seed]) {
          pieces.piece_of[w] = p;
          pieces.vertices.push_back(w);
        }
      }
    }
    pieces.offsets.push_back(static_cast<int32_t>(pieces.vertices.size()));
  }
  return pieces;
}

// The label among the settled neighbours of piece p that shares most edges
// with it (smallest label on ties), or -1 when it has no settled neighbour.
int32_t majority_neighbour(const Adjacency& adj, const OrphanPieces& pieces, const std::vector<char>& settled,
                           const std::vector<int32_t>& cell_of, int32_t p, std::vector<int32_t>& votes) {
  votes.clear();
  for (int32_t i = pieces.offsets[p]; i < pieces.offsets[p + 1]; ++i) {
    const int32_t v = pieces.vertices[i];
    for (int32_t j = adj.offsets[v]; j < adj.offsets[v + 1]; ++j) {
      const int32_t q = pieces.piece_of[adj.items[j]];
      if (q < 0 || (q != p && settled[q])) votes.push_back(cell_of[adj.items[j]]);
    }
  }
  std::sort(votes.begin(), votes.end());
  int32_t best = -1;
  size_t best_count = 0;
  for (size_t a = 0, b = 0; a < votes.size(); a = b) {
    while (b < votes.size() && votes[b] == votes[a]) ++b;
    if (b - a > best_count) best = votes[a], best_count = b - a;
  }
  return best;
}

// Per vertex, whether it is cut off from its cell's site under `after`,
// all cells connected under `before` (empty: nothing known). A changed cell
// whose kept part is proven connected (kept_connected) can only have cut off
// gained vertices; any other changed cell is walked from its site.
std::vector<char> orphans(const Adjacency& adj, const std::vector<int32_t>& sites, const std::vector<int32_t>& before,
                          const std::vector<int32_t>& after) {
  const size_t n = after.size();
  std::vector<char> orphan(n, 0), walk(sites.size(), before.empty() ? 1 : 0);
  if (!before.empty()) {
    const CellChanges changes = cell_changes(sites.size(), before, after);
    std::vector<char> state(n, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, sites.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
      std::vector<int32_t> scratch, pending;
      for (size_t k = r.begin(); k != r.end(); ++k) {
        const auto cell = static_cast<int32_t>(k);
        if (!kept_connected(adj, before, changes, cell, state, scratch, pending)) {
          walk[k] = 1;
        } else {
          mark_unjoined_gains(adj, before, after, changes, cell, orphan, pending);
        }
      }
    });
  }
  if (std::find(walk.begin(), walk.end(), 1) == walk.end()) return orphan;
  std::vector<size_t> size(sites.size(), 0);
  for (int32_t k : after) ++size[k];
  std::vector<char> reached(n, 0), broken(sites.size(), 0);
  // Cells touch disjoint vertices, so they can grow in parallel with the same result.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, sites.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<int32_t> queue;
    for (size_t k = r.begin(); k != r.end(); ++k)
      if (walk[k]) broken[k] = grow_from_site(adj, after, static_cast<int32_t>(k), sites[k], reached, queue) < size[k];
  });
  for (size_t v = 0; v < n; ++v)
    if (broken[after[v]] && !reached[v]) orphan[v] = 1;
  return orphan;
}

// Euclidean nearest sites jump across thin parts (two close sheets): a cell
// may own pieces not connected to its site (`orphan`). Each such piece joins
// the neighbouring cell it shares most edges with, counting only neighbours
// already connected to their site, so every join keeps the receiving cell
// connected; pieces walled in by other orphans wait for a later pass.
// Returns the number of vertices moved.
size_t connect_cells(const Adjacency& adj, const std::vector<char>& orphan, std::vector<int32_t>& cell_of) {
  if (std::find(orphan.begin(), orphan.end(), 1) == orphan.end()) return 0;
  const OrphanPieces pieces = orphan_pieces(adj, cell_of, orphan);
  const size_t num_pieces = pieces.offsets.size() - 1;
  std::vector<char> settled(num_pieces, 0);
  std::vector<int32_t> pending(num_pieces), still_pending, votes;
  for (size_t p = 0; p < num_pieces; ++p) pending[p] = static_cast<int32_t>(p);
  size_t moved = 0;
  while (!pending.empty()) {
    still_pending.clear();
    for (int32_t p : pending) {
      const int32_t label = majority_neighbour(adj, pieces, settled, cell_of, p, votes);
      if (label < 0) {
        still_pending.push_back(p);
        continue;
      }
      for (int32_t i = pieces.offsets[p]; i < pieces.offsets[p + 1]; ++i) cell_of[pieces.vertices[i]] = label;
      moved += pieces.offsets[p + 1] - pieces.offsets[p];
      settled[p] = 1;
    }
    // The mesh is connected, so each pass settles at least one piece.
    assert(still_pending.size() < pending.size());
    if (still_pending.size() == pending.size()) break;
    pending.swap(still_pending);
  }
  return moved;
}

// ---- Eq. 2 and 3: centroids, sites, energy ------------------------------

// Density-weighted mass centroid of `count` vertices; the plain mean when
// they carry no area (only degenerate triangles around them).
Eigen::Vector3d mass_centroid(const Context& ctx, const int32_t* vertices, size_t count) {
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero(), plain = Eigen::Vector3d::Zero();
  double mass = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d& p = ctx.positions[vertices[i]];
    weighted += ctx.density[vertices[i]] * p;
    plain += p;
    mass += ctx.density[vertices[i]];
  }
  return mass > 0.0 ? Eigen::Vector3d(weighted / mass) : Eigen::Vector3d(plain / static_cast<double>(count));
}

// The vertex among `vertices` nearest to `c`; the first in order on ties.
int32_t nearest_vertex(const Context& ctx, const int32_t* vertices, size_t count, const Eigen::Vector3d& c) {
  int32_t best = vertices[0];
  double best_dist = (ctx.positions[best] - c).squaredNorm();
  for (size_t i = 1; i < count; ++i) {
    const double d = (ctx.positions[vertices[i]] - c).squaredNorm();
    if (d < best_dist) best = vertices[i], best_dist = d;
  }
  return best;
}

// Vertices grouped by cell: cell k owns vertices[offsets[k] .. offsets[k + 1]),
// in increasing index order.
struct CellLists {
  std::vector<int32_t> offsets;
  std::vector<int32_t> vertices;
  size_t size(size_t k) const { return offsets[k + 1] - offsets[k]; }
  const int32_t* begin(size_t k) const { return vertices.data() + offsets[k]; }
};

CellLists cell_lists(size_t num_cells, const std::vector<int32_t>& cell_of) {
  CellLists lists;
  lists.offsets.assign(num_cells + 1, 0);
  for (int32_t k : cell_of) ++lists.offsets[k + 1];
  for (size_t k = 0; k < num_cells; ++k) lists.offsets[k + 1] += lists.offsets[k];
  std::vector<int32_t> fill(lists.offsets.begin(), lists.offsets.end() - 1);
  lists.vertices.resize(cell_of.size());
  for (size_t v = 0; v < cell_of.size(); ++v) lists.vertices[fill[cell_of[v]]++] = static_cast<int32_t>(v);
  return lists;
}

// Eq. 3, summed in vertex order so the result is reproducible.
double total_energy(const std::vector<Eigen::Vector3d>& positions, const std::vector<double>& density,
                    const VoronoiCells& cells) {
  double energy = 0.0;
  for (size_t v = 0; v < cells.cell_of.size(); ++v)
    energy += density[v] * (positions[v] - positions[cells.sites[cells.cell_of[v]]]).squaredNorm();
  return energy;
}

// Eq. 3 per cell, summed in vertex order so the result is reproducible.
std::vector<double> cell_energies(const Context& ctx, const std::vector<int32_t>& sites,
                                  const std::vector<int32_t>& cell_of) {
  std::vector<double> energy(sites.size(), 0.0);
  for (size_t v = 0; v < cell_of.size(); ++v)
    energy[cell_of[v]] += ctx.density[v] * (ctx.positions[v] - ctx.positions[sites[cell_of[v]]]).squaredNorm();
  return energy;
}

// Every cell's mass centroid (Eq. 2); returns Eq. 3 with the centroids as
// generators.
double update_centroids(const Context& ctx, const VoronoiCells& cells, std::vector<Eigen::Vector3d>& centroids) {
  const CellLists lists = cell_lists(cells.sites.size(), cells.cell_of);
  centroids.resize(cells.sites.size());
  double energy = 0.0;
  for (size_t k = 0; k < cells.sites.size(); ++k) {
    centroids[k] = mass_centroid(ctx, lists.begin(k), lists.size(k));
    for (size_t i = 0; i < lists.size(k); ++i) {
      const int32_t v = lists.begin(k)[i];
      energy += ctx.density[v] * (ctx.positions[v] - centroids[k]).squaredNorm();
    }
  }
  return energy;
}

// Moves each site to the vertex of its cell nearest the cell's centroid
// (§II-C). Staying inside the cell keeps sites distinct; on a tie the site
// stays where it is.
void snap_sites(const Context& ctx, const std::vector<Eigen::Vector3d>& centroids, VoronoiCells& cells) {
  std::vector<double> best(cells.sites.size());
  for (size_t k = 0; k < cells.sites.size(); ++k)
    best[k] = (ctx.positions[cells.sites[k]] - centroids[k]).squaredNorm();
  for (size_t v = 0; v < cells.cell_of.size(); ++v) {
    const int32_t k = cells.cell_of[v];
    const double d = (ctx.positions[v] - centroids[k]).squaredNorm();
    if (d < best[k]) best[k] = d, cells.sites[k] = static_cast<int32_t>(v);
  }
}

std::vector<Eigen::Vector3d> site_positions(const Context& ctx, const std::vector<int32_t>& sites) {
  std::vector<Eigen::Vector3d> points(sites.size());
  for (size_t k = 0; k < sites.size(); ++k) points[k] = ctx.positions[sites[k]];
  return points;
}

// ---- LBG splitting ------------------------------------------------------

// Replaces cell k by the halves `low` and `high` of its vertices; each
// half's site is its vertex nearest the half's mass centroid. The first half
// keeps label k, the second gets the next free label. An empty half (no
// spread) is made by halving in index order instead.
void split_into(const Context& ctx, const int32_t* vertices, size_t count, int32_t k, std::vector<int32_t>& low,
                std::vector<int32_t>& high, VoronoiCells& cells) {
  if (low.empty() || high.empty()) {
    low.assign(vertices, vertices + count / 2);
    high.assign(vertices + count / 2, vertices + count);
  }
  const auto new_label = static_cast<int32_t>(cells.sites.size());
  cells.sites[k] = nearest_vertex(ctx, low.data(), low.size(), mass_centroid(ctx, low.data(), low.size()));
  cells.sites.push_back(nearest_vertex(ctx, high.data(), high.size(), mass_centroid(ctx, high.data(), high.size())));
  // The halves seed the next assignment's search bounds.
  for (int32_t v : high) cells.cell_of[v] = new_label;
}

// The principal axis (largest eigenvalue) of density-weighted vectors about
// their weighted mean `mean`.
Eigen::Vector3d principal_axis(const Context& ctx, const int32_t* vertices, size_t count,
                               const std::vector<Eigen::Vector3d>& vectors, const Eigen::Vector3d& mean) {
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d d = vectors[vertices[i]] - mean;
    covariance += ctx.density[vertices[i]] * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  return eigen.eigenvectors().col(2);  // largest eigenvalue last
}

// Splits cell k in two by the sign of (vectors[v] - mean) along the vectors'
// principal axis (one deterministic 2-means step). Needs a cell of two
// vertices or more.
void split_cell_by(const Context& ctx, const CellLists& lists, int32_t k, const std::vector<Eigen::Vector3d>& vectors,
                   const Eigen::Vector3d& mean, VoronoiCells& cells) {
  const int32_t* vertices = lists.begin(k);
  const size_t count = lists.size(k);
  const Eigen::Vector3d axis = principal_axis(ctx, vertices, count, vectors, mean);
  std::vector<int32_t> low, high;
  for (size_t i = 0; i < count; ++i) (axis.dot(vectors[vertices[i]] - mean) < 0.0 ? low : high).push_back(vertices[i]);
  split_into(ctx, vertices, count, k, low, high, cells);
}

// LBG's split of cell k: by the plane through its mass centroid across its
// principal axis.
void split_cell(const Context& ctx, const CellLists& lists, int32_t k, VoronoiCells& cells) {
  split_cell_by(ctx, lists, k, ctx.positions, mass_centroid(ctx, lists.begin(k), lists.size(k)), cells);
}

// One LBG split: every cell, or when doubling would pass `target` only the
// cells of largest energy (Eq. 3). Single-vertex cells cannot split. Returns
// the number of cells split.
size_t split_round(const Context& ctx, size_t target, VoronoiCells& cells) {
  const size_t num_cells = cells.sites.size();
  const CellLists lists = cell_lists(num_cells, cells.cell_of);
  const std::vector<double> energy = cell_energies(ctx, cells.sites, cells.cell_of);
  std::vector<int32_t> chosen;
  for (size_t k = 0; k < num_cells; ++k)
    if (lists.size(k) >= 2) chosen.push_back(static_cast<int32_t>(k));
  const size_t budget = target - num_cells;
  if (chosen.size() > budget) {
    std::stable_sort(chosen.begin(), chosen.end(), [&](int32_t a, int32_t b) { return energy[a] > energy[b]; });
    chosen.resize(budget);
    std::sort(chosen.begin(), chosen.end());
  }
  for (int32_t k : chosen) split_cell(ctx, lists, k, cells);
  return chosen.size();
}

// Assignment to `generators` (Eq. 1) made surface-connected; `before` is the
// labeling it starts from (empty: check every cell). Returns the vertices
// moved by the connectivity repair.
size_t assign_connected(const Context& ctx, const std::vector<Eigen::Vector3d>& generators,
                        const std::vector<int32_t>& before, VoronoiCells& cells, AssignBounds* bounds = nullptr) {
  assign_nearest(ctx, generators, cells.sites, cells.cell_of, bounds);
  const std::vector<char> orphan = orphans(ctx.adjacency, cells.sites, before, cells.cell_of);
  const size_t moved = connect_cells(ctx.adjacency, orphan, cells.cell_of);
  // The repair moves orphans to a cell not their nearest generator's.
  if (bounds && moved > 0)
    for (size_t v = 0; v < orphan.size(); ++v)
      if (orphan[v]) bounds->forget(v);
  return moved;
}

// Lloyd relaxation with the cells' mass centroids as generators, until the
// cells stop changing, a step lowers the energy by less than `min_decrease`
// of it (or not at all: that step is undone), or the step budget is spent.
// Then the sites (vertices nearest the centroids) take over as generators for
// a last assignment, so the cells are the sites' own Voronoi cells.
void relax(const Context& ctx, int max_iterations, double min_decrease, VoronoiCells& cells,
           LbgReport::Round& round) {
  // Split halves are not connected cells: check every cell the first time.
  AssignBounds bounds;
  round.reassigned_vertices += assign_connected(ctx, site_positions(ctx, cells.sites), {}, cells, &bounds);
  std::vector<Eigen::Vector3d> centroids, next_centroids;
  double energy = update_centroids(ctx, cells, centroids);
  round.energy.push_back(energy);
  for (int it = 0; it < max_iterations; ++it) {
    VoronoiCells next = cells;
    snap_sites(ctx, centroids, next);  // the anchors that keep each cell non-empty and rooted
    const size_t moved = assign_connected(ctx, centroids, cells.cell_of, next, &bounds);
    if (next.cell_of == cells.cell_of) break;  // a fixed point: the centroids would not move
    const double next_energy = update_centroids(ctx, next, next_centroids);
    round.energy.push_back(next_energy);
    // The repair can undo a step's gain; keeping the lower-energy state also
    // rules out cycles.
    if (!(next_energy < energy)) break;
    round.reassigned_vertices += moved;
    cells = std::move(next);
    centroids.swap(next_centroids);
    const bool converged = next_energy > energy * (1.0 - min_decrease);
    energy = next_energy;
    if (converged) break;
  }
  if (max_iterations > 0) {
    snap_sites(ctx, centroids, cells);
    const std::vector<int32_t> before = cells.cell_of;
    round.reassigned_vertices += assign_connected(ctx, site_positions(ctx, cells.sites), before, cells);
  }
  round.site_energy = total_energy(ctx.positions, ctx.density, cells);
}

// ---- Curled cells (ours, not in the paper) -----------------------------

// Per vertex: its area-weighted normal, the vector area of its dual cell
// (a third of each triangle's) over its density (the dual cell's area), so
// its length is 1 on flat ground and less where the triangles around it turn.
std::vector<Eigen::Vector3d> dual_normals(const TriangleMesh& mesh, const std::vector<double>& density) {
  std::vector<Eigen::Vector3d> normal(mesh.positions.size(), Eigen::Vector3d::Zero());
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    const Eigen::Vector3d third = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a) / 6.0;
    for (int32_t v : t) normal[v] += third;
  }
  for (size_t v = 0; v < normal.size(); ++v) normal[v] = density[v] > 0.0 ? Eigen::Vector3d(normal[v] / density[v])
                                                                          : Eigen::Vector3d::Zero();
  return normal;
}

// Splits every cell whose vector area is less than `min_flatness` times its
// area, across its normals (the two halves face apart), at most `budget` of
// them, the most curled first. Returns the number split.
size_t split_curled(const Context& ctx, const std::vector<Eigen::Vector3d>& normal, double min_flatness,
                    size_t budget, VoronoiCells& cells) {
  const size_t num_cells = cells.sites.size();
  const CellLists lists = cell_lists(num_cells, cells.cell_of);
  std::vector<Eigen::Vector3d> mean(num_cells, Eigen::Vector3d::Zero());
  std::vector<double> flatness(num_cells, 1.0);
  std::vector<int32_t> chosen;
  for (size_t k = 0; k < num_cells; ++k) {
    if (lists.size(k) < 2) continue;
    double area = 0.0;
    for (size_t i = 0; i < lists.size(k); ++i) {
      const int32_t v = lists.begin(k)[i];
      mean[k] += ctx.density[v] * normal[v];
      area += ctx.density[v];
    }
    if (!(area > 0.0)) continue;
    mean[k] /= area;
    flatness[k] = mean[k].norm();
    if (flatness[k] < min_flatness) chosen.push_back(static_cast<int32_t>(k));
  }
  if (chosen.size() > budget) {
    std::stable_sort(chosen.begin(), chosen.end(), [&](int32_t a, int32_t b) { return flatness[a] < flatness[b]; });
    chosen.resize(budget);
    std::sort(chosen.begin(), chosen.end());
  }
  for (int32_t k : chosen) split_cell_by(ctx, lists, k, normal, mean[k], cells);
  return chosen.size();
}

}  // namespace

double voronoi_energy(const TriangleMesh& mesh, const std::vector<double>& density, const VoronoiCells& cells) {
  return total_energy(mesh.positions, density, cells);
}

StatusOr<VoronoiCells> lbg_sites(const TriangleMesh& mesh, const LbgOptions& options, LbgReport* report) {
  SRCODEC_RETURN_IF_ERROR(check_input(mesh, options));
  const Context ctx{mesh.positions, vertex_density(mesh), vertex_neighbors(mesh.positions.size(), mesh.triangles)};
  SRCODEC_RETURN_IF_ERROR(check_connected(ctx.adjacency));
  if (report) *report = LbgReport{};

  const size_t n = mesh.positions.size();
  VoronoiCells cells;
  if (options.target_sites == n) {  // every vertex a site: the only answer
    for (size_t v = 0; v < n; ++v) cells.sites.push_back(static_cast<int32_t>(v));
    cells.cell_of = cells.sites;
    return cells;
  }
  std::vector<int32_t> all(n);
  for (size_t v = 0; v < n; ++v) all[v] = static_cast<int32_t>(v);
  cells.sites = {nearest_vertex(ctx, all.data(), n, mass_centroid(ctx, all.data(), n))};
  cells.cell_of.assign(n, 0);

  while (cells.sites.size() < options.target_sites) {
    LbgReport::Round round;
    if (split_round(ctx, options.target_sites, cells) == 0)
      return internal_error("lbg_sites: no cell could be split at " + std::to_string(cells.sites.size()) + " sites");
    relax(ctx, options.max_lloyd_iterations, options.min_relative_decrease, cells, round);
    round.sites = cells.sites.size();
    if (report) report->rounds.push_back(std::move(round));
  }

  // Cells that wrap around a thin part (a tube, the rim of a flap) make base
  // triangles that cut across it, which no later level recovers from.
  if (options.min_flatness > 0.0) {
    const std::vector<Eigen::Vector3d> normal = dual_normals(mesh, ctx.density);
    const size_t limit = std::min(n, options.target_sites + options.target_sites / 4);
    for (int pass = 0; pass < kCurledPasses && cells.sites.size() < limit; ++pass) {
      LbgReport::Round round;
      const size_t split = split_curled(ctx, normal, options.min_flatness, limit - cells.sites.size(), cells);
      if (split == 0) break;
      // The sites' own Voronoi cells, without Lloyd: on a thin tube Lloyd
      // prefers cells that are slices around it (they have the lower energy)
      // and undoes the split.
      relax(ctx, 0, options.min_relative_decrease, cells, round);
      round.sites = cells.sites.size();
      round.curled_splits = split;
      if (report) report->rounds.push_back(std::move(round));
    }
  }
  return cells;
}

}  // namespace srcodec
