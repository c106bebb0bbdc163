// Splits a triangle mesh into manifold, consistently oriented components.
// Based on the cut-and-stitch scheme of Gueziec, Taubin, Lazarus and Horn,
// "Cutting and Stitching: Converting Sets of Polygons to Manifold Surfaces"
// (IEEE TVCG 7(2), 2001): cut every edge that has more than two faces, give
// each fan of faces around a vertex its own vertex copy, stitch back the cuts
// that keep the vertices manifold, then orient by breadth-first propagation
// and cut where the orientations clash.
#include "remesh/components.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "format/union_find.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

// Corner c = 3 f + k is corner k of face f. Half-edge h runs from corner h to
// the next corner of the same face.
int32_t next_corner(int32_t c) { return c - c % 3 + (c + 1) % 3; }
int32_t prev_corner(int32_t c) { return c - c % 3 + (c + 2) % 3; }
int32_t vertex_at(const Triangles& t, int32_t c) { return t[c / 3][c % 3]; }

// The corner of half-edge h's face that sits at vertex v (one of h's ends).
int32_t corner_at(const Triangles& t, int32_t h, int32_t v) { return vertex_at(t, h) == v ? h : next_corner(h); }

// Half-edges grouped by undirected edge: group g holds
// half_edges[begin[g]] .. half_edges[begin[g + 1] - 1].
struct EdgeGroups {
  std::vector<int32_t> half_edges;
  std::vector<int32_t> begin;
  std::vector<int32_t> group_of;  // per half-edge

  size_t count() const { return begin.size() - 1; }
  int32_t size(size_t g) const { return begin[g + 1] - begin[g]; }
  const int32_t* members(size_t g) const { return half_edges.data() + begin[g]; }
};

EdgeGroups group_edges(const Triangles& t) {
  std::vector<std::pair<uint64_t, int32_t>> keyed(3 * t.size());
  for (int32_t h = 0; h < static_cast<int32_t>(keyed.size()); ++h) {
    int32_t a = vertex_at(t, h), b = vertex_at(t, next_corner(h));
    if (a > b) std::swap(a, b);
    keyed[h] = {(static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b), h};
  }
  std::sort(keyed.begin(), keyed.end());
  EdgeGroups e;
  e.half_edges.resize(keyed.size());
  e.group_of.resize(keyed.size());
  e.begin.clear();
  for (size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) e.begin.push_back(static_cast<int32_t>(i));
    e.half_edges[i] = keyed[i].second;
    e.group_of[keyed[i].second] = static_cast<int32_t>(e.begin.size() - 1);
  }
  e.begin.push_back(static_cast<int32_t>(keyed.size()));
  return e;
}

// Relabels `labels` (each in [0, bound)) 0, 1, 2, ... in order of first
// occurrence, so results do not depend on union-find internals. Returns the
// number of distinct labels.
int32_t renumber(std::vector<int32_t>& labels, size_t bound) {
  std::vector<int32_t> id(bound, -1);
  int32_t n = 0;
  for (int32_t& l : labels) {
    if (id[l] < 0) id[l] = n++;
    l = id[l];
  }
  return n;
}

// One vertex per fan: corners at the same vertex that are joined across a
// glued edge (one with exactly two faces) share a vertex. Returns the vertex
// of every corner.
std::vector<int32_t> split_fans(const Triangles& t, const EdgeGroups& e, const std::vector<char>& glued,
                                int32_t* num_vertices) {
  UnionFind fans(3 * t.size());
  for (size_t g = 0; g < e.count(); ++g) {
    if (!glued[g]) continue;
    const int32_t h1 = e.members(g)[0], h2 = e.members(g)[1];
    const int32_t a = vertex_at(t, h1), b = vertex_at(t, next_corner(h1));
    fans.unite(corner_at(t, h1, a), corner_at(t, h2, a));
    fans.unite(corner_at(t, h1, b), corner_at(t, h2, b));
  }
  std::vector<int32_t> corner_vertex(3 * t.size());
  for (size_t c = 0; c < corner_vertex.size(); ++c) corner_vertex[c] = static_cast<int32_t>(fans.find(c));
  *num_vertices = renumber(corner_vertex, corner_vertex.size());
  return corner_vertex;
}

