#include "format/crease_normals.h"

#include <algorithm>
#include <numeric>
#include <string>
#include <utility>

#include "format/mesh_convert.h"
#include "format/union_find.h"

namespace srcodec {
namespace {

// A list per vertex, packed: vertex v's items are items[begin[v] .. begin[v + 1]).
struct PerVertex {
  std::vector<int32_t> begin, items;

  bool empty(int32_t v) const { return begin[v + 1] == begin[v]; }
  const int32_t* first(int32_t v) const { return items.data() + begin[v]; }
  const int32_t* last(int32_t v) const { return items.data() + begin[v + 1]; }
};

// Fills a PerVertex from `count` (items per vertex) and `each`, which calls
// its argument with (vertex, item) for every item.
template <typename Each>
PerVertex packed(std::vector<int32_t> count, const Each& each) {
  PerVertex out;
  out.begin.assign(count.size() + 1, 0);
  std::partial_sum(count.begin(), count.end(), out.begin.begin() + 1);
  out.items.resize(static_cast<size_t>(out.begin.back()));
  std::copy(out.begin.begin(), out.begin.end() - 1, count.begin());  // now the next free slot
  each([&](int32_t v, int32_t item) { out.items[static_cast<size_t>(count[v]++)] = item; });
  return out;
}

// The other ends of each vertex's crease edges.
PerVertex crease_neighbours(size_t vertices, const std::vector<std::array<int32_t, 2>>& creases) {
  std::vector<int32_t> count(vertices, 0);
  for (const auto& [a, b] : creases)
    if (a != b) ++count[a], ++count[b];
  return packed(std::move(count), [&](const auto& add) {
    for (const auto& [a, b] : creases)
      if (a != b) add(a, b), add(b, a);
  });
}

// The corners (3 t + k: corner k of triangle t) at each vertex on a crease
// edge; none at the others, which are one sector whatever their corners.
PerVertex crease_vertex_corners(const TriangleMesh& mesh, const PerVertex& sharp) {
  std::vector<int32_t> count(sharp.begin.size() - 1, 0);
  for (const auto& t : mesh.triangles)
    for (int32_t v : t)
      if (!sharp.empty(v)) ++count[v];
  return packed(std::move(count), [&](const auto& add) {
    for (size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        if (!sharp.empty(mesh.triangles[t][k])) add(mesh.triangles[t][k], static_cast<int32_t>(3 * t + k));
  });
}

// Numbers the sectors of vertex v, on a crease: two of its corners [first,
// last) are in one sector when their triangles share an edge (v, w) that is
// not a crease. Writes each corner's sector, 0 .. k - 1 in corner order, to
// `sector` and returns k. By the edges' other ends, sorted, so that a vertex
// with many triangles costs no more than a sort.
int32_t number_sectors(const TriangleMesh& mesh, int32_t v, const int32_t* first, const int32_t* last,
                       const PerVertex& sharp, std::vector<int32_t>& sector) {
  const auto m = static_cast<int32_t>(last - first);
  std::vector<std::pair<int32_t, int32_t>> ends;  // (w, i): corner first[i]'s triangle has the edge (v, w)
  ends.reserve(2 * static_cast<size_t>(m));
  for (int32_t i = 0; i < m; ++i) {
    const auto& t = mesh.triangles[static_cast<size_t>(first[i] / 3)];
    const int k = first[i] % 3;
    ends.emplace_back(t[(k + 1) % 3], i);
    ends.emplace_back(t[(k + 2) % 3], i);
  }
  std::sort(ends.begin(), ends.end());
  UnionFind sets(static_cast<size_t>(m));
  for (size_t a = 0, b = 0; a < ends.size(); a = b) {
    const int32_t w = ends[a].first;
    while (b < ends.size() && ends[b].first == w) ++b;
    if (w == v || std::find(sharp.first(v), sharp.last(v), w) != sharp.last(v)) continue;
    for (size_t c = a + 1; c < b; ++c) sets.unite(ends[a].second, ends[c].second);
  }
  std::vector<int32_t> id(static_cast<size_t>(m), -1);
  int32_t k = 0;
  for (int32_t i = 0; i < m; ++i) {
    int32_t& root = id[sets.find(static_cast<size_t>(i))];
    if (root < 0) root = k++;
    sector[static_cast<size_t>(first[i])] = root;
  }
  return k;
}

}  // namespace

SectorNormals crease_normals(const TriangleMesh& mesh, const std::vector<std::array<int32_t, 2>>& creases) {
  const size_t n = mesh.positions.size();
  const PerVertex sharp = crease_neighbours(n, creases);
  const PerVertex at = crease_vertex_corners(mesh, sharp);
  // Per corner, its sector among its vertex's (0 off the creases); per
  // vertex, its first sector.
  std::vector<int32_t> local(3 * mesh.triangles.size(), 0);
  std::vector<int32_t> first_sector(n + 1, 0);
  for (size_t v = 0; v < n; ++v) {
    const auto vertex = static_cast<int32_t>(v);
    const int32_t sectors = at.empty(vertex) ? 1 : number_sectors(mesh, vertex, at.first(vertex), at.last(vertex),
                                                                  sharp, local);
    first_sector[v + 1] = first_sector[v] + sectors;
  }
  SectorNormals out;
  const auto sectors = static_cast<size_t>(first_sector[n]);
  std::vector<Eigen::Vector3d> sum(sectors, Eigen::Vector3d::Zero());
  out.corners.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.positions[static_cast<size_t>(tri[0])];
    // Twice the area times the unit normal: the sum weighs by area.
    const Eigen::Vector3d face = (mesh.positions[static_cast<size_t>(tri[1])] - a)
                                     .cross(mesh.positions[static_cast<size_t>(tri[2])] - a);
    for (int k = 0; k < 3; ++k) {
      const int32_t s = first_sector[static_cast<size_t>(tri[k])] + local[3 * t + static_cast<size_t>(k)];
      out.corners[t][k] = s;
      sum[static_cast<size_t>(s)] += face;
    }
  }
  out.normals.resize(sectors);
  for (size_t s = 0; s < sectors; ++s) {
    const double length = sum[s].norm();
    out.normals[s] = length > 0 ? Eigen::Vector3f((sum[s] / length).cast<float>()) : Eigen::Vector3f::Zero();
  }
  out.vertex.resize(sectors);
  for (size_t v = 0; v < n; ++v)
    std::fill(out.vertex.begin() + first_sector[v], out.vertex.begin() + first_sector[v + 1], static_cast<int32_t>(v));
  return out;
}

StatusOr<std::vector<std::array<int32_t, 2>>> crease_pairs(const std::vector<uint32_t>& ids, size_t vertex_count) {
  if (ids.size() % 2 != 0)
    return invalid_argument("crease_edges: " + std::to_string(ids.size()) + " vertex ids, not two per edge");
  std::vector<std::array<int32_t, 2>> out(ids.size() / 2);
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] >= vertex_count)
      return invalid_argument("crease_edges: edge " + std::to_string(k / 2) + " has vertex " + std::to_string(ids[k]) +
                              ", but the mesh has " + std::to_string(vertex_count) + " vertices");
    out[k / 2][k % 2] = static_cast<int32_t>(ids[k]);
  }
  return out;
}

// <srcodec/mesh.h>: here rather than with the mesh files, since the
// browser's decoder (which has no files) shades with it too.
StatusOr<CornerNormals> corner_normals(const Mesh& mesh, const std::vector<uint32_t>& crease_edges) {
  SRCODEC_ASSIGN_OR_RETURN(const TriangleMesh m, from_public_mesh(mesh, "the mesh to shade"));
  SRCODEC_ASSIGN_OR_RETURN(const auto creases, crease_pairs(crease_edges, m.positions.size()));
  const SectorNormals s = crease_normals(m, creases);
  CornerNormals out;
  out.normals.reserve(3 * s.normals.size());
  for (const Eigen::Vector3f& n : s.normals) out.normals.insert(out.normals.end(), {n.x(), n.y(), n.z()});
  out.vertices.assign(s.vertex.begin(), s.vertex.end());
  out.corners.reserve(3 * s.corners.size());
  for (const auto& c : s.corners) out.corners.insert(out.corners.end(), c.begin(), c.end());
  return out;
}

}  // namespace srcodec
