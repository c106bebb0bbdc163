#include "format/mesh_files/mesh_clean.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>
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
  // Most faces are triangles: no copy for them.
  if (face.size() == 3) return face[0] != face[1] && face[1] != face[2] && face[2] != face[0];
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

// The squared norm of twice triangle abc's area: 0 when it has none.
double squared_double_area(const std::vector<Eigen::Vector3d>& pos, int32_t a, int32_t b, int32_t c) {
  return (pos[b] - pos[a]).cross(pos[c] - pos[a]).squaredNorm();
}

// For each zero-area triangle (zero[i]) with three distinct corners: the
// corner m opposite its longest edge p -> q lies between p and q. The one
// other triangle that has edge q -> p, (q, p, d), is replaced by (q, m, d)
// followed by (m, p, d), when both have area and m-d is a new edge: the
// halves take the places of the zero-area triangle's edges p-m and m-q, so
// dropping it leaves no hole. Triangles split once at most; the new halves
// are not zero. Returns the triangles split.
size_t close_needles(const std::vector<Eigen::Vector3d>& pos, std::unordered_set<uint64_t>& edges,
                     std::vector<char>& zero, std::vector<std::array<int32_t, 3>>& triangles) {
  struct Needle {
    int32_t p, q, m;
    int32_t across = -1;  // the triangle with edge q -> p; -2 when more than one has it
  };
  std::vector<Needle> needles;
  std::unordered_map<uint64_t, size_t> wanted;  // directed edge q -> p, to its needle
  auto directed = [](int32_t a, int32_t b) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
  };
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    if (!zero[i] || t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;
    int longest = 0;  // the edge opposite corner c runs from t[c + 1] to t[c + 2]
    double length = -1.0;
    for (int c = 0; c < 3; ++c) {
      const double l = (pos[t[(c + 1) % 3]] - pos[t[(c + 2) % 3]]).squaredNorm();
      if (l > length) {
        length = l;
        longest = c;
      }
    }
    const Needle n{t[(longest + 1) % 3], t[(longest + 2) % 3], t[longest]};
    if (wanted.emplace(directed(n.q, n.p), needles.size()).second) needles.push_back(n);
  }
  if (needles.empty()) return 0;
  for (size_t j = 0; j < triangles.size(); ++j) {
    if (zero[j]) continue;
    const auto& t = triangles[j];
    for (int c = 0; c < 3; ++c) {
      const auto it = wanted.find(directed(t[c], t[(c + 1) % 3]));
      if (it == wanted.end()) continue;
      Needle& n = needles[it->second];
      n.across = n.across == -1 ? static_cast<int32_t>(j) : -2;
    }
  }
  std::vector<char> split(triangles.size(), 0);
  std::vector<std::pair<size_t, std::array<int32_t, 3>>> second;  // (triangle, the half that follows it)
  for (const Needle& n : needles) {
    if (n.across < 0 || split[static_cast<size_t>(n.across)]) continue;
    auto& t = triangles[static_cast<size_t>(n.across)];
    int c = 0;
    while (!(t[c] == n.q && t[(c + 1) % 3] == n.p)) ++c;
    const int32_t d = t[(c + 2) % 3];
    if (d == n.m || edges.count(edge_key(n.m, d))) continue;
    if (!(squared_double_area(pos, n.q, n.m, d) > 0.0) || !(squared_double_area(pos, n.m, n.p, d) > 0.0)) continue;
    split[static_cast<size_t>(n.across)] = 1;
    edges.insert(edge_key(n.m, d));
    t = {n.q, n.m, d};
    second.emplace_back(static_cast<size_t>(n.across), std::array<int32_t, 3>{n.m, n.p, d});
  }
  if (second.empty()) return 0;
  std::sort(second.begin(), second.end());
  std::vector<std::array<int32_t, 3>> out;
  std::vector<char> out_zero;
  out.reserve(triangles.size() + second.size());
  out_zero.reserve(triangles.size() + second.size());
  size_t k = 0;
  for (size_t j = 0; j < triangles.size(); ++j) {
    out.push_back(triangles[j]);
    out_zero.push_back(zero[j]);
    if (k < second.size() && second[k].first == j) {
      out.push_back(second[k++].second);
      out_zero.push_back(0);
    }
  }
  triangles.swap(out);
  zero.swap(out_zero);
  return second.size();
}

}  // namespace

TriangleMesh clean_mesh(const PolygonMesh& in, CleanReport* report) {
  CleanReport local;
  CleanReport& r = report ? *report : local;
  r = CleanReport{};

  std::vector<char> referenced(in.positions.size(), 0);
  for (int32_t v : in.corners) referenced[v] = 1;
  const std::vector<int32_t> weld = weld_map(in, referenced, &r.welded_vertices);

  // Welded faces, one after the other: face f is corners[at[f] .. at[f + 1]).
  std::vector<int32_t> corners, face;
  std::vector<size_t> at{0};
  corners.reserve(in.corners.size());
  at.reserve(in.num_faces() + 1);
  bool polygons = false;
  for (size_t f = 0; f < in.num_faces(); ++f) {
    face.assign(in.face(f), in.face(f) + in.face_size(f));
    for (auto& v : face) v = weld[v];
    if (!simplify_face(face)) {
      ++r.degenerate_faces;
      continue;
    }
    polygons = polygons || face.size() > 3;
    corners.insert(corners.end(), face.begin(), face.end());
    at.push_back(corners.size());
  }
  // Every existing edge: diagonals and needle splits must avoid them. Built
  // only when a polygon or a zero-area triangle asks (a large scan has
  // neither, and tens of millions of edges).
  std::unordered_set<uint64_t> edges;
  const auto face_edges = [&] {
    for (size_t f = 0; f + 1 < at.size(); ++f)
      for (size_t i = at[f]; i < at[f + 1]; ++i)
        edges.insert(edge_key(corners[i], corners[i + 1 < at[f + 1] ? i + 1 : at[f]]));
  };
  if (polygons) face_edges();

  std::vector<std::array<int32_t, 3>> triangles;
  triangles.reserve(at.size() - 1);
  for (size_t f = 0; f + 1 < at.size(); ++f) {
    if (at[f + 1] - at[f] == 3) {
      triangles.push_back({corners[at[f]], corners[at[f] + 1], corners[at[f] + 2]});
    } else {
      ++r.polygons_triangulated;
      face.assign(corners.begin() + at[f], corners.begin() + at[f + 1]);
      triangulate(face, in.positions, edges, triangles);
    }
  }

  // Zero-area triangles go. Where one has three distinct corners, one of
  // them, m, lies on the segment between the other two, p and q; dropped
  // alone it would leave a hole of no width (p-q on one side, p-m-q on the
  // other), so the triangle across p-q is split at m, which closes it.
  std::vector<char> zero(triangles.size(), 0);
  for (size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    if (squared_double_area(in.positions, t[0], t[1], t[2]) == 0.0) {
      ++r.degenerate_faces;
      zero[i] = 1;
    }
  }
  if (std::find(zero.begin(), zero.end(), 1) != zero.end()) {
    if (!polygons) face_edges();
    r.split_faces = close_needles(in.positions, edges, zero, triangles);
  }

  // Duplicate triangles (either orientation) go; the first copy stays.
  std::vector<std::pair<std::array<int32_t, 3>, size_t>> keys;
  keys.reserve(triangles.size());
  std::vector<char> keep(triangles.size(), 1);
  for (size_t i = 0; i < triangles.size(); ++i) {
    if (zero[i]) {
      keep[i] = 0;
      continue;
    }
    std::array<int32_t, 3> key = triangles[i];
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