Triangles triangles_of(const std::vector<int32_t>& corner_vertex) {
  Triangles t(corner_vertex.size() / 3);
  for (size_t f = 0; f < t.size(); ++f)
    t[f] = {corner_vertex[3 * f], corner_vertex[3 * f + 1], corner_vertex[3 * f + 2]};
  return t;
}

// Joins again, two at a time, faces that cutting a non-manifold edge left
// alone on their copy of that edge. A join merges the two faces' copies of
// the edge's ends; it is kept only if every vertex around the joint still
// has a single fan with at most two faces per edge.
class Stitcher {
 public:
  Stitcher(const Triangles& t, std::vector<int32_t>* corner_vertex, int32_t num_vertices)
      : t_(t), corner_vertex_(*corner_vertex), copies_(num_vertices), faces_at_(num_vertices) {
    for (size_t c = 0; c < corner_vertex_.size(); ++c)
      faces_at_[corner_vertex_[c]].push_back(static_cast<int32_t>(c / 3));
  }

  void stitch_edge(const EdgeGroups& e, size_t g) {
    const int32_t* hs = e.members(g);
    const int32_t n = e.size(g);
    const int32_t u = vertex_at(t_, hs[0]), v = vertex_at(t_, next_corner(hs[0]));
    std::vector<int32_t> lone;
    for (int32_t i = 0; i < n; ++i) {
      int32_t sharing = 0;
      for (int32_t j = 0; j < n; ++j) sharing += ends(hs[i], u, v) == ends(hs[j], u, v);
      if (sharing == 1) lone.push_back(hs[i]);
    }
    std::vector<char> used(lone.size(), 0);
    for (const bool want_consistent : {true, false}) {
      for (size_t i = 0; i < lone.size(); ++i) {
        for (size_t j = i + 1; j < lone.size() && !used[i]; ++j) {
          const bool consistent = vertex_at(t_, lone[i]) != vertex_at(t_, lone[j]);
          if (used[j] || consistent != want_consistent) continue;
          if (try_join(lone[i], lone[j], u, v)) used[i] = used[j] = 1;
        }
      }
    }
  }

  // Writes the merged copies back into the corner vertices.
  int32_t finish() {
    for (int32_t& cv : corner_vertex_) cv = static_cast<int32_t>(copies_.find(cv));
    return renumber(corner_vertex_, faces_at_.size());
  }

 private:
  std::pair<int32_t, int32_t> ends(int32_t h, int32_t u, int32_t v) {
    return {find(corner_vertex_[corner_at(t_, h, u)]), find(corner_vertex_[corner_at(t_, h, v)])};
  }
  int32_t find(int32_t x) { return static_cast<int32_t>(copies_.find(x)); }
  // The copy of x as it would be after the tentative merge.
  int32_t rep(int32_t x) {
    x = find(x);
    for (const auto& [from, to] : merge_) x = x == from ? to : x;
    return x;
  }

  bool try_join(int32_t h1, int32_t h2, int32_t u, int32_t v) {
    const auto [a1, b1] = ends(h1, u, v);
    const auto [a2, b2] = ends(h2, u, v);
    if (a1 == a2 && b1 == b2) return true;  // an earlier join already put them on one edge
    merge_ = {{a2, a1}, {b2, b1}};
    std::vector<int32_t> check;
    for (const int32_t x : {a1, a2, b1, b2}) {
      for (const int32_t f : faces_at_[x])
        for (int32_t k = 0; k < 3; ++k) check.push_back(rep(corner_vertex_[3 * f + k]));
    }
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
    bool ok = true;
    for (size_t i = 0; i < check.size() && ok; ++i) ok = manifold_at(check[i]);
    merge_.clear();
    if (!ok) return false;
    merge(a1, a2);
    merge(b1, b2);
    return true;
  }

  void merge(int32_t x, int32_t y) {
    if (x == y) return;
    copies_.unite(x, y);
    const int32_t root = find(x), other = root == x ? y : x;
    faces_at_[root].insert(faces_at_[root].end(), faces_at_[other].begin(), faces_at_[other].end());
    faces_at_[other].clear();
  }

