#include "format/mesh_clean.h"

#include <algorithm>
#include <numeric>
#include <unordered_set>
#include <utility>

namespace srcodec {
namespace {

uint64_t edge_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Maps every referenced vertex to the first referenced vertex at exactly the
// same position. Only exact matches: a tolerance would glue thin parts.
std::vector<int32_t> weld_map(const PolygonMesh& in, const std::vector<char>& referenced, size_t* welded) {
  std::vector<int32_t> order;
  for (size_t v = 0; v < in.positions.size(); ++v)
    if (referenced[v]) order.push_back(static_cast<int32_t>(v));
  auto less = [&](int32_t a, int32_t b) {
    const auto &p = in.positions[a], &q = in.positions[b];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int32_t> map(in.positions.size());
  std::iota(map.begin(), map.end(), 0);
  for (size_t i = 1; i < order.size(); ++i) {
    if (in.positions[order[i]] == in.positions[order[i - 1]]) {
      map[order[i]] = map[order[i - 1]];
      ++*welded;
    }
  }
  return map;
}

// Removes repeated consecutive corners; false if the face is degenerate.
bool simplify_face(std::vector<int32_t>& face) {
  std::vector<int32_t> out;
  for (size_t i = 0; i < face.size(); ++i) {
    if (face[i] != face[(i + 1) % face.size()]) out.push_back(face[i]);
  }
  face.swap(out);
  if (face.size() < 3) return false;
  std::vector<int32_t> sorted = face;
  std::sort(sorted.begin(), sorted.end());
  return std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
}

// A fan from the corner whose diagonals are all new edges (so no face is
// duplicated and no edge gets a third face), preferring short diagonals.
void triangulate(const std::vector<int32_t>& face, const std::vector<Eigen::Vector3d>& pos,
                 std::unordered_set<uint64_t>& edges, std::vector<std::array<int32_t, 3>>& out) {
  const size_t n = face.size();
  size_t best = 0;
  double best_length = -1;
  for (size_t c = 0; c < n; ++c) {
    bool fresh = true;
    double length = 0;
    for (size_t k = 2; k + 1 < n; ++k) {
      int32_t a = face[c], b = face[(c + k) % n];
      if (edges.count(edge_key(a, b))) fresh = false;
      length += (pos[a] - pos[b]).norm();
    }
    if (fresh && (best_length < 0 || length < best_length)) {
      best = c;
      best_length = length;
    }
  }
  for (size_t k = 1; k + 1 < n; ++k) {
    int32_t a = face[best], b = face[(best + k) % n], c = face[(best + k + 1) % n];
    out.push_back({a, b, c});
    if (k + 2 < n) edges.insert(edge_key(a, c));
  }
}

}  // namespace

TriangleMesh clean_mesh(const PolygonMesh& in, CleanReport* report) {
  CleanReport local;
  CleanReport& r = report ? *report : local;
  r = CleanReport{};

  std::vector<char> referenced(in.positions.size(), 0);
  for (int32_t v : in.corners) referenced[v] = 1;
  const std::vector<int32_t> weld = weld_map(in, referenced, &r.welded_vertices);

  // Welded faces, and every existing edge (diagonals must avoid them).
  std::vector<std::vector<int32_t>> faces;
  std::unordered_set<uint64_t> edges;
  for (size_t f = 0; f < in.num_faces(); ++f) {
    std::vector<int32_t> face(in.face(f), in.face(f) + in.face_size(f));
    for (auto& v : face) v = weld[v];
    if (!simplify_face(face)) {
      ++r.degenerate_faces;
      continue;
    }
    for (size_t i = 0; i < face.size(); ++i) edges.insert(edge_key(face[i], face[(i + 1) % face.size()]));
    faces.push_back(std::move(face));
  }

  std::vector<std::array<int32_t, 3>> triangles;
  triangles.reserve(faces.size());
  for (const auto& face : faces) {
    if (face.size() == 3) {
      triangles.push_back({face[0], face[1], face[2]});
    } else {
      ++r.polygons_triangulated;
      triangulate(face, in.positions, edges, triangles);
    }
  }

  // Zero-area and duplicate triangles (either orientation) go; the first
  // copy of a duplicate stays.
  std::vector<std::pair<std::array<int32_t, 3>, size_t>> keys;
  keys.reserve(triangles.size());
  std::vector<char> keep(triangles.size(), 1);
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    const auto &a = in.positions[t[0]], &b = in.positions[t[1]], &c = in.positions[t[2]];
    if ((b - a).cross(c - a).squaredNorm() == 0.0) {
      ++r.degenerate_faces;
      keep[i] = 0;
      continue;
    }
    std::array<int32_t, 3> key = t;
    std::sort(key.begin(), key.end());
    keys.emplace_back(key, i);
  }
  std::sort(keys.begin(), keys.end());
  for (size_t i = 1; i < keys.size(); ++i) {
    if (keys[i].first == keys[i - 1].first) {
      keep[keys[i].second] = 0;
      ++r.duplicate_faces;
    }
  }
  std::vector<std::array<int32_t, 3>> kept;
  kept.reserve(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i)
    if (keep[i]) kept.push_back(triangles[i]);

  // Compact: keep referenced vertices in their original order.
  TriangleMesh out;
  std::vector<int32_t> new_index(in.positions.size(), -1);
  for (const auto& t : kept)
    for (int32_t v : t) new_index[v] = 0;
  for (size_t v = 0; v < in.positions.size(); ++v) {
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int32_t>(out.positions.size());
      out.positions.push_back(in.positions[v]);
    }
  }
  r.unreferenced_vertices = in.positions.size() - out.positions.size() - r.welded_vertices;
  out.triangles.reserve(kept.size());
  for (const auto& t : kept) out.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
  return out;
}

}  // namespace srcodec
