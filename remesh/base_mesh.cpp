// Base mesh by half-edge collapses and the MAPS parameterization (Lee,
// Sweldens, Schröder, Cowsar, Dobkin, "MAPS: Multiresolution Adaptive
// Parameterization of Surfaces", SIGGRAPH 1998), steered by the Voronoi cells
// of Kammoun, Payan, Antonini §III-A.
//
// Every removed vertex v leaves behind its 1-ring polygon, which the collapse
// re-triangulates as a fan around the kept neighbour w. MAPS's conformal map
// z -> z^a flattens the 1-ring (angles at v scaled to sum to 2π, or π on the
// boundary, where v then sits on the straight segment between its two
// boundary neighbours); in that plane the old faces and the new fan tile the
// same polygon, so every point stored in v's old faces (and v itself) finds
// its new face and barycentric coordinates there. Points are kept per current
// face in intrusive linked lists, so a collapse touches only the points of
// its own 1-ring.
//
// Why a collapse goes towards the cell's site: removing the vertices of a
// cell from its rim inwards (deepest in breadth-first hops first) shrinks the
// cell onto its site, so the surviving edges are the dual edges between
// neighbouring cells: the base triangles are the Voronoi cells' Delaunay-like
// dual, as in the paper.
#include "remesh/base_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_set>
#include <utility>

#include "format/union_find.h"
#include "remesh/adjacency.h"
#include "remesh/openmesh_types.h"

namespace srcodec {
namespace {

using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

constexpr double kPi = 3.14159265358979323846;

std::string str(size_t x) { return std::to_string(x); }

Status check_arguments(size_t n, const std::vector<int32_t>& sites, const std::vector<int32_t>& cell_of) {
  std::vector<int32_t> site_index(n, -1);
  for (size_t k = 0; k < sites.size(); ++k) {
    const int32_t s = sites[k];
    if (s < 0 || static_cast<size_t>(s) >= n)
      return invalid_argument("build_base_mesh: site " + str(k) + " is vertex " + std::to_string(s) +
                              ", outside 0.." + std::to_string(static_cast<int64_t>(n) - 1));
    if (site_index[s] >= 0)
      return invalid_argument("build_base_mesh: sites " + std::to_string(site_index[s]) + " and " + str(k) +
                              " are both vertex " + std::to_string(s));
    site_index[s] = static_cast<int32_t>(k);
  }
  if (cell_of.empty()) return ok_status();
  if (cell_of.size() != n)
    return invalid_argument("build_base_mesh: cell_of has " + str(cell_of.size()) + " entries for " + str(n) +
                            " vertices; give one per vertex or none");
  for (size_t v = 0; v < n; ++v)
    if (cell_of[v] < 0 || static_cast<size_t>(cell_of[v]) >= sites.size())
      return invalid_argument("build_base_mesh: cell_of[" + str(v) + "] is " + std::to_string(cell_of[v]) +
                              ", not a site index (" + str(sites.size()) + " sites)");
  for (size_t k = 0; k < sites.size(); ++k)
    if (cell_of[sites[k]] != static_cast<int32_t>(k))
      return invalid_argument("build_base_mesh: site " + str(k) + " (vertex " + std::to_string(sites[k]) +
                              ") is in cell " + std::to_string(cell_of[sites[k]]) + ", not its own");
  return ok_status();
}

uint64_t edge_key(int32_t a, int32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
}

// Crease edges must be edges of the mesh, and every crease vertex that is
// not fixed must lie on exactly two of them: a crease vertex is collapsed
// along its one curve, which a branch or an end would not give.
Status check_creases(const Adjacency& adj, const BaseMeshCreases& creases) {
  const size_t n = adj.size();
  std::vector<int32_t> degree(n, 0);
  std::vector<char> fixed(n, 0);
  for (int32_t v : creases.fixed) {
    if (v < 0 || static_cast<size_t>(v) >= n)
      return invalid_argument("build_base_mesh: fixed vertex " + std::to_string(v) + " is outside 0.." +
                              std::to_string(static_cast<int64_t>(n) - 1));
    fixed[v] = 1;
  }
  for (size_t k = 0; k < creases.edges.size(); ++k) {
    const auto [a, b] = creases.edges[k];
    const bool in_range = a >= 0 && b >= 0 && static_cast<size_t>(a) < n && static_cast<size_t>(b) < n;
    if (!in_range || !std::binary_search(adj.begin(a), adj.end(a), b))
      return invalid_argument("build_base_mesh: crease " + str(k) + " (" + std::to_string(a) + ", " +
                              std::to_string(b) + ") is not an edge of the mesh");
    ++degree[a];
    ++degree[b];
  }
  for (size_t v = 0; v < n; ++v)
    if (degree[v] != 0 && degree[v] != 2 && !fixed[v])
      return invalid_argument("build_base_mesh: vertex " + str(v) + " lies on " + std::to_string(degree[v]) +
                              " crease edges but is not fixed; the corners and ends of creases must be");
  return ok_status();
}

// The mesh must be what split_into_manifold_components promises; checked here
// rather than trusted because OpenMesh would otherwise build a structure with
// silently merged or dropped faces.
Status check_mesh(const TriangleMesh& mesh) {
  const size_t n = mesh.positions.size();
  if (n == 0 || mesh.triangles.empty()) return invalid_mesh("build_base_mesh: the mesh has no triangles");
  if (n > static_cast<size_t>(std::numeric_limits<int32_t>::max()) / 4 ||
      mesh.triangles.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max()) / 4)
    return invalid_mesh("build_base_mesh: the mesh exceeds the 32-bit index range");
  for (size_t v = 0; v < n; ++v)
    if (!mesh.positions[v].allFinite())
      return invalid_mesh("build_base_mesh: vertex " + str(v) + " has a non-finite coordinate");
  std::vector<int32_t> faces_at(n + 1, 0);
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    for (int32_t v : t)
      if (v < 0 || static_cast<size_t>(v) >= n)
        return invalid_mesh("build_base_mesh: triangle " + str(f) + " uses vertex " + std::to_string(v) +
                            ", outside 0.." + str(n - 1));
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return invalid_mesh("build_base_mesh: triangle " + str(f) + " repeats a vertex");
    for (int32_t v : t) ++faces_at[v + 1];
  }
  for (size_t v = 0; v < n; ++v)
    if (faces_at[v + 1] == 0) return invalid_mesh("build_base_mesh: vertex " + str(v) + " is used by no triangle");

