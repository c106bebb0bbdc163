#include "remesh/untangle.h"


#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <functional>
#include <unordered_map>

#include "remesh/adjacency.h"
#include "remesh/fit.h"
#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "remesh/point_cloud.h"
#include "remesh/small_lp.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

// One level's triangles around each vertex, and each triangle's neighbour
// across each edge (-1 on the boundary, or where more than two meet).
struct LevelAdjacency {
  std::vector<int32_t> offsets, around;  // around[offsets[v] .. offsets[v + 1]): the triangles at v
  std::vector<std::array<int32_t, 3>> across;

  // The triangles at v.
  std::vector<int32_t>::const_iterator begin(int32_t v) const {
    return around.begin() + offsets[static_cast<size_t>(v)];
  }
  std::vector<int32_t>::const_iterator end(int32_t v) const {
    return around.begin() + offsets[static_cast<size_t>(v) + 1];
  }

  LevelAdjacency(const Triangles& triangles, size_t n) : offsets(n + 1, 0), across(triangles_across(triangles)) {
    for (const auto& t : triangles)
      for (int32_t v : t) ++offsets[static_cast<size_t>(v) + 1];
    for (size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
    around.resize(static_cast<size_t>(offsets[n]));
    std::vector<int32_t> fill(offsets.begin(), offsets.end() - 1);
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int32_t v : triangles[t])
        around[static_cast<size_t>(fill[static_cast<size_t>(v)]++)] = static_cast<int32_t>(t);
  }
};

// How many vertices sit at each position, exactly. The untangling moves no
// vertex onto another's position: its candidates include input vertices,
// and two vertices moved onto one input vertex are pinched together once
// the output is read back with coincident vertices welded, as most tools
// (and our own cleaning) read it.
class Occupancy {
 public:
  explicit Occupancy(const std::vector<Eigen::Vector3d>& x) {
    count_.reserve(x.size());
    for (const Eigen::Vector3d& p : x) ++count_[key(p)];
  }
  bool taken(const Eigen::Vector3d& p) const { return count_.count(key(p)) > 0; }
  void move(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
    if (from == to) return;
    const auto it = count_.find(key(from));
    if (it != count_.end() && --it->second == 0) count_.erase(it);
    ++count_[key(to)];
  }

 private:
  using Key = std::array<double, 3>;
  struct Hash {
    size_t operator()(const Key& k) const {
      size_t h = 0;
      for (double d : k) h = h * 1000003u ^ std::hash<double>()(d);
      return h;
    }
  };
  static Key key(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }
  std::unordered_map<Key, int, Hash> count_;
};

// The best of the candidates tried so far: the fewest tangled triangles
// around, or as many but `factor` as deep.
struct Choice {
  size_t count;
  double energy;
  double factor = 0.5;
  bool offer(size_t c, double e) {
    if (!(c < count || (c == count && e < factor * energy))) return false;
    count = c;
    energy = e;
    return true;
  }
};

class Judge {
 public:
  Judge(const FoldCounter::Sides& side_at, const std::vector<Triangles>& levels, size_t n)
      : levels_(levels), side_at_(side_at) {
    for (const auto& level : levels) {
      adjacency_.emplace_back(level, n);
      neighbours_.emplace_back();
      for (size_t t = 0; t < level.size(); ++t)
        for (int32_t u : adjacency_.back().across[t])  // each pair once, from its lower triangle
          if (u > static_cast<int32_t>(t)) neighbours_.back().emplace_back(static_cast<int32_t>(t), u);
    }
  }

  const FoldCounter::Sides& side_at() const { return side_at_; }
  const LevelAdjacency& adjacency(size_t level) const { return adjacency_[level]; }

  // The folded triangles and pleats around vertex v, on every level; with
  // `energy`, also how deep they are: how far each folded triangle's facing
  // is below folded and each pleat's dihedral cosine past 150 degrees.
  size_t around(const std::vector<Eigen::Vector3d>& x, const std::vector<Eigen::Vector3d>& side, int32_t v,
                double* energy = nullptr) const {
    double e = 0.0;
    const size_t count = region(x, side, {v}, &e);
    if (energy) *energy = e;
    return count;
  }

