#include "remesh/disk_map.h"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "remesh/adjacency.h"

namespace srcodec {

std::vector<int32_t> disk_boundary_loop(size_t n, const std::vector<std::array<int32_t, 3>>& triangles) {
  // Directed edges, sorted by their undirected key: an interior edge shows
  // up once each way, a boundary edge once.
  struct Directed {
    int32_t low, high, from, to;
  };
  std::vector<Directed> directed;
  directed.reserve(3 * triangles.size());
  std::vector<char> used(n, 0);
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) {
      const int32_t a = t[c], b = t[(c + 1) % 3];
      if (a == b || a < 0 || b < 0 || static_cast<size_t>(a) >= n || static_cast<size_t>(b) >= n) return {};
      const auto [low, high] = std::minmax(a, b);
      directed.push_back({low, high, a, b});
      used[a] = 1;
    }
  std::sort(directed.begin(), directed.end(),
            [](const Directed& x, const Directed& y) { return std::tie(x.low, x.high) < std::tie(y.low, y.high); });
  std::vector<int32_t> next(n, -1);
  size_t boundary_edges = 0, edges = 0;
  for (size_t j = 0; j < directed.size();) {
    size_t k = j + 1;
    while (k < directed.size() && directed[k].low == directed[j].low && directed[k].high == directed[j].high) ++k;
    ++edges;
    if (k - j == 2) {
      if (directed[j].from == directed[j + 1].from) return {};  // the two triangles disagree on orientation
    } else if (k - j == 1) {
      if (next[directed[j].from] >= 0) return {};  // two boundary edges leave one vertex: pinched
      next[directed[j].from] = directed[j].to;
      ++boundary_edges;
    } else {
      return {};  // an edge of three or more triangles
    }
    j = k;
  }
  if (boundary_edges == 0) return {};
  std::vector<int32_t> loop;
  int32_t start = -1;
  for (size_t v = 0; v < n && start < 0; ++v)
    if (next[v] >= 0) start = static_cast<int32_t>(v);
  for (int32_t v = start; loop.size() <= boundary_edges;) {
    loop.push_back(v);
    v = next[v];
    if (v < 0) return {};
    if (v == start) break;
  }
  if (loop.size() != boundary_edges) return {};  // more than one loop
  const long long vertices = std::count(used.begin(), used.end(), 1);
  if (vertices - static_cast<long long>(edges) + static_cast<long long>(triangles.size()) != 1) return {};
  return loop;
}

bool convex_combination_map(size_t n, const std::vector<std::array<int32_t, 3>>& triangles,
                            const std::vector<Eigen::Vector3d>* positions, const std::vector<char>& fixed,
                            std::vector<Eigen::Vector2d>& uv) {
  uv.resize(n, Eigen::Vector2d::Zero());
  std::vector<int32_t> row(n, -1);
  int32_t free_count = 0;
  for (size_t v = 0; v < n; ++v)
    if (!fixed[v]) row[v] = free_count++;
  if (free_count == 0) return true;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(free_count, 2);
  std::vector<double> diagonal(free_count, 0.0);
  const Adjacency neighbors = vertex_neighbors(n, triangles);
  for (int32_t a = 0; a < static_cast<int32_t>(n); ++a)
    for (const int32_t* nb = neighbors.begin(a); nb != neighbors.end(a); ++nb) {
      const int32_t b = *nb;
      if (b < a) continue;  // each edge once, as (a, b) with a < b
      double w = 1.0;
      if (positions) {
        const double length = ((*positions)[a] - (*positions)[b]).norm();
        w = 1.0 / std::max(length, 1e-12);
      }
      const int32_t ra = row[a], rb = row[b];
      if (ra >= 0) diagonal[ra] += w;
      if (rb >= 0) diagonal[rb] += w;
      if (ra >= 0 && rb >= 0) {
        entries.emplace_back(ra, rb, -w);
        entries.emplace_back(rb, ra, -w);
      } else if (ra >= 0) {
        rhs.row(ra) += w * uv[b].transpose();
      } else if (rb >= 0) {
        rhs.row(rb) += w * uv[a].transpose();
      }
    }
  for (int32_t r = 0; r < free_count; ++r) entries.emplace_back(r, r, diagonal[r]);
  Eigen::SparseMatrix<double> m(free_count, free_count);
  m.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(m);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::MatrixX2d x = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !x.allFinite()) return false;
  for (size_t v = 0; v < n; ++v)
    if (row[v] >= 0) uv[v] = x.row(row[v]).transpose();
  return true;
}

