#include "codec/flags_coder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "tests/test_util.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

// An adaptive hierarchy over the cube's 12 triangles: at each level a random
// share of the leaves is split; then a few deep splits force balance splits
// of coarser leaves after the fact (what the remesher's later levels do).
TriangleHierarchy random_hierarchy(int levels, double share, uint32_t seed) {
  const TriangleMesh cube = test::unit_cube();
  TriangleHierarchy h = TriangleHierarchy::create(8, cube.triangles).value();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int level = 0; level < levels; ++level) {
    const size_t count = h.nodes().size();
    for (size_t n = 0; n < count; ++n)
      if (h.nodes()[n].level == level && h.nodes()[n].first_child < 0 && u(rng) < share)
        h.split(static_cast<int32_t>(n));
  }
  for (int k = 0; k < 3; ++k) {
    std::vector<int32_t> deepest;
    for (size_t n = 0; n < h.nodes().size(); ++n)
      if (h.nodes()[n].level == levels - 1 && h.nodes()[n].first_child < 0) deepest.push_back(static_cast<int32_t>(n));
    if (!deepest.empty()) h.split(deepest[rng() % deepest.size()]);
  }
  return h;
}

// The base triangles renumbered and rotated, as a base mesh coder may return them.
struct Shuffled {
  Triangles base;
  std::vector<int32_t> to_old_vertex, to_old_triangle;
};

Shuffled shuffle_base(const TriangleHierarchy& h, uint32_t seed) {
  std::mt19937 rng(seed);
  Shuffled s;
  s.to_old_vertex.resize(h.base_vertex_count());
  std::iota(s.to_old_vertex.begin(), s.to_old_vertex.end(), 0);
  std::shuffle(s.to_old_vertex.begin(), s.to_old_vertex.end(), rng);
  std::vector<int32_t> to_new(s.to_old_vertex.size());
  for (size_t i = 0; i < to_new.size(); ++i) to_new[s.to_old_vertex[i]] = static_cast<int32_t>(i);
  size_t base_count = 0;
  while (base_count < h.nodes().size() && h.nodes()[base_count].level == 0) ++base_count;
  s.to_old_triangle.resize(base_count);
  std::iota(s.to_old_triangle.begin(), s.to_old_triangle.end(), 0);
  std::shuffle(s.to_old_triangle.begin(), s.to_old_triangle.end(), rng);
  for (int32_t old : s.to_old_triangle) {
    const auto& v = h.nodes()[old].v;
    const int r = static_cast<int>(rng() % 3);
    s.base.push_back({to_new[v[r]], to_new[v[(r + 1) % 3]], to_new[v[(r + 2) % 3]]});
  }
  return s;
}

TriangleHierarchy decode_levels(const Shuffled& s, const ReplayedHierarchy& r, int levels) {
  TriangleHierarchy h = TriangleHierarchy::create(static_cast<int32_t>(s.to_old_vertex.size()), s.base).value();
  for (int j = 0; j < levels; ++j) {
    const Status st = decode_refinement_level(h, j, r.flags[j].data(), r.flags[j].size(), 1u << 20);
    EXPECT_TRUE(st.ok()) << st.message();
  }
  return h;
}