  // The folded triangles and pleats among the triangles of every level at
  // `vertices` (sorted), each pleat once, and in `energy` how deep they are
  // (as around()).
  size_t region(const std::vector<Eigen::Vector3d>& x, const std::vector<Eigen::Vector3d>& side,
                const std::vector<int32_t>& vertices, double* energy) const {
    size_t count = 0;
    double e = 0.0;
    for (size_t k = 0; k < levels_.size(); ++k) {
      const std::vector<int32_t> tris = triangles_at(k, vertices);
      for (int32_t t : tris) {
        const auto& tri = levels_[k][static_cast<size_t>(t)];
        const double f = facing(x, side, tri);
        if (folded(f)) {
          ++count;
          e += fold_depth(f);
        }
        for (int32_t u : adjacency_[k].across[static_cast<size_t>(t)]) {
          if (u < 0 || (u < t && std::binary_search(tris.begin(), tris.end(), u))) continue;
          const Eigen::Vector3d a = triangle_normal(x, tri), b = triangle_normal(x, levels_[k][static_cast<size_t>(u)]);
          if (pleat(a, b)) {
            ++count;
            e += pleat_depth(a, b);
          }
        }
      }
    }
    *energy = e;
    return count;
  }

  // Level k's triangles with a corner in `vertices`, sorted.
  std::vector<int32_t> triangles_at(size_t k, const std::vector<int32_t>& vertices) const {
    std::vector<int32_t> out;
    for (int32_t v : vertices) out.insert(out.end(), adjacency_[k].begin(v), adjacency_[k].end(v));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  const std::vector<Triangles>& levels() const { return levels_; }

  // Every level's folded triangles and pleats, counted, and per level the
  // triangles in either marked.
  TangleCount count(const std::vector<Eigen::Vector3d>& x, const std::vector<Eigen::Vector3d>& side,
                    std::vector<std::vector<char>>* marked) const {
    TangleCount out;
    marked->resize(levels_.size());
    for (size_t k = 0; k < levels_.size(); ++k) {
      const FoldCount c = count_by_sides(x, side, levels_[k], neighbours_[k], &(*marked)[k]);
      const bool finest = k + 1 == levels_.size();
      (finest ? out.folded : out.coarser_folded) += c.folded_by_nearest_input;
      (finest ? out.pleats : out.coarser_pleats) += c.pleats;
    }
    return out;
  }

 private:
  const std::vector<Triangles>& levels_;
  const FoldCounter::Sides& side_at_;
  std::vector<LevelAdjacency> adjacency_;
  std::vector<std::vector<std::pair<int32_t, int32_t>>> neighbours_;  // per level, each pair of neighbours once
};

// A point near x[v] where every triangle at v, on every level, faces along
// the sum of its corners' sides. Triangle (v, a, b) does where
// n(p) . r = r . (a x b) + p . (r x (b - a)) > 0, a half-space in p: a small
// linear program finds `deepest`, the point within `reach` of x[v] along
// each axis that is deepest inside all of them (the centre of the largest
// ball in their intersection), and `nearest` is the point of the way there
// nearest x[v] still inside them all by a quarter of that depth. False when
// no point is inside all.
bool fold_free_point(const std::vector<Triangles>& levels, const Judge& judge, const std::vector<Eigen::Vector3d>& x,
                     const std::vector<Eigen::Vector3d>& side, int32_t v, double reach, Eigen::Vector3d* deepest,
                     Eigen::Vector3d* nearest) {
  const size_t vi = static_cast<size_t>(v);
  const Eigen::Vector3d& p0 = x[vi];
  std::vector<Eigen::Vector3d> g;  // per triangle, with p = p0 + d: inside where c + g . d > 0
  std::vector<double> c;
  for (size_t k = 0; k < levels.size(); ++k) {
    const LevelAdjacency& adj = judge.adjacency(k);
    for (auto it = adj.begin(v); it != adj.end(v); ++it) {
      const auto& tri = levels[k][static_cast<size_t>(*it)];
      const int at = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
      const size_t a = static_cast<size_t>(tri[(at + 1) % 3]), b = static_cast<size_t>(tri[(at + 2) % 3]);
      const Eigen::Vector3d r = side[a] + side[b] + side[vi];
      const Eigen::Vector3d pa = x[a] - p0, pb = x[b] - p0;
      const Eigen::Vector3d gi = r.cross(pb - pa);
      if (!(gi.norm() > 1e-12 * (pb - pa).norm())) continue;  // no side to face, or a degenerate edge
      g.push_back(gi);
      c.push_back(r.dot(pa.cross(pb)));
    }
  }
  if (g.empty() || !(reach > 0.0)) return false;
  // Maximize the depth t (the distance inside every half-space) over d in
  // the box. The simplex wants variables >= 0 with 0 feasible: q = d + reach
  // in [0, 2 reach] and s = t + t0, t0 deep enough that c + g . d >= |g| t,
  // that is -g . q + |g| s <= c - reach (g . 1) + |g| t0, has a right-hand
  // side >= 0.
  const Eigen::Index m = static_cast<Eigen::Index>(g.size());
  double t0 = 0.0;
  for (size_t u = 0; u < g.size(); ++u) t0 = std::max(t0, (reach * g[u].sum() - c[u]) / g[u].norm());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m + 4, 4);
  Eigen::VectorXd rhs(m + 4);
  for (Eigen::Index i = 0; i < m; ++i) {
    const size_t u = static_cast<size_t>(i);
    A.block<1, 3>(i, 0) = -g[u].transpose();
    A(i, 3) = g[u].norm();
    rhs(i) = std::max(0.0, c[u] - reach * g[u].sum() + g[u].norm() * t0);
  }
  for (Eigen::Index k = 0; k < 3; ++k) {
    A(m + k, k) = 1.0;
    rhs(m + k) = 2.0 * reach;
  }
  A(m + 3, 3) = 1.0;  // no deeper than the box is wide, which bounds s
  rhs(m + 3) = t0 + 2.0 * reach;
  Eigen::VectorXd objective = Eigen::VectorXd::Zero(4), q;
  objective(3) = 1.0;
  if (!maximize_lp(A, rhs, objective, &q)) return false;
  const double depth = q(3) - t0;
  if (!(depth > 1e-6 * reach)) return false;
  const Eigen::Vector3d d = q.head<3>() - Eigen::Vector3d::Constant(reach);
  double lambda = 0.0;  // c + lambda g . d >= |g| depth / 4 for every triangle
  for (size_t u = 0; u < g.size(); ++u) {
    const double slope = g[u].dot(d);
    if (slope > 0.0) lambda = std::max(lambda, (0.25 * depth * g[u].norm() - c[u]) / slope);
  }
  *deepest = p0 + d;
  *nearest = p0 + std::min(lambda, 1.0) * d;
  return true;
}

