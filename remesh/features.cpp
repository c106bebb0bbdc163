#include "remesh/features.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "format/union_find.h"
#include "remesh/adjacency.h"
#include "remesh/geometry.h"

namespace srcodec {
namespace {

// A candidate must bend more than this many times the median bend of the
// edges around it: on a noisy scan every edge bends, and only what stands
// out of that noise can be a crease. The noise is estimated only from at
// least kNoiseSamples triangles: on a coarse CAD part (a cube of twelve
// triangles) the few around an edge are mostly creases themselves.
constexpr double kOverNoise = 3.0;
constexpr size_t kNoiseSamples = 16;
// Features are sought at a scale of at most this share of the bounding-box
// diagonal, however coarse the mesh.
constexpr double kLargestRadius = 0.1;

// The corner of triangle t that starts its edge a-b (either direction).
int corner_of_edge(const std::array<int32_t, 3>& t, int32_t a, int32_t b) {
  for (int c = 0; c < 3; ++c)
    if ((t[c] == a && t[(c + 1) % 3] == b) || (t[c] == b && t[(c + 1) % 3] == a)) return c;
  return 0;
}

struct Faces {
  std::vector<Eigen::Vector3d> normal;  // unit, or zero for no area
  std::vector<double> area;
  std::vector<Eigen::Vector3d> centroid;
};

Faces face_geometry(const TriangleMesh& mesh) {
  Faces f;
  const size_t n = mesh.triangles.size();
  f.normal.resize(n);
  f.area.resize(n);
  f.centroid.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto& t = mesh.triangles[i];
    const Eigen::Vector3d cross = triangle_normal(mesh.positions, t);
    const double norm = cross.norm();
    f.area[i] = 0.5 * norm;
    f.normal[i] = norm > 0 ? Eigen::Vector3d(cross / norm) : Eigen::Vector3d::Zero();
    f.centroid[i] = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3.0;
  }
  return f;
}

double median_edge_length(const TriangleMesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) lengths.push_back((mesh.positions[t[(c + 1) % 3]] - mesh.positions[t[c]]).norm());
  if (lengths.empty()) return 0.0;
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  return lengths[lengths.size() / 2];
}

// Walks over the triangles within a radius of a point, across edges.
class LocalWalk {
 public:
  LocalWalk(const Faces& faces, const std::vector<std::array<int32_t, 3>>& across)
      : faces_(faces), across_(across), stamp_(across.size(), 0) {}

  // The triangles within `radius` of `centre` reached from `start` without
  // crossing an edge marked in `barrier` (per triangle corner; none when
  // null); stops early, returning false, when it reaches `stop`.
  bool walk(int32_t start, int32_t stop, const Eigen::Vector3d& centre, double radius,
            const std::vector<std::array<char, 3>>* barrier) {
    ++visit_;
    reached_.assign({start});
    stamp_[start] = visit_;
    const double r2 = radius * radius;
    for (size_t q = 0; q < reached_.size(); ++q) {
      const int32_t f = reached_[q];
      if (f == stop) return false;
      for (int c = 0; c < 3; ++c) {
        const int32_t g = across_[f][c];
        if (g < 0 || (barrier && (*barrier)[f][c]) || stamp_[g] == visit_) continue;
        if ((faces_.centroid[g] - centre).squaredNorm() > r2) continue;
        stamp_[g] = visit_;
        reached_.push_back(g);
      }
    }
    return true;
  }
  const std::vector<int32_t>& reached() const { return reached_; }

 private:
  const Faces& faces_;
  const std::vector<std::array<int32_t, 3>>& across_;
  std::vector<uint32_t> stamp_;
  uint32_t visit_ = 0;
  std::vector<int32_t> reached_;
};

// Per vertex, its feature edges: (the other end, the edge's index).
using FeatureStar = std::vector<std::vector<std::pair<int32_t, int32_t>>>;

FeatureStar feature_star(size_t vertex_count, const std::vector<FeatureEdge>& edges) {
  FeatureStar at(vertex_count);
  for (size_t e = 0; e < edges.size(); ++e) {
    at[edges[e].a].push_back({edges[e].b, static_cast<int32_t>(e)});
    at[edges[e].b].push_back({edges[e].a, static_cast<int32_t>(e)});
  }
  return at;
}

