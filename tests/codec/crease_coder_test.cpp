#include "codec/crease_coder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "tests/test_util.h"

namespace srcodec {
namespace {

using Edges = std::vector<std::array<int32_t, 2>>;

Edges edges_of(const TriangleMesh& mesh) {
  std::set<std::array<int32_t, 2>> out;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) out.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  return Edges(out.begin(), out.end());
}

// Every edge of the mesh a crease with probability `share`.
Edges random_creases(const TriangleMesh& mesh, double share, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Edges out;
  for (const auto& e : edges_of(mesh))
    if (u(rng) < share) out.push_back(e);
  return out;
}

StatusOr<Edges> decode(const TriangleMesh& mesh, const std::vector<uint8_t>& bytes) {
  return decode_creases(mesh.triangles, static_cast<int32_t>(mesh.positions.size()), bytes.data(), bytes.size());
}

TEST(CreaseCoder, RoundTripsAnySetOfBaseEdges) {
  const TriangleMesh sphere = test::icosphere(2, 1.0);  // 480 edges
  for (double share : {0.0, 0.01, 0.1, 0.5, 1.0}) {
    for (uint32_t seed : {1u, 2u, 3u}) {
      const Edges creases = random_creases(sphere, share, seed);
      const std::vector<uint8_t> bytes = encode_creases(sphere.triangles, creases).value();
      EXPECT_FALSE(bytes.empty());
      StatusOr<Edges> back = decode(sphere, bytes);
      ASSERT_TRUE(back.ok()) << back.status().message();
      EXPECT_EQ(back.value(), creases) << share << " " << seed;
    }
  }
}

// Creases run in curves; the context of the creases known at an edge's ends
// makes a curve cost far less than as many edges scattered at random.
TEST(CreaseCoder, CurvesCostLessThanScatteredEdges) {
  const TriangleMesh grid = test::flat_square(30);
  // The grid's rows of vertices, joined: 10 straight curves.
  const Edges all = edges_of(grid);
  Edges curves;
  for (const auto& e : all) {
    const Eigen::Vector3d a = grid.positions[e[0]], b = grid.positions[e[1]];
    const double y = a.y() * 29;
    if (std::abs(a.y() - b.y()) < 1e-9 && static_cast<int>(std::lround(y)) % 3 == 0) curves.push_back(e);
  }
  ASSERT_GT(curves.size(), 200u);
  std::vector<Edges> scattered;
  size_t curve_bytes = encode_creases(grid.triangles, curves).value().size(), scattered_bytes = 0;
  std::mt19937 rng(5);
  Edges shuffled = all;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  shuffled.resize(curves.size());
  std::sort(shuffled.begin(), shuffled.end());
  scattered_bytes = encode_creases(grid.triangles, shuffled).value().size();
  EXPECT_LT(2 * curve_bytes, scattered_bytes) << curve_bytes << " " << scattered_bytes;
}

TEST(CreaseCoder, RefusesAnEdgeThatIsNotABaseEdge) {
  const TriangleMesh sphere = test::icosphere(1, 1.0);
  Edges creases = random_creases(sphere, 0.2, 7);
  const Edges edges = edges_of(sphere);
  std::array<int32_t, 2> diagonal{0, 1};
  while (std::binary_search(edges.begin(), edges.end(), diagonal)) ++diagonal[1];
  creases.push_back(diagonal);
  std::sort(creases.begin(), creases.end());
  StatusOr<std::vector<uint8_t>> bytes = encode_creases(sphere.triangles, creases);
  ASSERT_FALSE(bytes.ok());
  EXPECT_NE(bytes.status().message().find("not an edge"), std::string::npos) << bytes.status().message();
}

// Cut or lengthened chunks are errors naming the creases; random bytes give
// an error or some creases, each a base edge.
TEST(CreaseCoder, CutLongAndRandomChunks) {
  const TriangleMesh sphere = test::icosphere(2, 1.0);
  const std::vector<uint8_t> bytes = encode_creases(sphere.triangles, random_creases(sphere, 0.1, 9)).value();
  ASSERT_GT(bytes.size(), 4u);
  for (size_t n = 0; n < bytes.size(); ++n) {
    StatusOr<Edges> cut = decode(sphere, std::vector<uint8_t>(bytes.begin(), bytes.begin() + n));
    ASSERT_FALSE(cut.ok()) << n;
    EXPECT_NE(cut.status().message().find("creases: the chunk"), std::string::npos) << cut.status().message();
  }
  // The decoder reads up to 4 bytes ahead of the flags it has decided, so a
  // byte or two of garbage after the stream's end goes unseen (the checksum
  // is what catches damage); more is an error.
  std::vector<uint8_t> longer = bytes;
  longer.resize(bytes.size() + 4, 0);
  StatusOr<Edges> more = decode(sphere, longer);
  ASSERT_FALSE(more.ok());
  EXPECT_NE(more.status().message().find("bytes after the flags"), std::string::npos) << more.status().message();
  const Edges all = edges_of(sphere);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<uint8_t> noise(rng() % 64);
    for (auto& b : noise) b = static_cast<uint8_t>(rng());
    StatusOr<Edges> d = decode(sphere, noise);
    if (!d.ok()) continue;
    for (const auto& e : d.value()) EXPECT_TRUE(std::binary_search(all.begin(), all.end(), e));
  }
}

}  // namespace
}  // namespace srcodec