// One step of a joint move of the `free` vertices (sorted), with their
// other neighbours held and every corner's side held: each triangle of any
// level at them faces along its corners' summed sides r where
// r . ((b - a) x (c - a)) > 0, which changes by r x (c - b) . d_a with a
// move d_a of corner a (and so on round the triangle). Linearized in the
// moves, these are half-spaces, and a linear program finds the moves within
// reach[i] of each vertex along each axis that take the folded triangles
// inside theirs, by a depth of a twentieth of the largest reach (or as deep
// as they go), while the others keep half their facing, moving the vertices
// least. Sets `to`, the moved positions; false when the program has no
// answer.
bool joint_moves(const Judge& judge, const std::vector<Eigen::Vector3d>& x, const std::vector<Eigen::Vector3d>& side,
                 const std::vector<int32_t>& free, const std::vector<double>& reach,
                 std::vector<Eigen::Vector3d>* to) {
  const size_t nf = free.size();
  auto column = [&](int32_t v) -> Eigen::Index {
    const auto it = std::lower_bound(free.begin(), free.end(), v);
    return it != free.end() && *it == v ? static_cast<Eigen::Index>(it - free.begin()) : -1;
  };
  struct Row {
    std::array<Eigen::Index, 3> col;
    std::array<Eigen::Vector3d, 3> g;
    double slack;  // how far inside now (negative: outside)
    double norm;
    bool tangled;
  };
  std::vector<Row> rows;
  for (size_t k = 0; k < judge.levels().size(); ++k)
    for (int32_t t : judge.triangles_at(k, free)) {
      const auto& tri = judge.levels()[k][static_cast<size_t>(t)];
      const Eigen::Vector3d r = side[static_cast<size_t>(tri[0])] + side[static_cast<size_t>(tri[1])] +
                                side[static_cast<size_t>(tri[2])];
      Row row;
      double squared = 0.0;
      for (int c = 0; c < 3; ++c) {
        row.col[static_cast<size_t>(c)] = column(tri[static_cast<size_t>(c)]);
        const Eigen::Vector3d& next = x[static_cast<size_t>(tri[static_cast<size_t>((c + 1) % 3)])];
        const Eigen::Vector3d& prev = x[static_cast<size_t>(tri[static_cast<size_t>((c + 2) % 3)])];
        row.g[static_cast<size_t>(c)] = row.col[static_cast<size_t>(c)] < 0 ? Eigen::Vector3d::Zero()
                                                                              : Eigen::Vector3d(r.cross(prev - next));
        squared += row.g[static_cast<size_t>(c)].squaredNorm();
      }
      row.norm = std::sqrt(squared);
      if (!(row.norm > 0.0)) continue;
      const double sigma = r.dot(triangle_normal(x, tri));
      row.tangled = folded(x, side, tri);
      row.slack = row.tangled ? sigma : 0.5 * sigma;
      rows.push_back(row);
    }
  if (rows.empty()) return false;
  // Moves d = up - down with up, down in [0, reach] (per axis), and the
  // depth s - t0 of the folded triangles with s >= 0, t0 deep enough that
  // staying put (every variable 0) is feasible. The program reaches the depth `target` (or
  // as deep as it can) first, then moves the vertices least (the sum of |d|
  // over every axis).
  const Eigen::Index n = static_cast<Eigen::Index>(6 * nf + 1), m = static_cast<Eigen::Index>(rows.size());
  double t0 = 0.0, widest = 0.0;
  for (const Row& row : rows)
    if (row.tangled) t0 = std::max(t0, -row.slack / row.norm);
  for (double r : reach) widest = std::max(widest, r);
  const double target = 0.05 * widest;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m + n, n);
  Eigen::VectorXd rhs(m + n);
  for (Eigen::Index i = 0; i < m; ++i) {
    const Row& row = rows[static_cast<size_t>(i)];
    for (size_t c = 0; c < 3; ++c)
      if (row.col[c] >= 0) {
        A.block<1, 3>(i, 6 * row.col[c]) -= row.g[c].transpose();
        A.block<1, 3>(i, 6 * row.col[c] + 3) += row.g[c].transpose();
      }
    A(i, n - 1) = row.tangled ? row.norm : 0.0;
    rhs(i) = std::max(0.0, row.slack + (row.tangled ? row.norm * t0 : 0.0));
  }
  for (Eigen::Index j = 0; j + 1 < n; ++j) {
    A(m + j, j) = 1.0;
    rhs(m + j) = reach[static_cast<size_t>(j / 6)];
  }
  A(m + n - 1, n - 1) = 1.0;
  rhs(m + n - 1) = t0 + target;
  Eigen::VectorXd objective = Eigen::VectorXd::Constant(n, -1.0), q;
  objective(n - 1) = 100.0 * static_cast<double>(n);
  if (!maximize_lp(A, rhs, objective, &q, static_cast<int>(20 * (m + n)))) return false;
  to->resize(nf);
  for (size_t i = 0; i < nf; ++i)
    (*to)[i] = x[static_cast<size_t>(free[i])] + q.segment<3>(static_cast<Eigen::Index>(6 * i)) -
               q.segment<3>(static_cast<Eigen::Index>(6 * i + 3));
  return true;
}