// Walks the feature edges into curves: from every corner and end along each
// of its edges to the next corner or end, then the closed loops left.
std::vector<FeatureCurve> chain(const FeatureStar& at, const std::vector<FeatureEdge>& edges,
                                const std::vector<char>& stops) {
  const size_t vertex_count = at.size();
  std::vector<char> used(edges.size(), 0);
  std::vector<FeatureCurve> curves;
  auto walk = [&](int32_t start, int32_t to, int32_t edge) {
    FeatureCurve curve;
    curve.vertices = {start};
    for (;;) {
      used[edge] = 1;
      curve.vertices.push_back(to);
      if (stops[to] || to == start) break;
      int32_t next_edge = -1, next_vertex = -1;
      for (const auto& [w, e] : at[to])
        if (!used[e]) {
          next_edge = e;
          next_vertex = w;
          break;
        }
      if (next_edge < 0) break;
      edge = next_edge;
      to = next_vertex;
    }
    curves.push_back(std::move(curve));
  };
  for (size_t v = 0; v < vertex_count; ++v)
    if (stops[v])
      for (const auto& [w, e] : at[v])
        if (!used[e]) walk(static_cast<int32_t>(v), w, e);
  for (size_t e = 0; e < edges.size(); ++e)
    if (!used[e]) walk(edges[e].a, edges[e].b, static_cast<int32_t>(e));
  return curves;
}

// How sharply a feature curve turns at v (two feature edges, to vertices
// at[v]), in degrees: judged, like creases, over `radius` on either side (a
// jagged scan boundary turns at every vertex and goes straight at scale).
double turn_at(const TriangleMesh& mesh, const FeatureStar& at, int32_t v, double radius) {
  auto reach = [&](int32_t step) {
    int32_t previous = v, current = step;
    double length = (mesh.positions[step] - mesh.positions[v]).norm();
    for (size_t guard = 0; length < radius && at[current].size() == 2 && guard < mesh.positions.size(); ++guard) {
      const int32_t next = at[current][0].first == previous ? at[current][1].first : at[current][0].first;
      if (next == v) break;  // a small closed loop
      length += (mesh.positions[next] - mesh.positions[current]).norm();
      previous = current;
      current = next;
    }
    return Eigen::Vector3d(mesh.positions[current] - mesh.positions[v]);
  };
  return 180.0 - degrees_between(reach(at[v][0].first), reach(at[v][1].first));
}

// Corners, ends and curves of a set of feature edges (sorted by (a, b)).
Features assemble(const TriangleMesh& mesh, std::vector<FeatureEdge> edges, const FeatureOptions& options,
                  double radius) {
  const size_t nv = mesh.positions.size();
  const FeatureStar at = feature_star(nv, edges);
  std::vector<double> turn(nv, 0.0);
  for (size_t v = 0; v < nv; ++v)
    if (at[v].size() == 2) turn[v] = turn_at(mesh, at, static_cast<int32_t>(v), radius);
  Features out;
  std::vector<char> stops(nv, 0);
  for (size_t v = 0; v < nv; ++v) {
    const size_t valence = at[v].size();
    if (valence == 1) {
      out.ends.push_back(static_cast<int32_t>(v));
      stops[v] = 1;
    } else if (valence >= 3) {
      out.corners.push_back(static_cast<int32_t>(v));
      stops[v] = 1;
    } else if (valence == 2 && turn[v] > options.crease_degrees) {
      // Measured over a radius, the turn is high for every vertex near a
      // sharp one: the corner is where it peaks (ties to the lower index).
      bool peak = true;
      for (const auto& [w, e] : at[v])
        if (at[w].size() == 2 && (turn[w] > turn[v] || (turn[w] == turn[v] && w < static_cast<int32_t>(v))))
          peak = false;
      if (peak) {
        out.corners.push_back(static_cast<int32_t>(v));
        stops[v] = 1;
      }
    }
  }
  out.curves = chain(at, edges, stops);
  out.edges = std::move(edges);
  return out;
}

// Drops the connected sets of creases that span less than `radius` (the
// diagonal of their bounding box): below the scale features are sought at,
// a scratch or a knot of noise, not a crease. Boundaries stay.
std::vector<FeatureEdge> without_scratches(const TriangleMesh& mesh, std::vector<FeatureEdge> edges, double radius) {
  UnionFind sets(mesh.positions.size());
  for (const FeatureEdge& e : edges)
    if (e.kind == FeatureKind::kCrease) sets.unite(e.a, e.b);
  std::map<size_t, Eigen::AlignedBox3d> extent;
  for (const FeatureEdge& e : edges)
    if (e.kind == FeatureKind::kCrease) {
      Eigen::AlignedBox3d& box = extent[sets.find(e.a)];
      box.extend(mesh.positions[e.a]);
      box.extend(mesh.positions[e.b]);
    }
  std::vector<FeatureEdge> kept;
  for (const FeatureEdge& e : edges)
    if (e.kind != FeatureKind::kCrease || extent[sets.find(e.a)].diagonal().norm() >= radius) kept.push_back(e);
  return kept;
}

}  // namespace