size_t untangle_planar(size_t n, const std::vector<std::array<int32_t, 3>>& triangles, const std::vector<char>& fixed,
                       std::vector<Eigen::Vector2d>& uv, int passes) {
  // Per vertex, the triangles around it (a vertex's opposite edge in each
  // triangle, in the triangle's order, must have it on its left).
  const Adjacency around = vertex_triangles(n, triangles);
  auto flipped = [&](int32_t t) {
    const auto& tri = triangles[t];
    return !(signed_area2(uv[tri[0]], uv[tri[1]], uv[tri[2]]) > 0.0);
  };
  struct Line {
    Eigen::Vector2d normal;  // unit, pointing to the allowed side
    double offset;           // normal . x >= offset on the allowed side
  };
  std::vector<Line> lines;
  std::vector<char> queued(n, 0);
  size_t left = 0;
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<int32_t> todo;
    for (size_t t = 0; t < triangles.size(); ++t)
      if (flipped(static_cast<int32_t>(t)))
        for (int32_t v : triangles[t])
          if (!fixed[v] && !queued[v]) {
            queued[v] = 1;
            todo.push_back(v);
          }
    for (int32_t v : todo) queued[v] = 0;
    if (todo.empty()) return 0;
    std::sort(todo.begin(), todo.end());
    for (int32_t v : todo) {
      lines.clear();
      for (const int32_t* t = around.begin(v); t != around.end(v); ++t) {
        const auto& tri = triangles[*t];
        const int c = tri[0] == v ? 0 : tri[1] == v ? 1 : 2;
        const Eigen::Vector2d &a = uv[tri[(c + 1) % 3]], &b = uv[tri[(c + 2) % 3]];
        const Eigen::Vector2d d = b - a;
        const double length = d.norm();
        if (!(length > 0.0)) continue;
        const Eigen::Vector2d normal(-d.y() / length, d.x() / length);
        lines.push_back({normal, normal.dot(a)});
      }
      // The point maximizing the smallest margin normal . x - offset: a
      // linear program in (x, y, margin) whose optimum lies where three
      // margins are equal.
      double best = -std::numeric_limits<double>::infinity();
      Eigen::Vector2d best_x = uv[v];
      for (size_t i = 0; i < lines.size(); ++i)
        for (size_t j = i + 1; j < lines.size(); ++j)
          for (size_t k = j + 1; k < lines.size(); ++k) {
            Eigen::Matrix3d m;
            Eigen::Vector3d rhs;
            const Line* l[3] = {&lines[i], &lines[j], &lines[k]};
            for (int r = 0; r < 3; ++r) {
              m.row(r) << l[r]->normal.x(), l[r]->normal.y(), -1.0;
              rhs[r] = l[r]->offset;
            }
            const double det = m.determinant();
            if (!(std::abs(det) > 1e-12)) continue;
            const Eigen::Vector3d s = m.inverse() * rhs;
            double margin = std::numeric_limits<double>::infinity();
            for (const Line& line : lines) margin = std::min(margin, line.normal.dot(s.head<2>()) - line.offset);
            if (margin > best) {
              best = margin;
              best_x = s.head<2>();
            }
          }
      double now = std::numeric_limits<double>::infinity();
      for (const Line& line : lines) now = std::min(now, line.normal.dot(uv[v]) - line.offset);
      if (best > now) uv[v] = best_x;
    }
  }
  for (size_t t = 0; t < triangles.size(); ++t) left += flipped(static_cast<int32_t>(t));
  return left;
}

PlanarLocator::PlanarLocator(const std::vector<Eigen::Vector2d>& uv,
                             const std::vector<std::array<int32_t, 3>>& triangles)
    : uv_(uv), triangles_(triangles) {
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  lo_ = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  for (const auto& t : triangles)
    for (int32_t v : t) {
      lo_ = lo_.cwiseMin(uv[v]);
      hi = hi.cwiseMax(uv[v]);
    }
  if (triangles.empty()) {
    lo_.setZero();
    hi.setOnes();
  }
  side_ = std::max<int32_t>(1, static_cast<int32_t>(std::sqrt(static_cast<double>(triangles.size()) / 2.0)));
  cell_size_ = std::max((hi - lo_).maxCoeff() / side_, 1e-300);
  std::vector<std::pair<int32_t, int32_t>> cell_triangle;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Eigen::Vector2d a = uv[tri[0]].cwiseMin(uv[tri[1]]).cwiseMin(uv[tri[2]]);
    const Eigen::Vector2d b = uv[tri[0]].cwiseMax(uv[tri[1]]).cwiseMax(uv[tri[2]]);
    for (int32_t y = cell(a.y(), lo_.y(), cell_size_); y <= cell(b.y(), lo_.y(), cell_size_); ++y)
      for (int32_t x = cell(a.x(), lo_.x(), cell_size_); x <= cell(b.x(), lo_.x(), cell_size_); ++x)
        cell_triangle.emplace_back(y * side_ + x, static_cast<int32_t>(t));
  }
  std::sort(cell_triangle.begin(), cell_triangle.end());
  offsets_.assign(static_cast<size_t>(side_) * side_ + 1, 0);
  for (const auto& [c, t] : cell_triangle) ++offsets_[c + 1];
  for (size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
  items_.reserve(cell_triangle.size());
  for (const auto& [c, t] : cell_triangle) items_.push_back(t);
}

int32_t PlanarLocator::cell(double x, double lo, double size) const {
  const double c = std::floor((x - lo) / size);
  return static_cast<int32_t>(std::clamp(c, 0.0, static_cast<double>(side_ - 1)));
}

int32_t PlanarLocator::locate(const Eigen::Vector2d& p, Eigen::Vector3d* bary) const {
  const int32_t c = cell(p.y(), lo_.y(), cell_size_) * side_ + cell(p.x(), lo_.x(), cell_size_);
  double best = -std::numeric_limits<double>::infinity();
  int32_t found = -1;
  for (int32_t j = offsets_[c]; j < offsets_[c + 1]; ++j) {
    const auto& tri = triangles_[items_[j]];
    const Eigen::Vector2d &a = uv_[tri[0]], &b = uv_[tri[1]], &d = uv_[tri[2]];
    const double area = signed_area2(a, b, d);
    if (!(area > 0.0)) continue;
    const Eigen::Vector3d w(signed_area2(p, b, d) / area, signed_area2(a, p, d) / area, signed_area2(a, b, p) / area);
    if (w.minCoeff() > best) {
      best = w.minCoeff();
      found = items_[j];
      *bary = w;
      if (best >= 0.0) break;
    }
  }
  return found;
}

}  // namespace srcodec