  // True when the faces at x (under the tentative merge) form one fan whose
  // edges have at most two faces each: the link is one path or cycle.
  bool manifold_at(int32_t x) {
    std::vector<int32_t> faces = faces_at_[x];
    for (const auto& [from, to] : merge_)
      if (to == x && from != x) faces.insert(faces.end(), faces_at_[from].begin(), faces_at_[from].end());
    std::map<int32_t, std::vector<int32_t>> link;
    for (const int32_t f : faces) {
      int32_t k = 0;
      while (k < 3 && rep(corner_vertex_[3 * f + k]) != x) ++k;
      if (k == 3) return false;  // cannot happen: faces_at_ lists faces with a corner at x
      const int32_t p = rep(corner_vertex_[3 * f + (k + 1) % 3]), q = rep(corner_vertex_[3 * f + (k + 2) % 3]);
      if (p == x || q == x || p == q) return false;  // the merge would collapse this face
      link[p].push_back(q);
      link[q].push_back(p);
    }
    for (const auto& node : link)
      if (node.second.size() > 2) return false;
    std::vector<int32_t> stack{link.begin()->first};
    std::map<int32_t, char> seen{{stack[0], 1}};
    while (!stack.empty()) {
      const int32_t p = stack.back();
      stack.pop_back();
      for (const int32_t q : link[p])
        if (seen.emplace(q, 1).second) stack.push_back(q);
    }
    return seen.size() == link.size();
  }

  const Triangles& t_;
  std::vector<int32_t>& corner_vertex_;
  UnionFind copies_;
  std::vector<std::vector<int32_t>> faces_at_;  // per copy (valid at union-find roots)
  std::vector<std::pair<int32_t, int32_t>> merge_;  // tentative: copy -> copy it joins
};

// Vertex of every corner once the input is edge- and vertex-manifold.
std::vector<int32_t> make_manifold(const Triangles& t, ManifoldReport& r) {
  const EdgeGroups e = group_edges(t);
  std::vector<char> glued(e.count());
  std::vector<size_t> nonmanifold;
  for (size_t g = 0; g < e.count(); ++g) {
    glued[g] = e.size(g) == 2;
    if (e.size(g) > 2) nonmanifold.push_back(g);
  }
  r.nonmanifold_edges_cut = nonmanifold.size();
  int32_t num_vertices = 0;
  std::vector<int32_t> corner_vertex = split_fans(t, e, glued, &num_vertices);
  if (nonmanifold.empty()) return corner_vertex;
  // Faces of a cut edge that still meet around both of its ends now share a
  // copy of the edge (a fan around a vertex ends at most twice on one edge,
  // so never more than two do); the lone ones get stitched.
  Stitcher stitcher(t, &corner_vertex, num_vertices);
  for (const size_t g : nonmanifold) stitcher.stitch_edge(e, g);
  stitcher.finish();
  return corner_vertex;
}

struct Orientation {
  std::vector<char> flip;  // per face: reversed relative to the input
  std::vector<char> cut;   // per edge group: its two faces disagree
  size_t nonorientable = 0;
};

// Breadth-first from the lowest unvisited face: each neighbour is flipped to
// traverse the shared edge opposite to the face it is reached from. An edge
// whose faces are both visited and disagree is marked cut.
Orientation propagate_orientation(const Triangles& t, const EdgeGroups& e) {
  Orientation o;
  o.flip.assign(t.size(), 0);
  o.cut.assign(e.count(), 0);
  std::vector<char> seen(t.size(), 0);
  std::vector<int32_t> queue;
  for (size_t root = 0; root < t.size(); ++root) {
    if (seen[root]) continue;
    seen[root] = 1;
    queue.assign(1, static_cast<int32_t>(root));
    bool clash = false;
    for (size_t i = 0; i < queue.size(); ++i) {
      const int32_t f = queue[i];
      for (int32_t h = 3 * f; h < 3 * f + 3; ++h) {
        const int32_t g = e.group_of[h];
        if (e.size(g) != 2) continue;
        const int32_t other = e.members(g)[0] == h ? e.members(g)[1] : e.members(g)[0];
        const int32_t nf = other / 3;
        const char want = o.flip[f] ^ (vertex_at(t, h) == vertex_at(t, other));
        if (!seen[nf]) {
          seen[nf] = 1;
          o.flip[nf] = want;
          queue.push_back(nf);
        } else if (o.flip[nf] != want) {
          o.cut[g] = 1;
          clash = true;
        }
      }
    }
    o.nonorientable += clash;
  }
  return o;
}