  // Every directed edge at most once: each edge has at most two faces, and
  // two faces on an edge traverse it in opposite directions.
  std::vector<uint64_t> directed;
  directed.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      directed.push_back((static_cast<uint64_t>(t[c]) << 32) | static_cast<uint32_t>(t[(c + 1) % 3]));
  std::sort(directed.begin(), directed.end());
  for (size_t i = 1; i < directed.size(); ++i)
    if (directed[i] == directed[i - 1])
      return invalid_mesh("build_base_mesh: edge " + std::to_string(directed[i] >> 32) + "-" +
                          std::to_string(directed[i] & 0xffffffffu) +
                          " is not manifold or not consistently oriented; split the mesh into manifold components");

  // Vertex manifoldness: the link of v (edge a->b for every face (v, a, b))
  // is then a union of paths and cycles; v is manifold when it is one of them.
  for (size_t v = 0; v < n; ++v) faces_at[v + 1] += faces_at[v];
  std::vector<std::pair<int32_t, int32_t>> link(faces_at[n]);
  {
    std::vector<int32_t> fill(faces_at.begin(), faces_at.end() - 1);
    for (const auto& t : mesh.triangles)
      for (int c = 0; c < 3; ++c) link[fill[t[c]]++] = {t[(c + 1) % 3], t[(c + 2) % 3]};
  }
  for (size_t v = 0; v < n; ++v) {
    auto first = link.begin() + faces_at[v], last = link.begin() + faces_at[v + 1];
    std::sort(first, last);
    const size_t count = static_cast<size_t>(last - first);
    auto successor = [&](int32_t a) -> int32_t {
      auto it = std::lower_bound(first, last, std::make_pair(a, std::numeric_limits<int32_t>::min()));
      return it != last && it->first == a ? it->second : -1;
    };
    // Start a walk at a path's first vertex (one that is no edge's end) if
    // there is one, else anywhere on the cycle.
    int32_t start = first->first;
    {
      std::vector<int32_t> ends;
      for (auto it = first; it != last; ++it) ends.push_back(it->second);
      std::sort(ends.begin(), ends.end());
      for (auto it = first; it != last; ++it)
        if (!std::binary_search(ends.begin(), ends.end(), it->first)) {
          start = it->first;
          break;
        }
    }
    size_t steps = 0;
    for (int32_t a = successor(start); a >= 0 && steps < count; a = successor(a)) {
      ++steps;
      if (a == start) break;
    }
    if (steps != count)
      return invalid_mesh("build_base_mesh: vertex " + str(v) +
                          " is not manifold (its faces form more than one fan); split the mesh into manifold "
                          "components");
  }

  // One edge-connected component (with manifold vertices, vertex-connected is
  // the same).
  UnionFind sets(n);
  size_t components = n;
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 2; ++c)
      if (sets.unite(t[c], t[c + 1])) --components;
  if (components != 1)
    return invalid_mesh("build_base_mesh: the mesh has " + str(components) +
                        " connected components; build one base mesh per component");
  return ok_status();
}