// One call's state: the positions, each vertex's side, the judge and the
// tangled triangles (`marked`, per level), shared by the rounds of single
// moves and the joint moves.
struct Untangler {
  Untangler(const UntangleInput& input, const std::vector<Triangles>& levels_in, const std::vector<char>& fixed_in,
            std::vector<Eigen::Vector3d>* positions, const UntangleOptions& options_in, UntangleReport* report_in)
      : sides(input.mesh()),
        levels(levels_in),
        fixed(fixed_in),
        x(*positions),
        options(options_in),
        report(*report_in),
        n(x.size()),
        judge(input.side_at(), levels, n),
        side_at(judge.side_at()),
        side(side_at.of(x)),
        fine(levels.back()),
        fine_adj(judge.adjacency(levels.size() - 1)),
        component(input.component()),
        occupancy(x) {
    report.before = judge.count(x, side, &marked);
    report.after = report.before;
  }

  std::vector<int32_t> neighbours(int32_t v) const {
    std::vector<int32_t> out;
    for (auto it = fine_adj.begin(v); it != fine_adj.end(v); ++it)
      for (int32_t u : fine[static_cast<size_t>(*it)])
        if (u != v) out.push_back(u);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }
  bool movable(int32_t v) const { return !(static_cast<size_t>(v) < fixed.size() && fixed[static_cast<size_t>(v)]); }
  // Base vertices, which may only hop onto input vertices of their own
  // component (the component of the input vertex nearest them).
  bool hops(int32_t v) const {
    return options.input_vertex_hops > 0 && static_cast<size_t>(v) < fixed.size() &&
           fixed[static_cast<size_t>(v)] == 2;
  }
  // q onto the input's tangent plane near it.
  bool press(const Eigen::Vector3d& q, Eigen::Vector3d* out) const {
    const std::vector<uint32_t> near = side_at.nearest(q, 1);
    if (near.empty()) return false;
    const Eigen::Vector3d& normal = side_at.normal(near[0]);
    *out = q - (q - sides.positions[near[0]]).dot(normal) * normal;
    return true;
  }

