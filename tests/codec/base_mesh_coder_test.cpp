#include "codec/base_mesh_coder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <random>
#include <set>

#include "format/mesh_files/mesh_io.h"
#include "format/semi_regular/hierarchy.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

QuantizationGrid grid_for(const std::vector<Eigen::Vector3d>& positions, int bits) {
  Eigen::Vector3d lo = positions[0], hi = positions[0];
  for (const auto& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  QuantizationGrid grid;
  grid.origin = lo;
  grid.bits = bits;
  grid.step = std::max((hi - lo).maxCoeff(), 1e-9) / ((1 << bits) - 1);
  return grid;
}

// Grid torus: n around the tube axis, m around the tube.
TriangleMesh torus(int n, int m) {
  TriangleMesh t;
  const double kPi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * kPi * i / n, v = 2 * kPi * j / m;
      t.positions.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return t;
}

// A closed surface of genus 3: a flat grid with three square holes, a
// second (flipped) copy below it, and walls joining them along every boundary.
TriangleMesh genus3() {
  const int n = 12;
  auto in_hole = [](int i, int j) {
    return (i >= 2 && i < 4 && j >= 2 && j < 4) || (i >= 7 && i < 9 && j >= 2 && j < 4) ||
           (i >= 4 && i < 7 && j >= 7 && j < 9);
  };
  TriangleMesh m;
  const int32_t layer = (n + 1) * (n + 1);
  for (int lower = 0; lower < 2; ++lower) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) m.positions.emplace_back(i, j, lower ? -1.0 : 0.0);
    }
  }
  std::set<std::pair<int32_t, int32_t>> top_edges;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (in_hole(i, j)) continue;
      const int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
      m.triangles.push_back({a + layer, c + layer, b + layer});
      m.triangles.push_back({a + layer, d + layer, c + layer});
      for (auto e : {std::pair{a, b}, {b, c}, {c, a}, {a, c}, {c, d}, {d, a}}) top_edges.insert(e);
    }
  }
  for (const auto& [u, v] : top_edges) {
    if (top_edges.count({v, u})) continue;  // interior edge
    m.triangles.push_back({v, u, u + layer});
    m.triangles.push_back({v, u + layer, v + layer});
  }
  // Drop grid vertices inside holes (unused).
  std::vector<int32_t> remap(m.positions.size(), -1);
  std::vector<Eigen::Vector3d> used;
  for (auto& t : m.triangles) {
    for (auto& v : t) {
      if (remap[v] < 0) {
        remap[v] = static_cast<int32_t>(used.size());
        used.push_back(m.positions[v]);
      }
      v = remap[v];
    }
  }
  m.positions = used;
  return m;
}

// Random edge flips on a subdivided icosahedron: irregular valences.
TriangleMesh flipped_sphere(int subdivisions, int flips, unsigned seed) {
  TriangleMesh m = test::icosphere(subdivisions, 1.0);
  std::mt19937 rng(seed);
  std::vector<int> valence(m.positions.size(), 0);
  for (const auto& t : m.triangles) {
    for (int32_t v : t) ++valence[v];
  }
  for (int f = 0; f < flips; ++f) {
    std::map<std::pair<int32_t, int32_t>, std::pair<int, int>> edge;  // directed edge -> triangle, corner
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      for (int i = 0; i < 3; ++i) edge[{m.triangles[t][i], m.triangles[t][(i + 1) % 3]}] = {int(t), i};
    }
    const int t = std::uniform_int_distribution<int>(0, int(m.triangles.size()) - 1)(rng);
    const int i = std::uniform_int_distribution<int>(0, 2)(rng);
    const int32_t a = m.triangles[t][i], b = m.triangles[t][(i + 1) % 3], c = m.triangles[t][(i + 2) % 3];
    const auto [u, k] = edge.at({b, a});
    const int32_t d = m.triangles[u][(k + 2) % 3];
    if (valence[a] <= 3 || valence[b] <= 3 || edge.count({c, d}) || edge.count({d, c})) continue;
    m.triangles[t] = {a, d, c};
    m.triangles[u] = {b, c, d};
    --valence[a], --valence[b], ++valence[c], ++valence[d];
  }
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (auto& p : m.positions) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  return m;
}

TriangleMesh two_components() {
  TriangleMesh a = test::icosphere(1, 1.0), b = torus(10, 6);
  for (auto& p : b.positions) p += Eigen::Vector3d(5, 0, 0);
  append_mesh(a, b);
  return a;
}