// Breadth-first hops from each site inside its own cell. Without cell_of the
// cells are grown here, by a breadth-first search from all sites at once.
// Vertices their cell's search never reaches keep depth -1 (only a
// disconnected cell has them) and are left to the second phase.
void cell_depths(const Adjacency& adj, const std::vector<int32_t>& sites, std::vector<int32_t>& cell,
                 std::vector<int32_t>& depth) {
  const size_t n = adj.offsets.size() - 1;
  depth.assign(n, -1);
  const bool grow = cell.empty();
  if (grow) cell.assign(n, -1);
  std::vector<int32_t> queue;
  queue.reserve(n);
  for (size_t k = 0; k < sites.size(); ++k) {
    depth[sites[k]] = 0;
    cell[sites[k]] = static_cast<int32_t>(k);
    queue.push_back(sites[k]);
  }
  for (size_t head = 0; head < queue.size(); ++head) {
    const int32_t u = queue[head];
    for (int32_t i = adj.offsets[u]; i < adj.offsets[u + 1]; ++i) {
      const int32_t w = adj.items[i];
      if (depth[w] >= 0) continue;
      if (grow) {
        cell[w] = cell[u];
      } else if (cell[w] != cell[u]) {
        continue;
      }
      depth[w] = depth[u] + 1;
      queue.push_back(w);
    }
  }
}

using Point2 = Eigen::Vector2d;