  std::vector<int32_t> round_order() const;
  bool candidates(int32_t v, const std::vector<int32_t>& ring, const Eigen::Vector3d& centroid,
                  std::vector<Eigen::Vector3d>* candidates) const;
  bool move_one(int32_t v);
  void run_rounds();
  std::vector<std::vector<int32_t>> tangled_clusters() const;
  size_t move_cluster(const std::vector<int32_t>& cluster);
  size_t joint_phase();

  const TriangleMesh& sides;
  const std::vector<Triangles>& levels;
  const std::vector<char>& fixed;
  std::vector<Eigen::Vector3d>& x;
  const UntangleOptions& options;
  UntangleReport& report;
  const size_t n;
  const Judge judge;
  const FoldCounter::Sides& side_at;
  std::vector<Eigen::Vector3d> side;
  const Triangles& fine;
  const LevelAdjacency& fine_adj;
  const std::vector<int32_t>& component;
  Occupancy occupancy;
  std::vector<std::vector<char>> marked;
};

// The vertices of the tangled triangles of any level, and their neighbours
// on the finest, that may move.
std::vector<int32_t> Untangler::round_order() const {
  std::vector<char> take(n, 0);
  for (size_t k = 0; k < levels.size(); ++k)
    for (size_t t = 0; t < levels[k].size(); ++t)
      if (marked[k][t])
        for (int32_t v : levels[k][t]) take[static_cast<size_t>(v)] = 1;
  std::vector<int32_t> order;
  for (size_t v = 0; v < n; ++v)
    if (take[v]) {
      if (movable(static_cast<int32_t>(v)) || hops(static_cast<int32_t>(v))) order.push_back(static_cast<int32_t>(v));
      for (int32_t u : neighbours(static_cast<int32_t>(v)))
        if (movable(u) || hops(u)) order.push_back(u);
    }
  std::sort(order.begin(), order.end());
  order.erase(std::unique(order.begin(), order.end()), order.end());
  return order;
}

// The places vertex v may move to (UntangleOptions); false when it has
// none to try.
bool Untangler::candidates(int32_t v, const std::vector<int32_t>& ring, const Eigen::Vector3d& centroid,
                           std::vector<Eigen::Vector3d>* out) const {
  std::vector<Eigen::Vector3d>& candidates = *out;
  const Eigen::Vector3d was = x[static_cast<size_t>(v)];
  // Input vertices, each tried once: the searches around v and around its
  // centroid overlap, and a repeat could not win (Choice::offer takes
  // only a better one).
  std::vector<uint32_t> inputs;
  auto add_input = [&](uint32_t i) {
    if (std::find(inputs.begin(), inputs.end(), i) != inputs.end()) return;
    inputs.push_back(i);
    candidates.push_back(sides.positions[i]);
  };
  if (hops(v)) {
    const std::vector<uint32_t> here = side_at.nearest(was, 1);
    if (here.empty()) return false;
    for (const Eigen::Vector3d& around : {was, centroid})
      for (uint32_t i : side_at.nearest(around, options.input_vertex_hops))
        if (component[i] == component[here[0]]) add_input(i);
    return true;
  }
  auto add_pressed = [&](const Eigen::Vector3d& q) {
    Eigen::Vector3d pressed;
    if (press(q, &pressed)) candidates.push_back(pressed);
  };
  for (double w : {1.0, 0.5, 0.25}) {
    const Eigen::Vector3d q = was + w * (centroid - was);
    candidates.push_back(q);
    add_pressed(q);
  }
  for (uint32_t i : side_at.nearest(centroid, options.input_candidates)) add_input(i);
  if (options.wide_candidates > 0)
    for (const Eigen::Vector3d& around : {was, centroid})
      for (uint32_t i : side_at.nearest(around, options.wide_candidates)) add_input(i);
  for (int32_t u : ring)
    for (double w : {0.5, 0.8}) candidates.push_back(was + w * (x[static_cast<size_t>(u)] - was));
  // And, if there is one within half the ring's mean edge, a point where
  // every triangle at v faces out (v's side taken as it is now): pressed
  // onto the input's tangent plane first, then as found.
  double reach = 0.0;
  for (int32_t u : ring) reach += (x[static_cast<size_t>(u)] - was).norm();
  reach *= 0.5 / static_cast<double>(ring.size());
  Eigen::Vector3d deepest, nearest;
  if (fold_free_point(levels, judge, x, side, v, reach, &deepest, &nearest))
    for (const Eigen::Vector3d& q : {nearest, deepest}) {
      add_pressed(q);
      candidates.push_back(q);
    }
  return true;
}