// The input in a random vertex and triangle order with rotated corners, so
// the coder's permutations are exercised.
TriangleMesh shuffled(const TriangleMesh& m, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<int32_t> perm(m.positions.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  TriangleMesh out;
  out.positions.resize(m.positions.size());
  for (size_t v = 0; v < perm.size(); ++v) out.positions[perm[v]] = m.positions[v];
  for (const auto& t : m.triangles) {
    const int r = std::uniform_int_distribution<int>(0, 2)(rng);
    out.triangles.push_back({perm[t[r]], perm[t[(r + 1) % 3]], perm[t[(r + 2) % 3]]});
  }
  std::shuffle(out.triangles.begin(), out.triangles.end(), rng);
  return out;
}

bool is_rotation(const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b) {
  for (int r = 0; r < 3; ++r) {
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
  }
  return false;
}

bool is_permutation_of_range(std::vector<int32_t> v, size_t n) {
  if (v.size() != n) return false;
  std::sort(v.begin(), v.end());
  for (size_t i = 0; i < n; ++i) {
    if (v[i] != static_cast<int32_t>(i)) return false;
  }
  return true;
}

// Round trip with every check; returns the code.
BaseMeshCode round_trip(const TriangleMesh& m, const std::string& name, int bits = 12) {
  const QuantizationGrid grid = grid_for(m.positions, bits);
  auto code = encode_base_mesh(m.positions, m.triangles, grid);
  EXPECT_TRUE(code.ok()) << name << ": " << code.status().message();
  if (!code.ok()) return {};
  const auto decoded = decode_base_mesh(code->bytes.data(), code->bytes.size(), grid, m.positions.size(),
                                        m.triangles.size());
  EXPECT_TRUE(decoded.ok()) << name << ": " << decoded.status().message();
  if (!decoded.ok()) return {};
  EXPECT_EQ(decoded->triangles, code->triangles) << name;
  EXPECT_EQ(decoded->positions, code->positions) << name;
  EXPECT_TRUE(is_permutation_of_range(code->new_to_old_vertex, m.positions.size())) << name;
  EXPECT_TRUE(is_permutation_of_range(code->new_to_old_triangle, m.triangles.size())) << name;
  for (size_t t = 0; t < decoded->triangles.size(); ++t) {
    std::array<int32_t, 3> old{};
    for (int i = 0; i < 3; ++i) old[i] = code->new_to_old_vertex[decoded->triangles[t][i]];
    EXPECT_TRUE(is_rotation(old, m.triangles[code->new_to_old_triangle[t]])) << name << " triangle " << t;
  }
  for (size_t v = 0; v < decoded->positions.size(); ++v) {
    const Eigen::Vector3d d = decoded->positions[v] - m.positions[code->new_to_old_vertex[v]];
    EXPECT_LE(d.cwiseAbs().maxCoeff(), grid.step * 0.5 * (1 + 1e-9)) << name << " vertex " << v;
  }
  const auto hierarchy = TriangleHierarchy::create(static_cast<int32_t>(decoded->positions.size()), decoded->triangles);
  EXPECT_TRUE(hierarchy.ok()) << name << ": " << hierarchy.status().message();
  const double bits_per_triangle = 8.0 * code->bytes.size() / m.triangles.size();
  std::printf("%-22s V=%5zu T=%5zu bytes=%6zu  %.2f bits/triangle (connectivity and %d-bit positions)\n",
              name.c_str(), m.positions.size(), m.triangles.size(), code->bytes.size(), bits_per_triangle, bits);
  return std::move(code).value();
}

// Connectivity alone: on a 1-bit grid positions cost almost nothing.
double connectivity_bits_per_triangle(const TriangleMesh& m) {
  std::vector<Eigen::Vector3d> flat(m.positions.size(), Eigen::Vector3d::Zero());
  QuantizationGrid grid;
  grid.bits = 1;
  auto code = encode_base_mesh(flat, m.triangles, grid);
  EXPECT_TRUE(code.ok()) << code.status().message();
  return code.ok() ? 8.0 * code->bytes.size() / m.triangles.size() : 1e9;
}

TEST(BaseMeshCoder, RoundTripsIcosahedron) { round_trip(test::icosphere(0, 1.0), "icosahedron"); }

TEST(BaseMeshCoder, RoundTripsOpenGridPatch) {
  round_trip(test::flat_square(12), "grid patch");
  round_trip(shuffled(test::flat_square(20), 3), "grid patch shuffled");
}

TEST(BaseMeshCoder, RoundTripsTorus) { round_trip(shuffled(torus(24, 12), 5), "torus"); }

TEST(BaseMeshCoder, RoundTripsGenus3) { round_trip(shuffled(genus3(), 7), "genus 3"); }

TEST(BaseMeshCoder, RoundTripsTwoComponents) { round_trip(shuffled(two_components(), 11), "two components"); }

TEST(BaseMeshCoder, RoundTripsIrregularSphere) {
  const TriangleMesh m = flipped_sphere(3, 600, 13);
  std::vector<int> valence(m.positions.size(), 0);
  for (const auto& t : m.triangles) {
    for (int32_t v : t) ++valence[v];
  }
  const auto [lo, hi] = std::minmax_element(valence.begin(), valence.end());
  std::printf("irregular sphere valences %d..%d\n", *lo, *hi);
  EXPECT_LE(*lo, 3);
  EXPECT_GE(*hi, 11);
  round_trip(shuffled(m, 17), "irregular sphere");
}

TEST(BaseMeshCoder, BitsPerTriangleOnClosedMeshes) {
  const std::vector<std::pair<std::string, TriangleMesh>> meshes = {
      {"icosphere 3", shuffled(test::icosphere(3, 1.0), 1)},
      {"torus", shuffled(torus(40, 20), 2)},
      {"genus 3", shuffled(genus3(), 3)},
      {"irregular sphere", shuffled(flipped_sphere(3, 600, 4), 5)},
  };
  for (const auto& [name, m] : meshes) {
    const double connectivity = connectivity_bits_per_triangle(m);
    std::printf("%-22s connectivity %.2f bits/triangle\n", name.c_str(), connectivity);
    EXPECT_LT(connectivity, 3.0) << name;
    const BaseMeshCode code = round_trip(m, name);
    EXPECT_LT(8.0 * code.bytes.size() / m.triangles.size(), 20.0) << name;
  }
}

// Non-manifold vertices (two fans meeting at one vertex) satisfy the
// hierarchy's requirements, so the coder keeps them.
TEST(BaseMeshCoder, RoundTripsFansMeetingAtAVertex) {
  TriangleMesh m = test::tetrahedron();
  TriangleMesh b = test::tetrahedron();
  for (auto& p : b.positions) p += Eigen::Vector3d(1, 0, 0);
  append_mesh(m, b);
  for (auto& t : m.triangles) {
    for (auto& v : t) v = v == 5 ? 1 : v;  // vertex 1 of both
  }
  m.positions.erase(m.positions.begin() + 5);
  for (auto& t : m.triangles) {
    for (auto& v : t) v = v > 5 ? v - 1 : v;
  }
  round_trip(m, "bowtie tetrahedra");
}

TEST(BaseMeshCoder, RejectsInvalidInput) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  const QuantizationGrid grid = grid_for(ico.positions, 10);
  auto expect_invalid = [&](const std::vector<Eigen::Vector3d>& p, const Triangles& t, const std::string& what) {
    const auto code = encode_base_mesh(p, t, grid);
    EXPECT_FALSE(code.ok()) << what;
    if (!code.ok()) std::printf("%s: %s\n", what.c_str(), code.status().message().c_str());
  };
  Triangles flipped = ico.triangles;
  std::swap(flipped[4][0], flipped[4][1]);
  expect_invalid(ico.positions, flipped, "flipped triangle");
  Triangles fin = ico.triangles;
  auto extra = ico.positions;
  extra.emplace_back(3, 3, 3);
  fin.push_back({ico.triangles[0][1], ico.triangles[0][0], 12});  // a third triangle on one edge
  expect_invalid(extra, fin, "non-manifold edge");
  expect_invalid(extra, ico.triangles, "unused vertex");
  Triangles out_of_range = ico.triangles;
  out_of_range[3][2] = 12;
  expect_invalid(ico.positions, out_of_range, "index out of range");
  out_of_range[3][2] = -1;
  expect_invalid(ico.positions, out_of_range, "negative index");
  Triangles degenerate = ico.triangles;
  degenerate[2][1] = degenerate[2][0];
  expect_invalid(ico.positions, degenerate, "repeated vertex");
  expect_invalid(ico.positions, {}, "no triangles");
  QuantizationGrid bad = grid;
  bad.bits = 25;
  EXPECT_FALSE(encode_base_mesh(ico.positions, ico.triangles, bad).ok());
  bad.bits = 12;
  bad.step = 0;
  EXPECT_FALSE(encode_base_mesh(ico.positions, ico.triangles, bad).ok());
}

