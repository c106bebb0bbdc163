// Lifted Butterfly wavelet transform on adaptive semi-regular hierarchies
// (DESIGN.md wavelet/): predict with the modified Butterfly stencil (Zorin,
// Schröder, Sweldens 1996), update the even vertices (Schröder, Sweldens 1995
// lifting), and express each detail in a local frame of the coarser level
// (Khodakovsky, Schröder, Sweldens 2000). See wavelet/README.md for the rules.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

#include "format/status.h"
#include "format/semi_regular/hierarchy.h"

namespace srcodec {

// Every even vertex a moves by kUpdateWeight / valence(a) times each detail on
// its edges: 3/4 of the mean detail around it, which is u = 1/8 per edge at
// valence 6, the weight that keeps the mean position of a regular level
// unchanged (wavelet/README.md, "Update weight").
inline constexpr double kUpdateWeight = 0.75;

// A vertex on a crease with two sharp edges moves by 1/4 of the detail on
// each of them, the update of the 1D lifted 4-point scheme that keeps the
// mean of a curve (wavelet/README.md, "Creases"): the update divisor
// (LiftingPlan::Odd) that gives kUpdateWeight / divisor = 1/4 exactly.
inline constexpr uint32_t kCurveUpdateDivisor = 3;
static_assert(kUpdateWeight / kCurveUpdateDivisor == 0.25, "the curve update is 1/4 per edge");

// Connectivity-only precomputation for one hierarchy, shared by encoder and
// decoder: it depends only on the TriangleHierarchy, never on positions.
// Flat arrays: per level, its odd vertices in increasing id order, each with
// its prediction stencil (its four wings when regular, else taps: vertex ids
// and weights), its parent edge with the update weights of both ends, and the
// third corners of the one or two triangles on that edge (for the frame).
class LiftingPlan {
 public:
  // `levels` = finest level to transform (>= hierarchy.max_level() is fine;
  // vertices of levels above it get no coefficient). Fails on levels < 0 or a
  // hierarchy whose level meshes are not manifold.
  // `base_creases`: base edges (a < b, sorted, unique) along which the
  // surface is sharp (SemiRegularMesh::crease_edges); empty: none, and the
  // plan is the plain Butterfly's. Edges that refine a crease are creases at
  // every level, and the stencils and update weights near them follow the
  // crease rules (wavelet/README.md, "Creases"). Fails (invalid_argument) on
  // an entry that is not an edge of the base mesh, has a vertex outside the
  // base vertices or a >= b, or is not after the one before it (unsorted or
  // repeated: refused rather than sorted, as the list is a file's contents).
  static StatusOr<LiftingPlan> build(const TriangleHierarchy& hierarchy, int32_t levels,
                                     const std::vector<std::array<int32_t, 2>>& base_creases = {});

  int32_t levels() const { return levels_; }
  int32_t base_vertex_count() const { return base_vertex_count_; }
  int32_t vertex_count() const { return vertex_count_; }

  struct Tap {
    int32_t vertex;
    double weight;
  };
  // One vertex of level j >= 1, with everything its level step needs.
  struct Odd {
    int32_t v = -1;
    int32_t a = -1, b = -1;          // parent edge, as hierarchy.parent_edge(v)
    int32_t left = -1, right = -1;   // third corner of the level-(j-1) triangle on (a, b) / on (b, a); -1 if none
    // The regular case, most odd vertices: the 8-point stencil with its four
    // wings present, 1/2 on a and b, 1/8 on left and right, -1/16 on the
    // wings (the corners across the edges (left, b), (a, left), (right, a),
    // (b, right)). Such an odd has no taps. Otherwise wing[0] is -1 and
    // wing[1], wing[2] hold the range of its stencil in taps() (see
    // taps_begin(); one field for either keeps the plan 44 bytes an odd).
    std::array<int32_t, 4> wing{-1, -1, -1, -1};
    // The update divisors of a and b: each moves by kUpdateWeight / divisor
    // times this odd's detail. The divisor is the vertex's valence in the
    // level-(j-1) mesh; at a crease vertex, kCurveUpdateDivisor (1/4) for an
    // odd on one of its two sharp edges, 0 for no update (a corner or an end
    // of a crease, or an edge off the crease). Integers, not weights, to keep
    // the record 44 bytes.
    uint32_t update_divisor_a = 1, update_divisor_b = 1;
    bool regular() const { return wing[0] >= 0; }
    uint32_t taps_begin() const { return regular() ? 0 : static_cast<uint32_t>(wing[1]); }
    uint32_t taps_end() const { return regular() ? 0 : static_cast<uint32_t>(wing[2]); }
    double update_a() const { return update_weight(update_divisor_a); }
    double update_b() const { return update_weight(update_divisor_b); }
  };
  // kUpdateWeight / divisor (0 for a divisor of 0), looked up for the common
  // divisors (the same values as the division).
  static double update_weight(uint32_t divisor) {
    return divisor < kUpdateWeights.size() ? kUpdateWeights[divisor] : kUpdateWeight / divisor;
  }
  // The odd vertices of level j (1 <= j <= levels(); empty beyond max_level).
  const Odd* odd_begin(int32_t level) const;
  const Odd* odd_end(int32_t level) const;
  const std::vector<Tap>& taps() const { return taps_; }
  // True when every vertex is a base vertex or an odd one of levels 1 ..
  // `level`: inverse lifting to `level` then works in place.
  bool covers_every_vertex(int32_t level) const;
  // The prediction stencil of `o` as taps (a regular one spelled out, with
  // its eight terms in stencil order).
  std::vector<Tap> stencil(const Odd& o) const;