// Vertex v to the candidate leaving the fewest tangles around it (or as
// many, less deep); true when that is better than where it was.
bool Untangler::move_one(int32_t v) {
  const size_t vi = static_cast<size_t>(v);
  double e_now = 0.0;
  const size_t now = judge.around(x, side, v, &e_now);
  if (now == 0) return false;
  const std::vector<int32_t> ring = neighbours(v);
  if (ring.empty()) return false;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int32_t u : ring) centroid += x[static_cast<size_t>(u)];
  centroid /= static_cast<double>(ring.size());
  const Eigen::Vector3d was = x[vi], side_was = side[vi];
  std::vector<Eigen::Vector3d> tries;
  if (!candidates(v, ring, centroid, &tries)) return false;
  Choice best{now, e_now};
  Eigen::Vector3d best_at = was, best_side = side_was;
  for (const Eigen::Vector3d& q : tries) {
    if (q != was && occupancy.taken(q)) continue;
    x[vi] = q;
    side[vi] = side_at(q);
    double e = 0.0;
    const size_t c = judge.around(x, side, v, &e);
    if (best.offer(c, e)) {
      best_at = q;
      best_side = side[vi];
    }
  }
  const bool better = best.count < now || best.energy < e_now;
  occupancy.move(was, best_at);
  x[vi] = best_at;
  side[vi] = best_side;
  return better;
}

void Untangler::run_rounds() {
  for (int round = 0; round < options.rounds; ++round) {
    size_t moved = 0;
    for (int32_t v : round_order()) moved += move_one(v);
    report.moved += moved;
    ++report.rounds;
    report.after = judge.count(x, side, &marked);
    if (moved == 0) break;
  }
}

// The vertices of the tangled triangles, joined through them (any level)
// into clusters.
std::vector<std::vector<int32_t>> Untangler::tangled_clusters() const {
  std::vector<int32_t> parent(n);
  for (size_t v = 0; v < n; ++v) parent[v] = static_cast<int32_t>(v);
  auto find = [&](int32_t v) {
    while (parent[static_cast<size_t>(v)] != v)
      v = parent[static_cast<size_t>(v)] = parent[static_cast<size_t>(parent[static_cast<size_t>(v)])];
    return v;
  };
  std::vector<char> tangled(n, 0);
  for (size_t k = 0; k < levels.size(); ++k)
    for (size_t t = 0; t < levels[k].size(); ++t)
      if (marked[k][t]) {
        const auto& tri = levels[k][t];
        for (int32_t v : tri) tangled[static_cast<size_t>(v)] = 1;
        const int32_t a = find(tri[0]);
        for (int c = 1; c < 3; ++c) {
          const int32_t b = find(tri[static_cast<size_t>(c)]);
          if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
        }
      }
  std::vector<std::vector<int32_t>> clusters;
  std::unordered_map<int32_t, size_t> cluster_of;
  for (size_t v = 0; v < n; ++v)
    if (tangled[v]) {
      const auto [it, fresh] = cluster_of.emplace(find(static_cast<int32_t>(v)), clusters.size());
      if (fresh) clusters.emplace_back();
      clusters[it->second].push_back(static_cast<int32_t>(v));
    }
  return clusters;
}