TEST(BaseMeshCoder, DecoderRejectsLimitsAndTrailingBytes) {
  const TriangleMesh m = test::icosphere(1, 1.0);
  const QuantizationGrid grid = grid_for(m.positions, 12);
  auto code = encode_base_mesh(m.positions, m.triangles, grid);
  ASSERT_TRUE(code.ok());
  const auto& b = code->bytes;
  EXPECT_FALSE(decode_base_mesh(b.data(), b.size(), grid, m.positions.size() - 1, m.triangles.size()).ok());
  EXPECT_FALSE(decode_base_mesh(b.data(), b.size(), grid, m.positions.size(), m.triangles.size() - 1).ok());
  std::vector<uint8_t> longer = b;
  longer.push_back(0);
  const auto trailing = decode_base_mesh(longer.data(), longer.size(), grid, 1000, 1000);
  EXPECT_FALSE(trailing.ok());
  std::printf("trailing byte: %s\n", trailing.status().message().c_str());
  EXPECT_FALSE(decode_base_mesh(nullptr, 0, grid, 1000, 1000).ok());
}

TEST(BaseMeshCoder, EveryTruncationFails) {
  for (const TriangleMesh& m : {test::icosphere(2, 1.0), genus3(), test::flat_square(6)}) {
    const QuantizationGrid grid = grid_for(m.positions, 12);
    auto code = encode_base_mesh(m.positions, m.triangles, grid);
    ASSERT_TRUE(code.ok());
    for (size_t n = 0; n < code->bytes.size(); ++n) {
      EXPECT_FALSE(decode_base_mesh(code->bytes.data(), n, grid, 100000, 100000).ok()) << "length " << n;
    }
  }
}

