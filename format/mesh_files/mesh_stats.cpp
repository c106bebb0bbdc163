#include "format/mesh_files/mesh_stats.h"

#include <algorithm>
#include <unordered_map>

#include "format/union_find.h"

namespace srcodec {
namespace {

// One face edge, seen from its face: corners are global corner indices.
struct HalfEdge {
  int32_t lo, hi;       // vertex ids, lo < hi
  int32_t corner_lo;    // the face's corner at vertex lo
  int32_t corner_hi;    // the face's corner at vertex hi
  bool forward;         // the face walks lo -> hi
  bool operator<(const HalfEdge& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
};

bool is_degenerate(const PolygonMesh& mesh, size_t f) {
  const int32_t n = mesh.face_size(f);
  const int32_t* c = mesh.face(f);
  std::vector<int32_t> ids(c, c + n);
  std::sort(ids.begin(), ids.end());
  if (std::adjacent_find(ids.begin(), ids.end()) != ids.end()) return true;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // Newell: twice the vector area
  for (int32_t k = 0; k < n; ++k) normal += mesh.positions[c[k]].cross(mesh.positions[c[(k + 1) % n]]);
  return normal.squaredNorm() == 0.0;
}

}  // namespace

MeshStats compute_stats(const PolygonMesh& mesh) {
  MeshStats s;
  const size_t nv = mesh.positions.size();
  s.vertices = nv;
  s.faces = mesh.num_faces();
  s.bbox_diagonal = bounding_box_diagonal(mesh.positions);

  std::vector<char> referenced(nv, 0);
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(mesh.corners.size());
  UnionFind vertex_sets(nv);
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    const int32_t n = mesh.face_size(f);
    const int32_t first = mesh.face_offsets[f];
    s.triangles += n == 3;
    s.max_face_size = std::max<size_t>(s.max_face_size, n);
    if (is_degenerate(mesh, f)) ++s.degenerate_faces;
    for (int32_t k = 0; k < n; ++k) {
      const int32_t ca = first + k, cb = first + (k + 1) % n;
      const int32_t a = mesh.corners[ca], b = mesh.corners[cb];
      referenced[a] = 1;
      vertex_sets.unite(a, b);
      if (a == b) continue;
      half_edges.push_back(a < b ? HalfEdge{a, b, ca, cb, true} : HalfEdge{b, a, cb, ca, false});
    }
  }
  s.referenced_vertices = std::count(referenced.begin(), referenced.end(), 1);
  std::vector<char> root_seen(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    if (referenced[v] && !root_seen[vertex_sets.find(v)]) {
      root_seen[vertex_sets.find(v)] = 1;
      ++s.components;
    }
  }

  // Group the face edges by undirected edge. Corners around a vertex that
  // share an edge belong to one fan; more fans than one = non-manifold vertex.
  std::sort(half_edges.begin(), half_edges.end());
  UnionFind fans(mesh.corners.size());
  UnionFind boundary_sets(nv);
  std::vector<char> on_boundary(nv, 0);
  for (size_t i = 0; i < half_edges.size();) {
    size_t j = i;
    size_t forward = 0;
    while (j < half_edges.size() && half_edges[j].lo == half_edges[i].lo && half_edges[j].hi == half_edges[i].hi) {
      forward += half_edges[j].forward;
      fans.unite(half_edges[i].corner_lo, half_edges[j].corner_lo);
      fans.unite(half_edges[i].corner_hi, half_edges[j].corner_hi);
      ++j;
    }
    const size_t count = j - i;
    ++s.edges;
    if (count == 1) {
      ++s.boundary_edges;
      boundary_sets.unite(half_edges[i].lo, half_edges[i].hi);
      on_boundary[half_edges[i].lo] = on_boundary[half_edges[i].hi] = 1;
    } else if (count > 2) {
      ++s.nonmanifold_edges;
    } else if (forward != 1) {
      ++s.orientation_inconsistent_edges;
    }
    i = j;
  }
  std::fill(root_seen.begin(), root_seen.end(), 0);
  for (size_t v = 0; v < nv; ++v) {
    if (on_boundary[v] && !root_seen[boundary_sets.find(v)]) {
      root_seen[boundary_sets.find(v)] = 1;
      ++s.boundary_loops;
    }
  }

  // Count the fans at each vertex: distinct corner-set roots per vertex.
  std::vector<int32_t> fans_at(nv, 0);
  std::vector<char> fan_root_seen(mesh.corners.size(), 0);
  for (size_t c = 0; c < mesh.corners.size(); ++c) {
    const size_t root = fans.find(c);
    if (!fan_root_seen[root]) {
      fan_root_seen[root] = 1;
      ++fans_at[mesh.corners[c]];
    }
  }
  s.nonmanifold_vertices = std::count_if(fans_at.begin(), fans_at.end(), [](int32_t n) { return n > 1; });

  s.euler_characteristic = static_cast<long>(s.referenced_vertices) - static_cast<long>(s.edges) +
                           static_cast<long>(s.faces);
  const long twice_genus = 2 * static_cast<long>(s.components) - s.euler_characteristic -
                           static_cast<long>(s.boundary_loops);
  if (s.is_manifold() && twice_genus >= 0 && twice_genus % 2 == 0) s.genus = twice_genus / 2;
  return s;
}

}  // namespace srcodec