// One cluster, grown by its finest ring, moved together step by step;
// returns the steps kept.
size_t Untangler::move_cluster(const std::vector<int32_t>& cluster) {
  size_t kept = 0;
  std::vector<int32_t> free;
  for (int32_t v : cluster) {
    if (movable(v)) free.push_back(v);
    for (int32_t u : neighbours(v))
      if (movable(u)) free.push_back(u);
  }
  std::sort(free.begin(), free.end());
  free.erase(std::unique(free.begin(), free.end()), free.end());
  if (free.empty() || free.size() > options.joint_vertices) return 0;
  std::vector<double> reach(free.size(), 0.0);
  for (size_t i = 0; i < free.size(); ++i) {
    const std::vector<int32_t> ring = neighbours(free[i]);
    for (int32_t u : ring) reach[i] += (x[static_cast<size_t>(u)] - x[static_cast<size_t>(free[i])]).norm();
    reach[i] *= 0.5 / static_cast<double>(std::max<size_t>(ring.size(), 1));
  }
  // A trust region: the reach halves when a step is not kept (the
  // linearization holds better for smaller moves) and doubles back
  // when one is.
  double scale = 1.0;
  for (int step = 0; step < 12 && scale > 0.07; ++step) {
    double e_now = 0.0;
    const size_t now = judge.region(x, side, free, &e_now);
    if (now == 0) break;
    std::vector<Eigen::Vector3d> to;
    std::vector<double> scaled = reach;
    for (double& r : scaled) r *= scale;
    if (!joint_moves(judge, x, side, free, scaled, &to)) break;
    std::vector<Eigen::Vector3d> was(free.size()), side_was(free.size());
    for (size_t i = 0; i < free.size(); ++i) {
      was[i] = x[static_cast<size_t>(free[i])];
      side_was[i] = side[static_cast<size_t>(free[i])];
    }
    Choice best{now, e_now, 0.99};  // kept if it leaves fewer, or as many a little less deep: the next step goes on
    std::vector<Eigen::Vector3d> best_at;
    // The moves whole and in part (the linearization holds for small
    // ones), each as found and pressed onto the input's tangent plane.
    std::vector<std::vector<Eigen::Vector3d>> tries;
    for (double w : {1.0, 0.5, 0.25, 0.125}) {
      tries.push_back(to);
      for (size_t i = 0; i < free.size(); ++i) tries.back()[i] = was[i] + w * (to[i] - was[i]);
    }
    for (const auto& found : tries)
      for (bool pressed : {true, false}) {
        std::vector<Eigen::Vector3d> at = found;
        bool ok = true;
        for (size_t i = 0; i < free.size() && ok; ++i) {
          if (pressed) ok = press(found[i], &at[i]);
          ok = ok && (at[i] == was[i] || !occupancy.taken(at[i]));
        }
        if (!ok) continue;
        for (size_t i = 0; i < free.size(); ++i) {
          x[static_cast<size_t>(free[i])] = at[i];
          side[static_cast<size_t>(free[i])] = side_at(at[i]);
        }
        double e = 0.0;
        const size_t c = judge.region(x, side, free, &e);
        if (best.offer(c, e)) best_at = at;
        for (size_t i = 0; i < free.size(); ++i) {
          x[static_cast<size_t>(free[i])] = was[i];
          side[static_cast<size_t>(free[i])] = side_was[i];
        }
      }
    if (best_at.empty()) {
      scale *= 0.5;
      continue;
    }
    scale = std::min(1.0, 2.0 * scale);
    for (size_t i = 0; i < free.size(); ++i) {
      occupancy.move(was[i], best_at[i]);
      x[static_cast<size_t>(free[i])] = best_at[i];
      side[static_cast<size_t>(free[i])] = side_at(best_at[i]);
    }
    ++kept;
  }
  return kept;
}

// Joint moves, where single moves have stopped.
size_t Untangler::joint_phase() {
  size_t kept = 0;
  for (const std::vector<int32_t>& cluster : tangled_clusters()) kept += move_cluster(cluster);
  report.after = judge.count(x, side, &marked);
  return kept;
}

}  // namespace

UntangleInput::UntangleInput(const TriangleMesh& sides)
    : mesh_(sides), side_at_(sides), component_(vertex_components(sides.positions.size(), sides.triangles)) {}

UntangleReport untangle(const TriangleMesh& sides, const std::vector<Triangles>& levels, const std::vector<char>& fixed,
                        std::vector<Eigen::Vector3d>* positions, const UntangleOptions& options) {
  if (levels.empty() || levels.back().empty() || sides.positions.empty() || sides.triangles.empty()) return {};
  return untangle(UntangleInput(sides), levels, fixed, positions, options);
}