TEST(FlagsCoder, DecoderRebuildsTheReplayAndTheReplayIsTheRemesh) {
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    const TriangleHierarchy original = random_hierarchy(4, 0.45, seed);
    const Shuffled s = shuffle_base(original, seed);
    StatusOr<ReplayedHierarchy> r = encode_refinement(original, 4, s.base, s.to_old_vertex, s.to_old_triangle);
    ASSERT_TRUE(r.ok()) << r.status().message();
    ASSERT_EQ(r->flags.size(), 4u);
    const TriangleHierarchy decoded = decode_levels(s, r.value(), 4);
    ASSERT_EQ(decoded.nodes().size(), original.nodes().size());
    ASSERT_EQ(decoded.vertex_count(), original.vertex_count());
    for (size_t n = 0; n < decoded.nodes().size(); ++n) {
      EXPECT_EQ(decoded.nodes()[n].v, r->hierarchy.nodes()[n].v);
      EXPECT_EQ(decoded.nodes()[n].first_child, r->hierarchy.nodes()[n].first_child);
    }
    // Every replayed vertex is the original vertex with the same parent edge and level.
    const auto& map = r->to_original_vertex;
    for (int32_t v = original.base_vertex_count(); v < decoded.vertex_count(); ++v) {
      auto e = decoded.parent_edge(v);
      auto o = original.parent_edge(map[v]);
      std::array<int32_t, 2> mapped = {map[e[0]], map[e[1]]};
      std::sort(mapped.begin(), mapped.end());
      std::sort(o.begin(), o.end());
      EXPECT_EQ(mapped, o) << v;
      EXPECT_EQ(decoded.vertex_level(v), original.vertex_level(map[v]));
    }
  }
}

TEST(FlagsCoder, AnyLevelPrefixHoldsExactlyTheVerticesUpToThatLevel) {
  const TriangleHierarchy original = random_hierarchy(4, 0.5, 11);
  const Shuffled s = shuffle_base(original, 3);
  const ReplayedHierarchy r = encode_refinement(original, 4, s.base, s.to_old_vertex, s.to_old_triangle).value();
  for (int levels = 0; levels <= 4; ++levels) {
    const TriangleHierarchy partial = decode_levels(s, r, levels);
    int32_t expected = 0;
    for (int32_t v = 0; v < r.hierarchy.vertex_count(); ++v) expected += r.hierarchy.vertex_level(v) <= levels;
    ASSERT_EQ(partial.vertex_count(), expected) << levels;
    for (int32_t v = 0; v < partial.vertex_count(); ++v) {
      EXPECT_EQ(partial.parent_edge(v), r.hierarchy.parent_edge(v));
      EXPECT_LE(partial.vertex_level(v), levels);
    }
    EXPECT_EQ(partial.level_triangles(levels), r.hierarchy.level_triangles(levels)) << levels;
  }
}

TEST(FlagsCoder, UniformLevelsCostAByteAndAdaptiveOnesAreCompact) {
  const TriangleHierarchy uniform = random_hierarchy(3, 1.0, 5);
  const Shuffled s = shuffle_base(uniform, 5);
  const ReplayedHierarchy r = encode_refinement(uniform, 3, s.base, s.to_old_vertex, s.to_old_triangle).value();
  for (const auto& chunk : r.flags) EXPECT_LE(chunk.size(), 2u);

  const TriangleHierarchy adaptive = random_hierarchy(5, 0.5, 6);
  const Shuffled t = shuffle_base(adaptive, 6);
  const ReplayedHierarchy a = encode_refinement(adaptive, 5, t.base, t.to_old_vertex, t.to_old_triangle).value();
  size_t bytes = 0;
  for (const auto& chunk : a.flags) bytes += chunk.size();
  // Fewer than 1.1 bits per node: random 50% flags cost ~1 bit each.
  EXPECT_LT(8.0 * bytes, 1.1 * adaptive.nodes().size());
}

TEST(FlagsCoder, HostileFlagsStopAtTheVertexLimitOrDecodeSafely) {
  const TriangleMesh cube = test::unit_cube();
  std::mt19937 rng(9);
  for (int trial = 0; trial < 300; ++trial) {
    TriangleHierarchy h = TriangleHierarchy::create(8, cube.triangles).value();
    std::vector<uint8_t> bytes(rng() % 16);
    for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    for (int level = 0; level < 6; ++level) {
      const Status st = decode_refinement_level(h, level, bytes.data(), bytes.size(), 2000);
      if (!st.ok()) break;
    }
    EXPECT_LE(h.vertex_count(), 2000 + 3 * 4 * 64);  // one split past the limit at most
  }
}

}  // namespace
}  // namespace srcodec