double cross2(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

class Collapser {
 public:
  Collapser(const TriangleMesh& mesh, const std::vector<int32_t>& sites, const BaseMeshCreases& creases,
            BaseMeshReport& report)
      : positions_(mesh.positions), report_(report) {
    const size_t n = mesh.positions.size();
    om_.request_vertex_status();
    om_.request_edge_status();
    om_.request_halfedge_status();
    om_.request_face_status();
    om_.reserve(n, n + mesh.triangles.size(), mesh.triangles.size());
    for (const auto& p : mesh.positions) om_.add_vertex(OmMesh::Point(p.x(), p.y(), p.z()));
    corners_ = mesh.triangles;
    head_.assign(mesh.triangles.size(), -1);
    next_.assign(n, -1);
    bary_.assign(n, Eigen::Vector3d::Zero());
    is_site_.assign(n, 0);
    for (int32_t s : sites) is_site_[s] = 1;
    removed_.assign(n, 0);
    changed_.assign(n, 1);
    ring_slot_.assign(n, -1);
    in_ring_.assign(n, 0);
    fixed_.assign(n, 0);
    for (int32_t v : creases.fixed) fixed_[v] = 1;
    crease_degree_.assign(n, 0);
    for (const auto& [a, b] : creases.edges) {
      if (!creases_.insert(edge_key(a, b)).second) continue;
      ++crease_degree_[a];
      ++crease_degree_[b];
    }
  }

  Status build(const TriangleMesh& mesh) {
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      const auto& t = mesh.triangles[f];
      const FaceHandle fh = om_.add_face(VertexHandle(t[0]), VertexHandle(t[1]), VertexHandle(t[2]));
      if (!fh.is_valid() || fh.idx() != static_cast<int>(f))
        return invalid_mesh("build_base_mesh: triangle " + str(f) + " does not fit the surface of the ones before");
    }
    return ok_status();
  }

  // Whether v's 1-ring changed since v was last tried. The legality of
  // collapsing v depends only on its 1-ring and on its common neighbours
  // with the target, which change only when a neighbour of v is removed (or
  // v is the kept end of a collapse); a refused v is tried again only then.
  bool changed(int32_t v) const { return changed_[v] != 0; }
  void mark_changed(int32_t v) { changed_[v] = 1; }

  // The rules for choosing w among v's current neighbours.
  enum class Rule {
    kTowardsSite,  // a same-cell neighbour fewer hops from the site
    kSameCell,     // any same-cell neighbour (used for boundary vertices)
    kAny,          // any neighbour, same cell preferred
  };

  bool on_boundary(int32_t v) const { return om_.is_boundary(VertexHandle(v)); }
  // On the boundary or a crease: such vertices shrink to one per run of a
  // cell (phase 2 of build_base_mesh).
  bool on_sharp_curve(int32_t v) const { return on_boundary(v) || crease_degree_[v] > 0; }

  // Tries to remove v by collapsing it into one of its neighbours allowed by
  // `rule`, in order of preference. True when it was removed.
  bool try_remove(int32_t v, Rule rule, const std::vector<int32_t>& cell, const std::vector<int32_t>& depth) {
    changed_[v] = 0;
    if (fixed_[v]) return false;
    gather_ring(v);
    const int32_t k = static_cast<int32_t>(ring_.size());
    candidates_.clear();
    for (int32_t i = 0; i < k; ++i) {
      const int32_t r = ring_[i];
      int32_t key = 0;
      if (rule == Rule::kTowardsSite) {
        if (cell[r] != cell[v] || depth[r] < 0 || depth[r] >= depth[v]) continue;
        key = depth[r];
      } else if (rule == Rule::kSameCell) {
        if (cell[r] != cell[v]) continue;
        key = depth[r] < 0 ? std::numeric_limits<int32_t>::max() : depth[r];
      } else {
        key = cell[r] == cell[v] ? 0 : 1;
      }
      candidates_.push_back({key, (positions_[r] - positions_[v]).squaredNorm(), r, i});
    }
    std::sort(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
      if (a.key != b.key) return a.key < b.key;
      if (a.length2 != b.length2) return a.length2 < b.length2;
      return a.vertex < b.vertex;
    });
    for (const Candidate& c : candidates_) {
      if (try_collapse(v, c.slot)) return true;
    }
    return false;
  }

  // Writes the base mesh and the parameterization once no more collapses
  // are wanted. Base vertex b < sites.size() is site b; the kept non-site
  // vertices follow in input order.
  Status finish(const std::vector<int32_t>& sites, BaseMesh& out) {
    const size_t n = positions_.size();
    std::vector<int32_t> base_index(n, -1);
    for (int32_t s : sites) {
      base_index[s] = static_cast<int32_t>(out.input_vertex.size());
      out.input_vertex.push_back(s);
    }
    for (size_t v = 0; v < n; ++v)
      if (!removed_[v] && !is_site_[v]) {
        base_index[v] = static_cast<int32_t>(out.input_vertex.size());
        out.input_vertex.push_back(static_cast<int32_t>(v));
        ++report_.promoted_vertices;
      }
    for (int32_t v : out.input_vertex) out.mesh.positions.push_back(positions_[v]);

    out.param.assign(n, ParamPoint{});
    for (size_t f = 0; f < corners_.size(); ++f) {
      if (om_.status(FaceHandle(static_cast<int>(f))).deleted()) continue;
      const int32_t face = static_cast<int32_t>(out.mesh.triangles.size());
      std::array<int32_t, 3> t{};
      for (int c = 0; c < 3; ++c) {
        t[c] = base_index[corners_[f][c]];
        if (t[c] < 0) return internal_error("build_base_mesh: a base triangle uses a removed vertex");
      }
      out.mesh.triangles.push_back(t);
      for (int32_t p = head_[f]; p >= 0; p = next_[p]) out.param[p] = ParamPoint{face, bary_[p]};
      for (int c = 0; c < 3; ++c) {
        ParamPoint& corner = out.param[corners_[f][c]];
        if (corner.face < 0) {
          corner.face = face;
          corner.bary = Eigen::Vector3d::Zero();
          corner.bary[c] = 1.0;
        }
      }
    }
    for (size_t v = 0; v < n; ++v)
      if (out.param[v].face < 0) return internal_error("build_base_mesh: vertex " + str(v) + " lost its place");
    for (uint64_t key : creases_) {
      const int32_t a = base_index[key >> 32], b = base_index[key & 0xffffffffu];
      if (a < 0 || b < 0) return internal_error("build_base_mesh: a crease edge lost a vertex");
      out.crease_edges.push_back({std::min(a, b), std::max(a, b)});
    }
    std::sort(out.crease_edges.begin(), out.crease_edges.end());
    for (size_t v = 0; v < n; ++v)
      if (!removed_[v] && !is_site_[v] && (crease_degree_[v] > 0 || fixed_[v])) ++report_.crease_vertices_kept;
    return ok_status();
  }

 private:
  struct Candidate {
    int32_t key;
    double length2;
    int32_t vertex;
    int32_t slot;  // index in ring_
  };

  // v's neighbours r_0 .. r_{k-1} counter-clockwise (in the faces'
  // orientation), the outgoing half-edges v -> r_i, and the faces
  // (v, r_i, r_{i+1}): k of them inside, k - 1 on the boundary, where r_0 and
  // r_{k-1} are v's boundary neighbours.
  void gather_ring(int32_t v) {
    ring_.clear();
    out_.clear();
    faces_.clear();
    const VertexHandle vh(v);
    const HalfedgeHandle start = om_.halfedge_handle(vh);
    boundary_ = om_.is_boundary(start);  // OpenMesh keeps a boundary vertex's outgoing half-edge on the boundary
    if (boundary_) {
      // From the half-edge after the incoming boundary one round to the
      // outgoing boundary half-edge, which has no face.
      HalfedgeHandle h = om_.opposite_halfedge_handle(om_.prev_halfedge_handle(start));
      for (;;) {
        out_.push_back(h);
        ring_.push_back(om_.to_vertex_handle(h).idx());
        if (h == start) break;
        faces_.push_back(om_.face_handle(h).idx());
        h = om_.opposite_halfedge_handle(om_.prev_halfedge_handle(h));
      }
    } else {
      HalfedgeHandle h = start;
      do {
        out_.push_back(h);
        ring_.push_back(om_.to_vertex_handle(h).idx());
        faces_.push_back(om_.face_handle(h).idx());
        h = om_.opposite_halfedge_handle(om_.prev_halfedge_handle(h));
      } while (h != start);
    }
  }

  // Everything the rules ask of collapsing v into w = ring_[m]; does it when
  // allowed and moves the points of v's faces onto the new fan.
  bool try_collapse(int32_t v, int32_t m) {
    const int32_t k = static_cast<int32_t>(ring_.size());
    const int32_t nf = static_cast<int32_t>(faces_.size());
    const int32_t w = ring_[m];
    const HalfedgeHandle h = out_[m];

    // Boundary vertices move only along the boundary, and a boundary loop of
    // three edges would close up.
    if (boundary_) {
      if (m != 0 && m != k - 1) {
        ++report_.refused_link;
        return false;
      }
      const HalfedgeHandle b = out_[k - 1];  // v's outgoing boundary half-edge
      if (om_.next_halfedge_handle(om_.next_halfedge_handle(om_.next_halfedge_handle(b))) == b) {
        ++report_.refused_link;
        return false;
      }
    }
    // Crease vertices move only along their crease, and a crease loop of
    // three edges would close up. onward: the crease edge (v, onward) becomes (w, onward).
    int32_t onward = -1;
    if (crease_degree_[v] > 0) {
      for (int32_t r : ring_)
        if (r != w && creases_.count(edge_key(v, r))) onward = r;
      if (!creases_.count(edge_key(v, w)) || onward < 0 || creases_.count(edge_key(onward, w))) {
        ++report_.refused_link;
        return false;
      }
    }
    // The faces that stay: (v, r_i, r_{i+1}) becomes (w, r_i, r_{i+1}) unless
    // it has w.
    keep_.clear();
    for (int32_t i = 0; i < nf; ++i) {
      const int32_t j = (i + 1) % k;
      if (i != m && j != m) keep_.push_back(i);
    }
    // No fold in 3D, no face of zero area: tested before the link condition,
    // which costs more and passes most of the collapses this refuses.
    const Eigen::Vector3d& pv = positions_[v];
    const Eigen::Vector3d& pw = positions_[w];
    for (int32_t i : keep_) {
      const Eigen::Vector3d& a = positions_[ring_[i]];
      const Eigen::Vector3d& b = positions_[ring_[(i + 1) % k]];
      const Eigen::Vector3d before = (a - pv).cross(b - pv);
      const Eigen::Vector3d after = (a - pw).cross(b - pw);
      const double longest2 = std::max({(a - pw).squaredNorm(), (b - pw).squaredNorm(), (a - b).squaredNorm()});
      if (!(after.dot(before) > 0.0) || !(after.squaredNorm() > 1e-24 * longest2 * longest2)) {
        ++report_.refused_fold;
        return false;
      }
    }
    // The link condition.
    if (!link_condition(m)) {
      ++report_.refused_link;
      return false;
    }
    // A closed tetrahedron passes the link condition, but its collapse would
    // leave two triangles on the same three vertices.
    if (!boundary_ && k == 3) {
      const int32_t i = (m + 1) % k;  // the face (v, r_i, r_{i+1}) that stays
      const HalfedgeHandle across_edge = om_.opposite_halfedge_handle(om_.next_halfedge_handle(out_[i]));
      if (!om_.is_boundary(across_edge) &&
          om_.to_vertex_handle(om_.next_halfedge_handle(across_edge)).idx() == w) {
        ++report_.refused_link;
        return false;
      }
    }

    const bool ear = nf == 1;  // a boundary vertex with one face: the ear is cut off
    FaceHandle across;
    if (ear) {
      across = om_.face_handle(om_.opposite_halfedge_handle(om_.next_halfedge_handle(out_[0])));
      if (!across.is_valid()) {
        ++report_.refused_link;
        return false;
      }
    }

    // MAPS's conformal flattening of the 1-ring, v at the origin.
    if (!flatten(v)) {
      ++report_.refused_param;
      return false;
    }
    const Point2 fw = flat_[m];
    if (!ear) {
      for (int32_t i : keep_) {
        const Point2 a = flat_[i] - fw, b = flat_[(i + 1) % k] - fw;
        if (!(cross2(a, b) > 1e-10 * a.norm() * b.norm())) {
          ++report_.refused_param;
          return false;
        }
      }
    }

    // Allowed. Take the points out of v's faces, in the flattened plane.
    for (int32_t i = 0; i < k; ++i) ring_slot_[ring_[i]] = i;
    moving_.clear();
    moving_at_.clear();
    auto flat_of = [&](int32_t u) -> Point2 { return u == v ? Point2::Zero() : flat_[ring_slot_[u]]; };
    for (int32_t f : faces_) {
      const auto& c = corners_[f];
      const Point2 q0 = flat_of(c[0]), q1 = flat_of(c[1]), q2 = flat_of(c[2]);
      for (int32_t p = head_[f]; p >= 0; p = next_[p]) {
        moving_.push_back(p);
        moving_at_.push_back(bary_[p][0] * q0 + bary_[p][1] * q1 + bary_[p][2] * q2);
      }
      head_[f] = -1;
    }
    moving_.push_back(v);
    moving_at_.push_back(Point2::Zero());
    for (int32_t i = 0; i < k; ++i) ring_slot_[ring_[i]] = -1;

    om_.collapse(h);
    removed_[v] = 1;
    if (onward >= 0) {
      creases_.erase(edge_key(v, w));
      creases_.erase(edge_key(v, onward));
      creases_.insert(edge_key(w, onward));
    }
    for (int32_t r : ring_) changed_[r] = 1;
    ++report_.collapses;
    for (int32_t i : keep_) corners_[faces_[i]] = {w, ring_[i], ring_[(i + 1) % k]};

    if (ear) {
      place_on_edge(across.idx(), ring_[0], ring_[1]);
    } else {
      for (size_t j = 0; j < moving_.size(); ++j) place_in_fan(moving_[j], moving_at_[j], fw);
    }
    return true;
  }

  // The link condition for collapsing v into w = ring_[m] (Dey, Edelsbrunner
  // et al., "Topology preserving edge contraction", 1999): v and w share no
  // neighbour but the apexes of the edge's faces, which must differ and not
  // be ears held by two boundary edges; an inner edge may not join two
  // boundary vertices. The same answers as OpenMesh's is_collapse_ok, from
  // the 1-ring of v already gathered instead of three walks around v and w.
  bool link_condition(int32_t m) {
    const HalfedgeHandle h = out_[m];
    const HalfedgeHandle o = om_.opposite_halfedge_handle(h);
    // The apex of the face on each side of the edge (-1 on the boundary),
    // refused when that face's two other edges are both on the boundary.
    auto apex = [&](HalfedgeHandle e, int32_t& vertex) {
      vertex = -1;
      if (om_.is_boundary(e)) return true;
      const HalfedgeHandle e1 = om_.next_halfedge_handle(e), e2 = om_.next_halfedge_handle(e1);
      vertex = om_.to_vertex_handle(e1).idx();
      return !(om_.is_boundary(om_.opposite_halfedge_handle(e1)) && om_.is_boundary(om_.opposite_halfedge_handle(e2)));
    };
    int32_t left = -1, right = -1;
    if (!apex(h, left) || !apex(o, right) || left == right) return false;
    const int32_t w = ring_[m];
    for (int32_t r : ring_) in_ring_[r] = 1;
    bool shared = false;
    for (const VertexHandle u : om_.vv_range(VertexHandle(w))) {
      const int32_t x = u.idx();
      if (in_ring_[x] && x != left && x != right) {
        shared = true;
        break;
      }
    }
    for (int32_t r : ring_) in_ring_[r] = 0;
    if (shared) return false;
    return !(boundary_ && om_.is_boundary(VertexHandle(w)) && !om_.is_boundary(h) && !om_.is_boundary(o));
  }

  // flat_[i] = r_i under z -> z^a, a = 2π / (angle sum) inside and π / (angle
  // sum) on the boundary; lengths are divided by their mean first so the
  // power neither overflows nor underflows. On a crease each side's angles
  // are scaled to π instead (MAPS, §3.4, as for its feature lines), so v's
  // two crease neighbours lie on a line through it. False when the map is
  // not a valid flattening (a degenerate angle, or one that would open past π).
  bool flatten(int32_t v) {
    const int32_t k = static_cast<int32_t>(ring_.size());
    const int32_t nf = static_cast<int32_t>(faces_.size());
    const Eigen::Vector3d& pv = positions_[v];
    angle_.resize(nf);
    length_.resize(k);
    double total = 0.0, mean = 0.0;
    for (int32_t i = 0; i < k; ++i) {
      length_[i] = (positions_[ring_[i]] - pv).norm();
      mean += length_[i];
    }
    mean /= k;
    for (int32_t i = 0; i < nf; ++i) {
      const Eigen::Vector3d a = positions_[ring_[i]] - pv, b = positions_[ring_[(i + 1) % k]] - pv;
      angle_[i] = std::atan2(a.cross(b).norm(), a.dot(b));
      if (!(angle_[i] > 1e-12)) return false;
      total += angle_[i];
    }
    if (!(mean > 0.0)) return false;
    const double a = (boundary_ ? kPi : 2.0 * kPi) / total;
    scale_.assign(nf, a);
    if (crease_degree_[v] > 0 && !boundary_ && !crease_sides(v)) return false;
    flat_.resize(k);
    double phi = 0.0;
    for (int32_t i = 0; i < k; ++i) {
      const double rho = std::pow(length_[i] / mean, a);
      if (!std::isfinite(rho) || !(rho > 0.0)) return false;
      flat_[i] = Point2(rho * std::cos(phi), rho * std::sin(phi));
      if (i < nf) {
        // An old face opening to π or more would not be a triangle in the
        // plane (possible only for a very sharp interior vertex).
        if (nf > 1 && !(scale_[i] * angle_[i] < kPi * (1.0 - 1e-9))) return false;
        phi += scale_[i] * angle_[i];
      }
    }
    return true;
  }

  // scale_ for interior crease vertex v: the faces from one crease
  // neighbour round to the other open to π, and so do the rest. False when
  // the ring does not hold v's two crease edges.
  bool crease_sides(int32_t v) {
    const int32_t k = static_cast<int32_t>(ring_.size());
    int32_t first = -1, second = -1;
    for (int32_t i = 0; i < k; ++i)
      if (creases_.count(edge_key(v, ring_[i]))) (first < 0 ? first : second) = i;
    if (first < 0 || second < 0) return false;
    double side = 0.0, total = 0.0;
    for (int32_t i = 0; i < k; ++i) {
      total += angle_[i];
      if (i >= first && i < second) side += angle_[i];
    }
    if (!(side > 0.0) || !(total - side > 0.0)) return false;
    for (int32_t i = 0; i < k; ++i) scale_[i] = kPi / (i >= first && i < second ? side : total - side);
    return true;
  }

  // Puts point p (at q in the plane) into the fan triangle (w, r_i, r_{i+1})
  // that holds it; rounding can leave q just outside every one, and then the
  // nearest (largest smallest barycentric) is taken, clamped onto it.
  void place_in_fan(int32_t p, const Point2& q, const Point2& fw) {
    const int32_t k = static_cast<int32_t>(ring_.size());
    double best_min = -std::numeric_limits<double>::infinity();
    int32_t best = -1;
    Eigen::Vector3d best_bary = Eigen::Vector3d::Zero();
    for (int32_t i : keep_) {
      const Point2& a = flat_[i];
      const Point2& b = flat_[(i + 1) % k];
      const double area = cross2(a - fw, b - fw);
      const double l1 = cross2(b - a, q - a) / area;  // weight of w
      const double l2 = cross2(fw - b, q - b) / area;  // weight of a
      const double l3 = 1.0 - l1 - l2;                 // weight of b
      const double lo = std::min({l1, l2, l3});
      if (lo > best_min) {
        best_min = lo;
        best = i;
        best_bary = Eigen::Vector3d(l1, l2, l3);
        if (lo >= 0.0) break;
      }
    }
    if (best_min < 0.0) {
      if (best_min < -1e-6) ++report_.clamped_points;
      best_bary = best_bary.cwiseMax(0.0);
      best_bary /= best_bary.sum();
    }
    insert(p, faces_[best], best_bary);
  }

  // The ear (v, r_0, r_1) is cut off: its points go onto the edge r_0 r_1 of
  // the face across it, where the flattening (v on the straight segment
  // between r_0 and r_1) puts them.
  void place_on_edge(int32_t face, int32_t r0, int32_t r1) {
    const double x0 = flat_[0].x(), x1 = flat_[1].x();  // x0 > 0 > x1
    const auto& c = corners_[face];
    for (size_t j = 0; j < moving_.size(); ++j) {
      const double t = std::clamp((x0 - moving_at_[j].x()) / (x0 - x1), 0.0, 1.0);  // 0 at r_0, 1 at r_1
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        if (c[i] == r0) b[i] = 1.0 - t;
        if (c[i] == r1) b[i] = t;
      }
      insert(moving_[j], face, b);
    }
  }

  void insert(int32_t p, int32_t face, const Eigen::Vector3d& b) {
    bary_[p] = b;
    next_[p] = head_[face];
    head_[face] = p;
  }

  OmMesh om_;
  const std::vector<Eigen::Vector3d>& positions_;
  BaseMeshReport& report_;
  std::vector<std::array<int32_t, 3>> corners_;  // per face, in orientation; bary_ is in this order
  std::vector<int32_t> head_;                    // per face: first point stored in it, or -1
  std::vector<int32_t> next_;                    // per input vertex: next point of the same face
  std::vector<Eigen::Vector3d> bary_;            // per removed input vertex
  std::vector<char> is_site_, removed_, changed_;
  std::vector<int32_t> ring_slot_;  // scratch: index in ring_ of a vertex, else -1
  std::vector<char> in_ring_;       // scratch: 1 for the vertices of ring_ during link_condition
  std::vector<char> fixed_;                // per input vertex: never removed (BaseMeshCreases::fixed)
  std::vector<uint8_t> crease_degree_;     // per input vertex: its crease edges (0 or 2 unless fixed)
  std::unordered_set<uint64_t> creases_;   // the current crease edges, edge_key

  // Scratch for the vertex being removed.
  bool boundary_ = false;
  std::vector<int32_t> ring_, faces_, keep_;
  std::vector<HalfedgeHandle> out_;
  std::vector<Candidate> candidates_;
  std::vector<double> angle_, length_, scale_;
  std::vector<Point2> flat_;
  std::vector<int32_t> moving_;
  std::vector<Point2> moving_at_;
};

}  // namespace