UntangleReport untangle(const UntangleInput& input, const std::vector<Triangles>& levels,
                        const std::vector<char>& fixed, std::vector<Eigen::Vector3d>* positions,
                        const UntangleOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  UntangleReport report;
  const TriangleMesh& sides = input.mesh();
  if (levels.empty() || levels.back().empty() || sides.positions.empty() || sides.triangles.empty()) return report;
  Untangler untangler(input, levels, fixed, positions, options, &report);
  untangler.run_rounds();
  for (int pass = 0; pass < 2; ++pass) {
    const size_t kept = untangler.joint_phase();
    report.joint_moved += kept;
    if (kept == 0) break;
    untangler.run_rounds();
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

std::vector<TangledPlace> tangled_places(const UntangleInput& sides, const std::vector<Triangles>& levels,
                                         const std::vector<Eigen::Vector3d>& x, double reach) {
  struct Tangle {
    Eigen::Vector3d at;
    bool finest, fold;
  };
  std::vector<Tangle> tangles;
  const std::vector<Eigen::Vector3d> side = sides.side_at().of(x);
  for (size_t k = 0; k < levels.size(); ++k) {
    const Triangles& level = levels[k];
    const bool finest = k + 1 == levels.size();
    auto centroid = [&](size_t t) {
      return Eigen::Vector3d((x[static_cast<size_t>(level[t][0])] + x[static_cast<size_t>(level[t][1])] +
                              x[static_cast<size_t>(level[t][2])]) / 3.0);
    };
    for (size_t t = 0; t < level.size(); ++t)
      if (folded(x, side, level[t])) tangles.push_back({centroid(t), finest, true});
    const std::vector<std::array<int32_t, 3>> across = triangles_across(level);
    for (size_t t = 0; t < level.size(); ++t)
      for (int32_t u : across[t])  // each pair once, from its lower triangle (as Judge::count)
        if (u > static_cast<int32_t>(t) &&
            pleat(triangle_normal(x, level[t]), triangle_normal(x, level[static_cast<size_t>(u)])))
          tangles.push_back({0.5 * (centroid(t) + centroid(static_cast<size_t>(u))), finest, false});
  }
  if (tangles.empty()) return {};
  // Single linkage by union-find over the pairs within reach.
  std::vector<size_t> parent(tangles.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto root = [&](size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<Eigen::Vector3d> points;
  for (const Tangle& t : tangles) points.push_back(t.at);
  const PointCloud cloud{points};
  PointTree tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  tree.buildIndex();
  std::vector<std::pair<uint32_t, double>> near;
  for (size_t i = 0; i < points.size(); ++i) {
    tree.radiusSearch(points[i].data(), reach * reach, near, nanoflann::SearchParams());
    for (const auto& [j, d2] : near) parent[root(j)] = root(i);
  }
  std::vector<TangledPlace> places;
  std::vector<int32_t> place_of(tangles.size(), -1);
  std::vector<size_t> members;
  for (size_t i = 0; i < tangles.size(); ++i) {
    int32_t& p = place_of[root(i)];
    if (p < 0) {
      p = static_cast<int32_t>(places.size());
      places.emplace_back();
      members.push_back(0);
    }
    TangledPlace& place = places[static_cast<size_t>(p)];
    place.centre += tangles[i].at;
    ++members[static_cast<size_t>(p)];
    TangleCount& c = place.count;
    ++(tangles[i].fold ? (tangles[i].finest ? c.folded : c.coarser_folded)
                       : (tangles[i].finest ? c.pleats : c.coarser_pleats));
  }
  for (size_t p = 0; p < places.size(); ++p) places[p].centre /= static_cast<double>(members[p]);
  for (size_t i = 0; i < tangles.size(); ++i) {
    TangledPlace& place = places[static_cast<size_t>(place_of[root(i)])];
    place.radius = std::max(place.radius, (tangles[i].at - place.centre).norm());
  }
  std::sort(places.begin(), places.end(), [&](const TangledPlace& a, const TangledPlace& b) {
    if (a.count.total() != b.count.total()) return a.count.total() > b.count.total();
    return std::lexicographical_compare(a.centre.data(), a.centre.data() + 3, b.centre.data(), b.centre.data() + 3);
  });
  return places;
}

}  // namespace srcodec