 private:
  int32_t levels_ = 0;
  int32_t built_levels_ = 0;  // min(levels_, hierarchy.max_level())
  int32_t base_vertex_count_ = 0;
  int32_t vertex_count_ = 0;
  static constexpr std::array<double, 32> kUpdateWeights = [] {
    std::array<double, 32> w{};  // w[0] = 0: a divisor of 0 is no update
    for (size_t k = 1; k < w.size(); ++k) w[k] = kUpdateWeight / static_cast<double>(k);
    return w;
  }();

  std::vector<Odd> odds_;               // level by level
  std::vector<uint32_t> level_begin_;   // odds of level j: [level_begin_[j-1], level_begin_[j])
  std::vector<Tap> taps_;
};

struct WaveletCoefficients {
  // Per base vertex (ids 0 .. base_vertex_count - 1): its level-0
  // approximation after all update steps, world coordinates.
  std::vector<Eigen::Vector3d> base;
  // Per hierarchy vertex id (size hierarchy.vertex_count()): zero for base
  // vertices (and for vertices above plan.levels()); for a vertex of level
  // j >= 1 its detail in the local frame of the level-(j-1) reconstruction:
  // x = normal, y = tangent along the parent edge, z = n x y.
  std::vector<Eigen::Vector3d> detail;
};

// `positions` has one entry per hierarchy vertex (missing entries count as 0).
WaveletCoefficients forward_lifting(const LiftingPlan& plan, const std::vector<Eigen::Vector3d>& positions);

// Reconstructs the positions of every vertex of level <= `level`
// (0 .. plan.levels(), clamped); entries of finer vertices are zero. `base`
// has base_vertex_count entries, `detail` vertex_count entries (missing
// entries count as 0; details of levels > level are ignored). Pass `detail`
// as an rvalue when it is not needed after: its array then holds the result.
// `threads`: big levels run half of their steps on a second thread (the
// result is the same).
std::vector<Eigen::Vector3d> inverse_lifting(const LiftingPlan& plan, const std::vector<Eigen::Vector3d>& base,
                                             std::vector<Eigen::Vector3d> detail, int32_t level, bool threads = true);

// inverse_lifting's steps of levels first .. last (clamped to plan.levels())
// on one array: `x` has one entry per hierarchy vertex, each odd vertex of
// levels first .. last holding its detail, each vertex of a lower level its
// position (the base positions, from `base`, when first <= 1; the slots of
// finer levels are neither read nor written). Preconditions: x.size() ==
// plan.vertex_count() (asserted), and plan.covers_every_vertex(L) for the
// finest level L the caller reconstructs (its to check: inverse_lifting
// works in a copy otherwise). Levels 1 .. L in one call or in several give
// the same bits as inverse_lifting. For a decoder that knows the coarser levels' details
// before the finest level's. `threads`: as inverse_lifting's.
void inverse_lifting_in_place(const LiftingPlan& plan, const std::vector<Eigen::Vector3d>& base,
                              std::vector<Eigen::Vector3d>& x, int32_t first, int32_t last, bool threads = true);

}  // namespace srcodec
