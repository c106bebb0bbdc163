// Where a new vertex starts (Kammoun, Payan, Antonini §III-B, Fig. 4b-c):
// at the free input vertex nearest its parent edge's midpoint, so that every
// site stays on an input vertex as Eq. 2 wants. Where the input is too
// sparse for that (ours), on the input surface between its vertices or at
// the chord's midpoint, points added to the input's and marked off it.
#include "remesh/refiner.h"

namespace srcodec {

Eigen::Vector3d Refiner::on_base(const ParamPoint& p) const {
  const auto& t = base_.mesh.triangles[p.face];
  return p.bary[0] * base_.mesh.positions[t[0]] + p.bary[1] * base_.mesh.positions[t[1]] +
         p.bary[2] * base_.mesh.positions[t[2]];
}

std::vector<Eigen::Vector3d> Refiner::embed() const {
  std::vector<Eigen::Vector3d> out(input_.positions.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = on_base(param_[i]);
  return out;
}

void Refiner::build_face_points() {
  const size_t faces = base_.mesh.triangles.size();
  face_points_.offsets.assign(faces + 1, 0);
  for (const ParamPoint& p : base_.param) ++face_points_.offsets[p.face + 1];
  for (size_t f = 0; f < faces; ++f) face_points_.offsets[f + 1] += face_points_.offsets[f];
  std::vector<int32_t> fill(face_points_.offsets.begin(), face_points_.offsets.end() - 1);
  face_points_.items.resize(base_.param.size());
  for (size_t i = 0; i < base_.param.size(); ++i)
    face_points_.items[fill[param_[i].face]++] = static_cast<int32_t>(i);
}

bool Refiner::near_face(int32_t face, int32_t other) const {
  if (face == other) return true;
  for (int32_t c : base_.mesh.triangles[face])
    for (const int32_t* f = base_vertex_faces_.begin(c); f != base_vertex_faces_.end(c); ++f)
      if (*f == other) return true;
  return false;
}

Status Refiner::place_new_vertex(int32_t v) {
  const ParamPoint p = h_.nominal_param(v);
  const auto edge = h_.parent_edge(v);
  const Eigen::Vector3d a = points_[anchor_[edge[0]]], b = points_[anchor_[edge[1]]];  // copies: add_point may grow points_
  const Eigen::Vector3d midpoint = 0.5 * (a + b);
  const double edge_length = (a - b).norm();
  const Eigen::Vector3d side = normals_[anchor_[edge[0]]] + normals_[anchor_[edge[1]]];
  if (side.norm() > 0.0) {
    const Eigen::Vector3d axis = side.normalized();
    constexpr size_t kNear = 64;
    std::array<uint32_t, kNear> idx{};
    std::array<double, kNear> dist{};
    const size_t k = input_tree_.knnSearch(midpoint.data(), kNear, idx.data(), dist.data());
    int32_t best = -1;
    double best_d = kSparseFraction * edge_length;
    for (size_t j = 0; j < k; ++j) {
      const int32_t i = static_cast<int32_t>(idx[j]);
      // Free, of the site's kind, on the same part of the base domain and
      // on the same sheet (facing along the edge).
      if (site_of_[i] >= 0 || !allowed(v, i) || !near_face(p.face, param_[i].face) || !(normals_[i].dot(side) > 0.0))
        continue;
      const Eigen::Vector3d off = points_[i] - midpoint;
      const double along = off.dot(axis);
      const double across = (off - along * axis).norm();
      if (std::abs(along) < edge_length && across <= best_d && (across < best_d || i < best)) {
        best_d = across;
        best = i;
      }
    }
    if (best >= 0) return take(v, best);
  }
  // Else among the kInit free vertices nearest v's dyadic point on the base
  // domain, the one nearest in space to the edge's midpoint. The domain
  // picks the right sheet of the surface; space corrects the
  // parameterization's stretch.
  constexpr size_t kInit = 8;
  const Eigen::Vector3d target = on_base(p);
  for (size_t k : {64, 512, 4096}) {
    k = std::min(k, embedded_.size());
    std::vector<uint32_t> idx(k);
    std::vector<double> dist(k);
    k = tree_.knnSearch(target.data(), k, idx.data(), dist.data());
    int32_t best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    size_t seen = 0;
    for (size_t j = 0; j < k && seen < kInit; ++j) {
      const int32_t i = static_cast<int32_t>(idx[j]);
      if (site_of_[i] >= 0 || !allowed(v, i) || !near_face(p.face, param_[i].face)) continue;
      ++seen;
      const double d = (points_[i] - midpoint).squaredNorm();
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    if (best >= 0) {
      // Where the input is sparse, its nearest free vertex is far from the
      // edge: the new vertex goes to the input surface point nearest the
      // edge's midpoint instead (a forced split would otherwise stack
      // vertices and fold the mesh).
      if (!site_on_boundary_[v] && !keeps_to_crease(v) && std::sqrt(best_d) > kSparseFraction * edge_length) {
        const int32_t on_surface = surface_point(midpoint, p.face, best_d);
        if (on_surface >= 0) {
          ++surface_vertices_;
          return take(v, on_surface);
        }
      }
      return take(v, best);
    }
    if (k == embedded_.size()) break;
  }
  // The nearest points are all taken (the parameterization crowds them
  // elsewhere): widen ring by ring over the base faces around `face`.
  std::vector<int32_t> ring{p.face}, next;
  std::vector<char> seen(base_.mesh.triangles.size(), 0);
  seen[p.face] = 1;
  // Three rings out, a point is no longer near the edge: stop there rather
  // than scan the whole component for every vertex.
  for (int rings = 0; rings < 3 && !ring.empty(); ++rings) {
    int32_t best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (int32_t f : ring)
      for (const int32_t* i = face_points_.begin(f); i != face_points_.end(f); ++i) {
        const double d = (embedded_[*i] - target).squaredNorm();
        if (site_of_[*i] < 0 && allowed(v, *i) && (d < best_d || (d == best_d && *i < best))) {
          best_d = d;
          best = *i;
        }
      }
    if (best >= 0) return take(v, best);
    next.clear();
    for (int32_t f : ring)
      for (int32_t c : base_.mesh.triangles[f])
        for (const int32_t* g = base_vertex_faces_.begin(c); g != base_vertex_faces_.end(c); ++g)
          if (!seen[*g]) {
            seen[*g] = 1;
            next.push_back(*g);
          }
    ring.swap(next);
  }
  // No input vertex is left near the edge: the input is locally too coarse
  // for this level. The new vertex goes to its parent edge's midpoint, a
  // point that is not an input vertex (counted in the level report).
  Eigen::Vector3d normal = normals_[anchor_[edge[0]]] + normals_[anchor_[edge[1]]];
  if (normal.norm() > 0.0) normal.normalize();
  // On the boundary: halfway along the input's boundary between the
  // edge's ends (the chord's midpoint when they are neighbours on it); on a
  // crease, halfway along the crease.
  Eigen::Vector3d x = midpoint;
  double place = 0.0;
  const bool on_rim = site_on_boundary_[v] && rim_prev_[v] >= 0 && rim_next_[v] >= 0 &&
                      rim_middle(rim_prev_[v], rim_next_[v], &x, &place);
  int32_t curve = -1;
  const bool on_crease = keeps_to_crease(v) && site_crease_degree_[v] == 2 &&
                         crease_middle(site_crease_ends_[v][0], site_crease_ends_[v][1], &x, &curve, &place);
  const int32_t i =
      add_point(x, p, normal, site_on_boundary_[v], on_rim ? loop_[anchor_[rim_prev_[v]]] : -1, place);
  if (on_crease) {
    point_crease_[i] = 1;
    curve_[i] = curve;
    curve_pos_[i] = place;
  }
  ++midpoint_vertices_;
  return take(v, i);
}

Refiner::SurfacePoint Refiner::nearest_on_surface(const Eigen::Vector3d& x, int32_t face, double bound,
                                                  const Eigen::Vector3d& side) const {
  constexpr size_t kNear = 8;
  std::array<uint32_t, kNear> idx{};
  std::array<double, kNear> dist{};
  const size_t k = input_tree_.knnSearch(x.data(), kNear, idx.data(), dist.data());
  SurfacePoint out;
  int32_t best_triangle = -1;
  for (size_t j = 0; j < k; ++j) {
    const int32_t i = static_cast<int32_t>(idx[j]);
    if (input_on_boundary_[i] || !near_face(face, param_[i].face)) continue;
    for (const int32_t* t = input_around_.begin(i); t != input_around_.end(i); ++t) {
      const auto& tri = input_.triangles[*t];
      if (!(side.dot((points_[tri[1]] - points_[tri[0]]).cross(points_[tri[2]] - points_[tri[0]])) >= 0.0)) continue;
      const Eigen::Vector3d q = closest_on_triangle(x, points_[tri[0]], points_[tri[1]], points_[tri[2]]);
      const double d = (q - x).squaredNorm();
      if (d < bound) {
        bound = d;
        out.x = q;
        best_triangle = *t;
        out.vertex = i;
      }
    }
  }
  if (best_triangle < 0) return out;
  const auto& tri = input_.triangles[best_triangle];
  out.normal = (points_[tri[1]] - points_[tri[0]]).cross(points_[tri[2]] - points_[tri[0]]);
  if (out.normal.norm() > 0.0) out.normal.normalize();
  return out;
}

Refiner::SurfacePoint Refiner::nearest_on_boundary(const Eigen::Vector3d& x, int32_t face, int32_t site) const {
  auto on_arc = [&](int32_t i) {
    return site < 0 || on_rim_arc(site, i) || (rim_prev_[site] >= 0 && i == anchor_[rim_prev_[site]]) ||
           (rim_next_[site] >= 0 && i == anchor_[rim_next_[site]]);
  };
  constexpr size_t kNear = 16;
  std::array<uint32_t, kNear> idx{};
  std::array<double, kNear> dist{};
  const size_t k = input_tree_.knnSearch(x.data(), kNear, idx.data(), dist.data());
  SurfacePoint out;
  double bound = std::numeric_limits<double>::infinity();
  for (size_t j = 0; j < k; ++j) {
    const int32_t i = static_cast<int32_t>(idx[j]);
    if (!input_on_boundary_[i] || !near_face(face, param_[i].face)) continue;
    for (const int32_t* t = input_around_.begin(i); t != input_around_.end(i); ++t)
      for (int32_t other : input_.triangles[*t]) {
        if (other == i || !input_on_boundary_[other] ||
            triangles_on_edge(input_around_, input_.triangles, i, other) != 1 || !on_arc(i) || !on_arc(other))
          continue;
        const Eigen::Vector3d &a = points_[i], &b = points_[other];
        const double len2 = (b - a).squaredNorm();
        const double along = len2 > 0.0 ? std::clamp((x - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
        const Eigen::Vector3d q = a + along * (b - a);
        const double d = (q - x).squaredNorm();
        if (d < bound) {
          bound = d;
          out.x = q;
          out.vertex = along < 0.5 ? i : other;
          out.normal = normals_[out.vertex];
          out.loop = -1;
          const int32_t loop = loop_[i];
          if (loop >= 0 && loop_[other] == loop) {  // neighbours along the loop, one way or the other
            const double size = static_cast<double>(loop_walk_[loop].size());
            const bool forward = along_loop(i, other) == 1.0;
            out.loop = loop;
            out.loop_pos = forward ? loop_pos_[i] + along : std::fmod(loop_pos_[other] + 1.0 - along, size);
            if (out.loop_pos >= size) out.loop_pos -= size;
          }
        }
      }
  }
  return out;
}

int32_t Refiner::surface_point(const Eigen::Vector3d& x, int32_t face, double bound) {
  const SurfacePoint q = nearest_on_surface(x, face, bound);
  if (q.vertex < 0) return -1;
  return add_point(q.x, param_[q.vertex], q.normal, 0);
}

Status Refiner::take(int32_t v, int32_t i) {
  anchor_[v] = i;
  site_of_[i] = v;
  return ok_status();
}

void Refiner::move_site(int32_t s, int32_t i) {
  site_of_[anchor_[s]] = -1;
  anchor_[s] = i;
  site_of_[i] = s;
}

int32_t Refiner::nearest_input_vertex(int32_t a) const {
  if (a < static_cast<int32_t>(input_.positions.size())) return a;
  uint32_t nearest = 0;
  double d2 = 0.0;
  input_tree_.knnSearch(points_[a].data(), 1, &nearest, &d2);
  return static_cast<int32_t>(nearest);
}

int32_t Refiner::add_point(const Eigen::Vector3d& x, const ParamPoint& p, const Eigen::Vector3d& normal, char boundary,
                           int32_t loop, double place) {
  points_.push_back(x);
  param_.push_back(p);
  density_.push_back(0.0);
  normals_.push_back(normal);
  site_of_.push_back(-1);
  input_on_boundary_.push_back(boundary);
  loop_.push_back(loop);
  loop_pos_.push_back(place);
  if (has_creases_) {  // off the creases unless the caller puts it on one
    point_crease_.push_back(0);
    curve_.push_back(-1);
    curve_pos_.push_back(0.0);
  }
  return static_cast<int32_t>(points_.size() - 1);
}

void Refiner::drop_last_point() {
  points_.pop_back();
  param_.pop_back();
  density_.pop_back();
  normals_.pop_back();
  site_of_.pop_back();
  input_on_boundary_.pop_back();
  loop_.pop_back();
  loop_pos_.pop_back();
  if (has_creases_) {
    point_crease_.pop_back();
    curve_.pop_back();
    curve_pos_.pop_back();
  }
}

}  // namespace srcodec