StatusOr<BaseMesh> build_base_mesh(const TriangleMesh& mesh, const std::vector<int32_t>& sites,
                                   const std::vector<int32_t>& cell_of, BaseMeshReport* report,
                                   const BaseMeshCreases& creases) {
  const auto started = std::chrono::steady_clock::now();
  SRCODEC_RETURN_IF_ERROR(check_mesh(mesh));
  const size_t n = mesh.positions.size();
  SRCODEC_RETURN_IF_ERROR(check_arguments(n, sites, cell_of));

  BaseMeshReport local;
  BaseMeshReport& rep = report ? *report : local;
  rep = BaseMeshReport{};

  const Adjacency neighbours = vertex_neighbors(mesh.positions.size(), mesh.triangles);
  SRCODEC_RETURN_IF_ERROR(check_creases(neighbours, creases));
  std::vector<int32_t> cell = cell_of, depth;
  cell_depths(neighbours, sites, cell, depth);

  Collapser collapser(mesh, sites, creases, rep);
  SRCODEC_RETURN_IF_ERROR(collapser.build(mesh));

  // Phase 1, towards the sites: deepest first, by depth buckets. A refused
  // vertex is tried again as long as collapses around it keep happening,
  // first within its bucket, then with every shallower bucket.
  int32_t max_depth = 0;
  for (int32_t d : depth) max_depth = std::max(max_depth, d);
  std::vector<std::vector<int32_t>> bucket(static_cast<size_t>(max_depth) + 1);
  std::vector<int32_t> unreached;
  std::vector<char> site_flag(n, 0);
  for (int32_t s : sites) site_flag[s] = 1;
  for (size_t v = 0; v < n; ++v) {
    if (site_flag[v]) continue;
    if (depth[v] > 0) {
      bucket[depth[v]].push_back(static_cast<int32_t>(v));
    } else {
      unreached.push_back(static_cast<int32_t>(v));
    }
  }
  auto passes = [&](std::vector<int32_t> list, Collapser::Rule rule) {
    for (bool progress = true; progress && !list.empty();) {
      progress = false;
      std::vector<int32_t> refused;
      for (int32_t v : list) {
        if (!collapser.changed(v)) {
          refused.push_back(v);
        } else if (collapser.try_remove(v, rule, cell, depth)) {
          progress = true;
        } else {
          refused.push_back(v);
        }
      }
      list = std::move(refused);
    }
    return list;
  };
  std::vector<int32_t> pending;
  for (int32_t d = max_depth; d >= 1; --d) {
    pending.insert(pending.end(), bucket[d].begin(), bucket[d].end());
    pending = passes(std::move(pending), Collapser::Rule::kTowardsSite);
  }
  rep.collapses_towards_site = rep.collapses;

  // Phase 2: interior vertices still left go into any neighbour that takes
  // them. Boundary vertices only into a neighbour of their own cell: every
  // boundary run of a cell then shrinks to one vertex (its site, when the
  // site is on it) and that one is kept, so the base boundary passes through
  // every cell that reaches the boundary instead of being spanned by long
  // edges between a few survivors. Crease vertices likewise.
  pending.insert(pending.end(), unreached.begin(), unreached.end());
  std::vector<int32_t> interior, boundary;
  for (int32_t v : pending) {
    collapser.mark_changed(v);  // the new rule may allow what the old one refused
    (collapser.on_sharp_curve(v) ? boundary : interior).push_back(v);
  }
  for (size_t before = SIZE_MAX; before != boundary.size() + interior.size();) {
    before = boundary.size() + interior.size();
    boundary = passes(std::move(boundary), Collapser::Rule::kSameCell);
    interior = passes(std::move(interior), Collapser::Rule::kAny);
  }
  rep.boundary_vertices_kept = static_cast<size_t>(
      std::count_if(boundary.begin(), boundary.end(), [&](int32_t v) { return collapser.on_boundary(v); }));

  BaseMesh out;
  SRCODEC_RETURN_IF_ERROR(collapser.finish(sites, out));
  out.input_creases = creases;
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

}  // namespace srcodec