TEST(BaseMeshCoder, GarbageNeverCrashes) {
  const TriangleMesh m = shuffled(genus3(), 21);
  const QuantizationGrid grid = grid_for(m.positions, 12);
  auto code = encode_base_mesh(m.positions, m.triangles, grid);
  ASSERT_TRUE(code.ok());
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> byte(0, 255);
  int decoded_ok = 0;
  for (int i = 0; i < 1000; ++i) {  // random buffers, half behind a plausible header
    std::vector<uint8_t> buffer(std::uniform_int_distribution<size_t>(0, 600)(rng));
    for (auto& x : buffer) x = static_cast<uint8_t>(byte(rng));
    if (i % 2 && buffer.size() > 8) {
      std::vector<uint8_t> header = {1, 0xC8, 0x01, 0x90, 0x03};  // 200 vertices, 400 triangles
      std::copy(header.begin(), header.end(), buffer.begin());
      size_t rest = buffer.size() - 7;
      buffer[5] = static_cast<uint8_t>(0x80 | (rest & 0x7F));
      buffer[6] = static_cast<uint8_t>(rest >> 7);
    }
    decoded_ok += decode_base_mesh(buffer.data(), buffer.size(), grid, 5000, 10000).ok();
  }
  for (int i = 0; i < 1000; ++i) {  // one corrupted byte
    std::vector<uint8_t> buffer = code->bytes;
    buffer[std::uniform_int_distribution<size_t>(0, buffer.size() - 1)(rng)] ^=
        static_cast<uint8_t>(1 + byte(rng) % 255);
    const auto decoded = decode_base_mesh(buffer.data(), buffer.size(), grid, 5000, 10000);
    if (decoded.ok()) {
      ++decoded_ok;
      EXPECT_TRUE(TriangleHierarchy::create(static_cast<int32_t>(decoded->positions.size()), decoded->triangles).ok() ||
                  decoded->triangles.size() == 2);
    }
  }
  std::printf("garbage decoded without error: %d of 2000\n", decoded_ok);
}

// Base meshes written by `srcodec remesh --write-levels` (level 0), when present.
TEST(BaseMeshCoder, CorpusBaseMeshesIfPresent) {
  const char* dir = std::getenv("SRCODEC_BASE_MESH_DIR");
  if (!dir) GTEST_SKIP() << "set SRCODEC_BASE_MESH_DIR to a folder of *_lvl_l0.obj files";
  for (const std::string name : {"fandisk", "stanford-bunny", "lionstatue", "ogre"}) {
    const auto mesh = read_triangle_mesh(std::string(dir) + "/" + name + "_lvl_l0.obj");
    if (!mesh.ok()) continue;
    const BaseMeshCode code = round_trip(mesh.value(), name);
    const double connectivity = connectivity_bits_per_triangle(mesh.value());
    std::printf("%-22s connectivity %.2f bits/triangle, positions %.2f bits/vertex\n", name.c_str(), connectivity,
                (8.0 * code.bytes.size() - connectivity * mesh->triangles.size()) / mesh->positions.size());
  }
}

}  // namespace
}  // namespace srcodec