// Vertex of every corner with the cut edges opened. A cut only opens if one
// of its ends gets separate copies on its two sides; where neither does (a
// lone cut in the interior) the cut is extended by one more edge at its
// first end, which splits that vertex's fan between the two faces.
StatusOr<std::vector<int32_t>> open_cuts(const Triangles& t, const EdgeGroups& e, std::vector<char>& cut,
                                         int32_t* num_vertices) {
  for (int round = 0; round < 4; ++round) {
    std::vector<char> glued(e.count());
    for (size_t g = 0; g < e.count(); ++g) glued[g] = e.size(g) == 2 && !cut[g];
    std::vector<int32_t> corner_vertex = split_fans(t, e, glued, num_vertices);
    bool extended = false;
    for (size_t g = 0; g < e.count(); ++g) {
      if (!cut[g] || e.size(g) != 2) continue;
      const int32_t h1 = e.members(g)[0], h2 = e.members(g)[1];
      const int32_t u = vertex_at(t, h1), v = vertex_at(t, next_corner(h1));
      if (corner_vertex[corner_at(t, h1, u)] != corner_vertex[corner_at(t, h2, u)] ||
          corner_vertex[corner_at(t, h1, v)] != corner_vertex[corner_at(t, h2, v)])
        continue;
      // h1's face's other edge at u: an interior edge, or u's fan would
      // have been a path that the cut already split.
      cut[e.group_of[prev_corner(h1)]] = 1;
      extended = true;
    }
    if (!extended) return corner_vertex;
  }
  return internal_error("split_into_manifold_components: orientation cuts did not open");
}

double signed_volume_term(const TriangleMesh& in, int32_t f, bool flipped, const Eigen::Vector3d& origin) {
  const auto& tri = in.triangles[f];
  const Eigen::Vector3d a = in.positions[tri[0]] - origin;
  Eigen::Vector3d b = in.positions[tri[1]] - origin, c = in.positions[tri[2]] - origin;
  if (flipped) std::swap(b, c);
  return a.dot(b.cross(c));
}

// Turns whole components once their faces agree: a closed one to face
// outward (positive signed volume), any other one (or a closed one without
// volume, like a doubled sheet) to the orientation most of its input faces had.
void orient_components(const TriangleMesh& in, const EdgeGroups& e, const std::vector<int32_t>& component,
                       int32_t num_components, Orientation& o) {
  std::vector<char> open(num_components, 0);
  std::vector<double> volume(num_components, 0.0), magnitude(num_components, 0.0);
  std::vector<size_t> faces(num_components, 0), flipped(num_components, 0);
  std::vector<int32_t> first_face(num_components, -1);
  for (size_t f = 0; f < in.triangles.size(); ++f) {
    const int32_t c = component[f];
    if (first_face[c] < 0) first_face[c] = static_cast<int32_t>(f);
    for (size_t h = 3 * f; h < 3 * f + 3; ++h) open[c] |= e.size(e.group_of[h]) != 2 || o.cut[e.group_of[h]];
    // Relative to a point of the component: the same sum for a closed
    // surface, without the cancellation far from the origin.
    const Eigen::Vector3d& origin = in.positions[in.triangles[first_face[c]][0]];
    const double term = signed_volume_term(in, static_cast<int32_t>(f), o.flip[f], origin);
    volume[c] += term;
    magnitude[c] += std::abs(term);
    ++faces[c];
    flipped[c] += o.flip[f];
  }
  std::vector<char> turn(num_components);
  for (int32_t c = 0; c < num_components; ++c) {
    const bool has_volume = !open[c] && std::abs(volume[c]) > 1e-9 * magnitude[c];
    turn[c] = has_volume ? volume[c] < 0.0 : 2 * flipped[c] > faces[c];
  }
  for (size_t f = 0; f < in.triangles.size(); ++f) o.flip[f] ^= turn[component[f]];
}