std::vector<FeatureCurve> chain_feature_curves(size_t vertex_count, const std::vector<FeatureEdge>& edges,
                                               const std::vector<char>& stops) {
  return chain(feature_star(vertex_count, edges), edges, stops);
}

const FeatureEdge* Features::find(int32_t a, int32_t b) const {
  if (a > b) std::swap(a, b);
  const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(a, b),
                                   [](const FeatureEdge& e, const std::pair<int32_t, int32_t>& k) {
                                     return std::make_pair(e.a, e.b) < k;
                                   });
  return it != edges.end() && it->a == a && it->b == b ? &*it : nullptr;
}

Features detect_features(const TriangleMesh& mesh, const FeatureOptions& options) {
  const Faces faces = face_geometry(mesh);
  const auto across = triangles_across(mesh.triangles);
  const size_t nt = mesh.triangles.size();
  const double radius =
      std::min(options.scale * median_edge_length(mesh), kLargestRadius * bounding_box_diagonal(mesh.positions));

  // How much each edge bends: the angle between its triangles' normals.
  std::vector<std::array<double, 3>> bend(nt, {0, 0, 0});
  for (size_t f = 0; f < nt; ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t g = across[f][c];
      if (g >= 0 && faces.area[f] > 0 && faces.area[g] > 0)
        bend[f][c] = degrees_between(faces.normal[f], faces.normal[g]);
    }

  // Candidates: edges that bend more than the crease angle and stand out of
  // the bends around them.
  LocalWalk local(faces, across);
  std::vector<std::array<char, 3>> candidate(nt, {0, 0, 0});
  std::vector<double> around;
  for (size_t f = 0; f < nt; ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t g = across[f][c];
      if (g < static_cast<int32_t>(f) || !(bend[f][c] > options.crease_degrees)) continue;
      const auto& t = mesh.triangles[f];
      const Eigen::Vector3d centre = 0.5 * (mesh.positions[t[c]] + mesh.positions[t[(c + 1) % 3]]);
      local.walk(static_cast<int32_t>(f), -1, centre, radius, nullptr);
      around.clear();
      for (int32_t h : local.reached()) around.insert(around.end(), bend[h].begin(), bend[h].end());
      if (local.reached().size() >= kNoiseSamples) {
        const auto median = around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2);
        std::nth_element(around.begin(), median, around.end());
        if (!(bend[f][c] > kOverNoise * *median)) continue;
      }
      candidate[f][c] = 1;
      candidate[g][corner_of_edge(mesh.triangles[g], t[c], t[(c + 1) % 3])] = 1;
    }

  // Creases: candidates that, with the candidates near them, cut the
  // surface within the radius into two sides (else the walk goes round the
  // candidate's end), whose mean normals meet at more than the crease angle.
  std::vector<FeatureEdge> edges;
  for (size_t f = 0; f < nt; ++f)
    for (int c = 0; c < 3; ++c) {
      const auto& t = mesh.triangles[f];
      const int32_t a = t[c], b = t[(c + 1) % 3], g = across[f][c];
      if (g < 0) {
        if (options.boundaries) edges.push_back({std::min(a, b), std::max(a, b), FeatureKind::kBoundary});
        continue;
      }
      if (!candidate[f][c] || static_cast<int32_t>(f) > g) continue;
      const Eigen::Vector3d centre = 0.5 * (mesh.positions[a] + mesh.positions[b]);
      Eigen::Vector3d side[2];
      const int32_t start[2] = {static_cast<int32_t>(f), g};
      bool cut = true;
      for (int k = 0; k < 2 && cut; ++k) {
        cut = local.walk(start[k], start[1 - k], centre, radius, &candidate);
        side[k].setZero();
        for (int32_t h : local.reached()) side[k] += faces.area[h] * faces.normal[h];
      }
      if (cut && degrees_between(side[0], side[1]) > options.crease_degrees)
        edges.push_back({std::min(a, b), std::max(a, b), FeatureKind::kCrease});
    }
  std::sort(edges.begin(), edges.end(), [](const FeatureEdge& x, const FeatureEdge& y) {
    return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
  });
  // An edge where more than two triangles meet is seen once per triangle.
  edges.erase(std::unique(edges.begin(), edges.end(),
                          [](const FeatureEdge& x, const FeatureEdge& y) { return x.a == y.a && x.b == y.b; }),
              edges.end());

  return assemble(mesh, without_scratches(mesh, std::move(edges), radius), options, radius);
}

}  // namespace srcodec