Status validate(const TriangleMesh& mesh) {
  if (mesh.triangles.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max() / 3) ||
      mesh.positions.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
    return invalid_mesh("mesh too large: " + std::to_string(mesh.triangles.size()) + " triangles, " +
                        std::to_string(mesh.positions.size()) + " vertices");
  const auto nv = static_cast<int32_t>(mesh.positions.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& tri = mesh.triangles[f];
    for (const int32_t v : tri)
      if (v < 0 || v >= nv)
        return invalid_mesh("triangle " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                            " but the mesh has " + std::to_string(nv) + " vertices");
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0])
      return invalid_mesh("triangle " + std::to_string(f) + " repeats a vertex (run clean_mesh first)");
  }
  return ok_status();
}

// Cuts each component out of the repaired corner vertices, with its faces
// turned as `flip` says.
std::vector<ComponentMesh> assemble(const TriangleMesh& in, const std::vector<int32_t>& corner_vertex,
                                    int32_t num_vertices, const std::vector<int32_t>& component,
                                    int32_t num_components, const std::vector<char>& flip, ManifoldReport& r) {
  std::vector<ComponentMesh> out(num_components);
  std::vector<int32_t> local(num_vertices, -1);
  std::vector<int32_t> copies(in.positions.size(), 0);
  for (size_t f = 0; f < in.triangles.size(); ++f) {
    ComponentMesh& m = out[component[f]];
    std::array<int32_t, 3> tri;
    for (int32_t k = 0; k < 3; ++k) {
      const int32_t v = corner_vertex[3 * f + k];
      if (local[v] < 0) {
        const int32_t source = in.triangles[f][k];
        local[v] = static_cast<int32_t>(m.source_vertex.size());
        m.source_vertex.push_back(source);
        m.mesh.positions.push_back(in.positions[source]);
        ++copies[source];
      }
      tri[k] = local[v];
    }
    if (flip[f]) std::swap(tri[1], tri[2]);
    r.faces_flipped += flip[f];
    m.mesh.triangles.push_back(tri);
    m.source_triangle.push_back(static_cast<int32_t>(f));
  }
  r.nonmanifold_vertices_split = std::count_if(copies.begin(), copies.end(), [](int32_t n) { return n > 1; });
  return out;
}

}  // namespace

StatusOr<std::vector<ComponentMesh>> split_into_manifold_components(const TriangleMesh& mesh,
                                                                    ManifoldReport* report) {
  ManifoldReport local_report;
  ManifoldReport& r = report ? *report : local_report;
  r = ManifoldReport{};
  SRCODEC_RETURN_IF_ERROR(validate(mesh));

  // Manifold first, so the orientation pass sees at most two faces per edge.
  const Triangles manifold = triangles_of(make_manifold(mesh.triangles, r));
  const EdgeGroups e = group_edges(manifold);
  for (size_t g = 0; g < e.count(); ++g)
    if (e.size(g) > 2)
      return internal_error("split_into_manifold_components: an edge kept " + std::to_string(e.size(g)) + " faces");
  Orientation o = propagate_orientation(manifold, e);
  r.nonorientable_components = o.nonorientable;
  int32_t num_vertices = 0;
  SRCODEC_ASSIGN_OR_RETURN(const std::vector<int32_t> corner_vertex, open_cuts(manifold, e, o.cut, &num_vertices));

  // Components: every vertex is one fan now, so vertex- and edge-connected agree.
  UnionFind sets(num_vertices);
  const size_t nf = mesh.triangles.size();
  for (size_t f = 0; f < nf; ++f) {
    sets.unite(corner_vertex[3 * f], corner_vertex[3 * f + 1]);
    sets.unite(corner_vertex[3 * f], corner_vertex[3 * f + 2]);
  }
  std::vector<int32_t> component(nf);
  for (size_t f = 0; f < nf; ++f) component[f] = static_cast<int32_t>(sets.find(corner_vertex[3 * f]));
  const int32_t num_components = renumber(component, num_vertices);

  orient_components(mesh, e, component, num_components, o);
  return assemble(mesh, corner_vertex, num_vertices, component, num_components, o.flip, r);
}

}  // namespace srcodec
